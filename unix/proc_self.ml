let kb file field =
  match open_in ("/proc/self/" ^ file) with
  | exception Sys_error _ -> None
  | ic ->
      let prefix = field ^ ":" in
      let n = String.length prefix in
      let rec find () =
        match input_line ic with
        | exception End_of_file -> None
        | line when String.length line > n && String.sub line 0 n = prefix -> (
            match Scanf.sscanf (String.sub line n (String.length line - n)) " %d kB" Option.some with
            | r -> r
            | exception (Scanf.Scan_failure _ | Failure _ | End_of_file) -> None)
        | _ -> find ()
      in
      let r = find () in
      close_in_noerr ic;
      r
