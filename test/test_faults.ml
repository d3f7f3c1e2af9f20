(* Faults while rendering and writing, as a user meets them: Ctrl-C and
   kill during a render with worker processes, a worker killed from
   outside, a full disk, a read-only target, a missing directory, a file
   size limit, too little memory. Each must give one clear line and leave
   existing files as they were, with no temporary file and no process left
   behind.

   The tests run as root, which ignores permission bits; a read-only target
   is made in ways that bind root too: a read-only mount and a full
   file system in a private mount namespace ([unshare -rm]), an immutable
   file ([chattr +i]); permission bits are tested as the user nobody
   ([setpriv]). A test whose tool or privilege is missing is skipped
   (Helpers.skip: on the console, and a failure under CI=true). *)

let exe () = Helpers.raytrace ()

let contains what err expected =
  if not (Astring_free.contains err expected) then Alcotest.failf "%s: expected %S in %S" what expected err

let one_line what err =
  match String.split_on_char '\n' (String.trim err) with
  | [ _ ] -> ()
  | _ -> Alcotest.failf "%s: expected one line on stderr, got:\n%s" what err

let write path text =
  let oc = open_out_bin path in
  output_string oc text;
  close_out oc

let read = In_channel_free.read

(* The directory holds exactly [files], and [out.ppm] still says "old". *)
let unchanged what dir files =
  let found = Sys.readdir dir |> Array.to_list |> List.sort String.compare in
  Alcotest.(check (list string)) (what ^ ": files left in the directory") files found;
  if List.mem "out.ppm" files then Alcotest.(check string) (what ^ ": out.ppm kept") "old\n" (read (Filename.concat dir "out.ppm"))

let fresh_dir () =
  let dir = Helpers.temp_dir () in
  write (Filename.concat dir "out.ppm") "old\n";
  dir

(* A shell command as a string, for sh -c: the arguments quoted. *)
let command args = String.concat " " (List.map Filename.quote args)

let sh script = Helpers.run "/bin/sh" [ "-c"; script ]
let fst3 (a, _, _) = a
let available = Helpers.on_path

let skip what why = Helpers.skip ("faults: " ^ what) ~why

(* Whether this user may mount a tmpfs and remount it read-only in a
   private mount namespace: [unshare -rm] alone may work where mounting
   does not (an unprivileged user in gVisor). *)
let private_mounts () =
  fst3 (sh "unshare -rm sh -c 'd=$(mktemp -d) && mount -t tmpfs tmpfs $d && mount -o remount,ro $d' 2>/dev/null") = 0

let no_private_mounts = "unshare -rm cannot mount a tmpfs and remount it read-only here"

(* Starting raytrace in the background, with SIGINT at its default action
   even if this test was started with it ignored (a shell's background
   job). *)
let spawn args =
  let err = Filename.temp_file "rt" ".err" in
  let fd = Unix.openfile err [ O_WRONLY; O_TRUNC ] 0o600 in
  let previous = Sys.signal Sys.sigint Sys.Signal_default in
  let pid =
    Fun.protect
      ~finally:(fun () -> Sys.set_signal Sys.sigint previous)
      (fun () -> Unix.create_process (exe ()) (Array.of_list (exe () :: args)) Unix.stdin Unix.stdout fd)
  in
  Unix.close fd;
  (pid, err)

let children pid =
  match read (Printf.sprintf "/proc/%d/task/%d/children" pid pid) with
  | text -> String.split_on_char ' ' (String.trim text) |> List.filter_map int_of_string_opt
  | exception Sys_error _ -> []

(* Waits up to 10 s for [pid] to have [n] children. *)
let wait_children pid n =
  let rec go tries =
    let c = children pid in
    if List.length c >= n then c
    else if tries = 0 then Alcotest.failf "raytrace did not start %d workers" n
    else (
      Unix.sleepf 0.005;
      go (tries - 1))
  in
  go 2000

(* A process is alive if it exists and is not a zombie. *)
let alive pid =
  match read (Printf.sprintf "/proc/%d/stat" pid) with
  | stat -> (
      match String.rindex_opt stat ')' with
      | Some i when i + 2 < String.length stat -> stat.[i + 2] <> 'Z' && stat.[i + 2] <> 'X'
      | _ -> false)
  | exception Sys_error _ -> false

let none_alive what pids =
  let rec go tries =
    match List.filter alive pids with
    | [] -> ()
    | left when tries = 0 -> Alcotest.failf "%s: workers %s still run" what (String.concat ", " (List.map string_of_int left))
    | _ ->
        Unix.sleepf 0.01;
        go (tries - 1)
  in
  go 500

