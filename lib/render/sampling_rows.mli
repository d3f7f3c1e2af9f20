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
    @raise Invalid_argument if [i] is not a pass, [step < 1], or the
    canvas sizes or the averaging disagree.
    @raise Limits.Work_exceeded when [tr] passes its budget. *)
