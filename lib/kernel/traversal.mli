(** Traversal: the closest hit and the shadow blockers of the ray in the
    per-ray record, over every object in scene order or through the
    bounding volume hierarchy ({!Bvh}; the planes, unbounded, are tested
    before each walk), with the roots of each kind of object.

    Two ways to intersect a sphere. The document's mode (the scene gives
    an epsilon) uses the textbook quadratic of section 6.1 in CGFS's order
    of operations, so that it reproduces the document's images byte for
    byte. The robust mode uses cancellation-free roots ({!Sphere.roots}'s
    arithmetic) and needs no epsilon: a secondary ray cannot hit the
    sphere it leaves except at that sphere's other root, and only if it
    goes into the sphere by more than the rounding of [<f, D>] can
    explain.

    Ties between equal roots go to the object earlier in the scene, as
    the document's loop keeps the first: the hierarchy, which visits
    objects in another order, gives the same answer. Each traversal is
    specialised once per kind of ray and of scene (spheres alone,
    triangles alone, any objects; camera or secondary rays), inside this
    module: the copy for spheres alone reads no object's kind. *)

val closest : Tracer.t -> int
(** [closest tr] is the slot of the closest object hit by the ray in [s]
    with [t_min < t < t_max], or [-1]; its [t] is left in [s.t]
    ([infinity] if none), its slot in [tr.hit]. *)

val closest_in : Tracer.t -> spheres:bool -> int
(** [closest_in tr ~spheres] is {!closest} where the caller knows whether
    the scene has spheres alone ([spheres], {!Prepared.t}'s
    [all_spheres]). *)

val primary_hit_spheres : Tracer.t -> int
(** [primary_hit_spheres tr] is {!closest} for a camera ray of a scene of
    spheres alone, from the camera's per-frame constants; with
    [tr.assumed] naming an object (CGFS's subsampling), that object is
    tested first and alone, the full search made only if it is missed (an
    object in front of it is then not seen); with [-1], no object. *)

val primary_hit_objects : Tracer.t -> int
(** [primary_hit_objects tr] is {!primary_hit_spheres} for any scene. *)

val shadowed : Tracer.t -> int -> bool
(** [shadowed tr l] is [true] iff some object blocks the shadow ray in [s]
    toward light [l] (section 7.7). With the skips it stops at the first
    blocker and tries light [l]'s last blocker first; without, it searches
    the closest hit as the document does. The same answer: [blocks] has
    [closest]'s roots. *)

val instance_number : Tracer.t -> int -> int
(** [instance_number tr i] is the number, in [tr.p.instances], of the
    instance in slot [i]. *)

val instance_hit : Tracer.t -> int -> Tracer.t
(** [instance_hit tr i] is the tracer of the bottom level of the instance
    in slot [i], its per-ray record holding the ray of [tr.s] carried into
    the instance's frame and the closest hit there ([hit], and [t] in its
    record): the hit that {!closest} found in that instance, as the search
    remembered it ([tr.inner_slot], [tr.inner_hit]) when slot [i] was the
    last instance to find one, or found again by the same search bounded
    by the hit kept. To be called after the closest search that kept slot
    [i] and before any other search of [tr]. *)

val roots : Tracer.t -> int -> Vec3.t -> Vec3.t -> float * float
(** [roots tr k o d] is {!Trace.roots}. *)
