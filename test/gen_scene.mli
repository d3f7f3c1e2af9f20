(** Random valid scenes, for properties. *)

val gen : Raytrace.Scene.t QCheck.Gen.t
(** [gen] generates scenes that satisfy {!Raytrace.Scene.validate}: small
    canvases (so that rendering them is quick), 0 to 6 spheres in front of
    the camera, none or 1 to 4 planes, triangles and boxes, 0 to 4 lights of every kind, random materials including the
    edge values (matte, specular 0, reflective 0 and 1), glass on one
    object in three (transparency up to [1 - reflective], its edge value
    included, index 1, 1.5 or in [\[0.5, 2.5\]], Fresnel or not), with or without
    epsilon, with or without a camera path of 1 to 4 keys. *)

val crowd : Raytrace.Scene.t QCheck.Gen.t
(** [crowd] generates scenes of 9 to 80 spheres, more than
    {!Raytrace.Prepared.bvh_threshold}, so that the tracer uses its
    hierarchy: clustered, overlapping, nested and duplicated spheres, often
    a huge ground sphere, sometimes spheres around the camera; often
    triangles and boxes among them, sometimes duplicated. *)

val material : Raytrace.Material.t QCheck.Gen.t
(** [material] generates the materials of {!gen}'s shapes: any colour,
    matte, specular 0 or up to 1000, reflective 0, 1 or between, and glass
    one time in three. *)

val shrink : Raytrace.Scene.t QCheck.Shrink.t
(** [shrink s] is the scenes of [s] with fewer spheres, shapes or lights. *)

val arbitrary : Raytrace.Scene.t QCheck.arbitrary
(** [arbitrary] is {!gen} with a printer (the scene file) and shrinking of
    the sphere and light lists. *)

val with_patterns : Random.State.t -> Raytrace.Scene.t -> Raytrace.Scene.t
(** [with_patterns rand s] is [s] with a checker of a random colour and
    size (0.05 to 2.05) on about half of its spheres, planes, triangles
    and boxes, drawn from [rand]. *)

val with_textures : Random.State.t -> Raytrace.Scene.t -> Raytrace.Scene.t
(** [with_textures rand s] is [s] with a random image (1 to 5 pixels a
    side) on about half of its spheres, planes and boxes that have no
    pattern, by the mapping of each kind, a plane's copies 0.05 to 2.05
    wide, drawn from [rand]. *)
