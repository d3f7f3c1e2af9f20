(** Random scenes placed on the kernel's boundaries, for the properties
    that hold the fast tracer to {!Raytrace.Literal}.

    Every object kind (sphere, plane, triangle, box, closed and open
    meshes, CSG solids of every operation on any operands, glass and
    checkers) on every side of every light: a point light's objects in
    front of it, beyond it and around it, a directional light's where it
    comes from and on the other side. Surfaces that touch or coincide
    (a box on the floor, boxes sharing a face, the same box twice in two
    materials, tangent spheres, a triangle in the floor's plane, CSG
    operands that touch). The camera inside solids and glass. Pixel rays
    exactly through the edges and vertices of triangles, boxes, meshes
    and CSG solids, and planes that hold a row of rays: the deciding
    coordinates are dyadic, so that the boundary is met exactly in
    floats. Every scene gives an epsilon (the document's mode, where the
    fast tracer must give the oracle's bytes); canvases are 3 to 16
    pixels a side, mostly 8 or 16, and only those of 8 or 16 have
    grazing objects (elsewhere their coordinates would be rounded). *)

val gen : Raytrace.Scene.t QCheck.Gen.t
(** [gen] generates such scenes with every kind of object. *)

val spheres : Raytrace.Scene.t QCheck.Gen.t
(** [spheres] generates such scenes of spheres alone, with no glass nor
    pattern: the kernel's loops for spheres (the textbook loop, the tile
    culling, and the hierarchy beyond {!Raytrace.Private.Prepared.bvh_threshold}
    spheres). *)

val flat : Raytrace.Scene.t QCheck.Gen.t
(** [flat] generates such scenes of planes, triangles, boxes and meshes
    alone (no sphere nor CSG solid, whose exact hits {!Exact_hits} does
    not compute), with no glass (whose invisible surfaces a camera ray
    crosses) nor pattern, on canvases of 8 or 16 pixels a side, where
    every grazing boundary is exact. *)

val print : Raytrace.Scene.t -> string
(** [print s] is [s] in the scene-file syntax, followed by the OBJ text
    of each of its meshes as a comment headed by its file name (write
    them beside the scene to read it back). *)

val arbitrary : Raytrace.Scene.t QCheck.arbitrary
(** [arbitrary] is {!gen} with {!print} and {!Gen_scene.shrink}. *)

val arbitrary_spheres : Raytrace.Scene.t QCheck.arbitrary
(** [arbitrary_spheres] is {!spheres} with {!print} and {!Gen_scene.shrink}. *)

val arbitrary_flat : Raytrace.Scene.t QCheck.arbitrary
(** [arbitrary_flat] is {!flat} with {!print} and {!Gen_scene.shrink}. *)
