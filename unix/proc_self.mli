(** This process's counters in Linux's [/proc/self]. *)

val kb : string -> string -> int option
(** [kb file field] is [n] of the first line ["field: n kB"] of
    [/proc/self/file] (such as [kb "status" "VmHWM"], the peak resident
    size), or [None] where the file cannot be read or has no such line. *)
