(** The kernel's dispatch on the kind of a shape stored in a geometry
    table ([Prepared]'s [geom], the CSG table's): the one [match] per
    routine that a new kind adds a line to, checked for exhaustiveness by
    the compiler. The traversal ([Traversal]), the surfaces ([Surface])
    and the CSG table ({!Csg}) send here every kind that has no path of
    its own (spheres, triangles, CSG solids and instances have theirs).

    Floats travel in the per-ray record: these return a [bool] or
    nothing, and allocate nothing. *)

val roots : Kind.t -> Scratch.t -> float array -> int -> bool
(** [roots k s g o] is [true] iff the ray in [s] meets the shape of kind
    [k] stored at offset [o] of [g]; its roots are then in [s.near] and
    [s.far] (nearer first), as the kind's module computes them.
    @raise Invalid_argument for a sphere, a triangle, a CSG solid or an instance. *)

val normal : Kind.t -> Scratch.t -> float array -> int -> unit
(** [normal k s g o] sets [s.nx], [s.ny], [s.nz] to the unit normal of
    the shape of kind [k] stored at offset [o] of [g] at the hit point
    [s.px], [s.py], [s.pz] of the ray in [s] whose root is [s.near]
    (a box's face is the one that root crosses). The side is the
    module's (outward for a closed shape): callers turn it.
    @raise Invalid_argument for a sphere, a triangle, a CSG solid or an instance. *)
