(** Rendering in several processes: {!Raytrace.Render} with [jobs] worker
    processes that trace interleaved rows into shared memory
    ({!Parallel}). The image is the same, byte for byte, whatever the
    number of jobs: each pixel is traced alone, by the same code. *)

val image :
  ?limits:Limits.t ->
  ?jobs:int ->
  ?skips:bool ->
  ?samples:int ->
  ?adaptive:int ->
  ?subsample:bool ->
  ?progress:(rows:int -> total:int -> rays:int -> unit) ->
  Scene.valid ->
  (Image.t * Stats.t, [> `Msg of string ]) result
(** [image ~limits ~jobs ~skips ~samples ~adaptive ~subsample ~progress scene] is
    {!Raytrace.Render.image} traced by [jobs] processes (default 1: this one), timed
    by the wall clock. With several jobs, [progress] is called about ten
    times a second by this process (the workers count their rows in shared
    memory), with the meaning it has for {!Raytrace.Render.image}. Besides {!Raytrace.Render.image}'s errors, [Error] before
    anything is allocated if the image needs more memory than the system
    has available, and [Error] if no shared memory can be had or a worker
    process dies.
    @raise Invalid_argument if [jobs < 1]. *)

val region_image :
  ?limits:Limits.t ->
  ?jobs:int ->
  ?skips:bool ->
  ?samples:int ->
  ?adaptive:int ->
  ?subsample:bool ->
  ?progress:(rows:int -> total:int -> rays:int -> unit) ->
  Scene.valid ->
  Region.t ->
  (Image.t * Stats.t, [> `Msg of string ]) result
(** [region_image ~limits ~jobs ~skips ~samples ~adaptive ~subsample ~progress scene r]
    is {!Raytrace.Render.region_image} traced by [jobs] processes, with the errors
    of {!image}.
    @raise Invalid_argument if [jobs < 1] or [r] is not inside the
    canvas. *)
