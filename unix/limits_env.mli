(** The resource bounds set by the environment.

    The core library reads no environment: a program reads the variables
    [RAYTRACE_MAX_*] once, here, and passes the {!Raytrace.Limits.t} to what it
    calls. *)

val read : unit -> (Limits.t, [> `Msg of string ]) result
(** [read ()] is {!Raytrace.Limits.of_lookup} on the process environment. *)