(* Long enough (seconds) to be interrupted while the workers run. *)
let long_render dir = [ "render"; "--width"; "4000"; "--height"; "4000"; "--jobs"; "2"; "-o"; Filename.concat dir "out.ppm" ]

let interrupted signal name () =
  let dir = fresh_dir () in
  let pid, err = spawn (long_render dir) in
  let workers = wait_children pid 2 in
  Unix.kill pid signal;
  let _, status = Unix.waitpid [] pid in
  (match status with
  | Unix.WSIGNALED s when s = signal -> ()
  | WSIGNALED s -> Alcotest.failf "%s: ended by signal %d" name s
  | WEXITED c -> Alcotest.failf "%s: exited with status %d: %s" name c (read err)
  | WSTOPPED _ -> Alcotest.fail "stopped");
  none_alive name workers;
  unchanged name dir [ "out.ppm" ]

let tests =
  [
    Alcotest.test_case "Ctrl-C during a render with 2 jobs leaves no file and no worker" `Quick
      (interrupted Sys.sigint "SIGINT");
    Alcotest.test_case "SIGTERM during a render with 2 jobs leaves no file and no worker" `Quick
      (interrupted Sys.sigterm "SIGTERM");
    Alcotest.test_case "workers of a parent killed with SIGKILL stop by themselves" `Quick (fun () ->
        let dir = fresh_dir () in
        let pid, _ = spawn (long_render dir) in
        let workers = wait_children pid 2 in
        Unix.kill pid Sys.sigkill;
        ignore (Unix.waitpid [] pid);
        none_alive "SIGKILL" workers;
        unchanged "SIGKILL" dir [ "out.ppm" ]);
    Alcotest.test_case "a worker killed from outside fails the render, no black stripe" `Quick (fun () ->
        let dir = fresh_dir () in
        let pid, err = spawn (long_render dir) in
        let workers = wait_children pid 2 in
        Unix.kill (List.nth workers 1) Sys.sigkill;
        let _, status = Unix.waitpid [] pid in
        Alcotest.(check bool) __LOC__ true (status = Unix.WEXITED 1);
        let err = read err in
        one_line __LOC__ err;
        Alcotest.(check string) __LOC__ "raytrace: worker 2 of 2 was killed by SIGKILL\n" err;
        none_alive "killed worker" workers;
        unchanged "killed worker" dir [ "out.ppm" ]);
    Alcotest.test_case "SIGTERM while the file is written leaves the old file and no temporary" `Quick
      (fun () ->
        let dir = fresh_dir () in
        let path = Filename.concat dir "out.ppm" in
        flush stdout;
        flush stderr;
        match Unix.fork () with
        | 0 ->
            ignore
              (Raytrace_unix.File_io.write_atomic path (fun oc ->
                   output_string oc "new, half written";
                   Unix.kill (Unix.getpid ()) Sys.sigterm;
                   output_string oc " and the rest"));
            Unix._exit 0
        | child ->
            let _, status = Unix.waitpid [] child in
            Alcotest.(check bool) __LOC__ true (status = Unix.WSIGNALED Sys.sigterm);
            unchanged "write interrupted" dir [ "out.ppm" ]);
    Alcotest.test_case "a full disk is one line and leaves the old file" `Quick (fun () ->
        (* /dev/full is written directly (a device); a small tmpfs tests the
           temporary file and the rename. *)
        let code, _, err = Helpers.run (exe ()) [ "render"; "--width"; "8"; "--height"; "8"; "-o"; "/dev/full" ] in
        Alcotest.(check int) __LOC__ 1 code;
        Alcotest.(check string) __LOC__ "raytrace: /dev/full: No space left on device\n" err;
        if not (private_mounts ()) then skip "full tmpfs" no_private_mounts
        else
          let dir = fresh_dir () in
          let out = Filename.concat dir "out.ppm" in
          let code, listing, err =
            sh
              (Printf.sprintf
                 "unshare -rm sh -c 'mount -t tmpfs -o size=16k tmpfs %s && echo old > %s && %s; echo \
                  status $?; ls -A %s; cat %s'"
                 dir out
                 (command [ exe (); "render"; "--width"; "100"; "--height"; "100"; "--jobs"; "1"; "-o"; out ])
                 dir out)
          in
          Alcotest.(check int) __LOC__ 0 code;
          Alcotest.(check string) __LOC__ (Printf.sprintf "raytrace: %s: No space left on device\n" out) err;
          Alcotest.(check string) __LOC__ "status 1\nout.ppm\nold\n" listing);
    Alcotest.test_case "a read-only file system is one line and leaves the old file" `Quick (fun () ->
        if not (private_mounts ()) then skip "read-only mount" no_private_mounts
        else
          let dir = Helpers.temp_dir () in
          let out = Filename.concat dir "out.ppm" in
          let code, listing, err =
            sh
              (Printf.sprintf
                 "unshare -rm sh -c 'mount -t tmpfs tmpfs %s && echo old > %s && mount -o remount,ro %s && \
                  %s; echo status $?; ls -A %s; cat %s'"
                 dir out dir
                 (command [ exe (); "render"; "--width"; "8"; "--height"; "8"; "-o"; out ])
                 dir out)
          in
          Alcotest.(check int) __LOC__ 0 code;
          Alcotest.(check string) __LOC__ (Printf.sprintf "raytrace: %s: cannot be replaced: Read-only file system\n" out) err;
          Alcotest.(check string) __LOC__ "status 1\nout.ppm\nold\n" listing);
    Alcotest.test_case "an immutable target is one line and stays as it was" `Quick (fun () ->
        let dir = fresh_dir () in
        let out = Filename.concat dir "out.ppm" in
        if fst3 (sh (command [ "chattr"; "+i"; out ] ^ " 2>/dev/null")) <> 0 then
          skip "immutable file" "chattr +i is not supported here"
        else
          let code, _, err =
            Fun.protect
              ~finally:(fun () -> ignore (sh (command [ "chattr"; "-i"; out ])))
              (fun () -> Helpers.run (exe ()) [ "render"; "--width"; "8"; "--height"; "8"; "-o"; out ])
          in
          Alcotest.(check int) __LOC__ 1 code;
          Alcotest.(check string) __LOC__ (Printf.sprintf "raytrace: %s: cannot be replaced: Operation not permitted\n" out) err;
          unchanged "immutable" dir [ "out.ppm" ]);
    Alcotest.test_case "read-only files and directories are refused to an unprivileged user" `Quick (fun () ->
        if Unix.geteuid () <> 0 || not (available "setpriv") then skip "as nobody" "not root, or no setpriv"
        else
          let dir = fresh_dir () in
          let out = Filename.concat dir "out.ppm" in
          let as_nobody args =
            Helpers.run "setpriv" ([ "--reuid=65534"; "--regid=65534"; "--clear-groups"; exe () ] @ args)
          in
          (* A read-only file in a directory that nobody may write to: the
             rename would replace it, but the file must stay. *)
          Unix.chmod dir 0o777;
          Unix.chmod out 0o444;
          let code, _, err = as_nobody [ "render"; "--width"; "8"; "--height"; "8"; "-o"; out ] in
          Alcotest.(check int) __LOC__ 1 code;
          Alcotest.(check string) __LOC__ (Printf.sprintf "raytrace: %s: cannot be replaced: Permission denied\n" out) err;
          unchanged "read-only file" dir [ "out.ppm" ];
          Unix.chmod dir 0o555;
          let fresh = Filename.concat dir "new.ppm" in
          let code, _, err = as_nobody [ "render"; "--width"; "8"; "--height"; "8"; "-o"; fresh ] in
          Unix.chmod dir 0o755;
          Alcotest.(check int) __LOC__ 1 code;
          Alcotest.(check string) __LOC__
            (Printf.sprintf "raytrace: %s: cannot create a file in its directory: Permission denied\n" fresh)
            err;
          unchanged "read-only directory" dir [ "out.ppm" ]);
    Alcotest.test_case "a file size limit (ulimit -f) is an error, not a kill" `Quick (fun () ->
        let dir = fresh_dir () in
        let out = Filename.concat dir "out.ppm" in
        (* 10 KiB (20 blocks of 512 bytes): the 30 KB image does not fit. *)
        let code, _, err =
          sh ("ulimit -f 20; exec " ^ command [ exe (); "render"; "--width"; "100"; "--height"; "100"; "--jobs"; "1"; "-o"; out ])
        in
        Alcotest.(check int) __LOC__ 1 code;
        Alcotest.(check string) __LOC__ (Printf.sprintf "raytrace: %s: File too large\n" out) err;
        unchanged "ulimit -f" dir [ "out.ppm" ];
        (* With workers, the shared image itself is over the limit. *)
        let code, _, err =
          sh ("ulimit -f 20; exec " ^ command [ exe (); "render"; "--width"; "100"; "--height"; "100"; "--jobs"; "2"; "-o"; out ])
        in
        Alcotest.(check int) __LOC__ 1 code;
        one_line __LOC__ err;
        contains __LOC__ err "File too large";
        unchanged "ulimit -f, 2 jobs" dir [ "out.ppm" ]);
    Alcotest.test_case "with /dev/shm full, a render with workers is traced in one process: the same picture" `Quick
      (fun () ->
        if not (private_mounts ()) then skip "small /dev/shm" no_private_mounts
        else
          let dir = fresh_dir () in
          let out = Filename.concat dir "out.ppm" in
          let expected = Filename.concat dir "expected.ppm" in
          (* /dev/shm of 16 KiB: the image (120000 bytes) does not fit. Of
             128 KiB: it fits, the adaptive sampling's buffers do not (they
             were an internal error, status 125). *)
          List.iter
            (fun (size, extra) ->
              let args = [ "render"; "--width"; "200"; "--height"; "200" ] @ extra in
              let code, _, err = Helpers.run (exe ()) (args @ [ "--jobs"; "1"; "-o"; expected ]) in
              Alcotest.(check int) err 0 code;
              let what = size ^ " " ^ String.concat " " extra in
              let code, out_text, err =
                sh
                  (Printf.sprintf "unshare -rm sh -c 'mount -t tmpfs -o size=%s tmpfs /dev/shm && %s; echo status $?'" size
                     (command ([ exe () ] @ args @ [ "--jobs"; "2"; "-o"; out ])))
              in
              Alcotest.(check int) what 0 code;
              Alcotest.(check string) what "status 0\n" out_text;
              let wrote = Printf.sprintf "raytrace: wrote %s (" out in
              Alcotest.(check string) what wrote (String.sub err 0 (min (String.length err) (String.length wrote)));
              one_line what err;
              Alcotest.(check bool) (what ^ ": the picture of one job") true (String.equal (read expected) (read out)))
            [ ("16k", []); ("128k", [ "--samples"; "3"; "--adaptive"; "2" ]); ("16k", [ "--tile"; "1/2" ]) ];
          Sys.remove expected;
          Sys.remove out);
    Alcotest.test_case "an image too large for the memory allowed is an error" `Quick (fun () ->
        (* 400 MB of address space; the 12000 x 12000 image needs 432 MB
           on top of the program. *)
        let dir = fresh_dir () in
        let out = Filename.concat dir "out.ppm" in
        List.iter
          (fun jobs ->
            let code, _, err =
              sh
                ("ulimit -v 400000; exec "
                ^ command [ exe (); "render"; "--width"; "12000"; "--height"; "12000"; "--jobs"; jobs; "-o"; out ])
            in
            Alcotest.(check int) (jobs ^ " jobs") 1 code;
            one_line __LOC__ err;
            (* With 2 jobs, the shared image cannot be had either: the
               render falls back to one process, which says so. *)
            let expected = "raytrace: not enough memory for a 12000x12000 image (412 MiB)\n" in
            Alcotest.(check string) (jobs ^ " jobs") expected err;
            unchanged "no memory" dir [ "out.ppm" ])
          [ "1"; "2" ]);
    Alcotest.test_case "a missing directory, a directory and the input itself are refused" `Quick (fun () ->
        let dir = fresh_dir () in
        let scene = Filename.concat dir "s.scene" in
        write scene "(light ambient (intensity 1))\n";
        let link = Filename.concat dir "link.scene" in
        Unix.symlink scene link;
        List.iter
          (fun (args, expected) ->
            let code, _, err = Helpers.run (exe ()) ([ "render"; "--width"; "4"; "--height"; "4" ] @ args) in
            Alcotest.(check int) expected 1 code;
            Alcotest.(check string) __LOC__ ("raytrace: " ^ expected ^ "\n") err)
          [
            ( [ "-o"; Filename.concat dir "missing/x.ppm" ],
              Filename.concat dir "missing/x.ppm" ^ ": cannot create a file in its directory: No such file or directory" );
            ([ "-o"; dir ], dir ^ ": is a directory");
            ([ scene; "-o"; scene ], scene ^ ": the output file is the input scene; choose another output path");
            ([ scene; "-o"; link ], link ^ ": the output file is the input scene; choose another output path");
          ];
        Alcotest.(check string) __LOC__ "(light ambient (intensity 1))\n" (read scene);
        unchanged "refused outputs" dir [ "link.scene"; "out.ppm"; "s.scene" ]);
    Alcotest.test_case "an output through a symbolic link replaces the link's target" `Quick (fun () ->
        let dir = fresh_dir () in
        let link = Filename.concat dir "link.ppm" in
        Unix.symlink "out.ppm" link;
        Unix.chmod (Filename.concat dir "out.ppm") 0o640;
        let code, _, err = Helpers.run (exe ()) [ "render"; "--width"; "4"; "--height"; "4"; "-o"; link ] in
        Alcotest.(check int) err 0 code;
        Alcotest.(check bool) __LOC__ true ((Unix.lstat link).st_kind = S_LNK);
        Alcotest.(check int) "permissions kept" 0o640 (Unix.stat link).st_perm;
        Alcotest.(check string) __LOC__ "P6\n4 4\n255\n" (String.sub (read link) 0 11));
    Alcotest.test_case "limits on the command line say how to raise them" `Quick (fun () ->
        let code, _, err = Helpers.run (exe ()) [ "render"; "--depth"; "100"; "-o"; "/tmp/never.ppm" ] in
        Alcotest.(check int) __LOC__ 1 code;
        Alcotest.(check string) __LOC__
          "raytrace: recursion depth 100 is too deep, more than the limit of 64 (set RAYTRACE_MAX_DEPTH to \
           raise it)\n"
          err;
        let code, _, err =
          sh ("RAYTRACE_MAX_DEPTH=100 " ^ command [ exe (); "render"; "--depth"; "100"; "--width"; "4"; "--height"; "4"; "-o"; "-" ] ^ " >/dev/null")
        in
        Alcotest.(check int) err 0 code;
        let code, _, err = Helpers.run (exe ()) [ "render"; "--width"; "65536"; "--height"; "65536"; "-o"; "/tmp/never.ppm" ] in
        Alcotest.(check int) __LOC__ 1 code;
        Alcotest.(check string) __LOC__
          "raytrace: canvas 65536x65536 has 4294967296 pixels, more than the limit of 268435456 (set \
           RAYTRACE_MAX_PIXELS to raise it)\n"
          err;
        let scene = Helpers.scene_path "cgfs.scene" in
        let code, _, err = sh ("RAYTRACE_MAX_SCENE_BYTES=100 " ^ command [ exe (); "render"; scene; "-o"; "/tmp/never.ppm" ]) in
        Alcotest.(check int) __LOC__ 1 code;
        Alcotest.(check string) __LOC__
          (Printf.sprintf
             "raytrace: %s: the scene is %d bytes long, more than the limit of 100 (set \
              RAYTRACE_MAX_SCENE_BYTES to raise it)\n"
             scene (Unix.stat scene).st_size)
          err;
        Alcotest.(check bool) "no output" false (Sys.file_exists "/tmp/never.ppm"));
    Alcotest.test_case "a scene read from a pipe renders, and its size is bounded too" `Quick (fun () ->
        let scene = Helpers.scene_path "cgfs.scene" in
        let code, out, err =
          sh ("cat " ^ Filename.quote scene ^ " | " ^ command [ exe (); "render"; "/dev/stdin"; "--width"; "4"; "--height"; "4"; "-o"; "-" ])
        in
        Alcotest.(check int) err 0 code;
        Alcotest.(check string) __LOC__ "P6\n4 4\n255\n" (String.sub out 0 11);
        let code, _, err =
          sh ("cat " ^ Filename.quote scene ^ " | RAYTRACE_MAX_SCENE_BYTES=100 " ^ command [ exe (); "render"; "/dev/stdin"; "-o"; "-" ])
        in
        Alcotest.(check int) __LOC__ 1 code;
        one_line __LOC__ err;
        contains __LOC__ err "RAYTRACE_MAX_SCENE_BYTES");
    Alcotest.test_case "a mesh that is a directory, a FIFO, a device or over the byte bound is one located line naming it"
      `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let f = Filename.concat dir in
        Unix.mkdir (f "d.obj") 0o755;
        Unix.mkfifo (f "fifo.obj") 0o600;
        write (f "big.obj") "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n";
        let scene mesh =
          write (f "s.scene") ("(canvas (width 4) (height 4))\n(mesh (file \"" ^ mesh ^ "\") (color 255 0 0))\n")
        in
        let out = f "out.ppm" in
        List.iter
          (fun (mesh, env, expected) ->
            scene mesh;
            (* A FIFO with no writer blocked the open for ever, /dev/zero was
               read for ever: a time limit makes a hang a failure. *)
            let code, _, err =
              sh (env ^ "timeout 20 " ^ command [ exe (); "render"; f "s.scene"; "-o"; out ])
            in
            Alcotest.(check int) (mesh ^ ": status") 1 code;
            Alcotest.(check string) mesh (Printf.sprintf "raytrace: %s:2:7: %s\n" (f "s.scene") expected) err;
            Alcotest.(check bool) (mesh ^ ": no output") false (Sys.file_exists out))
          [
            ("d.obj", "", "cannot read mesh file: " ^ f "d.obj" ^ ": is a directory");
            ("fifo.obj", "", "cannot read mesh file: " ^ f "fifo.obj" ^ ": is a FIFO, not a regular file");
            ("/dev/zero", "", "cannot read mesh file: /dev/zero: is a character device, not a regular file");
            (* 4 lines: 10 + 9 + 8 + 8 = 35 bytes. *)
            ( "big.obj", "RAYTRACE_MAX_MESH_BYTES=34 ",
              "mesh file " ^ f "big.obj" ^ " is 35 bytes long, more than the limit of 34 (set RAYTRACE_MAX_MESH_BYTES to raise it)" );
          ];
        (* A file whose size is not known ahead (a /proc file, 0 bytes to
           stat) is bounded as it is read: its lines are statements that
           are skipped, which could go on for ever. *)
        (match Files.read_mesh ~limits:(Raytrace.Limits.with_bound Raytrace.Limits.default `Mesh_bytes 100.) "/proc/self/maps" with
        | Ok _ -> Alcotest.fail "/proc/self/maps read past the bound"
        | Error (`Msg m) -> contains __LOC__ m "more than the limit of 100 (set RAYTRACE_MAX_MESH_BYTES to raise it)");
        scene "big.obj";
        let code, _, err = sh ("RAYTRACE_MAX_MESH_BYTES=35 " ^ command [ exe (); "render"; f "s.scene"; "-o"; out ]) in
        Alcotest.(check int) err 0 code);
    Alcotest.test_case "a scene FIFO that no program writes is an error after 5 s; a writer that comes later is read" `Quick
      (fun () ->
        let dir = Helpers.temp_dir () in
        let fifo = Filename.concat dir "s.fifo" and out = Filename.concat dir "out.ppm" in
        Unix.mkfifo fifo 0o600;
        let t0 = Unix.gettimeofday () in
        let code, _, err = sh ("timeout 20 " ^ command [ exe (); "render"; fifo; "-o"; out ]) in
        let waited = Unix.gettimeofday () -. t0 in
        Alcotest.(check int) __LOC__ 1 code;
        Alcotest.(check string) __LOC__
          (Printf.sprintf
             "raytrace: %s: is a FIFO that no program wrote to within 5 s; start the program that writes it first, or pipe its data to /dev/stdin\n"
             fifo)
          err;
        if waited < 4.9 || waited > 15. then Alcotest.failf "waited %.1f s, not about 5" waited;
        (* The writer opens the FIFO a second after raytrace: read, as before. *)
        let code, _, err =
          sh
            (Printf.sprintf "(sleep 1; echo '(canvas (width 4) (height 4))' > %s) & %s; s=$?; wait; exit $s"
               (Filename.quote fifo)
               (command [ exe (); "render"; fifo; "-o"; out ]))
        in
        Alcotest.(check int) err 0 code;
        Alcotest.(check string) __LOC__ "P6\n4 4\n255\n" (String.sub (read out) 0 11));
    Alcotest.test_case "diff refuses an image file larger than the pixel bound before reading it" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let big = Filename.concat dir "big.ppm" in
        write big ("P6\n1 1\n255\n" ^ String.make 2_000_000 '\000');
        let code, _, err =
          sh ("RAYTRACE_MAX_PIXELS=10 " ^ command [ exe (); "diff"; big; big ])
        in
        Alcotest.(check int) __LOC__ 1 code;
        (* 3 bytes x 10 pixels + 1 MiB of header = 1048606 bytes *)
        Alcotest.(check string) __LOC__
          (Printf.sprintf
             "raytrace: %s: the file is 2000011 bytes, more than a PPM image of at most 10 pixels can be \
              (1048606 bytes; set RAYTRACE_MAX_PIXELS to raise the limit)\n"
             big)
          err);
  ]
