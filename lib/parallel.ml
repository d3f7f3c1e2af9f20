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

let cores () =
  let from_status () =
    match File_io.read "/proc/self/status" with
    | Error _ -> None
    | Ok text ->
        String.split_on_char '\n' text
        |> List.find_map (fun line ->
               match String.index_opt line ':' with
               | Some i when String.sub line 0 i = "Cpus_allowed_list" ->
                   let n = count_cpu_list (String.sub line (i + 1) (String.length line - i - 1)) in
                   if n > 0 then Some n else None
               | _ -> None)
  in
  match from_status () with Some n -> n | None -> 1

(* "MemAvailable:   12345678 kB" -> 12345678 * 1024 *)
let available_memory () =
  match File_io.read "/proc/meminfo" with
  | Error _ -> None
  | Ok text ->
      String.split_on_char '\n' text
      |> List.find_map (fun line ->
             match String.split_on_char ':' line with
             | [ "MemAvailable"; v ] -> (
                 match String.split_on_char ' ' (String.trim v) with
                 | [ n; "kB" ] -> Option.map (fun k -> k * 1024) (int_of_string_opt n)
                 | _ -> None)
             | _ -> None)

let map_shared kind n =
  (* A file in memory-backed /dev/shm when there is one, unlinked at once:
     the mapping outlives the name. *)
  let dir = if Sys.file_exists "/dev/shm" then "/dev/shm" else Filename.get_temp_dir_name () in
  let path = Filename.temp_file ~temp_dir:dir "raytrace" ".shm" in
  let fd = Unix.openfile path [ O_RDWR; O_CLOEXEC ] 0o600 in
  Fun.protect
    ~finally:(fun () ->
      Unix.close fd;
      try Sys.remove path with Sys_error _ -> ())
    (fun () ->
      Bigarray.array1_of_genarray (Unix.map_file fd kind Bigarray.c_layout true [| max 1 n |]))

let shared_bytes n = map_shared Bigarray.int8_unsigned n
let shared_ints n = map_shared Bigarray.int64 n

let signal_name s =
  let names =
    Sys.
      [
        (sigkill, "SIGKILL"); (sigterm, "SIGTERM"); (sigint, "SIGINT"); (sigsegv, "SIGSEGV");
        (sigabrt, "SIGABRT"); (sigbus, "SIGBUS"); (sigfpe, "SIGFPE"); (sighup, "SIGHUP");
        (sigquit, "SIGQUIT"); (sigpipe, "SIGPIPE"); (sigusr1, "SIGUSR1"); (sigusr2, "SIGUSR2");
      ]
  in
  match List.assoc_opt s names with Some n -> n | None -> Printf.sprintf "signal %d" s

let describe_status = function
  | Unix.WEXITED c -> Printf.sprintf "exited with status %d" c
  | Unix.WSIGNALED s -> "was killed by " ^ signal_name s
  | Unix.WSTOPPED s -> "was stopped by " ^ signal_name s

let rec wait_pid pid =
  match Unix.waitpid [] pid with
  | _, status -> status
  | exception Unix.Unix_error (EINTR, _, _) -> wait_pid pid

let run n work =
  flush stdout;
  flush stderr;
  let pids =
    Array.init n (fun w ->
        match Unix.fork () with
        | 0 ->
            let code =
              match work w with
              | () -> 0
              | exception e ->
                  prerr_endline ("raytrace worker: " ^ Printexc.to_string e);
                  2
            in
            Unix._exit code
        | pid -> pid)
  in
  let first_error = ref None in
  Array.iteri
    (fun w pid ->
      match wait_pid pid with
      | Unix.WEXITED 0 -> ()
      | status ->
          if !first_error = None then begin
            first_error := Some (Printf.sprintf "worker %d of %d %s" (w + 1) n (describe_status status));
            (* The image is lost anyway: stop the others now. *)
            Array.iter (fun p -> try Unix.kill p Sys.sigterm with Unix.Unix_error _ -> ()) pids
          end)
    pids;
  match !first_error with None -> Ok () | Some m -> Error (`Msg m)
