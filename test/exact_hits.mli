(** Where a ray first meets a plane, a triangle, a box or a mesh, in exact
    rational arithmetic (Zarith) on the given floats, written from the
    definitions and sharing no code with the kernel: the true answer that
    the kernel's rounded one is held to on the scenes whose boundaries
    are exact ({!Gen_placed.flat}).

    The conventions are the kernel's documented ones: a triangle and a
    box are closed sets (a ray through an edge or a vertex, or touching a
    box's edge, meets them there); a ray parallel to a plane, or to a
    triangle's plane, meets neither, even lying in it; a box met by a ray
    that lies in a face's plane is met where the other axes let it in. *)

val roots : Raytrace.Scene.t -> (origin:Raytrace.Vec3.t -> direction:Raytrace.Vec3.t -> t_min:Q.t -> Q.t option) array
(** [roots s] is, for each object of [s] in the order of
    {!Raytrace.Private.Trace.hit_object} (the shapes in scene order, a mesh
    one object per triangle that is not degenerate), the function that
    gives the nearest [t > t_min] at which the ray [origin + t direction]
    meets it, if any. (A line that misses, in floats, the object's
    bounding box grown by a millionth of its coordinates is not tried in
    exact arithmetic: it misses.)
    @raise Invalid_argument if [s] has spheres or CSG solids. *)

val neighbours : Raytrace.Scene.t -> int -> int -> bool
(** [neighbours s i j] is whether objects [i] and [j] of {!roots}' order
    are two triangles of one mesh, flat (no [vn]), that share an edge (two
    corners with the same coordinates) and lie in one plane (exactly): a
    ray within rounding of that edge may be given to either by a
    watertight test, with the same point, plane, normal and material. *)
