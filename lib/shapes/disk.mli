(** Disks: the points of the plane through [center] across [normal]
    within [radius] of the centre. Flat, seen from both sides, not a
    solid (no CSG operand).

    Scene text: [(disk (center x y z) (normal x y z) (radius r) ...)],
    the material's fields after. *)

type t = private { center : Vec3.t; normal : Vec3.t; radius : float; material : Material.t }
(** The type for disks: [normal] need not be of unit length. *)

val v : center:Vec3.t -> normal:Vec3.t -> radius:float -> Material.t -> t
(** [v ~center ~normal ~radius m] is a disk, not validated. *)

val validate : t -> (t, [> `Msg of string ]) result
(** [validate d] checks the centre and normal ({!Limits.check_point}),
    that the normal is not zero, the radius ({!Limits.check_size}) and
    the material. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] are equal field by field,
    floats compared with [=]. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf d] prints [d] as its scene-text form; it reads back as [d]. *)

val show : t -> string
(** [show d] is [d] formatted by {!pp}. *)

val desc : t Shape_desc.t
(** [desc] is the disk's description: its form, bounds (the box of its
    circle, {!rim_extent} either side of the centre, rounded outward), its
    stored floats and its literal crossing. *)

val rim_extent : float -> Vec3.t -> Vec3.t
(** [rim_extent r n] is how far a circle of radius [r] across the
    non-zero vector [n] reaches from its centre along x, y and z, each
    [r sqrt (1 - n_i^2 / |n|^2)] rounded up (by [32 u] relatively; the
    test suite checks in exact arithmetic that it is never below): [0]
    along an axis that [n] points along. *)

(**/**)

(* Internal: the kernel's side of this module, hidden from the
   documentation. Not for users: it changes without notice. *)

val store : t -> float array -> int -> unit
(** [store d g o] writes [d] at [g.(o)] (7 floats): the centre, the
    normal scaled by a power of two (exactly) so that its largest
    coordinate is in [[1/4, 1/2)], and the radius. *)

val roots : Scratch.t -> float array -> int -> bool
(** [roots s g o] is [true] iff the line of the ray of [s] crosses the
    disk stored at [g.(o)], with the root in [s.near = s.far]: the
    plane's root [t = -<O - C, N> / <D, N>] and the test
    [|(O - C) + t D|^2 <= r^2]; a ray parallel to the stored normal's
    plane misses. Allocates nothing.

    Accuracy (checked by the test suite in exact rational arithmetic,
    test/test_cylinder.ml, with [u = 2^-53] and [S = |O - C| + |t D|]):
    the root puts the exact point [O + t D] within [16 u S] of the exact
    plane, and a ray is reported as a hit or a miss as the exact line
    says, unless it crosses the plane within [16 u S] of the rim. *)

val normal : Scratch.t -> float array -> int -> unit
(** [normal s g o] sets [s.nx], [s.ny], [s.nz] to the unit normal of the
    disk stored at [g.(o)] (the side given; the kernel turns it toward
    the ray). Allocates nothing. *)
