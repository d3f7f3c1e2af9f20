(* Outputs that must not destroy inputs, output channels that fail, and
   signals (issue 11, classes 1, 4 and 5). Every case runs the real
   program. *)

let exe () = Helpers.raytrace ()
let read = In_channel_free.read

let write path text =
  let oc = open_out_bin path in
  output_string oc text;
  close_out oc

let command args = String.concat " " (List.map Filename.quote args)
let sh script = Helpers.run "/bin/sh" [ "-c"; script ]

let one_line what err =
  match String.split_on_char '\n' (String.trim err) with
  | [ l ] when String.length l > 10 && String.sub l 0 10 = "raytrace: " -> ()
  | _ -> Alcotest.failf "%s: expected one line on stderr, got:\n%S" what err

let small = [ "--width"; "4"; "--height"; "4" ]
let image_4x4 () = Helpers.run (exe ()) ([ "render" ] @ small @ [ "-o"; "-" ]) |> fun (_, out, _) -> out

(* A directory with a scene, a part and an image in it. *)
let workspace () =
  let dir = Helpers.temp_dir () in
  let path f = Filename.concat dir f in
  write (path "s.scene") (read (Helpers.scene_path "cgfs.scene"));
  let code, _, err = Helpers.run (exe ()) ([ "render"; path "s.scene"; "--tile"; "1/1" ] @ small @ [ "-o"; path "p.ppm" ]) in
  if code <> 0 then Alcotest.failf "part: %s" err;
  write (path "i.ppm") (image_4x4 ());
  (dir, path)

(* [args] is refused with [expected] (a substring), and no file of [dir]
   changed; none was added. *)
let refused dir what ?(script = false) args expected =
  let snapshot () =
    Sys.readdir dir |> Array.to_list |> List.sort compare
    |> List.map (fun f ->
           let p = Filename.concat dir f in
           (f, if Sys.is_directory p then "dir" else read p))
  in
  let before = snapshot () in
  let code, _, err = if script then sh (String.concat " " args) else Helpers.run (exe ()) args in
  Alcotest.(check int) (what ^ ": status") 1 code;
  one_line what err;
  if not (Astring_free.contains err expected) then Alcotest.failf "%s: expected %S in %S" what expected err;
  if snapshot () <> before then Alcotest.failf "%s: the files of %s changed" what dir

let no_output_destroys_an_input () =
  let dir, path = workspace () in
  Unix.link (path "s.scene") (path "hard.scene");
  Unix.mkdir (path "sub") 0o755;
  Unix.symlink dir (path "sub/up");
  Unix.symlink (path "p.ppm") (path "part-link.ppm");
  Unix.mkdir (path "f0") 0o755;
  Unix.mkdir (path "f1") 0o755;
  let scene = path "s.scene" in
  let input_scene = "the output file is the input scene" in
  refused dir "a hard link to the scene" [ "render"; scene; "-o"; path "hard.scene" ] input_scene;
  refused dir "the scene through .." [ "render"; scene; "-o"; path "sub/../s.scene" ] input_scene;
  refused dir "the scene through a linked directory" [ "render"; scene; "-o"; path "sub/up/s.scene" ] input_scene;
  refused dir "the scene as a frame"
    [ "render"; Helpers.scene_path "orbit.scene"; "--frames"; "0:1"; "-o"; path "f%d/../o.ppm" ]
    "frame 0 and frame 1 would be written to the same file";
  refused dir "a part as the merged image" [ "merge"; path "p.ppm"; "-o"; path "part-link.ppm" ]
    "the output file is the input part";
  refused dir "stdout appended to the scene" ~script:true
    [ command [ exe (); "render"; scene; "-o"; "-" ]; ">>"; Filename.quote scene ]
    "standard output: the output file is the input scene";
  refused dir "stdout appended to an image given to diff" ~script:true
    [ command [ exe (); "diff"; path "i.ppm"; path "i.ppm" ]; ">>"; Filename.quote (path "i.ppm") ]
    "standard output: the output file is the input image";
  refused dir "/dev/stdout appended to a part" ~script:true
    [ command [ exe (); "merge"; path "p.ppm"; "-o"; "/dev/stdout" ]; ">>"; Filename.quote (path "p.ppm") ]
    "/dev/stdout: the output file is the input part"

(* A scene's mesh is an input like the scene: no render, frame or part
   may replace it, by any name. *)
