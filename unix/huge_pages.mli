(** Transparent huge pages for the heap.

    A million objects take about 180 MB, first touched in 4 KiB pages:
    66,000 page faults for the million-triangle knot, and as many entries
    of the processor's page tables to miss during its trace. Linux backs
    memory with 2 MiB pages where a program asks for them with
    [madvise(MADV_HUGEPAGE)] (where
    [/sys/kernel/mm/transparent_hugepage/enabled] is [madvise], a usual
    setting). The [raytrace] program is linked with [-Wl,--wrap=malloc]:
    each block of 4 MiB or more that its code (the OCaml runtime's heap
    and bigarrays included) allocates is then marked so (this module's C
    part), and nothing else changes. [RAYTRACE_HUGE_PAGES=0] turns it off.
    Programs linked without the flag are left as they are. *)

type mode = Always | Madvise | Never | Unknown  (** The kernel's setting, {!mode}. *)

val mode_of_setting : string -> mode
(** [mode_of_setting s] is the mode selected in [s], the text of
    [/sys/kernel/mm/transparent_hugepage/enabled]: the bracketed word of
    ["always madvise never"], or [Unknown]. *)

val mode : unit -> mode
(** [mode ()] is the running kernel's mode, [Unknown] where the file
    cannot be read (not Linux, or a kernel without huge pages). *)

val variable : string
(** [variable] is ["RAYTRACE_HUGE_PAGES"]. *)

val wrapped : unit -> bool
(** [wrapped ()] is [true] iff this program's allocations go through the
    wrapper (it was linked with [-Wl,--wrap=malloc]). *)

val enabled : unit -> bool
(** [enabled ()] is [false] iff {!variable} is [0], [off], [no] or
    [false]. *)

val asked : unit -> int
(** [asked ()] is the number of blocks marked for huge pages so far. *)

val resident_mb : unit -> float option
(** [resident_mb ()] is the megabytes of huge pages this process holds
    now ([AnonHugePages] of [/proc/self/smaps_rollup]), if known. *)

val status : unit -> string
(** [status ()] says whether this process asks for huge pages and holds
    some, for [--stats]: ["on, N MB"] or ["off (reason)"]. *)
