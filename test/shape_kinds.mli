(** The described kinds of issue 26 ({!Raytrace.Private.Cylinder},
    {!Raytrace.Private.Disk}, {!Raytrace.Private.Cone},
    {!Raytrace.Private.Torus}) seen through their descriptions, for the
    tests that move every object of a scene. *)

val map_primitive :
  point:(Raytrace.Vec3.t -> Raytrace.Vec3.t) ->
  length:(float -> float) ->
  material:(Raytrace.Material.t -> Raytrace.Material.t) ->
  Raytrace.Private.Shape_desc.primitive ->
  Raytrace.Private.Shape_desc.primitive
(** [map_primitive ~point ~length ~material p] is the described shape [p]
    with its points mapped by [point] (a scaling and a translation), its
    radii by [length] and its material by [material]; a disk's normal and
    a torus's axis are kept. Raises [Invalid_argument] for another kind. *)
