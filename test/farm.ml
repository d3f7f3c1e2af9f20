(* Throwaway render farms for the recipe tests: a single-node Slurm cluster
   and ssh "hosts", real daemons started in a temporary directory, on free
   ports of 127.0.0.1, and stopped after, whatever the test did. Daemons run
   in the foreground as children of the test, so stopping them needs only
   their process IDs. *)

let write path text =
  let oc = open_out_bin path in
  output_string oc text;
  close_out oc

let read path = try In_channel_free.read path with Sys_error _ -> ""

(* The last lines of a daemon's log, for a failure message. *)
let tail path =
  let lines = String.split_on_char '\n' (String.trim (read path)) in
  let n = List.length lines in
  String.concat "\n" (List.filteri (fun i _ -> i >= n - 15) lines)

let free_port () =
  let s = Unix.socket PF_INET SOCK_STREAM 0 in
  Fun.protect
    ~finally:(fun () -> Unix.close s)
    (fun () ->
      Unix.bind s (ADDR_INET (Unix.inet_addr_loopback, 0));
      match Unix.getsockname s with ADDR_INET (_, port) -> port | ADDR_UNIX _ -> assert false)

(* [spawn ~env log prog args] starts [prog] with its output in [log]. *)
let spawn ?(env = Unix.environment ()) log prog args =
  let fd = Unix.openfile log [ O_WRONLY; O_CREAT; O_APPEND ] 0o644 in
  let pid =
    Fun.protect
      ~finally:(fun () -> Unix.close fd)
      (fun () -> Unix.create_process_env prog (Array.of_list (prog :: args)) env Unix.stdin fd fd)
  in
  pid

(* Ends a daemon: SIGTERM, then SIGKILL if it is still there after 10 s. *)
let stop pid =
  (try Unix.kill pid Sys.sigterm with Unix.Unix_error _ -> ());
  let rec wait tries =
    match Unix.waitpid [ WNOHANG ] pid with
    | 0, _ when tries > 0 ->
        Unix.sleepf 0.05;
        wait (tries - 1)
    | 0, _ ->
        (try Unix.kill pid Sys.sigkill with Unix.Unix_error _ -> ());
        ignore (Unix.waitpid [] pid)
    | _ -> ()
    | exception Unix.Unix_error (ECHILD, _, _) -> ()
  in
  wait 200

let exited pid = match Unix.waitpid [ WNOHANG ] pid with 0, _ -> false | _ -> true | exception Unix.Unix_error _ -> true

(* Polls [ready] every 0.1 s for [seconds]. *)
let rec until ?(seconds = 60.) ready =
  ready ()
  ||
  if seconds <= 0. then false
  else (
    Unix.sleepf 0.1;
    until ~seconds:(seconds -. 0.1) ready)

(* The skip, if a farm cannot run here: real daemons need root (munged and
   slurmd switch users, sshd needs its privilege separation) and their
   programs. *)
let unavailable what progs =
  if Unix.geteuid () <> 0 then (
    Helpers.skip what ~why:"not root: the real daemons of the farm tests need root (CI runs as root)";
    true)
  else
    match Helpers.missing progs with
    | [] -> false
    | missing ->
        Helpers.skip what ~why:(String.concat ", " missing ^ " not installed (make deps installs them)");
        true

let env vars =
  let names = List.map (fun v -> String.sub v 0 (String.index v '=')) vars in
  let keep v = match String.index_opt v '=' with Some i -> not (List.mem (String.sub v 0 i) names) | None -> true in
  Array.of_list (vars @ List.filter keep (Array.to_list (Unix.environment ())))

(* Slurm *)

type slurm = { dir : string; vars : string list }

let slurm_vars s = s.vars

let slurm_programs = [ "munged"; "slurmctld"; "slurmd"; "sbatch"; "scontrol"; "sinfo"; "squeue"; "scancel" ]

let slurm_conf ~dir ~ctld_port ~slurmd_port ~cpus =
  Printf.sprintf
    {|# A single-node cluster for the tests (test/farm.ml), in %s.
ClusterName=raytrace-test
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=%d
SlurmdPort=%d
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=%s/munge/socket
StateSaveLocation=%s/state
SlurmdSpoolDir=%s/spool
SlurmctldPidFile=%s/slurmctld.pid
SlurmdPidFile=%s/slurmd.pid
SlurmctldLogFile=%s/slurmctld.log
SlurmdLogFile=%s/slurmd.log
# Two CPUs whatever the machine has (config_overrides): two tasks at a time.
# No cgroups, no accounting: what works in a container without systemd.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SlurmdParameters=config_overrides
ReturnToService=2
# Schedule at once: the tests wait for their jobs.
SchedulerParameters=sched_interval=1,bf_interval=1
KillWait=5
MinJobAge=600
NodeName=rtnode NodeAddr=127.0.0.1 NodeHostname=localhost CPUs=%d State=UNKNOWN
PartitionName=test Nodes=rtnode Default=YES MaxTime=INFINITE State=UP
|}
    dir ctld_port slurmd_port dir dir dir dir dir dir dir cpus

let scontrol s args = Helpers.run ~env:(env s.vars) "scontrol" args

let node_state s =
  let _, out, _ = Helpers.run ~env:(env s.vars) "sinfo" [ "-h"; "-n"; "rtnode"; "-o"; "%t" ] in
  String.trim out

let with_slurm what f =
  if not (unavailable what slurm_programs) then begin
    let dir = Helpers.temp_dir () in
    List.iter (fun d -> Unix.mkdir (Filename.concat dir d) 0o755) [ "munge"; "state"; "spool" ];
    let key = Filename.concat dir "munge/munge.key" in
    let urandom = open_in_bin "/dev/urandom" in
    write key (really_input_string urandom 1024);
    close_in urandom;
    Unix.chmod key 0o400;
    let conf = Filename.concat dir "slurm.conf" in
    write conf (slurm_conf ~dir ~ctld_port:(free_port ()) ~slurmd_port:(free_port ()) ~cpus:2);
    (* slurmd 22.05 loads a cgroup plugin even when nothing uses it and
       knows no "disabled"; the v1 plugin's loading touches no cgroup file,
       so it should load on cgroup v2 hosts too (tried only here, on v1). *)
    write (Filename.concat dir "cgroup.conf") "CgroupPlugin=cgroup/v1\nCgroupAutomount=no\n";
    let s = { dir; vars = [ "SLURM_CONF=" ^ conf ] } in
    let daemons = ref [] in
    let start log prog args = daemons := spawn ~env:(env s.vars) (Filename.concat dir log) prog args :: !daemons in
    let stop_all () =
      (* Jobs first, so that no slurmstepd outlives its slurmd. *)
      ignore (Helpers.run ~env:(env s.vars) "scancel" [ "--user=root" ]);
      ignore
        (until ~seconds:20. (fun () ->
             let _, out, _ = Helpers.run ~env:(env s.vars) "squeue" [ "-h" ] in
             String.trim out = ""));
      List.iter stop !daemons
    in
    Fun.protect ~finally:stop_all (fun () ->
        let m = Filename.concat dir "munge" in
        start "munged.log" "munged"
          [
            "-F"; "--socket=" ^ m ^ "/socket"; "--key-file=" ^ key; "--pid-file=" ^ m ^ "/pid"; "--seed-file=" ^ m ^ "/seed";
            "--log-file=" ^ m ^ "/log";
          ];
        if not (until ~seconds:10. (fun () -> Sys.file_exists (m ^ "/socket"))) then
          Alcotest.failf "munged did not start:\n%s" (tail (m ^ "/log"));
        start "slurmctld.out" "slurmctld" [ "-D"; "-i"; "-f"; conf ];
        start "slurmd.out" "slurmd" [ "-D"; "-f"; conf; "-N"; "rtnode" ];
        if not (until ~seconds:60. (fun () -> node_state s = "idle")) then
          Alcotest.failf "the Slurm node is %S, not idle, after 60 s:\n%s\n%s" (node_state s)
            (tail (Filename.concat dir "slurmctld.log"))
            (tail (Filename.concat dir "slurmd.log"));
        if List.exists exited !daemons then Alcotest.fail "a Slurm daemon exited";
        f s)
  end

(* The states of a job's tasks (one per array task), and the reason each
   waits, from scontrol's one-line records. *)
let job_states s id =
  let _, out, _ = scontrol s [ "show"; "job"; "-o"; id ] in
  let field name line =
    List.find_map
      (fun kv ->
        match String.index_opt kv '=' with
        | Some i when String.sub kv 0 i = name -> Some (String.sub kv (i + 1) (String.length kv - i - 1))
        | _ -> None)
      (String.split_on_char ' ' line)
  in
  String.split_on_char '\n' out
  |> List.filter_map (fun line ->
         match (field "JobState" line, field "Reason" line) with
         | Some st, Some r -> Some (st, r)
         | Some st, None -> Some (st, "None")
         | None, _ -> None)

let finished = [ "COMPLETED"; "FAILED"; "CANCELLED"; "TIMEOUT"; "NODE_FAIL"; "OUT_OF_MEMORY"; "PREEMPTED"; "BOOT_FAIL"; "DEADLINE" ]

let wait_job ?(seconds = 300.) s id =
  let ended () =
    match job_states s id with
    | [] -> false
    | l -> List.for_all (fun (st, _) -> List.mem st finished) l
  in
  if not (until ~seconds ended) then
    Alcotest.failf "Slurm job %s did not end in %.0f s: %s" id seconds
      (String.concat ", " (List.map (fun (st, r) -> st ^ " (" ^ r ^ ")") (job_states s id)));
  List.map fst (job_states s id)

let wait_running ?(seconds = 120.) s id =
  if not (until ~seconds (fun () -> List.exists (fun (st, _) -> st = "RUNNING") (job_states s id))) then
    Alcotest.failf "Slurm job %s did not start in %.0f s" id seconds

(* ssh *)

type ssh = { config : string; homes : (string * string) list }

let ssh_programs = [ "sshd"; "ssh"; "ssh-keygen"; "rsync" ]
let ssh_command h = "ssh -F " ^ h.config
let home h host = List.assoc host h.homes

(* sshd logs each accepted login (LogLevel VERBOSE). *)
let logins h host =
  let log = Filename.concat (Filename.dirname h.config) ("sshd-" ^ host ^ ".log") in
  List.length (List.filter (fun l -> Astring_free.contains l "Accepted publickey") (String.split_on_char '\n' (read log)))

let keygen path =
  let code, out, err = Helpers.run "ssh-keygen" [ "-q"; "-t"; "ed25519"; "-N"; ""; "-C"; "raytrace-test"; "-f"; path ] in
  if code <> 0 then Alcotest.failf "ssh-keygen failed: %s%s" out err

(* sshd sits in /usr/sbin, often not on a user's PATH. *)
let sshd_path () =
  List.find_opt Sys.file_exists [ "/usr/sbin/sshd"; "/usr/local/sbin/sshd"; "/sbin/sshd" ]

let with_sshd what hosts f =
  let sshd = sshd_path () in
  if sshd = None then Helpers.skip what ~why:"sshd not installed (make deps installs openssh-server)"
  else if not (unavailable what (List.filter (( <> ) "sshd") ssh_programs)) then begin
    let sshd = Option.get sshd in
    let dir = Helpers.temp_dir () in
    let key = Filename.concat dir "user_key" and host_key = Filename.concat dir "host_key" in
    keygen key;
    keygen host_key;
    let authorized = Filename.concat dir "authorized_keys" in
    write authorized (read (key ^ ".pub"));
    (* sshd refuses to start without its privilege separation directory,
       which systemd would create. *)
    if not (Sys.file_exists "/run/sshd") then Unix.mkdir "/run/sshd" 0o755;
    let daemons = ref [] in
    let ssh_config = Buffer.create 512 in
    Fun.protect
      ~finally:(fun () -> List.iter stop !daemons)
      (fun () ->
        let homes =
          List.map
            (fun host ->
              let home = Filename.concat dir ("home-" ^ host) in
              Unix.mkdir home 0o755;
              let port = free_port () in
              let conf = Filename.concat dir ("sshd_config-" ^ host) in
              (* Both hosts are this machine and would log in to root's
                 one home; the forced command gives each its own login
                 directory, so files must travel (rsync) as they would
                 between machines. *)
              write conf
                (Printf.sprintf
                   "ListenAddress 127.0.0.1\nPort %d\nHostKey %s\nPidFile %s/sshd-%s.pid\nAuthorizedKeysFile %s\n\
                    PermitRootLogin prohibit-password\nPasswordAuthentication no\nKbdInteractiveAuthentication no\n\
                    UsePAM no\nStrictModes no\nLogLevel VERBOSE\n\
                    ForceCommand cd %s && HOME=%s && export HOME && eval \"$SSH_ORIGINAL_COMMAND\"\n"
                   port host_key dir host authorized home home);
              daemons := spawn (Filename.concat dir ("sshd-" ^ host ^ ".log")) sshd [ "-D"; "-e"; "-f"; conf ] :: !daemons;
              Buffer.add_string ssh_config
                (Printf.sprintf
                   "Host %s\n  HostName 127.0.0.1\n  Port %d\n  User root\n  IdentityFile %s\n  IdentitiesOnly yes\n\
                   \  BatchMode yes\n  StrictHostKeyChecking no\n  UserKnownHostsFile %s/known_hosts\n  LogLevel ERROR\n"
                   host port key dir);
              (host, home))
            hosts
        in
        let config = Filename.concat dir "ssh_config" in
        write config (Buffer.contents ssh_config);
        let h = { config; homes } in
        List.iter
          (fun host ->
            let ok () = let code, _, _ = Helpers.run "ssh" [ "-F"; config; host; "true" ] in code = 0 in
            if not (until ~seconds:30. ok) then
              Alcotest.failf "cannot ssh to the test's sshd for %s:\n%s" host
                (tail (Filename.concat dir ("sshd-" ^ host ^ ".log"))))
          hosts;
        f h)
  end
