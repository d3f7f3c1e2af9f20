(** The rows of a sampled image: the plans by which the renderers trace
    an image or a region with some {!Raytrace.Render.Sampling.t}, pass by pass and row by
    row, in this process or in workers that share its buffers.

    {b Internal}: the kernel's side of {!Raytrace.Render.Sampling}, for the renderers of
    this project ([Render], [raytrace.unix]) and their tests. It changes
    without notice.

    @canonical Raytrace.Private.Sampling_rows *)

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

type plan
(** The type for the work of rendering one image with some settings: its
    passes, and the buffers through which they pass results on.

    @canonical Raytrace.Private.Sampling_rows.plan *)

val plan : ?memory:memory -> Sampling.t -> Image.t -> canvas:int * int -> at:int * int -> plan
(** [plan ~memory s img ~canvas:(cw, ch) ~at:(x, y)] is the work of
    rendering with [s] the rectangle of a [cw x ch] canvas whose top-left
    pixel is [(x, y)] (image coordinates) into [img], of the rectangle's
    size: byte for byte those pixels of the whole image. Adaptive sampling
    and subsampling also trace the first rays of a margin around the
    rectangle, so that they decide as the whole image does: one pixel wide,
    or under a lens 4 (the reach of a circle of confusion, see
    {!Raytrace.Render.Sampling}), whose room adaptive plans always keep. The
    buffers that carry results from pass to pass come from [memory]
    (default [local]): with memory shared with forked processes, passes
    may run in workers.
    @raise Invalid_argument if the rectangle is not inside the canvas.
    @raise Failure or [Out_of_memory] if [memory] does. *)

val passes : plan -> int
(** [passes pl] is the number of passes of [pl]: 1 for {!Raytrace.Render.Sampling.one} and full
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
    must be {!Raytrace.Render.Sampling.averaging}. After each row it checks [tr]'s work budget
    ({!Raytrace.Private.Trace.check_budget}).
    With [step = 1], a pass whose pixels read no neighbour's ray (neither
    adaptive sampling nor subsampling) in a scene with a hierarchy is
    traced as {!band} traces it, in squares: the same bytes.
    @raise Invalid_argument if [i] is not a pass, [step < 1], or the
    canvas sizes or the averaging disagree.
    @raise Limits.Work_exceeded when [tr] passes its budget. *)

val square : int
(** [square] is 64, the side in pixels of the squares in which {!band}
    traces. *)

val band_rows : plan -> Trace.t -> int
(** [band_rows pl tr] is the number of rows a {!band} call of [pl] with
    tracer [tr] should take at a time: {!square} where it traces squares,
    [1] where it traces row by row (a caller that reports progress a band
    at a time then reports it a row at a time, as before). *)

val band : plan -> int -> Trace.t -> first:int -> last:int -> unit
(** [band pl i tr ~first ~last] runs pass [i] of [pl] on rows [first] to
    [last - 1] of the rows that pass works on, as {!rows} runs each of them
    alone, with the same checks and the same bytes. Where the pass's
    pixels read no neighbour's ray (neither adaptive sampling nor
    subsampling) and the scene has a hierarchy, it traces them in squares
    of {!square} pixels a side (bands of {!square} rows, each a column of
    squares after the other), not row after row: the camera rays of a
    square meet the same few objects and walk the same nodes of their
    hierarchies while those are in the cache. The
    work budget is checked after each row of a square.
    @raise Invalid_argument as {!rows} does, or if [first < 0] or [last]
    is past the pass's rows.
    @raise Limits.Work_exceeded when [tr] passes its budget. *)
