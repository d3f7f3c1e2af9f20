(** Progressive rendering: a coarse picture at once, refined to the full
    image, in steps small enough to keep a window responsive.

    The passes trace blocks of {!coarsest}, 8 and 4 pixels, then single
    pixels: pass [s] traces the pixels whose column and row are multiples
    of [s], skipping those that an earlier pass traced; after it, the
    [s x s] block below and to the right of each such pixel can be shown in
    its colour. Every pixel is traced once, as {!Raytrace.Private.Trace.pixel} traces it, so
    the image after these passes is {!Raytrace.Render.image}'s byte for byte. With
    antialiasing ([samples > 1]) one more pass traces every pixel with
    {!Raytrace.Private.Antialias.store}: the final image is then {!Raytrace.Private.Antialias.image}'s.

    One {!step} traces one band of the current pass: [s] image rows of a
    coarse pass, or as many rows as asked of a full-resolution pass. Given
    {!workers} (worker processes of [Raytrace_unix.Progressive_workers]),
    the full-resolution rows of a step are traced by them, interleaved;
    the image is the same whatever their number. This module itself
    starts no process. *)

type t
(** The type for renders in progress. *)

val coarsest : int
(** [coarsest] is [16]: the block size of the first pass, in pixels. *)

type workers = {
  jobs : int;  (** The most workers a step uses. *)
  image : Image.t;
      (** The image the workers write into (memory shared with them). *)
  run : int -> (int -> int array) -> (int array array, [ `Msg of string ]) result;
      (** [run n work] runs [work w] for each [w] in [\[0, n)], each in a
          worker, and is their results in order, or [Error] if a worker
          failed. A result is the work counters of that worker. *)
  budget : Render_work.counters;
      (** Memory shared with the workers, {!Raytrace.Private.Render_work.counter_fields}
          per worker: their share of the work budget
          ({!Raytrace.Private.Render_work.refill}). *)
}
(** The type for workers that trace rows of full-resolution passes. One
    value serves frame after frame of the same size. *)

val create : ?limits:Raytrace.Limits.t -> ?samples:int -> ?workers:workers -> Scene.valid -> t
(** [create ~limits ~samples ~workers scene] is the render of [scene] about to
    start, with [samples x samples] samples per pixel in its last pass
    (default 1). With [workers], the image is [workers.image]
    (overwritten; a render started later with the same [workers]
    overwrites it again) and the full-resolution passes are traced by
    them. The work it may do is the [`Work] bound of [limits] (default
    {!Raytrace.Limits.default}; see {!stopped}).
    @raise Invalid_argument if [samples < 1], or [workers.image] is not of
    the canvas size. *)

type band = {
  size : int;  (** Block size of the pass: 16, 8, 4 or 1. *)
  top : int;  (** First image row of the band, a multiple of [size]. *)
  rows : int;  (** Image rows in the band: see {!step}. *)
}
(** The type for the part of the image that one step updated: rows [top]
    to [top + rows - 1]. For [size = 1], every pixel of these rows is
    traced; for a coarse band, row [top] is traced at every column that is
    a multiple of [size], and the [size x size] block starting there may be
    shown in that pixel's colour. *)

val step : ?rows:int -> t -> band option
(** [step ~rows r] traces the next band and is [Some band], or is [None]
    (and does nothing) when the image is complete. A band of a
    full-resolution pass has [rows] rows (default 1), or fewer at the
    bottom; a coarse band has its block size. If a worker fails (or no
    worker can be started), the band is traced again in this process, as
    are all later ones ({!failure}). A band that {!advance} paused is
    finished first, with its own rows.
    @raise Invalid_argument if [rows < 1]. *)

type poll =
  | Between_pixels  (** A pixel was just traced: pausing here loses nothing. *)
  | Inside_pixel  (** A pixel is being traced: pausing here traces it again later. *)
(** The type for where {!advance} asks the front end whether to pause. *)

type outcome =
  | Band of band  (** The band traced, as {!step}'s. *)
  | Paused  (** The front end asked for its thread back: the band is unfinished. *)
  | Done  (** The image is complete; nothing was done. *)
(** The type for the outcomes of {!advance}. *)

val advance : ?rows:int -> ?poll:(poll -> bool) -> t -> outcome
(** [advance ~rows ~poll r] is {!step}, but calls [poll] every few
    milliseconds of tracing (every {!poll_tests} tests, counted as they
    are done), between pixels and inside them (at each hit of a ray tree,
    where one pixel of a deep glass scene can take seconds), and is
    [Paused] as soon as it says [true]. The next call goes on from where
    this one paused (the pixel it was inside is traced again, from the
    start, so the image is the same), with [rows] as the band was begun.
    Bands traced by workers are not polled: a front end that must answer
    gives a single row when rows are slow.
    @raise Invalid_argument if [rows < 1]. *)

val poll_tests : int
(** [poll_tests] is the intersection tests between two calls of
    {!advance}'s [poll]: [65536] (docs/window.md, docs/web.md). *)

val failure : t -> string option
(** [failure r] is why the workers of [r] stopped being used, if they
    did: the first worker failure (the message of [run]'s [Error]). *)

val stopped : t -> string option
(** [stopped r] is why [r] ended before its last pass, if it did: the
    message of {!Raytrace.Limits.work_exceeded} once the tests counted by [r]'s
    tracer (and its workers) pass {!Raytrace.Limits.work_budget}, checked after each
    pixel (and at each hit of a ray tree). [r] is then {!finished}; its image is incomplete. With workers,
    each may do a band's share beyond the budget before the count is
    summed. *)

val finished : t -> bool
(** [finished r] is [true] iff the image is complete. *)

val image : t -> Image.t
(** [image r] is the image being rendered: complete once {!finished};
    before, only the pixels traced so far are set (the others are black). *)

val samples : t -> int
(** [samples r] is the side of the sample grid of the last pass. *)

val tracer : t -> Trace.t
(** [tracer r] is the tracer of [r], whose {!Raytrace.Private.Trace.val-counters} count the
    work done so far. *)
