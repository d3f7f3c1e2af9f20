(* "0-3,8,10-11" -> 7 *)
let count_cpu_list s =
  String.split_on_char ',' (String.trim s)
  |> List.fold_left
       (fun acc part ->
         match String.split_on_char '-' part with
         | [ a ] -> ( match int_of_string_opt a with Some _ -> acc + 1 | None -> acc)
         | [ a; b ] -> (
             match (int_of_string_opt a, int_of_string_opt b) with
             | Some a, Some b when b >= a -> acc + (b - a + 1)
             | _ -> acc)
         | _ -> acc)
       0

(* The value of the first "key: value" line of a /proc file that [parse]
   accepts. *)
let proc_field file key parse =
  match File_io.read file with
  | Error _ -> None
  | Ok text ->
      String.split_on_char '\n' text
      |> List.find_map (fun line ->
             match String.index_opt line ':' with
             | Some i when String.sub line 0 i = key -> parse (String.trim (String.sub line (i + 1) (String.length line - i - 1)))
             | _ -> None)

let cores () =
  let positive n = if n > 0 then Some n else None in
  match proc_field "/proc/self/status" "Cpus_allowed_list" (fun v -> positive (count_cpu_list v)) with
  | Some n -> n
  | None -> 1

(* "0.52 0.61 0.70 2/84 12345": 2 running or runnable, this process one of
   them (it runs while it reads). The least of a few looks: a task that
   wakes for a moment (a shell, a timer) is seldom in all of them, a busy
   one is in each. *)
let others_running () =
  let look () =
    match File_io.read "/proc/loadavg" with
    | Error _ -> None
    | Ok text -> (
        match String.split_on_char ' ' (String.trim text) with
        | _ :: _ :: _ :: field :: _ -> (
            match String.split_on_char '/' field with
            | [ r; _ ] -> Option.map (fun r -> max 0 (r - 1)) (int_of_string_opt r)
            | _ -> None)
        | _ -> None)
  in
  let rec looks k least =
    if k = 0 then least
    else
      match look () with
      | None -> None
      | Some n ->
          let least = match least with Some m -> Some (min m n) | None -> Some n in
          if k > 1 && n > 0 then Unix.sleepf 0.001;
          if n = 0 then least else looks (k - 1) least
  in
  looks 3 None

let idle_core () = match others_running () with Some n -> n < cores () - 1 | None -> true

(* "MemAvailable:   12345678 kB" -> 12345678 * 1024 *)
let available_memory () =
  proc_field "/proc/meminfo" "MemAvailable" (fun v ->
      match String.split_on_char ' ' v with
      | [ n; "kB" ] -> Option.map (fun k -> k * 1024) (int_of_string_opt n)
      | _ -> None)

(* The file is filled with zeros before it is mapped: a full /dev/shm or a
   file-size limit is then an error here, not a SIGBUS in a worker that
   touches a page the file system cannot back. *)
let fill_zeros fd bytes =
  let chunk = Bytes.make 65536 '\000' in
  let rec go left =
    if left > 0 then begin
      let k = Unix.write fd chunk 0 (min left (Bytes.length chunk)) in
      go (left - k)
    end
  in
  go bytes

