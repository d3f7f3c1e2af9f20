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

val save_work : ?base:int -> counters -> int -> Trace.t -> unit
(** [save_work ~base ints slot tr] saves [tr]'s work counters alone (tests
    less [base], default [0], and box tests: {!Trace.work} less [base]) in
    slot [slot] of [ints]; it allocates nothing, for a worker to publish
    its work in the middle of a row. *)

val refill :
  ?base:int -> ?wait:(unit -> unit) -> counters -> slots:int -> slot:int -> budget:int -> jobs:int -> Trace.t -> int
(** [refill ~base ~wait ints ~slots ~slot ~budget ~jobs tr] is the next
    budget of the tracer [tr] of slot [slot], one of [jobs] workers that
    share a budget of [budget] tests over the first [slots] slots of
    [ints] (a {!Trace} [refill]), [tr] having done [base] (default [0])
    tests before they started. It publishes [tr]'s work less [base]
    ({!save_work}), then reserves a [jobs]th of the budget that no slot
    has done or reserved, but at least [budget / (64 jobs)] (and 1); when
    every test is reserved, it calls [wait] (default: return at once) and
    looks again until the others have done or given back theirs
    ({!release}), then takes that least share. It returns [base], [tr]'s
    work since, and the share, without overflow. Together the workers
    then pass [budget] by at most [jobs] least shares plus a pixel's work
    each. It allocates nothing but what [wait] does.
    @raise Limits.Work_exceeded with [base] plus the slots' work if that
    work is beyond [budget]. *)

val release : ?base:int -> counters -> int -> Trace.t -> unit
(** [release ~base ints slot tr] gives back what slot [slot] reserved
    beyond [tr]'s work (less [base], default [0]), once its worker is
    done: a worker that ends holding a reservation would keep the others
    waiting in {!refill}. *)

val stats :
  counters -> slots:int -> pixels:int -> jobs:int -> prepare_s:float -> trace_s:float -> Stats.t
(** [stats ints ~slots ~pixels ~jobs ~prepare_s ~trace_s] sums the
    counters of the first [slots] slots of [ints] into statistics. *)

(** {1:progress Progress} *)

val rays : Trace.t -> int
(** [rays tr] is the number of rays [tr] has cast so far. *)

val total_rows : Sampling_rows.plan -> int
(** [total_rows pl] is the number of rows of work of [pl]: the rows of
    every pass ([Raytrace.Sampling_rows.pass_rows]). *)
