(** Rendering (document section 8): every pixel of the canvas, traced.

    [Render] walks the pixels, asks {!Trace} for each one's colour and
    stores it in an {!Image.t}, in one process or several. The image is the
    same, byte for byte, whatever the number of jobs: each pixel is traced
    alone, by the same code. *)

val image :
  ?jobs:int ->
  ?skips:bool ->
  ?samples:int ->
  ?adaptive:int ->
  ?subsample:bool ->
  ?progress:(rows:int -> total:int -> rays:int -> unit) ->
  Scene.t ->
  (Image.t * Stats.t, [> `Msg of string ]) result
(** [image ~jobs ~skips ~samples ~adaptive ~subsample ~progress scene] is the image
    of [scene] and what it cost. [jobs] (default 1) processes trace
    interleaved rows; [skips] is passed to {!Prepared.prepare};
    [samples] (default 1: the document's image), [adaptive] and
    [subsample] are the rays per pixel of {!Sampling.v}. The image is the
    same for every [jobs], and with or without [skips].

    [progress ~rows ~total ~rays], if given, is called as the render goes:
    [rows] of the [total] rows of work (the rows of every pass of
    {!Sampling.passes}: [total] is the image height or more) are finished
    and [rays] were cast so far. With one job it is called after each row;
    with several, about ten times a second by the parent process (the
    workers count their rows in shared memory). [rows] never decreases, and
    the last call has [rows = total]. What [progress] allocates is not
    counted in the statistics' [minor_words]; it must not raise.

    [Error], before
    anything is allocated, if the rays per pixel exceed
    {!Limits.check_samples}, the render needs more work than
    {!Scene.check_work} allows, or the image more memory than the system
    has available; [Error] if no memory can be had for the image, or if a
    worker process dies.
    @raise Invalid_argument if [scene] fails {!Scene.validate},
    [jobs < 1], or {!Sampling.v} refuses the sampling settings. *)

val region_image :
  ?jobs:int ->
  ?skips:bool ->
  ?samples:int ->
  ?adaptive:int ->
  ?subsample:bool ->
  ?progress:(rows:int -> total:int -> rays:int -> unit) ->
  Scene.t ->
  Region.t ->
  (Image.t * Stats.t, [> `Msg of string ]) result
(** [region_image ~jobs ~skips ~samples ~adaptive ~subsample ~progress scene r] is
    the image of the region [r] of [scene]'s canvas, [r.w x r.h] pixels,
    and what it cost: byte for byte the pixels of {!image} there, for every
    sampling (adaptive sampling and subsampling trace the first rays of a
    one-pixel margin around [r] too, to decide as the whole image does).
    The arguments are as for {!image}.
    @raise Invalid_argument if [scene] fails {!Scene.validate}, [jobs < 1],
    [r] is not inside the canvas, or {!Sampling.v} refuses the sampling
    settings. *)

val image_exn :
  ?jobs:int -> ?skips:bool -> ?samples:int -> ?adaptive:int -> ?subsample:bool -> Scene.t -> Image.t
(** [image_exn] is the image of {!image}.
    @raise Failure with the message of {!image}'s [Error]. *)