(* [map_shared ~keep kind n] is [n] elements of [kind] mapped from a file
   filled with zeros, and [None]; with [keep], from a file of that size
   with no memory yet (a hole: a page touched before it is written is a
   SIGBUS), and the file's descriptor, still open, to fill. *)
let map_shared_file ~keep kind n =
  (* A file in memory-backed /dev/shm when there is one, unlinked at once:
     the mapping outlives the name. Filling a large file takes a while: a
     signal meanwhile removes it too. *)
  let dir = if Sys.file_exists "/dev/shm" then "/dev/shm" else Filename.get_temp_dir_name () in
  let bytes = max 1 n * Bigarray.kind_size_in_bytes kind in
  let created = ref None in
  let remove () =
    Option.iter (fun path -> try Sys.remove path with Sys_error _ -> ()) !created;
    created := None
  in
  match
    Signals.protect ~cleanup:remove (fun () ->
        Signals.without_sigxfsz (fun () ->
            let path = Filename.temp_file ~temp_dir:dir "raytrace" ".shm" in
            created := Some path;
            let fd = Unix.openfile path [ O_RDWR; O_CLOEXEC ] 0o600 in
            match
              Fun.protect ~finally:remove (fun () ->
                  if not keep then fill_zeros fd bytes;
                  Bigarray.array1_of_genarray (Unix.map_file fd kind Bigarray.c_layout true [| max 1 n |]))
            with
            | a when keep -> (a, Some fd)
            | a -> Unix.close fd; (a, None)
            | exception e -> Unix.close fd; raise e))
  with
  | a -> a
  | exception (Unix.Unix_error (e, _, _)) ->
      failwith (Printf.sprintf "cannot get %d bytes of shared memory in %s: %s" bytes dir (Unix.error_message e))
  | exception Sys_error e -> failwith (Printf.sprintf "cannot get shared memory in %s: %s" dir e)

let map_shared kind n = fst (map_shared_file ~keep:false kind n)
let shared_bytes n = map_shared Bigarray.int8_unsigned n
let shared_ints n = map_shared Bigarray.int64 n
let shared_floats n = map_shared Bigarray.float64 n

type reserved_later = {
  floats : (float, Bigarray.float64_elt, Bigarray.c_layout) Bigarray.Array1.t;
  reserve : int -> unit;
  release : unit -> unit;
}

let shared_floats_later n =
  match map_shared_file ~keep:true Bigarray.float64 n with
  | _, None -> assert false
  | floats, Some fd ->
      let closed = ref false in
      let release () = if not !closed then begin closed := true; Unix.close fd end in
      let reserve k =
        if k < 0 || k > n then invalid_arg "Parallel.shared_floats_later: reserve";
        if !closed then failwith "the shared floats were released";
        ignore (Unix.lseek fd 0 Unix.SEEK_SET);
        match Signals.without_sigxfsz (fun () -> fill_zeros fd (8 * k)) with
        | () -> ()
        | exception Unix.Unix_error (e, _, _) ->
            failwith (Printf.sprintf "cannot get %d bytes of shared memory: %s" (8 * k) (Unix.error_message e))
      in
      { floats; reserve; release }

let signal_name s =
  let names =
    Sys.
      [
        (sigkill, "SIGKILL"); (sigterm, "SIGTERM"); (sigint, "SIGINT"); (sigsegv, "SIGSEGV");
        (sigabrt, "SIGABRT"); (sigbus, "SIGBUS"); (sigfpe, "SIGFPE"); (sighup, "SIGHUP");
        (sigquit, "SIGQUIT"); (sigpipe, "SIGPIPE"); (sigusr1, "SIGUSR1"); (sigusr2, "SIGUSR2");
        (sigalrm, "SIGALRM"); (sigxcpu, "SIGXCPU"); (sigxfsz, "SIGXFSZ"); (sigvtalrm, "SIGVTALRM");
        (sigprof, "SIGPROF"); (sigill, "SIGILL"); (sigtrap, "SIGTRAP"); (sigsys, "SIGSYS");
        (sigstop, "SIGSTOP"); (sigtstp, "SIGTSTP"); (sigttin, "SIGTTIN"); (sigttou, "SIGTTOU");
      ]
  in
  match List.assoc_opt s names with Some n -> n | None -> Printf.sprintf "signal %d" s

let describe_status = function
  | Unix.WEXITED c -> Printf.sprintf "exited with status %d" c
  | Unix.WSIGNALED s -> "was killed by " ^ signal_name s
  | Unix.WSTOPPED s -> "was stopped by " ^ signal_name s

(* In a worker: the pid of its parent, to notice that the parent died.
   0 outside workers. *)
let parent = ref 0

(* The parent's temporary files (a file it was writing while the workers
   traced) are removed: a parent killed outright cannot. *)
let exit_if_orphaned () =
  if !parent <> 0 && Unix.getppid () <> !parent then begin
    File_io.remove_temporaries ();
    Unix._exit 3
  end

let read_message fd =
  let b = Bytes.create 512 in
  match Unix.read fd b 0 512 with
  | n when n > 0 -> Some (String.trim (Bytes.sub_string b 0 n))
  | _ -> None
  | exception Unix.Unix_error _ -> None

let close_quietly fd = try Unix.close fd with Unix.Unix_error _ -> ()

