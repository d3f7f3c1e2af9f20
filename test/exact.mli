(** Exact arithmetic on the floats of a ray and a sphere, with Zarith's
    rationals: every finite float is a rational, so these are the true
    values for the given float inputs, free of rounding. The stress tests
    measure the floating-point formulas against them. *)

val line_distance2 : Raytrace.Sphere.t -> origin:Raytrace.Vec3.t -> direction:Raytrace.Vec3.t -> Q.t
(** [line_distance2 s ~origin ~direction] is the exact squared distance
    from the center of [s] to the line [O + t D]: [|f|^2 - <f, D>^2 / |D|^2]
    with [f = O - C]. *)

val surface_distance : Raytrace.Sphere.t -> origin:Raytrace.Vec3.t -> direction:Raytrace.Vec3.t -> float -> float
(** [surface_distance s ~origin ~direction t] is the distance from the exact
    point [O + t D] to the surface of [s], [| |P - C| - r |], computed as
    [|g(t)| / (|P - C| + r)] with [g(t) = |P - C|^2 - r^2] exact (the
    division and square root are then rounded once, a relative error of a
    few ulps in the result, which is all a bound check needs). *)

(** {1:q Rationals of floats} *)

val q : float -> Q.t
(** [q x] is the float [x] as the rational it is exactly. *)

val qv : Raytrace.Vec3.t -> Q.t * Q.t * Q.t
(** [qv v] is [v]'s coordinates as rationals. *)

val dot : Q.t * Q.t * Q.t -> Q.t * Q.t * Q.t -> Q.t
(** [dot a b] is the exact dot product. *)

val sub : Q.t * Q.t * Q.t -> Q.t * Q.t * Q.t -> Q.t * Q.t * Q.t
(** [sub a b] is [a - b], exactly. *)

val add : Q.t * Q.t * Q.t -> Q.t * Q.t * Q.t -> Q.t * Q.t * Q.t
(** [add a b] is [a + b], exactly. *)

val scale : Q.t -> Q.t * Q.t * Q.t -> Q.t * Q.t * Q.t
(** [scale k a] is [k a], exactly. *)
