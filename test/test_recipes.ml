(* The recipes of docs/farm.md for existing engines, run as a user runs them:
   GNU parallel on this machine and over ssh (a stand-in ssh that runs each
   "host" in its own directory, so the scene and parts really travel), and
   Slurm job arrays (a stand-in sbatch that runs the jobs at once with
   Slurm's environment). Each must give the bytes of a single render. *)

let exe () = Helpers.raytrace ()
let contrib name = Filename.concat (Filename.concat (Sys.getcwd ()) "../contrib") name
let here name = Filename.concat (Sys.getcwd ()) name

let read path =
  match Raytrace_unix.File_io.read path with Ok s -> s | Error (`Msg m) -> Alcotest.fail m

let on_path = Helpers.on_path

(* [with_tools progs f] runs [f] if every program is installed (make deps
   installs them), and otherwise says why it did not: this Alcotest has no
   skip. *)
let with_tools progs f () =
  match List.filter (fun p -> not (on_path p)) progs with
  | [] -> f ()
  | missing -> Printf.printf "SKIPPED: %s not installed (make deps installs it)\n" (String.concat ", " missing)

(* The environment with [vars] set (replacing earlier values). *)
let env vars =
  let names = List.map (fun v -> String.sub v 0 (String.index v '=')) vars in
  let keep v = match String.index_opt v '=' with Some i -> not (List.mem (String.sub v 0 i) names) | None -> true in
  Array.of_list (vars @ List.filter keep (Array.to_list (Unix.environment ())))

let sh ?(vars = []) dir script =
  let code, out, err = Helpers.run ~env:(env vars) "/bin/sh" [ "-c"; Printf.sprintf "cd %s && %s" (Filename.quote dir) script ] in
  if code <> 0 then Alcotest.failf "%s\nexited with %d:\n%s%s" script code out err;
  (out, err)

(* A directory to work in, the stand-in Slurm's state directory, and the
   environment that puts its sbatch first on the PATH. *)
let slurm () =
  let dir = Helpers.temp_dir () in
  let bin = Filename.concat dir "bin" and state = Filename.concat dir "slurm" in
  Unix.mkdir bin 0o755;
  Unix.mkdir state 0o755;
  Unix.symlink (here "fake-sbatch") (Filename.concat bin "sbatch");
  let path = bin ^ ":" ^ Option.value (Sys.getenv_opt "PATH") ~default:"/usr/bin:/bin" in
  (dir, state, [ "PATH=" ^ path; "FAKE_SLURM=" ^ state; "RAYTRACE=" ^ exe () ])

let size = "--width 97 --height 61"
let scene () = Helpers.scene_path "mirrors.scene" |> Filename.concat (Sys.getcwd ())

let single dir name =
  ignore (sh dir (Printf.sprintf "%s render %s %s -o %s" (Filename.quote (exe ())) (scene ()) size name));
  read (Filename.concat dir name)

let tests =
  [
    Alcotest.test_case "GNU parallel on this machine gives the single render's bytes" `Quick
      (with_tools [ "parallel" ] @@ fun () ->
        let dir = Helpers.temp_dir () in
        let expected = single dir "single.ppm" in
        ignore
          (sh dir
             ~vars:[ "RAYTRACE=" ^ exe (); "RAYTRACE_OPTS=" ^ size; "TMPDIR=" ^ dir ]
             (Printf.sprintf "%s %s 7 tiled.ppm" (contrib "parallel-tiles.sh") (scene ())));
        Alcotest.(check bool) "tiled = single" true (String.equal expected (read (Filename.concat dir "tiled.ppm")));
        Alcotest.(check (list string)) "the parts are cleaned up" [ "single.ppm"; "tiled.ppm" ]
          (List.sort String.compare (Array.to_list (Sys.readdir dir))));
    Alcotest.test_case "GNU parallel over ssh sends the scene and fetches the parts" `Quick
      (with_tools [ "parallel"; "rsync" ] @@ fun () ->
        let dir = Helpers.temp_dir () in
        let remote = Helpers.temp_dir () in
        let expected = single dir "single.ppm" in
        ignore
          (sh dir
             ~vars:[ "RAYTRACE=" ^ exe (); "RAYTRACE_OPTS=" ^ size; "TMPDIR=" ^ dir; "FAKE_REMOTE=" ^ remote ]
             (Printf.sprintf "%s %s 4 tiled.png --ssh %s --sshlogin 2/hostA,2/hostB" (contrib "parallel-tiles.sh") (scene ())
                (here "fake-ssh")));
        let code, out, _ = Helpers.run (exe ()) [ "diff"; "--max-diff"; "0"; Filename.concat dir "single.ppm"; Filename.concat dir "tiled.png" ] in
        Alcotest.(check int) out 0 code;
        ignore expected;
        let hosts = String.split_on_char '\n' (String.trim (read (Filename.concat remote "hosts-used"))) in
        Alcotest.(check (list string)) "both hosts worked" [ "hostA"; "hostB" ] (List.sort_uniq String.compare hosts);
        (* --cleanup leaves the hosts' login directories empty again. *)
        List.iter
          (fun h -> Alcotest.(check (array string)) h [||] (Sys.readdir (Filename.concat remote h)))
          [ "hostA"; "hostB" ]);
    Alcotest.test_case "GNU parallel renders frames, one job each, here and over ssh" `Quick
      (with_tools [ "parallel"; "rsync" ] @@ fun () ->
        let dir = Helpers.temp_dir () and remote = Helpers.temp_dir () in
        (* The scene where the recipe's lines expect it. *)
        Unix.mkdir (Filename.concat dir "scenes") 0o755;
        Unix.symlink
          (Filename.concat (Sys.getcwd ()) (Helpers.scene_path "orbit.scene"))
          (Filename.concat dir "scenes/orbit.scene");
        let raytrace = Filename.quote (exe ()) in
        (* The recipe's two lines, with the test's binary and a small canvas. *)
        ignore
          (sh dir
             (Printf.sprintf
                "parallel --will-cite %s render scenes/orbit.scene --width 24 --height 18 --frames {} -o orbit-{}.png ::: $(seq -w 9 10)"
                raytrace));
        ignore
          (sh dir ~vars:[ "FAKE_REMOTE=" ^ remote ]
             (Printf.sprintf
                "parallel --will-cite --ssh %s -S hostA,hostB --bf scenes/orbit.scene --return remote-{}.png --cleanup %s render \
                 scenes/orbit.scene --width 24 --height 18 --frames {} -o remote-{}.png ::: $(seq -w 9 10)"
                (here "fake-ssh") raytrace));
        Alcotest.(check bool) "the hosts worked" true (Sys.file_exists (Filename.concat remote "hosts-used"));
        ignore (sh dir (Printf.sprintf "%s render scenes/orbit.scene --width 24 --height 18 --frames 9:10 -o 'one-%%02d.png'" raytrace));
        List.iter
          (fun i ->
            let f p = Filename.concat dir (Printf.sprintf "%s-%02d.png" p i) in
            Alcotest.(check bool) (string_of_int i) true (String.equal (read (f "one")) (read (f "orbit")));
            Alcotest.(check bool) (string_of_int i ^ " remote") true (String.equal (read (f "one")) (read (f "remote"))))
          [ 9; 10 ]);
    Alcotest.test_case "the Slurm job array and its merge give the single render's bytes" `Quick (fun () ->
        let dir, slurm, vars = slurm () in
        let expected = single dir "single.ppm" in
        let out, _ =
          sh dir
            ~vars
            (Printf.sprintf "%s %s 7 slurm.ppm %s" (contrib "slurm-render.sh") (scene ()) size)
        in
        Alcotest.(check string) "job IDs" "tiles: job 101; merge: job 102\n" out;
        Alcotest.(check bool) "no job failed" false (Sys.file_exists (Filename.concat slurm "failed"));
        Alcotest.(check bool) "slurm = single" true (String.equal expected (read (Filename.concat dir "slurm.ppm")));
        Alcotest.(check bool) "the merge job removes the parts" false (Sys.file_exists (Filename.concat dir "slurm.ppm.parts")));
    Alcotest.test_case "a failed tile task stops the Slurm merge" `Quick (fun () ->
        let dir, slurm, vars = slurm () in
        (* A depth beyond the limit: every tile task fails. *)
        ignore
          (sh dir
             ~vars
             (Printf.sprintf "%s %s 3 slurm.ppm %s --depth 99" (contrib "slurm-render.sh") (scene ()) size));
        if not (Astring_free.contains (read (Filename.concat slurm "job-101.log")) "recursion depth 99 is too deep") then
          Alcotest.fail "the tasks' log lacks raytrace's message";
        Alcotest.(check string) "failed jobs" "101\n102\n" (read (Filename.concat slurm "failed"));
        Alcotest.(check bool) "no image" false (Sys.file_exists (Filename.concat dir "slurm.ppm")));
    Alcotest.test_case "the Slurm frames array renders each frame as --frames does" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let slurm = Filename.concat dir "slurm" in
        Unix.mkdir slurm 0o755;
        let orbit = Filename.concat (Sys.getcwd ()) (Helpers.scene_path "orbit.scene") in
        ignore
          (sh dir
             ~vars:[ "FAKE_SLURM=" ^ slurm; "RAYTRACE=" ^ exe () ]
             (Printf.sprintf "%s --array=46-48 %s %s 'f-%%04d.ppm' --width 24 --height 18" (here "fake-sbatch")
                (contrib "slurm-frames.sbatch") orbit));
        ignore (sh dir (Printf.sprintf "%s render %s --width 24 --height 18 --frames 46:48 -o 'g-%%04d.ppm'" (Filename.quote (exe ())) orbit));
        List.iter
          (fun i ->
            let f p = Filename.concat dir (Printf.sprintf "%s-%04d.ppm" p i) in
            Alcotest.(check bool) (string_of_int i) true (String.equal (read (f "g")) (read (f "f"))))
          [ 46; 47; 48 ]);
  ]
