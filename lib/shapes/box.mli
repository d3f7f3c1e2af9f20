(** Axis-aligned boxes.

    A box is the solid [min <= P <= max], coordinate by coordinate. It is
    closed: a ray from inside meets its walls from within. *)

(** {1:boxes Boxes} *)

type t = private { min : Vec3.t; max : Vec3.t; material : Material.t }
(** The type for boxes: [min] and [max] are opposite corners, in world units.
    Read its fields, make one with {!v}. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf x] prints [x] as its form in the scene-file syntax,
    [(box (min x y z) (max x y z) ...)], the material's fields as {!Material.pp} prints them. *)

val show : t -> string
(** [show x] is [x] formatted by {!pp}. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] are equal field by field, floats
    compared with [=]. *)

val v : min:Vec3.t -> max:Vec3.t -> Material.t -> t
(** [v ~min ~max m] is a box, not validated. *)

val validate : t -> (t, [> `Msg of string ]) result
(** [validate b] checks the corners ({!Limits.check_point}), that
    [min < max] on every axis, and the material. *)

val intersect : t -> origin:Vec3.t -> direction:Vec3.t -> float * float
(** [intersect b ~origin ~direction] is [(near, far)] of [roots], or
    [(infinity, infinity)]. *)

(**/**)

(* Internal: the kernel's side of this module, for the tracer and the tests, hidden from the documentation. Not for users: it changes without notice. *)

(** {1:kernel The kernel's routines}

    A box is stored in a float array at an offset [o]: [min] at
    [o .. o + 2], [max] at [o + 3 .. o + 5]. *)

val store : t -> float array -> int -> unit
(** [store b g o] writes [b] to [g] at offset [o] (6 floats). *)

val roots : Scratch.t -> float array -> int -> bool
(** [roots s g o] is [true] iff the line of the ray of [s] meets the box
    stored at [o] in [g], with the parameters where it enters and leaves
    it in [s.near <= s.far] (the slab method: for each axis
    [(min - O) / D] and [(max - O) / D]; an axis along which [D] is [0]
    bounds nothing if [O] lies between its planes, and misses otherwise).

    Accuracy (checked by the test suite in exact rational arithmetic):
    each slab parameter is within [2 u] of its exact value relatively
    ([u = 2^-53]: one rounding in the difference, one in the quotient), so
    [near] and [far] are, and a ray is reported as a hit or a miss exactly
    when the exact parameters say so, unless the exact entry and exit lie
    within [4 u] of each other relatively (the ray grazes an edge). *)

val normal : Scratch.t -> float array -> int -> unit
(** [normal s g o] sets [s.nx], [s.ny], [s.nz] to the outward unit normal
    of the face of the box nearest to the hit point [s.px], [s.py],
    [s.pz] (faces tried in the order -x, +x, -y, +y, -z, +z; the first of
    equally near ones wins, at edges and corners). With a point alone
    ({!Shape.normal}); the kernel's hits take [hit_normal], which knows
    the ray. *)

val hit_normal : Scratch.t -> float array -> int -> unit
(** [hit_normal s g o] sets [s.nx], [s.ny], [s.nz] to the outward unit
    normal of the face of the box stored at [o] that the ray of [s]
    crosses at its root [s.near] (one of those [roots] found, for the
    same ray): the slab method's face, the one whose slab decides the
    root. Where the ray enters ([s.near] at or before the entry, as for a
    line that only touches an edge), the face of the slab it enters last;
    where it leaves, the face of the slab it leaves first; of slabs
    entered or left at the same parameter (a ray through an edge or a
    corner), the first axis in the order x, y, z. A ray sliding along a
    face, or leaving through an edge, so never gets the normal of a face
    it does not cross, as the nearest face to the hit point ([normal])
    may be. Allocates nothing. *)

