(** Infinite planes.

    A plane is the set of points [P] with [<P - P0, N> = 0]. It is seen
    from both sides: shading uses the normal turned toward the incoming
    ray. *)

(** {1:planes Planes} *)

type t = private {
  point : Vec3.t;  (** [P0], a point of the plane, in world units. *)
  normal : Vec3.t;  (** [N], not zero; any length (it is normalised when used). *)
  material : Material.t;
}
(** The type for planes: read its fields, make one with {!v}. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf x] prints [x] as its form in the scene-file syntax,
    [(plane (point x y z) (normal x y z) ...)], the material's fields as {!Material.pp} prints them. *)

val show : t -> string
(** [show x] is [x] formatted by {!pp}. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] are equal field by field, floats
    compared with [=]. *)

val v : point:Vec3.t -> normal:Vec3.t -> Material.t -> t
(** [v ~point ~normal m] is a plane, not validated. *)

val validate : t -> (t, [> `Msg of string ]) result
(** [validate p] checks the point ({!Limits.check_point}), that the normal is
    finite and of a length that can be normalised, and the material. *)

val intersect : t -> origin:Vec3.t -> direction:Vec3.t -> float
(** [intersect p ~origin ~direction] is the root of [roots], or [infinity]. *)

(**/**)

(* Internal: the kernel's side of this module, for the tracer and the tests, hidden from the documentation. Not for users: it changes without notice. *)

(** {1:kernel The kernel's routines}

    A plane is stored in a float array at an offset [o]: [P0] at
    [o .. o + 2], the unit normal at [o + 3 .. o + 5], the normal as
    given times a power of two (its largest coordinate in [\[1/4, 1/2)])
    at [o + 6 .. o + 8]. The tracer calls these routines, and so do
    {!Raytrace.Private.Literal} and the tests. *)

val store : t -> float array -> int -> unit
(** [store p g o] writes [p] to [g] at offset [o] (9 floats). *)

val roots : Scratch.t -> float array -> int -> bool
(** [roots s g o] is [true] iff the line of the ray of [s] meets the plane
    stored at [o] in [g], at [t = <P0 - O, N> / <D, N>] ([N] the normal as
    given, times a power of two), left in [s.near] and [s.far]; [false]
    (and [infinity] there) when the ray is parallel to the plane,
    [<D, N> = 0] (so for a ray exactly parallel to the normal as given,
    to which the rounded unit normal need not be perpendicular).

    Accuracy (checked by the test suite in exact rational arithmetic): the
    exact point [O + t D] lies within [16 u (|P0 - O| + |t D|)] of the
    plane ([u = 2^-53]), whatever the angle of the ray: a grazing ray's
    root is as uncertain as its direction, along its length [|t D|]. *)

val normal : Scratch.t -> float array -> int -> unit
(** [normal s g o] sets [s.nx], [s.ny], [s.nz] to the unit normal of the
    plane (the side it was given with). *)