(* Worker [w] in the child process: its exit code, and an exception's text
   on its pipe. *)
let child work w me (fds : (Unix.file_descr * Unix.file_descr) array) =
  Signals.reset_in_child ();
  parent := me;
  Array.iteri (fun i (r, wr) -> close_quietly r; if i <> w then close_quietly wr) fds;
  let code =
    match work w with
    | () -> 0
    | exception e ->
        let m = Printexc.to_string e in
        (try ignore (Unix.write_substring (snd fds.(w)) m 0 (min 500 (String.length m))) with Unix.Unix_error _ -> ());
        2
  in
  Unix._exit code

(* The CPU seconds (user and system) that process [pid] has had, from
   fields 14 and 15 of /proc/PID/stat, in the kernel's USER_HZ ticks (100
   a second on Linux, whatever the kernel's own tick), counted after the
   command's name, which may hold spaces and parentheses. *)
let cpu_of pid =
  match File_io.read (Printf.sprintf "/proc/%d/stat" pid) with
  | Error _ -> None
  | Ok text -> (
      match String.rindex_opt text ')' with
      | None -> None
      | Some i -> (
          let fields = String.split_on_char ' ' (String.trim (String.sub text (i + 1) (String.length text - i - 1))) in
          match List.filteri (fun k _ -> k = 11 || k = 12) fields with
          | [ u; s ] -> (
              match (int_of_string_opt u, int_of_string_opt s) with
              | Some u, Some s -> Some (Float.of_int (u + s) /. 100.)
              | _ -> None)
          | _ -> None))

let cpu_self () =
  let t = Unix.times () in
  t.tms_utime +. t.tms_stime

(* The child is given as much work as the caller did meanwhile ([mine] CPU
   seconds since the fork): at the rate it has had ([theirs] CPU seconds in
   [wall]), what it has left takes [(mine - theirs) * wall / theirs];
   done here it takes [mine]. Under 5 ticks of the caller's CPU time,
   the counts are too coarse to judge by: not late. *)
let late ~mine ~theirs ~wall = mine >= 0.05 && mine > theirs && (mine -. theirs) *. wall > mine *. theirs

(* The child sends [Ok v] or [Error message]; a child killed before it
   has sent all of it leaves the parent at the end of the pipe. *)
let beside ?(take_over = false) f =
  flush stdout;
  flush stderr;
  match Unix.pipe ~cloexec:true () with
  | exception Unix.Unix_error _ -> fun () -> ( match f () with v -> Ok v | exception e -> Error (`Msg (Printexc.to_string e)))
  | r, w -> (
      match Unix.fork () with
      | exception Unix.Unix_error _ ->
          close_quietly r;
          close_quietly w;
          fun () -> ( match f () with v -> Ok v | exception e -> Error (`Msg (Printexc.to_string e)))
      | 0 ->
          Signals.reset_in_child ();
          close_quietly r;
          let oc = Unix.out_channel_of_descr w in
          let result = match f () with v -> Ok v | exception e -> Error ("raised " ^ Printexc.to_string e) in
          let code =
            match Marshal.to_channel oc result []; flush oc with
            | () -> 0
            | exception Invalid_argument m ->
                (* A function in the result: nothing of it was written. *)
                (match Marshal.to_channel oc (Error ("could not send its result: " ^ m) : (unit, string) result) []; flush oc with
                | () -> 0
                | exception _ -> 2)
            | exception _ -> 2
          in
          Unix._exit code
      | pid ->
          close_quietly w;
          let waited = ref false in
          let t0 = Unix.gettimeofday () and c0 = cpu_self () in
          let taken_over () =
            take_over
            && (match Unix.select [ r ] [] [] 0. with [], _, _ -> true | _ -> false | exception Unix.Unix_error _ -> false)
            &&
            match cpu_of pid with
            | Some theirs when late ~mine:(cpu_self () -. c0) ~theirs ~wall:(Unix.gettimeofday () -. t0) ->
                (try Unix.kill pid Sys.sigkill with Unix.Unix_error _ -> ());
                close_quietly r;
                let rec reap () =
                  match Unix.waitpid [] pid with _ -> () | exception Unix.Unix_error (EINTR, _, _) -> reap ()
                in
                (try reap () with Unix.Unix_error _ -> ());
                true
            | _ -> false
          in
          fun () ->
            if !waited then invalid_arg "Parallel.beside: waited for twice";
            waited := true;
            if taken_over () then (match f () with v -> Ok v | exception e -> Error (`Msg (Printexc.to_string e)))
            else
            let ic = Unix.in_channel_of_descr r in
            let sent = match Marshal.from_channel ic with v -> Some v | exception (End_of_file | Failure _) -> None in
            close_in_noerr ic;
            let rec reap () =
              match Unix.waitpid [] pid with
              | _, status -> status
              | exception Unix.Unix_error (EINTR, _, _) -> reap ()
            in
            let status = match reap () with s -> Some s | exception Unix.Unix_error _ -> None in
            match (sent, status) with
            | Some (Ok v), _ -> Ok v
            | Some (Error m), _ -> Error (`Msg ("the child process " ^ m))
            | None, Some (Unix.WEXITED 0) | None, None -> Error (`Msg "the child process sent no result")
            | None, Some s -> Error (`Msg ("the child process " ^ describe_status s)))

(* Workers report finished tasks on a pipe, 4 bytes a task: writes of
   fewer than PIPE_BUF bytes are atomic, so the pipe always holds whole
   indices. A read or write is a system call, which orders memory: what a
   worker wrote before reporting a task is visible to the parent once it has
   read the index. The parent keeps the write end open, so the read end
   never reads as ended; it is non-blocking, to be drained. *)
type reports = { from_workers : Unix.file_descr; to_parent : Unix.file_descr; index : Bytes.t; read_buffer : Bytes.t }

let reports () =
  let r, w = Unix.pipe ~cloexec:true () in
  Unix.set_nonblock r;
  { from_workers = r; to_parent = w; index = Bytes.create 4; read_buffer = Bytes.create 4096 }

(* Byte by byte: a boxed [Int32] would be an allocation per task. *)
let rec report t task =
  for k = 0 to 3 do
    Bytes.unsafe_set t.index k (Char.unsafe_chr ((task lsr (8 * k)) land 0xff))
  done;
  match Unix.write t.to_parent t.index 0 4 with
  | _ -> ()
  | exception Unix.Unix_error (EINTR, _, _) -> report t task

let rec drain t f =
  match Unix.read t.from_workers t.read_buffer 0 (Bytes.length t.read_buffer) with
  | n when n > 0 ->
      for k = 0 to (n / 4) - 1 do
        f (Int32.to_int (Bytes.get_int32_le t.read_buffer (4 * k)))
      done;
      drain t f
  | _ -> ()
  | exception Unix.Unix_error ((EAGAIN | EWOULDBLOCK), _, _) -> ()
  | exception Unix.Unix_error (EINTR, _, _) -> drain t f

let close_reports t =
  close_quietly t.from_workers;
  close_quietly t.to_parent

let run ?tick ?reports n work =
  flush stdout;
  flush stderr;
  let me = Unix.getpid () in
  let pids = Array.make n 0 in
  let done_ = Array.make n false in
  let kill_live () =
    Array.iteri
      (fun w pid -> if pid > 0 && not done_.(w) then try Unix.kill pid Sys.sigkill with Unix.Unix_error _ -> ())
      pids
  in
  let reap_live () =
    Array.iteri
      (fun w pid ->
        if pid > 0 && not done_.(w) then begin
          (try ignore (Unix.waitpid [] pid) with Unix.Unix_error _ -> ());
          done_.(w) <- true
        end)
      pids
  in
  let fds = Array.init n (fun _ -> Unix.pipe ~cloexec:true ()) in
  let close_pipes () = Array.iter (fun (r, w) -> close_quietly r; close_quietly w) fds in
  let first_error = ref None in
  let fail m =
    if !first_error = None then begin
      first_error := Some m;
      (* The image is lost anyway: stop the others now. *)
      kill_live ()
    end
  in
  (* Interrupted: no worker may outlive the parent. *)
  Signals.protect ~cleanup:(fun () -> kill_live (); reap_live ()) (fun () ->
      (try
         for w = 0 to n - 1 do
           match Unix.fork () with 0 -> child work w me fds | pid -> pids.(w) <- pid
         done
       with Unix.Unix_error (e, _, _) ->
         fail (Printf.sprintf "cannot start worker processes: %s" (Unix.error_message e));
         Array.iteri (fun w pid -> if pid = 0 then done_.(w) <- true) pids);
      Array.iter (fun (_, wr) -> close_quietly wr) fds;
      (* Not waited for in order, so that a dead worker is noticed at once
         even while the others still run: a worker's pipe becomes readable
         (end of file) when it exits, however it exits, which wakes
         [select]; then the exited workers are reaped. *)
      let rec wait () =
        let progress = ref false in
        Array.iteri
          (fun w pid ->
            if not done_.(w) then
              match Unix.waitpid [ WNOHANG; WUNTRACED ] pid with
              | 0, _ -> ()
              | _, Unix.WSTOPPED _ ->
                  (* Stopped (SIGSTOP, or SIGTSTP to it alone): the render
                     would wait for it for ever. It is continued; after a
                     Ctrl-Z that stopped us all, the extra SIGCONT is
                     harmless. *)
                  (try Unix.kill pid Sys.sigcont with Unix.Unix_error _ -> ())
              | _, Unix.WEXITED 0 ->
                  done_.(w) <- true;
                  progress := true
              | _, status ->
                  done_.(w) <- true;
                  progress := true;
                  let detail =
                    match (status, read_message (fst fds.(w))) with
                    | Unix.WEXITED _, Some m -> describe_status status ^ ": " ^ m
                    | _ -> describe_status status
                  in
                  fail (Printf.sprintf "worker %d of %d %s" (w + 1) n detail)
              | exception Unix.Unix_error (EINTR, _, _) -> ()
              | exception Unix.Unix_error (e, _, _) ->
                  done_.(w) <- true;
                  fail (Printf.sprintf "worker %d of %d was lost: %s" (w + 1) n (Unix.error_message e)))
          pids;
        if Array.exists not done_ then begin
          if not !progress then begin
            let live = List.filter_map (fun w -> if done_.(w) then None else Some (fst fds.(w))) (List.init n Fun.id) in
            let live = match reports with Some (t, _) -> t.from_workers :: live | None -> live in
            (* [select] takes descriptors below 1024 only: with more than 256
               workers (two descriptors each while they start), poll. *)
            (* With a [tick], wake up often enough to call it a few
               times a second. *)
            let timeout = match tick with None -> 1. | Some _ -> 0.1 in
            try if n <= 256 then ignore (Unix.select live [] [] timeout) else Unix.sleepf 0.005
            with Unix.Unix_error (EINTR, _, _) -> ()
          end;
          Option.iter (fun (t, f) -> drain t f) reports;
          Option.iter (fun tick -> tick ()) tick;
          wait ()
        end
        else
          (* What the workers reported before they exited. *)
          Option.iter (fun (t, f) -> drain t f) reports
      in
      Fun.protect ~finally:close_pipes wait);
  match !first_error with None -> Ok () | Some m -> Error (`Msg m)

(* A pipe filled with the task indices, 4 bytes each, before the workers
   start, its write end closed: a read of 4 bytes from a pipe that holds a
   multiple of 4 bytes takes exactly one index, atomically, whatever the
   number of readers; end of file means no task is left. *)
type queue = { read_end : Unix.file_descr; buffer : Bytes.t }

let max_tasks = 16384

let queue m =
  if m < 0 || m > max_tasks then invalid_arg (Printf.sprintf "Parallel.queue: %d tasks" m);
  let r, w = Unix.pipe ~cloexec:true () in
  let data = Bytes.create (4 * m) in
  for t = 0 to m - 1 do
    Bytes.set_int32_le data (4 * t) (Int32.of_int t)
  done;
  let rec write off =
    if off < Bytes.length data then write (off + Unix.write w data off (Bytes.length data - off))
  in
  Fun.protect ~finally:(fun () -> Unix.close w) (fun () -> write 0);
  { read_end = r; buffer = Bytes.create 4 }

let rec take q =
  match Unix.read q.read_end q.buffer 0 4 with
  | 4 -> Int32.to_int (Bytes.get_int32_le q.buffer 0)
  | _ -> -1
  | exception Unix.Unix_error (EINTR, _, _) -> take q

let close_queue q = close_quietly q.read_end