let no_output_replaces_a_mesh () =
  let dir = Helpers.temp_dir () in
  let path f = Filename.concat dir f in
  write (path "frame-0001.obj") "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n";
  Unix.mkdir (path "sub") 0o755;
  write (path "sub/s.scene")
    "(canvas (width 4) (height 4))\n\
     (camera-path (key (frame 0) (position 0 0 -1) (look-at 0 0 3)) (key (frame 2) (position 1 0 -1) (look-at 0 0 3)))\n\
     (mesh (file \"../frame-0001.obj\") (color 255 0 0) (translate 0 0 3))\n\
     (light ambient (intensity 1))\n";
  Unix.symlink (path "frame-0001.obj") (path "link.obj");
  Unix.link (path "frame-0001.obj") (path "hard.obj");
  let scene = path "sub/s.scene" in
  let input_mesh = "the output file is the input mesh; choose another output path" in
  refused dir "the mesh by its name" [ "render"; scene; "-o"; path "frame-0001.obj" ] (path "frame-0001.obj: " ^ input_mesh);
  refused dir "the mesh through a symbolic link" [ "render"; scene; "-o"; path "link.obj" ] input_mesh;
  refused dir "the mesh through a hard link" [ "render"; scene; "-o"; path "hard.obj" ] input_mesh;
  refused dir "the mesh through .." [ "render"; scene; "-o"; path "sub/../frame-0001.obj" ] input_mesh;
  refused dir "the mesh as a part" [ "render"; scene; "--tile"; "1/2"; "-o"; path "hard.obj" ] input_mesh;
  refused dir "the mesh as frame 1"
    [ "render"; scene; "--frames"; "0:2"; "-o"; path "frame-%04d.obj" ]
    (path "frame-0001.obj: " ^ input_mesh);
  refused dir "stdout appended to the mesh" ~script:true
    [ command [ exe (); "render"; scene; "-o"; "-" ]; ">>"; Filename.quote (path "hard.obj") ]
    ("standard output: " ^ input_mesh)

let special_files_are_written_to () =
  let dir = Helpers.temp_dir () in
  let log = Filename.concat dir "log" in
  let image = image_4x4 () in
  List.iter
    (fun target ->
      write log "old\n";
      let inode = (Unix.stat log).st_ino in
      let code, _, err = sh (command ([ exe (); "render" ] @ small @ [ "-o"; target ]) ^ " >> " ^ Filename.quote log) in
      Alcotest.(check int) (target ^ ": " ^ err) 0 code;
      Alcotest.(check string) (target ^ " after >>: the old lines kept, the image appended") ("old\n" ^ image) (read log);
      Alcotest.(check int) (target ^ ": the same file, not a new one") inode (Unix.stat log).st_ino;
      let code, _, err = sh (command ([ exe (); "render" ] @ small @ [ "-o"; target ]) ^ " > " ^ Filename.quote log) in
      Alcotest.(check int) (target ^ ": " ^ err) 0 code;
      Alcotest.(check string) (target ^ " after >") image (read log);
      Alcotest.(check int) (target ^ ": the same file, not a new one") inode (Unix.stat log).st_ino)
    [ "-"; "/dev/stdout"; "/proc/self/fd/1" ];
  (* Two frames to a stream are written in turn. *)
  let code, out, err =
    Helpers.run (exe ()) ([ "render"; Helpers.scene_path "orbit.scene"; "--frames"; "0:1" ] @ small @ [ "-o"; "/dev/stdout" ])
  in
  Alcotest.(check int) err 0 code;
  Alcotest.(check int) "two images" (2 * String.length image) (String.length out);
  let fifo = Filename.concat dir "fifo" in
  Unix.mkfifo fifo 0o600;
  let got = Filename.concat dir "got" in
  let code, _, err =
    sh (Printf.sprintf "cat %s > %s & %s; s=$?; wait; exit $s" (Filename.quote fifo) (Filename.quote got)
          (command ([ exe (); "render" ] @ small @ [ "-o"; fifo ])))
  in
  Alcotest.(check int) err 0 code;
  Alcotest.(check string) "through the FIFO" image (read got);
  Alcotest.(check bool) "still a FIFO" true ((Unix.stat fifo).st_kind = S_FIFO)

