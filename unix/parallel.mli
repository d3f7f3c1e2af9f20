(** Worker processes over shared memory.

    OCaml 4.13 has no domains: to use every core, the renderer forks
    processes that write into one [Bigarray] mapped shared between them.
    A worker that dies (killed, out of memory, an exception) is detected
    and reported; its part of the output is never used. *)

val cores : unit -> int
(** [cores ()] is the number of processors this process may run on
    (its CPU affinity, as [nproc] reports), at least 1. *)

val others_running : unit -> int option
(** [others_running ()] is the fewest tasks (processes or threads) other
    than the caller that the system had running or ready to run in three
    looks at the fourth field of [/proc/loadavg], about a millisecond
    apart, or [None] where that file cannot be read or parsed. The count
    is the whole system's, not only of the cores this process may run
    on; a task that runs now and then (a shell, a compiler between files)
    rarely shows in all three looks, a busy one always does. It takes
    about 2 ms. *)

val idle_core : unit -> bool
(** [idle_core ()] is [true] if a process forked now would likely find a
    core of its own: {!others_running} is below [cores () - 1], or cannot
    be known. A render splits a phase whose split half is waited for (the
    hierarchy's build, the trace) only where it is [true]: with the other
    core busy, the child's half comes late and the copy-on-write faults of
    the fork cost more than it saves (docs/performance.md, "Issue 31,
    round 3"). *)

val available_memory : unit -> int option
(** [available_memory ()] is the memory, in bytes, that the system can give
    to new allocations without swapping ([MemAvailable] of
    [/proc/meminfo]), or [None] where it cannot be known. *)

val shared_bytes : int -> (int, Bigarray.int8_unsigned_elt, Bigarray.c_layout) Bigarray.Array1.t
(** [shared_bytes n] is [n] zeroed bytes that forked children share with
    their parent: their writes are visible to it. The memory is reserved
    (written) before it is mapped, so that a worker never meets a page
    that cannot be backed (SIGBUS).
    @raise Failure with a one-line message if no shared memory can be had
    (a full [/dev/shm], a file-size limit). *)

val shared_ints : int -> (int64, Bigarray.int64_elt, Bigarray.c_layout) Bigarray.Array1.t
(** [shared_ints n] is [n] zeroed 64-bit integers shared like
    {!shared_bytes}. *)

val shared_floats : int -> (float, Bigarray.float64_elt, Bigarray.c_layout) Bigarray.Array1.t
(** [shared_floats n] is [n] zeroed 64-bit floats shared like
    {!shared_bytes}. *)

type reserved_later = {
  floats : (float, Bigarray.float64_elt, Bigarray.c_layout) Bigarray.Array1.t;
      (** Floats shared like {!shared_floats}, but none backed by memory
          until reserved: touching one beyond the reserved ones is a
          SIGBUS. *)
  reserve : int -> unit;
      (** [reserve k] backs the first [k] floats of [floats] with memory,
          zeroed, in the process that calls it (forked after
          {!shared_floats_later}, or the one that called it). Where none can
          be had (a full [/dev/shm], a file-size limit) it raises
          [Failure] with a one-line message, and touches nothing.
          @raise Invalid_argument if [k] is not in [0 .. n]. *)
  release : unit -> unit;
      (** [release ()] lets go of what {!reserve} needs (a descriptor) in
          the calling process; [floats] stay mapped. Later [reserve]s
          raise [Failure]. *)
}
(** The type for shared floats reserved as they are needed. *)

val shared_floats_later : int -> reserved_later
(** [shared_floats_later n] is [n] shared floats of which a process forked
    later reserves what it writes, as it learns how many: none are written
    before the fork, by the caller (for {!shared_floats}, [8 n] bytes of
    zeros are written before the call returns).
    @raise Failure as {!shared_floats}. *)

type reports
(** The type for the channel on which the workers of a {!run} tell the
    parent which tasks they have finished. *)

val run :
  ?tick:(unit -> unit) -> ?reports:reports * (int -> unit) -> int -> (int -> unit) -> (unit, [> `Msg of string ]) result
(** [run ~tick ~reports:(r, finished) n work] runs [work 0], ..., [work (n - 1)], each in a forked child
    process, and waits for all of them, calling [tick ()] in the parent
    about ten times a second meanwhile (e.g. to report progress that the
    workers count in shared memory), and [finished t] in the parent as soon as
    it can for each task [t] that a worker passed to {!report} [r] (all of
    them before [run] returns, in the order of the reports); [tick] and
    [finished] must not raise. [Error] names the first worker that
    raised (with the exception), exited with a non-zero status or was
    killed by a signal ([worker 2 of 4 was killed by SIGKILL]), noticed as
    soon as it happens; the others are then killed. [Error] too if the
    workers cannot be started. Children leave with [Unix._exit], never
    running the parent's [at_exit] handlers or flushing its buffers. A
    worker that is stopped (SIGSTOP) is continued (SIGCONT) within a
    second, so that the parent never waits for it for ever.

    If the parent gets a signal of {!Signals.handled} (SIGINT, SIGTERM,
    SIGHUP, SIGUSR1, ...) while the workers run, it kills and reaps them
    before it ends
    ({!Signals.protect}); a worker whose parent died anyway (SIGKILL) ends
    at its next {!exit_if_orphaned}. *)

val exit_if_orphaned : unit -> unit
(** [exit_if_orphaned ()], called by [work] now and then (once per image
    row), ends the worker process at once if the parent that forked it has
    died, after removing the parent's temporary files of
    {!File_io.remove_temporaries}; outside a worker of {!run} it does
    nothing. It allocates nothing. *)

val beside : ?take_over:bool -> (unit -> 'a) -> unit -> ('a, [> `Msg of string ]) result
(** [beside ~take_over f] starts computing [f ()] in a forked child process and is
    [wait]: [wait ()] waits for the child and is its result, sent back on
    a pipe with [Marshal] (so [f]'s result must hold no functions). The
    caller works meanwhile: [let wait = beside f in let a = g () in
    (a, wait ())] computes [f ()] and [g ()] on two cores. [wait] is
    [Error] if [f] raised (with the exception), if the result could not be
    sent (it held a function), or if the child ended without sending it
    (killed by a signal: [the child process was killed by SIGKILL]). If
    no process can be forked, [f ()] is computed by [wait] itself, in the
    caller. With [take_over] (default [false]), a child that has not
    answered when [wait] is called and is late is killed (SIGKILL), and
    [f ()] is computed by [wait] in the caller: late where, at the rate
    of CPU time it has had since the fork ([/proc/PID/stat]), the work
    the caller did meanwhile (its own CPU time since the fork, which the
    child's share is assumed to equal) would take it longer to finish
    than the caller takes to do it all (never before the caller has had
    0.05 s of CPU time since the fork: the counts are in hundredths of a
    second); so that a child that finds no
    core free costs the caller at most the fork. [wait] must be called once: until then the child may wait,
    blocked on a full pipe; a child whose parent ended dies on that
    pipe ([SIGPIPE]). The child leaves with [Unix._exit], never running
    the parent's [at_exit] handlers or flushing its buffers; it allocates
    in its own copy of the heap, so a big result costs the parent its
    size once more while it is read. *)

(** {1:queue Task queues}

    Workers that take tasks as they go, rather than a fixed share each,
    finish together even when one core runs slower than another. *)

type queue
(** The type for queues of task indices, shared by the workers of a
    {!run} started after the queue was made. *)

val max_tasks : int
(** [max_tasks] is [16384]: the most tasks a queue holds (4 bytes each in a
    pipe, whose buffer is 64 KiB). *)

val queue : int -> queue
(** [queue m] holds the tasks [0 .. m - 1].
    @raise Invalid_argument if [m < 0] or [m > max_tasks].
    @raise Unix.Unix_error if no pipe can be made. *)

val take : queue -> int
(** [take q] is the next task of [q], or [-1] when none is left. Each task
    is taken by exactly one process, whatever the number of processes that
    take from [q]. *)

val reports : unit -> reports
(** [reports ()] is a new channel for the {!run} that it is passed to.
    @raise Unix.Unix_error if no pipe can be made. *)

val report : reports -> int -> unit
(** [report r t], in a worker, tells the parent that task [t] is finished:
    whatever the worker wrote to shared memory before is visible to the
    parent when it is told. It allocates nothing. *)

val close_reports : reports -> unit
(** [close_reports r] releases [r]'s descriptors (in the parent, after
    {!run}). *)

val close_queue : queue -> unit
(** [close_queue q] releases [q]'s descriptors (in the parent, after
    {!run}). *)
