(* The progress line of `raytrace render`: shown on a terminal (a
   pseudo-terminal made by util-linux's `script`), rewritten in place and
   erased at the end, with the same image as without it; absent when stderr
   is not a terminal and with --quiet. The line appears after a fifth of a
   second here (RAYTRACE_PROGRESS_AFTER), not after one: renders of about a
   second are enough, on a fast machine too. *)

let exe () = Helpers.raytrace ()

let env () = Array.append [| "RAYTRACE_PROGRESS_AFTER=0.2" |] (Unix.environment ())

(* Without `script` there is no pseudo-terminal to test on. *)
let with_script f () =
  match Helpers.missing [ "script" ] with
  | [] -> f ()
  | _ -> Helpers.skip "progress: a terminal" ~why:"script (util-linux) is not installed: no pseudo-terminal to test on"

(* [on_terminal args] runs raytrace with [args] with stdout and stderr on a
   pseudo-terminal, and is its status and what the terminal received. *)
let on_terminal args =
  let command = String.concat " " (List.map Filename.quote (exe () :: args)) in
  let code, out, err = Helpers.run ~env:(env ()) "script" [ "-qec"; command; "/dev/null" ] in
  if err <> "" then Alcotest.failf "script wrote on stderr: %s" err;
  (code, out)

let contains s sub =
  let n = String.length s and k = String.length sub in
  let rec at i = i + k <= n && (String.sub s i k = sub || at (i + 1)) in
  at 0

let read_file path =
  match Raytrace_unix.File_io.read path with Ok s -> s | Error (`Msg m) -> Alcotest.fail m

(* A progress line: "\rraytrace: 42%, 12.3 M rays/s, 2 s left". *)
let check_progress_shown what out =
  let lines = String.split_on_char '\r' out in
  let progress = List.map String.trim (List.filter (fun l -> contains l "rays/s") lines) in
  if progress = [] then Alcotest.failf "%s: no progress line in %S" what out;
  List.iter
    (fun l ->
      match Scanf.sscanf l "raytrace: %d%%, %f M rays/s, %[^\n]" (fun p r rest -> (p, r, rest)) with
      | p, r, rest ->
          if p < 0 || p > 100 || r <= 0. || not (contains rest " left") then
            Alcotest.failf "%s: a progress line of %d%% at %g M rays/s: %S" what p r l
      | exception (Scanf.Scan_failure _ | Failure _ | End_of_file) -> Alcotest.failf "%s: not a progress line: %S" what l)
    progress;
  (* Erased before the line that says what was written: spaces, then a
     carriage return. *)
  if not (contains out "    \rraytrace: wrote") then Alcotest.failf "%s: the progress line is not erased: %S" what out;
  progress

let render_both ~what args outputs =
  let dir = Helpers.temp_dir () in
  let path name = Filename.concat dir name in
  let args which = List.map (fun a -> if a = "OUT" then path (which ^ "-%d.ppm") else a) args in
  let code, out = on_terminal (args "tty") in
  Alcotest.(check int) (what ^ ": status on a terminal") 0 code;
  let progress = check_progress_shown what out in
  let code, stdout, stderr = Helpers.run ~env:(env ()) (exe ()) (args "plain") in
  Alcotest.(check int) (what ^ ": status without a terminal") 0 code;
  Alcotest.(check string) (what ^ ": stdout without a terminal") "" stdout;
  (* Without a terminal, exactly what was printed before progress existed:
     one line per file written. *)
  let lines = String.split_on_char '\n' stderr in
  Alcotest.(check int) (what ^ ": lines on stderr without a terminal") (List.length outputs + 1) (List.length lines);
  List.iter2
    (fun line f ->
      let expected = "raytrace: wrote " ^ path ("plain-" ^ f) in
      if String.length line < String.length expected || String.sub line 0 (String.length expected) <> expected then
        Alcotest.failf "%s: expected %S..., got %S" what expected line)
    (List.filteri (fun i _ -> i < List.length outputs) lines)
    outputs;
  if String.contains stderr '\r' then Alcotest.failf "%s: a carriage return without a terminal: %S" what stderr;
  List.iter
    (fun f ->
      if read_file (path ("tty-" ^ f)) <> read_file (path ("plain-" ^ f)) then
        Alcotest.failf "%s: %s differs with the progress line" what f)
    outputs;
  (dir, progress)

let tests =
  [
    Alcotest.test_case "a long render shows its progress on a terminal, and the same image" `Slow
      (with_script (fun () ->
           let args = [ "render"; Helpers.scene_path "cgfs.scene"; "--width"; "600"; "--height"; "600"; "--samples"; "3"; "--jobs"; "1"; "-o"; "OUT" ] in
           ignore (render_both ~what:"1 job, 3 x 3 samples" args [ "%d.ppm" ])));
    Alcotest.test_case "progress works with jobs, frames, tiles and adaptive sampling" `Slow
      (with_script (fun () ->
           let args =
             [ "render"; Helpers.scene_path "orbit.scene"; "--width"; "1200"; "--height"; "1200"; "--samples"; "5";
               "--adaptive"; "0"; "--jobs"; "2"; "--frames"; "0:1"; "--tile"; "1/2"; "-o"; "OUT" ]
           in
           let _, progress = render_both ~what:"2 jobs, 2 frames, a tile" args [ "0.ppm"; "1.ppm" ] in
           List.iter
             (fun l -> if not (contains l " of 2)") then Alcotest.failf "no frame count in %S" l)
             progress));
    Alcotest.test_case "--quiet shows nothing on a terminal" `Slow
      (with_script (fun () ->
           let dir = Helpers.temp_dir () in
           let out = Filename.concat dir "q.ppm" in
           let code, printed =
             on_terminal [ "render"; "--quiet"; "--width"; "600"; "--height"; "600"; "--samples"; "3"; "--jobs"; "1"; "-o"; out ]
           in
           Alcotest.(check int) __LOC__ 0 code;
           Alcotest.(check string) __LOC__ "" printed;
           Alcotest.(check bool) "the image is written" true (Sys.file_exists out)));
  ]