(* Each command with its stdout [fault]: [`Full] (/dev/full), [`Closed]
   (>&-) or [`Broken] (a pipe whose reader is gone). *)
let with_stdout fault args =
  let err = Filename.temp_file "rt" ".err" in
  let fd_err = Unix.openfile err [ O_WRONLY; O_TRUNC ] 0o600 in
  flush stdout;
  flush stderr;
  let pid =
    match Unix.fork () with
    | 0 -> (
        try
          Unix.dup2 fd_err Unix.stderr;
          (match fault with
          | `Full -> Unix.dup2 (Unix.openfile "/dev/full" [ O_WRONLY ] 0) Unix.stdout
          | `Closed -> Unix.close Unix.stdout
          | `Broken ->
              let r, w = Unix.pipe () in
              Unix.close r;
              Unix.dup2 w Unix.stdout);
          Unix.execv (exe ()) (Array.of_list (exe () :: args))
        with _ -> Unix._exit 99)
    | pid -> pid
  in
  Unix.close fd_err;
  let _, status = Unix.waitpid [] pid in
  let text = read err in
  Sys.remove err;
  (status, text)

let every_channel_fails_cleanly () =
  let dir, path = workspace () in
  ignore dir;
  let commands =
    [
      [ "--help" ]; [ "--version" ]; [ "render"; "--help" ]; [ "merge"; "--help=plain" ]; [ "diff"; "--help=groff" ];
      [ "render"; "--width"; "300"; "--height"; "300"; "-o"; "-" ];
      [ "render"; path "s.scene"; "--tile"; "1/1"; "--width"; "8"; "--height"; "8"; "-o"; "/dev/stdout" ];
      [ "merge"; path "p.ppm"; "-o"; "-" ]; [ "diff"; path "i.ppm"; path "i.ppm" ];
    ]
  in
  List.iter
    (fun args ->
      List.iter
        (fun (fault, name, reason) ->
          let what = name ^ " " ^ String.concat " " args in
          let status, err = with_stdout fault args in
          match fault with
          | `Broken ->
              (* A reader gone is normal on a pipeline: the command ends as
                 Unix tools do there, by SIGPIPE (141 in the shell), quietly. *)
              if status <> Unix.WSIGNALED Sys.sigpipe then Alcotest.failf "%s: not ended by SIGPIPE; stderr %S" what err;
              Alcotest.(check string) (what ^ ": nothing on stderr") "" err
          | `Full | `Closed ->
              if status <> Unix.WEXITED 1 then Alcotest.failf "%s: status not 1; stderr %S" what err;
              one_line what err;
              (* "standard output: ...", or the name given, "/dev/stdout: ..." *)
              let expected = ": " ^ reason in
              if not (Astring_free.contains err expected) then Alcotest.failf "%s: expected %S in %S" what expected err)
        [ (`Full, "stdout /dev/full", "No space left on device"); (`Closed, "stdout closed", "Bad file descriptor");
          (`Broken, "stdout a broken pipe", "") ])
    commands;
  (* stderr closed or full: the commands still work, and say nothing. *)
  List.iter
    (fun redirect ->
      let out = Filename.concat dir "o.ppm" in
      let code, stdout, _ =
        sh (command [ exe (); "render"; path "s.scene"; "--width"; "4"; "--height"; "4"; "-o"; out ] ^ " " ^ redirect ^ "; echo $?")
      in
      Alcotest.(check int) __LOC__ 0 code;
      Alcotest.(check string) redirect "0\n" stdout;
      Alcotest.(check string) (redirect ^ ": the image") (image_4x4 ()) (read out);
      let _, stdout, _ = sh (command [ exe (); "render"; "--width"; "x" ] ^ " " ^ redirect ^ "; echo $?") in
      Alcotest.(check string) (redirect ^ ": a bad command line") "124\n" stdout)
    [ "2>&-"; "2>/dev/full"; "2>&- 0<&-" ]

(* The workers of a render started in the background, once both run. *)
let terminating =
  Sys.
    [
      (sigint, "INT"); (sigterm, "TERM"); (sighup, "HUP"); (sigquit, "QUIT"); (sigusr1, "USR1"); (sigusr2, "USR2");
      (sigalrm, "ALRM"); (sigxcpu, "XCPU"); (sigxfsz, "XFSZ"); (sigvtalrm, "VTALRM"); (sigprof, "PROF");
    ]

