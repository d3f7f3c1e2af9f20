(** Throwaway render farms for the recipe tests: a single-node Slurm
    cluster and ssh hosts, real daemons ([munged], [slurmctld], [slurmd],
    [sshd]) started in a temporary directory on free ports of 127.0.0.1
    and stopped after the test, whether it passed or failed.

    Both need root (CI runs as root) and the daemons' programs ([make deps]
    installs them); without them, the test is skipped with
    {!Helpers.skip}. *)

val env : string list -> string array
(** [env vars] is this process's environment with the ["NAME=value"]
    bindings [vars] added, replacing earlier values of the same names. *)

val write : string -> string -> unit
(** [write path text] makes [path] a file holding exactly [text]. *)

(** {1:slurm Slurm} *)

type slurm
(** A running single-node cluster: node [rtnode] with 2 CPUs, partition
    [test], no cgroups ([proctrack/linuxproc], [task/none]), munge on its
    own socket and key. *)

val with_slurm : string -> (slurm -> unit) -> unit
(** [with_slurm what f] starts a cluster, waits until its node is idle,
    runs [f] on it, then cancels its jobs and stops its daemons, also when
    [f] raises. Skips [what] without root or the programs, and fails the
    test if the cluster does not come up within a minute (with the last
    lines of the daemons' logs). *)

val slurm_vars : slurm -> string list
(** [slurm_vars s] is the environment ([SLURM_CONF=...]) under which
    [sbatch], [scontrol] and the other clients talk to [s]. *)

val wait_job : ?seconds:float -> slurm -> string -> string list
(** [wait_job s id] waits until every task of job [id] has ended and is
    their states ([COMPLETED], [FAILED], [CANCELLED] ...), one per task.
    Fails the test after [seconds] (default 300). *)

val wait_running : ?seconds:float -> slurm -> string -> unit
(** [wait_running s id] waits until a task of job [id] runs. Fails the
    test after [seconds] (default 120). *)

(** {1:ssh ssh} *)

type ssh
(** Running ssh hosts: one [sshd] per host name, each on its own port of
    127.0.0.1 with a throwaway host key, accepting a throwaway user key
    for root, and logging in to its own fresh directory. *)

val with_sshd : string -> string list -> (ssh -> unit) -> unit
(** [with_sshd what hosts f] starts one [sshd] per name of [hosts], waits
    until [ssh] logs in to each, runs [f], then stops them, also when [f]
    raises. Skips [what] without root or the programs. *)

val ssh_command : ssh -> string
(** [ssh_command h] is the [ssh] command line (with its own configuration
    file: keys, ports, a fresh known-hosts file) that reaches the hosts of
    [h] by name, e.g. for GNU parallel's [--ssh]. *)

val home : ssh -> string -> string
(** [home h host] is the login directory of [host]. *)

val logins : ssh -> string -> int
(** [logins h host] is the number of logins [host]'s [sshd] accepted. *)
