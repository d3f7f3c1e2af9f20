(** The parts of a render shared by {!Render} (one process) and the
    multi-process renderer of [raytrace.unix]: the checks made before
    anything is allocated, the work counters, the statistics. Internal.

    @canonical Raytrace.Private.Render_work *)

val check :
  limits:Limits.t -> Scene.valid -> Region.t -> Sampling.t -> (unit, [> `Msg of string ]) result
(** [check ~limits scene region sampling] is [Ok ()] if the rays per pixel
    of [sampling] (at most [samples x samples]) are within [limits]
    ({!Limits.check_samples}) and so is the work of rendering [region] of
    [scene] ({!Scene.check_work}). *)

val inside : string -> Scene.valid -> Region.t -> unit
(** [inside fn scene r] checks that [r] lies inside [scene]'s canvas.
    @raise Invalid_argument naming the public function [fn] if not. *)

val out_of_memory : Region.t -> ('a, [> `Msg of string ]) result
(** [out_of_memory r] is the error of a failed allocation of [r]'s image. *)

val counter_fields : int
(** [counter_fields] is the number of counters a tracer saves, and its
    reservation of a shared work budget ({!refill}). *)

type counters = (int64, Bigarray.int64_elt, Bigarray.c_layout) Bigarray.Array1.t
(** The type for the counters of workers, {!counter_fields} per slot. *)

val save : counters -> int -> Trace.t -> float -> unit
(** [save ints slot tr words] saves [tr]'s counters and the [words]
    allocated by its loops in slot [slot] of [ints]. *)

val save_work : counters -> int -> Trace.t -> unit
(** [save_work ints slot tr] saves [tr]'s work counters alone (tests and
    box tests, {!Trace.work}) in slot [slot] of [ints]; it allocates
    nothing, for a worker to publish its work in the middle of a row. *)

val refill : counters -> slots:int -> slot:int -> budget:int -> jobs:int -> Trace.t -> int
(** [refill ints ~slots ~slot ~budget ~jobs tr] is the next budget of the
    tracer [tr] of slot [slot], one of [jobs] workers that share a budget
    of [budget] tests over the first [slots] slots of [ints] (a {!Trace}
    [refill]): it publishes [tr]'s work ({!save_work}), then reserves and
    returns [tr]'s work plus a [jobs]th of the budget that no slot has done
    or reserved, but at least [budget / (64 jobs)] (and 1), without
    overflow. Together the workers then pass [budget] by at most a 64th
    of it, plus a pixel's work each. It allocates nothing.
    @raise Limits.Work_exceeded if the slots' work is beyond [budget]. *)

val release : counters -> int -> Trace.t -> unit
(** [release ints slot tr] gives back what slot [slot] reserved beyond
    [tr]'s work, once its worker is done. *)

val stats :
  counters -> slots:int -> pixels:int -> jobs:int -> prepare_s:float -> trace_s:float -> Stats.t
(** [stats ints ~slots ~pixels ~jobs ~prepare_s ~trace_s] sums the
    counters of the first [slots] slots of [ints] into statistics. *)

(** {1:progress Progress} *)

val rays : Trace.t -> int
(** [rays tr] is the number of rays [tr] has cast so far. *)

val total_rows : Sampling.plan -> int
(** [total_rows pl] is the number of rows of work of [pl]: the rows of
    every pass ({!Sampling.pass_rows}). *)
