(** Tori: the points within [minor] of the core circle of radius [major]
    about the axis through [center] (a ring torus: [0 < minor < major]).
    A torus is closed: it may be a CSG operand, and a line meets its
    solid in up to two intervals.

    Scene text: [(torus (center x y z) (axis x y z) (major R) (minor r) ...)],
    the material's fields after (docs/scene-format.md). *)

(** {1:tori Tori} *)

type t = private { center : Vec3.t; axis : Vec3.t; major : float; minor : float; material : Material.t }
(** The type for tori: [axis] is any non-zero vector along the axis, as
    written (the torus's axis is its float unit vector, [Vec3.unit axis]);
    [major] and [minor] are radii in world units. *)

val v : center:Vec3.t -> axis:Vec3.t -> major:float -> minor:float -> Material.t -> t
(** [v ~center ~axis ~major ~minor m] is a torus, not validated. *)

val validate : t -> (t, [> `Msg of string ]) result
(** [validate x] checks the center and axis ({!Limits.check_point}), that
    the axis is not zero, the radii ({!Limits.check_size}), that
    [minor < major], and the material. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] are equal field by field, floats compared with [=]. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf x] prints [x] as its scene-text form, which reads back as [x]. *)

val bounds : t -> Vec3.t * Vec3.t
(** [bounds x] is the box that holds [x]: about [center], [major *
    sqrt (1 - a_i^2) + minor] on axis [i] for the unit axis [a], rounded
    outward. *)

val literal : t -> origin:Vec3.t -> direction:Vec3.t -> (float * Vec3.t) list
(** [literal x ~origin ~direction] is the line's crossings of [x]'s
    surface, nearer first, with the outward unit normals: the executable
    specification's answer, by sphere tracing the exact distance to the
    surface and bisecting each change of side, a side counted only where
    the distance exceeds its rounding error (not the kernel's method).
    The [torus] suite checks its crossings in exact arithmetic as it
    checks the kernel's roots. *)

val desc : t Shape_desc.t
(** [desc] is the torus's description ({!Shape_desc.t}). *)

(**/**)

(* Internal: the kernel's side of this module, for the tracer and the tests, hidden from the documentation. Not for users: it changes without notice. *)

(** {1:kernel The kernel's routines}

    A torus is stored at offset [o] of a float array (8 floats): the
    center at [o .. o + 2], the unit axis times [major] at [o + 3 .. o + 5]
    (every float of the torus's size: the robust mode's offset reads the
    largest as its extent), [major] at [o + 6], [minor] at [o + 7]. *)

val store : t -> float array -> int -> unit
(** [store x g o] writes [x] at offset [o] of [g]. *)

val roots : Scratch.t -> float array -> int -> bool
(** [roots s g o] is [true] iff the line of the ray in [s] meets the solid
    torus stored at [o] of [g] in an interval whose exit lies beyond
    [s.t_min]: the first such, its entry in [s.near] (perhaps before
    [s.t_min]: the ray starts inside) and its exit in [s.far]. Called
    again with [s.t_min] set to that exit, it gives the second interval.
    Allocates nothing.

    Method: the line is [q + s D], [q] its point nearest the center; the
    quartic [G(s)] of the torus has at most three critical points (the
    cubic [G'] bracketed between the roots of the quadratic [G'']),
    between which it is monotone; each change of sign there is refined by
    Newton steps kept in the bracket, with bisection, on
    [F = (rho - major)^2 + z^2 - minor^2], of [G]'s sign but without its
    cancellation. No closed-form solver: those lose roots near tangency
    and at a distance.

    Accuracy, with [delta = 8 u (|O - center| + major + minor)] ([u =
    2^-53]), checked in exact rational arithmetic by the [torus] suite on
    this routine, over scales 1e-6 to 1e6, translations by 1e6 and
    grazing rays: each root is the parameter of a point within [delta] of
    the exact surface (the exact quartic of minor radius [minor + delta]
    is [<= 0] there, that of [minor - delta] [>= 0]: the quartic touches
    zero within the bound); between two roots the exact quartic has the
    sign the intervals say; and the roots are as many as the exact
    quartic's real roots (Sturm's theorem), unless the line passes within
    [2 delta] of tangency. *)

val normal : Scratch.t -> float array -> int -> unit
(** [normal s g o] sets [s.nx, s.ny, s.nz] to the outward unit normal of
    the torus stored at [o] of [g] at the point [s.px, s.py, s.pz]: from
    the core circle's nearest point to it. *)

val unit_axis : t -> Vec3.t
(** [unit_axis x] is [Vec3.unit x.axis], the torus's axis. *)
