(** Rays per pixel: supersampling, adaptive supersampling and CGFS's
    subsampling, the knobs that trade run time for error (with the
    recursion depth of {!Scene.t}).

    - {e Supersampling} with [samples = n] traces the [n x n] regular grid
      of {!Raytrace.Private.Trace.sample} in every pixel and averages it; deterministic.
      Each sample is clamped to [\[0, 255\]] before the average and the mean
      is rounded once ({!Raytrace.Private.Trace.accumulate} says why). [n = 1] is exactly
      the document's image.
    - {e Adaptive} supersampling with threshold [th] and an odd [n] first
      traces one ray per pixel, through its centre, then traces the rest
      of the [n x n] grid only in pixels whose first ray hit another
      sphere than, or whose bytes differ by more than [th] in some channel
      from, those of a pixel above, below, left or right (CGFS's
      suggestion; POV-Ray's adaptive method 1 is the peer). The grid of an
      odd [n] has the centre as its middle sample, so a refined pixel
      reuses its first ray and is exactly the pixel of full supersampling,
      and an unrefined one is exactly the document's pixel: adaptive
      sampling never traces more rays than full supersampling. (An even
      [n] has no centre sample: the first ray would be wasted or taken off
      centre, which measurably raises the error; it is refused.)
    - {e Subsampling} (CGFS, "Performance Optimizations") traces one ray
      per pixel but skips the search for the primary ray's sphere where
      the two neighbours on either side (left and right on even rows, above
      and below on odd rows) hit the same sphere, and assumes it hits that
      one ({!Raytrace.Private.Trace.pixel_assuming}). Approximate, opt-in, measured by the
      benchmark.

    Every mode gives the same image whatever the number of processes: a
    plan runs in passes, and a pass reads only what earlier passes wrote.

    @canonical Raytrace.Render.Sampling *)

(** {1:settings Settings} *)

type t = private {
  samples : int;  (** [n]: at most [n x n] rays per pixel, [1 <= n <= max_samples]. *)
  adaptive : int option;  (** Adaptive threshold, in [\[0, 255\]] (then [samples] is odd, [>= 3]), or full sampling. *)
  subsample : bool;  (** CGFS's subsampling (then [samples = 1], not adaptive). *)
}
(** The type for sampling settings.

    @canonical Raytrace.Render.Sampling.t *)

val max_samples : int
(** [max_samples] is [64]: the largest grid side, 4096 rays per pixel. *)

val v : ?samples:int -> ?adaptive:int -> ?subsample:bool -> unit -> (t, [> `Msg of string ]) result
(** [v ~samples ~adaptive ~subsample ()] is the settings, or [Error] with a
    one-line message if [samples] (default 1) is outside
    [\[1, max_samples\]], [adaptive] is outside [\[0, 255\]] or given with
    an even [samples] or [samples = 1], or [subsample] (default [false]) is
    combined with [samples > 1]. *)

val one : t
(** [one] is one ray per pixel through its centre: the document's image. *)

val is_one : t -> bool
(** [is_one s] is [true] iff [s] is {!one}. *)

val averaging : t -> bool
(** [averaging s] is [true] iff [s] averages samples, so that tracers must
    be created with [Trace.create ~averaging:true]. *)

val to_string : t -> string
(** [to_string s] is a short description, e.g. ["1x1"], ["4x4"],
    ["adaptive 5x5 t=8"], ["subsampled"]. *)

type plan
(** The type for the work of rendering one image with some settings: its
    passes, and the buffers through which they pass results on.

    @canonical Raytrace.Render.Sampling.plan *)

(**/**)

(* Internal: the kernel's side of this module, for the tracer and the tests, hidden from the documentation. Not for users: it changes without notice. *)

(** {1:plans Plans} *)

type memory = {
  bytes : int -> Image.buffer;  (** [bytes n] is [n] bytes. *)
  floats : int -> Trace.samples;  (** [floats n] is [n] floats. *)
  ints : int -> (int64, Bigarray.int64_elt, Bigarray.c_layout) Bigarray.Array1.t;  (** [ints n] is [n] integers. *)
  at_row : unit -> unit;  (** Called before each row: a worker may stop there. *)
}
(** The type for where a plan keeps the buffers that carry results from
    pass to pass: process memory ([local]) or memory shared with worker
    processes (the system library [raytrace.unix]). *)

val local : memory
(** [local] allocates in this process; its [at_row] does nothing. *)

val plan : ?memory:memory -> t -> Image.t -> canvas:int * int -> at:int * int -> plan
(** [plan ~memory s img ~canvas:(cw, ch) ~at:(x, y)] is the work of
    rendering with [s] the rectangle of a [cw x ch] canvas whose top-left
    pixel is [(x, y)] (image coordinates) into [img], of the rectangle's
    size: byte for byte those pixels of the whole image. Adaptive sampling
    and subsampling also trace the first rays of a one-pixel margin around
    the rectangle, so that they decide as the whole image does. The
    buffers that carry results from pass to pass come from [memory]
    (default [local]): with memory shared with forked processes, passes
    may run in workers.
    @raise Invalid_argument if the rectangle is not inside the canvas.
    @raise Failure or [Out_of_memory] if [memory] does. *)

val passes : plan -> int
(** [passes pl] is the number of passes of [pl]: 1 for {!one} and full
    supersampling, 2 for adaptive sampling and subsampling. Pass [i + 1]
    may start only when pass [i] has finished on every row. *)

val pass_rows : plan -> int -> int
(** [pass_rows pl i] is the number of rows that pass [i] of [pl] works on:
    [rows pl i tr ~first:r ~step:(pass_rows pl i)] runs row [r] alone, for
    [r] in [\[0, pass_rows pl i - 1\]].
    @raise Invalid_argument if [i] is not a pass. *)

val rows : plan -> int -> Trace.t -> first:int -> step:int -> unit
(** [rows pl i tr ~first ~step] runs pass [i] of [pl] on rows [first],
    [first + step], ... of the rows that pass works on (the rectangle's, or
    the margin's, all of them or every other one), with tracer [tr], whose
    scene must have the canvas size of [pl] and whose {!Raytrace.Private.Trace.averaging}
    must be {!averaging}. After each row it checks [tr]'s work budget
    ({!Raytrace.Private.Trace.check_budget}).
    @raise Invalid_argument if [i] is not a pass, [step < 1], or the
    canvas sizes or the averaging disagree.
    @raise Limits.Work_exceeded when [tr] passes its budget. *)
