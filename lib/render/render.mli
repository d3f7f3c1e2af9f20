(** Rendering (document section 8): every pixel of the canvas, traced.

    [Render] walks the pixels, asks the tracer for each one's colour and
    stores it in an {!Image.t}, in this process. The system library
    [raytrace.unix] renders the same image, byte for byte, in several
    processes ([Raytrace_unix.Render_jobs]): each pixel is traced alone, by
    the same code. *)

val image :
  ?limits:Limits.t ->
  ?clock:(unit -> float) ->
  ?skips:bool ->
  ?samples:int ->
  ?adaptive:int ->
  ?subsample:bool ->
  ?progress:(rows:int -> total:int -> rays:int -> unit) ->
  Scene.valid ->
  (Image.t * Stats.t, [> `Msg of string ]) result
(** [image ~limits ~clock ~skips ~samples ~adaptive ~subsample ~progress scene] is
    the image of [scene] and what it cost. [skips] (default [true]) enables
    the exact skips of the fast tracer (the image is the same without
    them); [samples] (default 1: the document's image), [adaptive] and
    [subsample] are the rays per pixel of {!Sampling.v}; [clock] (default
    [Sys.time]) times the statistics. [Error], before anything is
    allocated, if {!Sampling.v} refuses the sampling settings or they are
    adaptive with an even [samples] and the camera has no lens
    ({!Sampling.even_message}), or the rays
    per pixel or the work of the render exceed [limits] (default
    {!Limits.default}; {!Scene.check_work}); [Error] if no memory can be
    had for the image.

    [progress ~rows ~total ~rays], if given, is called after each row:
    [rows] of the [total] rows of work (the rows of every pass of
    the sampling, one or two: [total] is the image height or more) are finished
    and [rays] were cast so far. [rows] never decreases, and the last call
    has [rows = total]. What [progress] allocates is not counted in the
    statistics' [minor_words]; it must not raise. *)

val region_image :
  ?limits:Limits.t ->
  ?clock:(unit -> float) ->
  ?skips:bool ->
  ?samples:int ->
  ?adaptive:int ->
  ?subsample:bool ->
  ?progress:(rows:int -> total:int -> rays:int -> unit) ->
  Scene.valid ->
  Region.t ->
  (Image.t * Stats.t, [> `Msg of string ]) result
(** [region_image ~limits ~clock ~skips ~samples ~adaptive ~subsample ~progress scene r]
    is the image of the region [r] of [scene]'s canvas, [r.w x r.h]
    pixels, and what it cost: byte for byte the pixels of {!image} there,
    for every sampling (adaptive sampling and subsampling trace the first
    rays of a one-pixel margin around [r] too, to decide as the whole image
    does). The arguments and errors are as for {!image}.
    @raise Invalid_argument if [r] is not inside the canvas (make regions
    with {!Region.tile} or {!Region.of_corners}, which check). *)
