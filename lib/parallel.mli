(** Worker processes over shared memory.

    OCaml 4.13 has no domains: to use every core, the renderer forks
    processes that write into one [Bigarray] mapped shared between them.
    A worker that dies (killed, out of memory, an exception) is detected
    and reported; its part of the output is never used. *)

val cores : unit -> int
(** [cores ()] is the number of processors this process may run on
    (its CPU affinity, as [nproc] reports), at least 1. *)

val available_memory : unit -> int option
(** [available_memory ()] is the memory, in bytes, that the system can give
    to new allocations without swapping ([MemAvailable] of
    [/proc/meminfo]), or [None] where it cannot be known. *)

val shared_bytes : int -> (int, Bigarray.int8_unsigned_elt, Bigarray.c_layout) Bigarray.Array1.t
(** [shared_bytes n] is [n] zeroed bytes that forked children share with
    their parent: their writes are visible to it.
    @raise Failure if no shared memory can be mapped. *)

val shared_ints : int -> (int64, Bigarray.int64_elt, Bigarray.c_layout) Bigarray.Array1.t
(** [shared_ints n] is [n] zeroed 64-bit integers shared like
    {!shared_bytes}. *)

val run : int -> (int -> unit) -> (unit, [> `Msg of string ]) result
(** [run n work] runs [work 0], ..., [work (n - 1)], each in a forked child
    process, and waits for all of them. [Error] names the first worker that
    raised, exited with a non-zero status or was killed by a signal; the
    others are then killed. Children leave with [Unix._exit], never running
    the parent's [at_exit] handlers or flushing its buffers. *)
