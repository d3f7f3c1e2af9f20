(* The render-farm recipes of contrib/ (docs/farm.md), run as a user runs them, against
   real engines: GNU parallel on this machine and over ssh to a real sshd
   (two "hosts" on 127.0.0.1, each with its own login directory, so the
   scene and parts really travel), and Slurm job arrays on a real
   single-node cluster (munged, slurmctld, slurmd) started for the test
   (test/farm.ml). Each must give the bytes of a single render, and a
   failed or cancelled tile must leave no merged image. Without root or
   the programs, the tests are skipped (Helpers.skip). *)

let exe () = Helpers.raytrace ()
let contrib name = Filename.concat (Filename.concat (Sys.getcwd ()) "../contrib") name

let read path =
  match Raytrace_unix.File_io.read path with Ok s -> s | Error (`Msg m) -> Alcotest.fail m

let with_tools what progs f () =
  match Helpers.missing progs with
  | [] -> f ()
  | missing -> Helpers.skip what ~why:(String.concat ", " missing ^ " not installed (make deps installs it)")

let sh ?(vars = []) dir script =
  let code, out, err = Helpers.run ~env:(Farm.env vars) "/bin/sh" [ "-c"; Printf.sprintf "cd %s && %s" (Filename.quote dir) script ] in
  if code <> 0 then Alcotest.failf "%s\nexited with %d:\n%s%s" script code out err;
  (out, err)

let size = "--width 97 --height 61"
let scene () = Helpers.scene_path "mirrors.scene" |> Filename.concat (Sys.getcwd ())

let single ?(options = size) dir name =
  ignore (sh dir (Printf.sprintf "%s render %s %s -o %s" (Filename.quote (exe ())) (scene ()) options name));
  read (Filename.concat dir name)

let files dir = List.sort String.compare (Array.to_list (Sys.readdir dir))

(* The job IDs that contrib/slurm-render.sh prints. *)
let job_ids out =
  match Scanf.sscanf out "tiles: job %s@; merge: job %s@\n" (fun a m -> (a, m)) with
  | ids -> ids
  | exception _ -> Alcotest.failf "slurm-render.sh printed %S" out

let check_states what expected actual =
  Alcotest.(check (list string)) what expected (List.sort_uniq String.compare actual)

let merge_log dir merge = String.trim (read (Filename.concat dir (Printf.sprintf "raytrace-merge-%s.log" merge)))

let one_line what text =
  match String.split_on_char '\n' text with
  | [ _ ] -> ()
  | _ -> Alcotest.failf "%s: expected one line, got:\n%s" what text

let contains what text expected =
  if not (Astring_free.contains text expected) then Alcotest.failf "%s: expected %S in:\n%s" what expected text

(* Submits slurm-render.sh in [dir] on cluster [s] and waits for its merge
   job: the IDs and the final states of the array's tasks and the merge. *)
let slurm_render ?(vars = []) ?(before_wait = fun _ _ -> ()) s dir args =
  let out, _ =
    sh dir ~vars:(Farm.slurm_vars s @ [ "RAYTRACE=" ^ exe () ] @ vars) (contrib "slurm-render.sh" ^ " " ^ args)
  in
  let array, merge = job_ids out in
  before_wait array merge;
  let merge_states = Farm.wait_job s merge in
  let array_states = Farm.wait_job s array in
  (array, merge, array_states, merge_states)

let tests =
  [
    Alcotest.test_case "GNU parallel on this machine gives the single render's bytes" `Quick
      (with_tools "recipes: GNU parallel" [ "parallel" ] @@ fun () ->
        let dir = Helpers.temp_dir () in
        let expected = single dir "single.ppm" in
        ignore
          (sh dir
             ~vars:[ "RAYTRACE=" ^ exe (); "RAYTRACE_OPTS=" ^ size; "TMPDIR=" ^ dir ]
             (Printf.sprintf "%s %s 7 tiled.ppm" (contrib "parallel-tiles.sh") (scene ())));
        Alcotest.(check bool) "tiled = single" true (String.equal expected (read (Filename.concat dir "tiled.ppm")));
        Alcotest.(check (list string)) "the parts are cleaned up" [ "single.ppm"; "tiled.ppm" ] (files dir));
    Alcotest.test_case "a failed tile stops GNU parallel's recipe before the merge: no image, nothing left" `Quick
      (with_tools "recipes: GNU parallel, a failed tile" [ "parallel" ] @@ fun () ->
        let dir = Helpers.temp_dir () in
        let code, _, err =
          Helpers.run
            ~env:(Farm.env [ "RAYTRACE=" ^ exe (); "RAYTRACE_OPTS=" ^ size ^ " --depth 99"; "TMPDIR=" ^ dir ])
            (contrib "parallel-tiles.sh")
            [ scene (); "4"; Filename.concat dir "tiled.ppm" ]
        in
        Alcotest.(check int) "status" 1 code;
        contains "stderr" err "raytrace: recursion depth 99 is too deep";
        Alcotest.(check (list string)) "no image, no temporary directory" [] (files dir));
    Alcotest.test_case "GNU parallel over ssh to a real sshd sends the scene and fetches the parts" `Quick
      (with_tools "recipes: GNU parallel over ssh" [ "parallel" ] @@ fun () ->
        Farm.with_sshd "recipes: GNU parallel over ssh" [ "hostA"; "hostB" ] @@ fun h ->
        let dir = Helpers.temp_dir () in
        ignore (single dir "single.ppm");
        ignore
          (sh dir
             ~vars:[ "RAYTRACE=" ^ exe (); "RAYTRACE_OPTS=" ^ size; "TMPDIR=" ^ dir ]
             (Printf.sprintf "%s %s 4 tiled.png --ssh %s --sshlogin 2/hostA,2/hostB" (contrib "parallel-tiles.sh") (scene ())
                (Filename.quote (Farm.ssh_command h))));
        let code, out, _ = Helpers.run (exe ()) [ "diff"; "--max-diff"; "0"; Filename.concat dir "single.ppm"; Filename.concat dir "tiled.png" ] in
        Alcotest.(check int) out 0 code;
        List.iter
          (fun host ->
            if Farm.logins h host < 2 then Alcotest.failf "%s: sshd saw %d logins, not a job and its transfers" host (Farm.logins h host);
            (* --cleanup leaves the hosts' login directories as they were,
               but for the empty directory the parts were in. *)
            let home = Farm.home h host in
            List.iter
              (fun d -> Alcotest.(check (array string)) (host ^ ": " ^ d) [||] (Sys.readdir (Filename.concat home d)))
              (files home))
          [ "hostA"; "hostB" ];
        Alcotest.(check (list string)) "here, the parts are cleaned up" [ "single.ppm"; "tiled.png" ] (files dir));
    Alcotest.test_case "GNU parallel renders frames, one job each, here and over ssh to a real sshd" `Quick
      (with_tools "recipes: GNU parallel frames" [ "parallel" ] @@ fun () ->
        Farm.with_sshd "recipes: GNU parallel frames over ssh" [ "hostA"; "hostB" ] @@ fun h ->
        let dir = Helpers.temp_dir () in
        (* The scene where the lines of docs/farm.md expect it. *)
        Unix.mkdir (Filename.concat dir "scenes") 0o755;
        Unix.symlink
          (Filename.concat (Sys.getcwd ()) (Helpers.scene_path "orbit.scene"))
          (Filename.concat dir "scenes/orbit.scene");
        let raytrace = Filename.quote (exe ()) in
        (* The two lines of docs/farm.md, with the test's binary and a small canvas. *)
        ignore
          (sh dir
             (Printf.sprintf
                "parallel --will-cite %s render scenes/orbit.scene --width 24 --height 18 --frames {} -o orbit-{}.png ::: $(seq -w 9 10)"
                raytrace));
        ignore
          (sh dir
             (Printf.sprintf
                "parallel --will-cite --ssh %s -S hostA,hostB --bf scenes/orbit.scene --return remote-{}.png --cleanup %s render \
                 scenes/orbit.scene --width 24 --height 18 --frames {} -o remote-{}.png ::: $(seq -w 9 10)"
                (Filename.quote (Farm.ssh_command h)) raytrace));
        if Farm.logins h "hostA" + Farm.logins h "hostB" < 2 then Alcotest.fail "the hosts were not used";
        ignore (sh dir (Printf.sprintf "%s render scenes/orbit.scene --width 24 --height 18 --frames 9:10 -o 'one-%%02d.png'" raytrace));
        List.iter
          (fun i ->
            let f p = Filename.concat dir (Printf.sprintf "%s-%02d.png" p i) in
            Alcotest.(check bool) (string_of_int i) true (String.equal (read (f "one")) (read (f "orbit")));
            Alcotest.(check bool) (string_of_int i ^ " remote") true (String.equal (read (f "one")) (read (f "remote"))))
          [ 9; 10 ]);
    Alcotest.test_case "the Slurm job array and its merge give the single render's bytes" `Quick (fun () ->
        Farm.with_slurm "recipes: Slurm tiles" @@ fun s ->
        let dir = Helpers.temp_dir () in
        let expected = single dir "single.ppm" in
        let array, merge, array_states, merge_states =
          slurm_render s dir (Printf.sprintf "%s 7 slurm.ppm %s" (scene ()) size)
        in
        check_states "the tile tasks" [ "COMPLETED" ] array_states;
        Alcotest.(check int) "7 tasks" 7 (List.length array_states);
        check_states "the merge" [ "COMPLETED" ] merge_states;
        Alcotest.(check bool) "slurm = single" true (String.equal expected (read (Filename.concat dir "slurm.ppm")));
        Alcotest.(check bool) "the merge job removes the parts" false (Sys.file_exists (Filename.concat dir "slurm.ppm.parts"));
        (* Each task logs what raytrace says, where #SBATCH --output puts it. *)
        contains "tile 3's log" (read (Filename.concat dir (Printf.sprintf "raytrace-tile-%s_3.log" array))) "slurm.ppm.parts/part-3.ppm";
        Alcotest.(check string) "the merge's log" "raytrace: wrote slurm.ppm (97x61, from 7 parts)" (merge_log dir merge));
    Alcotest.test_case "a failed Slurm tile task makes the merge refuse in one line, no image" `Quick (fun () ->
        Farm.with_slurm "recipes: Slurm, a failed tile" @@ fun s ->
        let dir = Helpers.temp_dir () in
        (* Task 2 fails as a crashed node would; the others render. *)
        let crashing = Filename.concat dir "crashing-raytrace" in
        Farm.write crashing
          (Printf.sprintf
             "#!/bin/sh\nif [ \"${SLURM_ARRAY_TASK_ID:-}\" = 2 ]; then echo 'node crashed' >&2; exit 1; fi\nexec %s \"$@\"\n"
             (Filename.quote (exe ())));
        Unix.chmod crashing 0o755;
        let _, merge, array_states, merge_states =
          slurm_render s dir ~vars:[ "RAYTRACE=" ^ crashing ] (Printf.sprintf "%s 4 slurm.ppm %s" (scene ()) size)
        in
        check_states "the tile tasks" [ "COMPLETED"; "FAILED" ] array_states;
        check_states "the merge" [ "FAILED" ] merge_states;
        let log = merge_log dir merge in
        one_line "the merge's log" log;
        contains "the merge's log" log "a part is missing";
        Alcotest.(check bool) "no image" false (Sys.file_exists (Filename.concat dir "slurm.ppm"));
        Alcotest.(check (list string)) "the other parts stay" [ "part-1.ppm"; "part-3.ppm"; "part-4.ppm" ]
          (files (Filename.concat dir "slurm.ppm.parts"));
        (* Every task failing (a depth beyond the limit): the merge finds no part. *)
        let array, merge, array_states, merge_states =
          slurm_render s dir (Printf.sprintf "%s 3 deep.ppm %s --depth 99" (scene ()) size)
        in
        check_states "the deep tile tasks" [ "FAILED" ] array_states;
        check_states "the deep merge" [ "FAILED" ] merge_states;
        contains "a task's log" (read (Filename.concat dir (Printf.sprintf "raytrace-tile-%s_1.log" array))) "recursion depth 99 is too deep";
        let log = merge_log dir merge in
        one_line "the deep merge's log" log;
        contains "the deep merge's log" log "no part in deep.ppm.parts";
        Alcotest.(check bool) "no deep image" false (Sys.file_exists (Filename.concat dir "deep.ppm")));
    Alcotest.test_case "a Slurm render cancelled mid-render (scancel) leaves no merged image" `Quick (fun () ->
        Farm.with_slurm "recipes: Slurm, scancel" @@ fun s ->
        let dir = Helpers.temp_dir () in
        (* Tiles that take seconds each, so that scancel finds them running. *)
        let big = "--width 1500 --height 1500 --samples 4" in
        let _, merge, array_states, merge_states =
          slurm_render s dir (Printf.sprintf "%s 4 slurm.ppm %s" (scene ()) big) ~before_wait:(fun array _ ->
              Farm.wait_running s array;
              ignore (Helpers.run ~env:(Farm.env (Farm.slurm_vars s)) "scancel" [ array ]))
        in
        if not (List.mem "CANCELLED" array_states) then
          Alcotest.failf "no tile task was cancelled: %s" (String.concat ", " array_states);
        check_states "the merge" [ "FAILED" ] merge_states;
        one_line "the merge's log" (merge_log dir merge);
        Alcotest.(check bool) "no image" false (Sys.file_exists (Filename.concat dir "slurm.ppm"));
        (* A killed raytrace removes its temporary file: only whole parts, if any. *)
        let parts = Filename.concat dir "slurm.ppm.parts" in
        if Sys.file_exists parts then
          List.iter
            (fun f -> if not (List.mem f [ "part-1.ppm"; "part-2.ppm"; "part-3.ppm"; "part-4.ppm" ]) then Alcotest.failf "left behind: %s" f)
            (files parts));
    Alcotest.test_case "the Slurm frames array renders each frame as --frames does" `Quick (fun () ->
        Farm.with_slurm "recipes: Slurm frames" @@ fun s ->
        let dir = Helpers.temp_dir () in
        let orbit = Filename.concat (Sys.getcwd ()) (Helpers.scene_path "orbit.scene") in
        let out, _ =
          sh dir
            ~vars:(Farm.slurm_vars s @ [ "RAYTRACE=" ^ exe () ])
            (Printf.sprintf "sbatch --parsable --array=46-48 %s %s 'f-%%04d.ppm' --width 24 --height 18" (contrib "slurm-frames.sbatch") orbit)
        in
        check_states "the frame tasks" [ "COMPLETED" ] (Farm.wait_job s (String.trim out));
        ignore (sh dir (Printf.sprintf "%s render %s --width 24 --height 18 --frames 46:48 -o 'g-%%04d.ppm'" (Filename.quote (exe ())) orbit));
        List.iter
          (fun i ->
            let f p = Filename.concat dir (Printf.sprintf "%s-%04d.ppm" p i) in
            Alcotest.(check bool) (string_of_int i) true (String.equal (read (f "g")) (read (f "f"))))
          [ 46; 47; 48 ]);
  ]
