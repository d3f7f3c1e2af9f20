(** Cleaning up when the process is interrupted.

    While a file is half written or worker processes run, a signal whose
    default action ends the process (SIGINT from Ctrl-C, SIGTERM from
    [kill], SIGHUP from a closed terminal, SIGXCPU from a CPU time limit,
    and the others of {!handled}) must not leave a temporary file or a
    stray process behind.
    {!protect} installs handlers for these signals around such a section
    only: elsewhere the signals keep their previous behaviour (by default
    they end the process at once, which is then safe since nothing needs
    cleaning). A handler does the cleanup, then what the signal would have
    done before: it calls the previous OCaml handler, or restores the
    default action and delivers the signal again, so that the process ends
    with the signal's usual exit status (130 for SIGINT, 143 for SIGTERM,
    as a shell reports it). Signals that were ignored stay ignored.

    OCaml 4.13 runs signal handlers only at allocations and system calls:
    the sections protected here are system calls (writing, waiting for
    workers), so a handler runs at once. *)

val handled : int list
(** [handled] is every signal whose default action ends the process and
    that a process can handle: SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1,
    SIGUSR2, SIGALRM, SIGPIPE, SIGXCPU, SIGXFSZ, SIGVTALRM and SIGPROF.
    (SIGKILL and SIGSTOP cannot be handled; SIGSEGV, SIGBUS, SIGFPE,
    SIGILL, SIGABRT and SIGTRAP come from faults of the program itself.) *)

val leave_alone : int -> unit
(** [leave_alone s] takes [s] out of the signals that {!protect} and
    {!reset_in_child} touch, for good: for a signal that the C code of
    another library handles, such as the SIGALRM of Graphics' refresh
    timer. (OCaml cannot see such a C handler: {!protect} would take the
    signal over and then restore the default action, which ends the
    process at the next tick.) *)

val protect : cleanup:(unit -> unit) -> (unit -> 'a) -> 'a
(** [protect ~cleanup f] is [f ()], during which each signal of {!handled}
    that is not ignored first calls [cleanup ()] (at most once), then acts
    as it did before [protect]. The previous handlers are restored when
    [f] returns or raises. [cleanup] must not raise. Sections may nest:
    an inner section's handler cleans up, then calls the outer one's. *)

val reset_in_child : unit -> unit
(** [reset_in_child ()], called first thing in a process just forked
    inside {!protect}, gives each signal of {!handled} that was not ignored
    its default action back, so that a child ends at once when it is
    interrupted, and never runs the parent's cleanup. *)

val without_sigxfsz : (unit -> 'a) -> 'a
(** [without_sigxfsz f] is [f ()] with SIGXFSZ ignored. A file-size limit
    ([ulimit -f]) sends SIGXFSZ, whose default action kills the process
    and leaves a temporary file behind; ignored, the write that crosses the
    limit fails with [EFBIG] ("File too large"), an error like a full
    disk. *)