let spawn_render args =
  let err = Filename.temp_file "rt" ".err" in
  let fd = Unix.openfile err [ O_WRONLY; O_TRUNC ] 0o600 in
  (* Every signal at its default action in the render, even if the tests
     run in a background job, which ignores SIGINT, or under nohup, which
     ignores SIGHUP: an ignored signal stays ignored across exec, and the
     render rightly keeps it so. *)
  let previous = List.map (fun (signal, _) -> (signal, Sys.signal signal Sys.Signal_default)) terminating in
  let pid =
    Fun.protect
      ~finally:(fun () -> List.iter (fun (signal, p) -> Sys.set_signal signal p) previous)
      (fun () ->
        (* Through a shell that sets no core file (SIGQUIT dumps one) and
           then becomes raytrace, with the same pid. *)
        Unix.create_process "/bin/sh"
          [| "/bin/sh"; "-c"; "ulimit -c 0; exec " ^ command (exe () :: args) |]
          Unix.stdin Unix.stdout fd)
  in
  Unix.close fd;
  let children () =
    match read (Printf.sprintf "/proc/%d/task/%d/children" pid pid) with
    | text -> String.split_on_char ' ' (String.trim text) |> List.filter_map int_of_string_opt
    | exception Sys_error _ -> []
  in
  let rec workers tries =
    match children () with
    | [ _; _ ] as w -> w
    | _ when tries = 0 -> Alcotest.fail "the render did not start 2 workers"
    | _ ->
        Unix.sleepf 0.005;
        workers (tries - 1)
  in
  (pid, err, workers 4000)

let gone pid =
  match read (Printf.sprintf "/proc/%d/stat" pid) with
  | stat -> (
      match String.rindex_opt stat ')' with Some i -> stat.[i + 2] = 'Z' | None -> true)
  | exception Sys_error _ -> true

let none_left what dir workers =
  let rec go tries =
    if not (List.for_all gone workers) then
      if tries = 0 then Alcotest.failf "%s: a worker still runs" what
      else (
        Unix.sleepf 0.01;
        go (tries - 1))
  in
  go 500;
  Alcotest.(check (list string)) (what ^ ": files left") [ "out.ppm" ] (List.sort compare (Array.to_list (Sys.readdir dir)));
  Alcotest.(check string) (what ^ ": old file kept") "old\n" (read (Filename.concat dir "out.ppm"))

let long_render dir = [ "render"; "--width"; "4000"; "--height"; "4000"; "--jobs"; "2"; "-o"; Filename.concat dir "out.ppm" ]

let fresh () =
  let dir = Helpers.temp_dir () in
  write (Filename.concat dir "out.ppm") "old\n";
  dir

let every_signal_to_the_parent () =
  List.iter
    (fun (signal, name) ->
      let dir = fresh () in
      let pid, err, workers = spawn_render (long_render dir) in
      Unix.kill pid signal;
      let _, status = Unix.waitpid [] pid in
      if status <> Unix.WSIGNALED signal then Alcotest.failf "SIG%s: not ended by it; stderr %S" name (read err);
      (* Reaped by the parent before it ended, not left to notice it. *)
      if not (List.for_all gone workers) then Alcotest.failf "SIG%s: the workers outlived the parent" name;
      none_left ("SIG" ^ name) dir workers)
    terminating;
  (* SIGPIPE is ignored on purpose (a broken pipe is an error message):
     the render goes on, and SIGTERM then ends it as usual. *)
  let dir = fresh () in
  let pid, _, workers = spawn_render (long_render dir) in
  Unix.kill pid Sys.sigpipe;
  Unix.sleepf 0.2;
  Alcotest.(check bool) "alive after SIGPIPE" false (gone pid);
  Unix.kill pid Sys.sigterm;
  let _, status = Unix.waitpid [] pid in
  Alcotest.(check bool) "then ended by SIGTERM" true (status = Unix.WSIGNALED Sys.sigterm);
  none_left "SIGPIPE" dir workers

(* The signal arrives while the temporary file is half written: the
   process ends by it, the old file stays, the temporary is gone. *)
