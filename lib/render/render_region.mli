(** {!Render.region_image} with one more argument, for the system
    libraries of this project: a way to build a part of a big hierarchy on
    another core, a kernel type that the public {!Render} does not show. *)

val region_image :
  ?limits:Limits.t ->
  ?clock:(unit -> float) ->
  ?skips:bool ->
  ?beside:Bvh.beside ->
  ?samples:int ->
  ?adaptive:int ->
  ?subsample:bool ->
  ?progress:(rows:int -> total:int -> rays:int -> unit) ->
  Scene.valid ->
  Region.t ->
  (Image.t * Stats.t, [> `Msg of string ]) result
(** [region_image ~beside ...] is {!Render.region_image} with the same
    arguments, whose scene is prepared by {!Prepared.prepare} with
    [beside] (if given), which builds a part of a big hierarchy elsewhere:
    the image is the same bytes with it or without it. *)
