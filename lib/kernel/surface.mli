(** The surface at a hit: the normal, the view vector and the material
    of the point where the ray in the per-ray record meets the object the
    traversal found, and the mirror ray from there. With {!Traversal}'s
    [test] and [blocks], the kernel's dispatch on an object's {!Kind.t}:
    an exhaustive [match], so that a new kind makes the compiler name it
    here. *)

val sphere_hit : Tracer.t -> int -> unit
(** [sphere_hit tr i] sets, for the hit point [s.px..] on the sphere in
    slot [i] and the ray direction [s.dx..], its outward unit normal
    [s.nx..] and the view vector [s.vx..] ([-D]), and marks [i] as the
    sphere the next secondary rays leave ([tr.origin_sphere]): in the
    robust mode they handle it exactly, with no offset. *)

val shape_hit : Tracer.t -> int -> int
(** [shape_hit tr i] is the material number of the hit point [s.px..] on
    the object in slot [i] (not a sphere: {!sphere_hit}), for the ray in
    [s] (a CSG solid's is the material of the leaf hit). It sets the
    normal [s.nx..] turned toward the ray (planes and triangles are seen
    from both sides; a box or a solid from inside shows the inner side),
    a smooth triangle's interpolated normal on the side the ray sees, and
    the view vector [s.vx..]. In the robust mode it then moves [s.px..]
    off the surface toward the ray by a bound on its rounding error
    ([32 u] times the magnitudes of origin, point and extent), so that
    shadow and mirror rays leaving from there meet this surface, or any
    surface through the point, only at negative roots, with no constant
    tied to the scene's scale (Ray Tracing Gems, chapter 6).
    @raise Invalid_argument on a sphere's slot. *)

val local_material : Tracer.t -> int -> int -> int
(** [local_material tr i m] is the material whose colour the hit at [s.t]
    on the object in slot [i], of material [m], shows: [m], or the
    material of its pattern's second colour in the cells that show it
    ({!Pattern.odd}, at the hit point before the robust mode moved it).
    A textured [m] is [m], its colour at the hit written to [tr.red],
    [tr.green] and [tr.blue] ({!Texturing.colour}; on an instance, by
    {!shape_hit}, which looked it up in the object's frame). Out of line: its code
    would make the loops too big to inline where they are called. *)

val mirror_ray : Prepared.t -> Scratch.t -> unit
(** [mirror_ray p s] sets the mirror ray [R = 2 <V, N> N - V] from the hit
    point [s.px..], with the range [(epsilon, inf)]. *)
