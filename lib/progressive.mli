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

    One {!step} traces one band of the current pass: [s] image rows. *)

type t
(** The type for renders in progress. *)

val coarsest : int
(** [coarsest] is [16]: the block size of the first pass, in pixels. *)

val create : ?samples:int -> Scene.t -> t
(** [create ~samples scene] is the render of [scene] about to start, with
    [samples x samples] samples per pixel in its last pass (default 1).
    @raise Invalid_argument if [scene] fails {!Scene.validate} or
    [samples < 1]. *)

type band = {
  size : int;  (** Block size of the pass: 16, 8, 4 or 1. *)
  top : int;  (** First image row of the band, a multiple of [size]. *)
  rows : int;  (** Image rows in the band: [size], or fewer at the bottom. *)
}
(** The type for the part of the image that one step updated: rows [top]
    to [top + rows - 1]; in each, every block of [size] columns starting at
    a multiple of [size] may be shown in the colour of its first pixel in
    row [top]. *)

val step : t -> band option
(** [step r] traces the next band and is [Some band], or is [None] (and
    does nothing) when the image is complete. *)

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