let every_signal_while_writing () =
  List.iter
    (fun (signal, name) ->
      let dir = fresh () in
      flush stdout;
      flush stderr;
      match Unix.fork () with
      | 0 ->
          (* As the program starts: not ignored, even in a background job. *)
          Sys.set_signal signal Sys.Signal_default;
          ignore
            (Raytrace_unix.File_io.write_atomic (Filename.concat dir "out.ppm") (fun oc ->
                 output_string oc "new, half written";
                 Unix.kill (Unix.getpid ()) signal;
                 output_string oc " and the rest"));
          Unix._exit 0
      | child ->
          let _, status = Unix.waitpid [] child in
          if status <> Unix.WSIGNALED signal then Alcotest.failf "SIG%s: the writer was not ended by it" name;
          none_left ("SIG" ^ name ^ " while writing") dir [])
    (* SIGXFSZ is ignored while writing (a size limit is an error);
       SIGQUIT would dump a core of this test process. *)
    (List.filter (fun (s, _) -> s <> Sys.sigxfsz && s <> Sys.sigquit) terminating)

let every_signal_to_a_worker () =
  List.iter
    (fun (signal, name) ->
      let dir = fresh () in
      let pid, err, workers = spawn_render (long_render dir) in
      Unix.kill (List.nth workers 1) signal;
      let _, status = Unix.waitpid [] pid in
      let err = read err in
      Alcotest.(check bool) (name ^ ": status 1") true (status = Unix.WEXITED 1);
      Alcotest.(check string) name (Printf.sprintf "raytrace: worker 2 of 2 was killed by SIG%s\n" name) err;
      none_left ("SIG" ^ name ^ " to a worker") dir workers)
    (List.filter (fun (s, _) -> s <> Sys.sigquit) terminating)

let a_stopped_worker_is_continued () =
  let dir = fresh () in
  let out = Filename.concat dir "out.ppm" in
  let pid, err, workers = spawn_render [ "render"; "--width"; "1500"; "--height"; "1500"; "--jobs"; "2"; "-o"; out ] in
  Unix.kill (List.hd workers) Sys.sigstop;
  (* Before, the parent waited for ever; 120 s is far beyond the render. *)
  let rec wait tries =
    match Unix.waitpid [ WNOHANG ] pid with
    | 0, _ when tries = 0 ->
        List.iter (fun p -> try Unix.kill p Sys.sigkill with Unix.Unix_error _ -> ()) (pid :: workers);
        ignore (Unix.waitpid [] pid);
        Alcotest.fail "the render hangs on its stopped worker"
    | 0, _ ->
        Unix.sleepf 0.05;
        wait (tries - 1)
    | _, status -> status
  in
  let status = wait 2400 in
  Alcotest.(check bool) ("finished: " ^ read err) true (status = Unix.WEXITED 0);
  Alcotest.(check string) __LOC__ "P6\n1500 1500\n255\n" (String.sub (read out) 0 17)

let tests =
  [
    Alcotest.test_case "no output is an input or another output, by any name" `Quick no_output_destroys_an_input;
    Alcotest.test_case "no render, frame or part replaces the mesh a scene reads, by any name" `Quick no_output_replaces_a_mesh;
    Alcotest.test_case "stdout, /dev/stdout and FIFOs are written to, never replaced" `Quick special_files_are_written_to;
    Alcotest.test_case "render -o - | head -c 10 ends quietly, by SIGPIPE, as Unix tools do" `Quick (fun () ->
        (* 300 x 300 x 3 bytes: more than the pipe holds, so the write
           meets the reader gone. *)
        let code, out, err =
          sh
            ("(" ^ command [ exe (); "render"; "--width"; "300"; "--height"; "300"; "-o"; "-" ]
           ^ "; echo \"status $?\" >&2) | head -c 10")
        in
        Alcotest.(check int) __LOC__ 0 code;
        Alcotest.(check string) "what head read" "P6\n300 300" out;
        Alcotest.(check string) "no message; the shell's status for SIGPIPE" "status 141\n" err);
    Alcotest.test_case "a full, closed or broken stdout or stderr is one line for every command" `Quick
      every_channel_fails_cleanly;
    Alcotest.test_case "every terminating signal to the parent leaves no file and no worker" `Quick
      every_signal_to_the_parent;
    Alcotest.test_case "every terminating signal while the file is written leaves the old file" `Quick
      every_signal_while_writing;
    Alcotest.test_case "every terminating signal to a worker fails the render in one line" `Quick
      every_signal_to_a_worker;
    Alcotest.test_case "a stopped worker is continued, not waited for forever" `Quick a_stopped_worker_is_continued;
  ]
