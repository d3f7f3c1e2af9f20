(** Progressive rendering: a coarse picture at once, refined to the full
    image, in steps small enough to keep a window responsive.

    The passes trace blocks of {!coarsest}, 8 and 4 pixels, then single
    pixels: pass [s] traces the pixels whose column and row are multiples
    of [s], skipping those that an earlier pass traced; after it, the
    [s x s] block below and to the right of each such pixel can be shown in
    its colour. Every pixel is traced once, as {!Trace.pixel} traces it, so
    the image after these passes is {!Render.image}'s byte for byte. With
    antialiasing ([samples > 1]) one more pass traces every pixel with
    {!Antialias.store}: the final image is then {!Antialias.image}'s.

    One {!step} traces one band of the current pass: [s] image rows of a
    coarse pass, or as many rows as asked of a full-resolution pass. Given
    {!shared} memory, the full-resolution rows of a step are traced by
    worker processes ({!Parallel.run}), interleaved; the image is the same
    whatever their number. *)

type t
(** The type for renders in progress. *)

val coarsest : int
(** [coarsest] is [16]: the block size of the first pass, in pixels. *)

type shared
(** The type for memory shared with worker processes: an image and their
    work counters. One value serves frame after frame of the same size. *)

val shared : jobs:int -> width:int -> height:int -> shared
(** [shared ~jobs ~width ~height] is memory for [jobs] workers rendering
    [width x height] images.
    @raise Invalid_argument if [jobs < 2].
    @raise Failure or [Unix.Unix_error] if no shared memory can be mapped. *)

val create : ?samples:int -> ?shared:shared -> Scene.t -> t
(** [create ~samples ~shared scene] is the render of [scene] about to
    start, with [samples x samples] samples per pixel in its last pass
    (default 1). With [shared], the image is [shared]'s (overwritten; a
    render started later with the same [shared] overwrites it again) and
    the full-resolution passes are traced by its workers.
    @raise Invalid_argument if [scene] fails {!Scene.validate},
    [samples < 1], or [shared] is not of the canvas size. *)

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
    are all later ones ({!failure}).
    @raise Invalid_argument if [rows < 1]. *)

val failure : t -> string option
(** [failure r] is why the workers of [r] stopped being used, if they
    did: the first worker failure ({!Parallel.run}'s message). *)

val finished : t -> bool
(** [finished r] is [true] iff the image is complete. *)

val image : t -> Image.t
(** [image r] is the image being rendered: complete once {!finished};
    before, only the pixels traced so far are set (the others are black). *)

val samples : t -> int
(** [samples r] is the side of the sample grid of the last pass. *)

val tracer : t -> Trace.t
(** [tracer r] is the tracer of [r], whose {!Trace.counters} count the
    work done so far. *)
