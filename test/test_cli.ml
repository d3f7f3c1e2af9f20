(* The raytrace command as a user runs it: exit statuses, one-line errors,
   no backtraces, no partial output files. *)

let run = Helpers.run
let exe () = Helpers.raytrace ()

let no_backtrace what err =
  List.iter
    (fun bad ->
      if Astring_free.contains err bad then Alcotest.failf "%s: stderr shows %S:\n%s" what bad err)
    [ "Raised at"; "Fatal error"; "exception"; "Called from" ]

let one_line what err =
  match String.split_on_char '\n' (String.trim err) with
  | [ _ ] -> ()
  | _ -> Alcotest.failf "%s: expected one line on stderr, got:\n%s" what err

let bad_scenes =
  [
    ("syntax error", "(sphere (center 0 0 3)", ":1:23: syntax error");
    ("unknown field", "(sphere (center 0 0 3) (radius 1) (colour 1 2 3))", ":1:36: unknown sphere field colour");
    ("negative radius", "(sphere (center 0 0 3) (radius -1) (color 1 2 3))", ":1:32: sphere radius must be > 0, got -1");
    ("reflective outside [0, 1]", "(sphere (center 0 0 3) (radius 1) (color 1 2 3) (reflective -0.1))",
     ":1:61: sphere reflective must lie in [0, 1], got -0.1");
    ("a NaN", "(light ambient (intensity nan))", ":1:27: light ambient intensity must be a finite number, got nan");
    ("missing light position", "(light point (intensity 0.5))", ":1:1: light point is missing its (position ...) field");
    ("degenerate triangle", "(triangle (vertices (0 0 0) (1 1 1) (2 2 2)) (color 1 2 3))",
     ":1:11: triangle vertices must not lie on a line");
    ("missing mesh file", "(mesh (file \"none.obj\") (color 1 2 3))", ":1:7: cannot read mesh file: ");
    ("bad mesh file", "(mesh (file \"bad.obj\") (color 1 2 3))", ":1:7: ");
  ]

let tests =
  [
    Alcotest.test_case "render with 2 or 3 jobs writes the file while it traces, byte for byte as 1 job" `Quick
      (fun () ->
        let dir = Helpers.temp_dir () in
        let render jobs =
          let out = Filename.concat dir (Printf.sprintf "j%d.ppm" jobs) in
          let code, _, err =
            run (exe ())
              [ "render"; Helpers.scene_path "cgfs.scene"; "--width"; "700"; "--height"; "900"; "--jobs";
                string_of_int jobs; "-o"; out ]
          in
          Alcotest.(check int) err 0 code;
          match Raytrace_unix.File_io.read out with Ok s -> s | Error (`Msg m) -> Alcotest.fail m
        in
        let one = render 1 in
        Alcotest.(check bool) "2 jobs" true (String.equal one (render 2));
        Alcotest.(check bool) "3 jobs" true (String.equal one (render 3));
        (* No temporary file is left beside them. *)
        Alcotest.(check (list string)) __LOC__ [ "j1.ppm"; "j2.ppm"; "j3.ppm" ]
          (List.sort compare (Array.to_list (Sys.readdir dir))));
    Alcotest.test_case "render --jobs 2 of a small image traces in one process, in two with RAYTRACE_SPLIT=always"
      `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let without =
          Array.of_list
            (List.filter
               (fun v -> not (String.length v >= 15 && String.sub v 0 15 = "RAYTRACE_SPLIT="))
               (Array.to_list (Unix.environment ())))
        in
        let render name env =
          let out = Filename.concat dir name in
          let code, _, err =
            run ~env (exe ()) [ "render"; "--width"; "64"; "--height"; "48"; "--jobs"; "2"; "--stats"; "-o"; out ]
          in
          Alcotest.(check int) err 0 code;
          let jobs =
            List.find_map
              (fun l ->
                match String.split_on_char ' ' l |> List.filter (( <> ) "") with
                | [ "jobs"; n ] -> Some n
                | _ -> None)
              (String.split_on_char '\n' err)
          in
          (jobs, match Raytrace_unix.File_io.read out with Ok s -> s | Error (`Msg m) -> Alcotest.fail m)
        in
        let auto_jobs, auto = render "auto.ppm" without in
        let forced_jobs, forced = render "forced.ppm" (Array.append [| "RAYTRACE_SPLIT=always" |] without) in
        Alcotest.(check (option string)) "auto: processes" (Some "1") auto_jobs;
        Alcotest.(check (option string)) "always: processes" (Some "2") forced_jobs;
        Alcotest.(check bool) "the same bytes" true (String.equal auto forced));
    Alcotest.test_case "render writes a P6 image of the canvas size" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let out = Filename.concat dir "x.ppm" in
        let code, _, err = run (exe ()) [ "render"; "--width"; "40"; "--height"; "30"; Helpers.scene_path "cgfs.scene"; "-o"; out ] in
        Alcotest.(check int) err 0 code;
        match Raytrace_unix.Files.read_ppm out with
        | Ok img -> Alcotest.(check (pair int int)) __LOC__ (40, 30) (Raytrace.Image.width img, Raytrace.Image.height img)
        | Error (`Msg m) -> Alcotest.fail m);
    Alcotest.test_case "render -o - writes the image to stdout" `Quick (fun () ->
        let code, out, _ = run (exe ()) [ "render"; "--width"; "8"; "--height"; "8"; "-o"; "-" ] in
        Alcotest.(check int) __LOC__ 0 code;
        Alcotest.(check string) __LOC__ "P6\n8 8\n255\n" (String.sub out 0 11);
        Alcotest.(check int) __LOC__ (11 + (8 * 8 * 3)) (String.length out));
    Alcotest.test_case "bad scenes: one located line, status 1, no output file" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        List.iter
          (fun (what, text, expected) ->
            let scene = Filename.concat dir "bad.scene" and out = Filename.concat dir "bad.ppm" in
            (* An OBJ file with a face beyond its vertices, beside the scene. *)
            let oc = open_out_bin (Filename.concat dir "bad.obj") in
            output_string oc "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n";
            close_out oc;
            let oc = open_out_bin scene in
            output_string oc text;
            close_out oc;
            let code, _, err = run (exe ()) [ "render"; scene; "-o"; out ] in
            Alcotest.(check int) what 1 code;
            one_line what err;
            no_backtrace what err;
            if not (Astring_free.contains err (scene ^ expected)) then
              Alcotest.failf "%s: expected %S in %S" what (scene ^ expected) err;
            if what = "bad mesh file" && not (Astring_free.contains err "bad.obj:4:7: vertex index 4 is out of range") then
              Alcotest.failf "the OBJ file's line and column: %S" err;
            Alcotest.(check bool) (what ^ ": no output file") false (Sys.file_exists out))
          bad_scenes);
    Alcotest.test_case "a missing scene file is one line and status 1" `Quick (fun () ->
        let code, _, err = run (exe ()) [ "render"; "no-such.scene"; "-o"; "/tmp/never.ppm" ] in
        Alcotest.(check int) __LOC__ 1 code;
        Alcotest.(check string) __LOC__ "raytrace: no-such.scene: No such file or directory\n" err);
    Alcotest.test_case "unwritable outputs are errors and leave no file" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        List.iter
          (fun (out, expected) ->
            let code, _, err = run (exe ()) [ "render"; "--width"; "4"; "--height"; "4"; "-o"; out ] in
            Alcotest.(check int) out 1 code;
            one_line out err;
            no_backtrace out err;
            if not (Astring_free.contains err expected) then Alcotest.failf "expected %S in %S" expected err)
          [
            ("/nonexistent-dir/x.ppm", "No such file or directory");
            (dir, "is a directory");
            ("/dev/full", "No space left on device");
          ];
        Alcotest.(check (array string)) __LOC__ [||] (Sys.readdir dir));
    Alcotest.test_case "the output may not overwrite the input scene" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let scene = Filename.concat dir "s.scene" in
        let oc = open_out scene in
        output_string oc "(light ambient (intensity 1))";
        close_out oc;
        let code, _, err = run (exe ()) [ "render"; scene; "-o"; scene ] in
        Alcotest.(check int) __LOC__ 1 code;
        one_line __LOC__ err;
        let ic = open_in scene in
        Alcotest.(check string) __LOC__ "(light ambient (intensity 1))" (input_line ic);
        close_in ic);
    Alcotest.test_case "bad command-line overrides are refused" `Quick (fun () ->
        List.iter
          (fun (args, expected) ->
            let code, _, err = run (exe ()) ("render" :: args @ [ "-o"; "/tmp/never.ppm" ]) in
            Alcotest.(check int) __LOC__ 1 code;
            Alcotest.(check string) __LOC__ expected err)
          [
            ([ "--width"; "0" ], "raytrace: canvas width must lie in [1, 65536], got 0\n");
            ([ "--jobs"; "0" ], "raytrace: --jobs must lie in [1, 1024], got 0\n");
            ([ "--jobs"; "100000" ], "raytrace: --jobs must lie in [1, 1024], got 100000\n");
          ];
        Alcotest.(check bool) __LOC__ false (Sys.file_exists "/tmp/never.ppm"));
    Alcotest.test_case "an integer option too large for an int is one whole line, not a message cut short" `Quick
      (fun () ->
        (* Cmdliner wraps its message at 78 columns; the first line alone
           ended in "expected an". *)
        List.iter
          (fun (option, value) ->
            let code, _, err = run (exe ()) [ "render"; option; value; "-o"; "/tmp/never.ppm" ] in
            Alcotest.(check int) __LOC__ 124 code;
            Alcotest.(check string) __LOC__
              (Printf.sprintf
                 "raytrace: option '%s': invalid value '%s', expected an integer; see 'raytrace render --help'\n"
                 option value)
              err)
          [ ("--width", "99999999999999999999"); ("--jobs", "9999999999999999999999999") ];
        Alcotest.(check bool) __LOC__ false (Sys.file_exists "/tmp/never.ppm"));
    Alcotest.test_case "without a display, view says so in one line and exits 3" `Quick (fun () ->
        let env =
          Unix.environment () |> Array.to_list
          |> List.filter (fun v -> not (String.length v >= 8 && String.sub v 0 8 = "DISPLAY="))
          |> Array.of_list
        in
        let code, _, err = run ~env (exe ()) [ "view"; Helpers.scene_path "cgfs.scene" ] in
        Alcotest.(check int) __LOC__ 3 code;
        one_line __LOC__ err;
        no_backtrace __LOC__ err;
        if not (Astring_free.contains err "raytrace render") then Alcotest.failf "no hint in %S" err;
        if not (Astring_free.contains err "DISPLAY is not set") then Alcotest.failf "no reason in %S" err);
    Alcotest.test_case "diff prints the metrics and --max-diff sets the status" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let a = Filename.concat dir "a.ppm" and b = Filename.concat dir "b.ppm" in
        let img = Raytrace.Image.create 2 1 in
        ignore (Raytrace_unix.Files.write_ppm a img);
        Raytrace.Image.set img 0 0 10 22 30;
        ignore (Raytrace_unix.Files.write_ppm b img);
        let code, out, _ = run (exe ()) [ "diff"; a; b ] in
        Alcotest.(check int) __LOC__ 0 code;
        (* channel differences 10, 22, 30 and three zeros: mean 62 / 6;
           MSE (100 + 484 + 900) / 6 = 247.33; PSNR 10 log10 (65025 / 247.33) = 24.20 *)
        Alcotest.(check string) __LOC__
          "pixels=2 differing=1 differing_gt1=1 max_abs=30 mean_abs=10.333333 psnr=24.20\n" out;
        let code, _, err = run (exe ()) [ "diff"; "--max-diff"; "1"; a; b ] in
        Alcotest.(check int) __LOC__ 1 code;
        one_line __LOC__ err;
        let code, _, err = run (exe ()) [ "diff"; a; Helpers.scene_path "cgfs.scene" ] in
        Alcotest.(check int) __LOC__ 1 code;
        one_line __LOC__ err);
    Alcotest.test_case "every command has a manual with examples" `Quick (fun () ->
        List.iter
          (fun cmd ->
            let code, out, _ = run (exe ()) (cmd @ [ "--help=plain" ]) in
            Alcotest.(check int) __LOC__ 0 code;
            if not (Astring_free.contains out "EXAMPLES") then Alcotest.failf "%s: no EXAMPLES" (String.concat " " cmd))
          [ []; [ "view" ]; [ "render" ]; [ "diff" ] ]);
    Alcotest.test_case "render's manual names every bound's variable, the mesh file's included" `Quick (fun () ->
        let code, out, _ = run (exe ()) [ "render"; "--help=plain" ] in
        Alcotest.(check int) __LOC__ 0 code;
        List.iter
          (fun name ->
            let v = Raytrace.Limits.variable name in
            if not (Astring_free.contains out v) then Alcotest.failf "render --help does not name %s" v)
          [ `Pixels; `Depth; `Samples; `Spheres; `Lights; `Scene_bytes; `Form_bytes; `Mesh_bytes; `Work ]);
    Alcotest.test_case "--samples 1 writes the plain render's bytes, --samples N --adaptive T the library's" `Quick
      (fun () ->
        let dir = Helpers.temp_dir () in
        let out name = Filename.concat dir name in
        let scene = Helpers.scene_path "cgfs.scene" and size = [ "--width"; "30"; "--height"; "20" ] in
        let render name args =
          let code, _, err = run (exe ()) ([ "render"; scene; "-o"; out name ] @ size @ args) in
          Alcotest.(check int) err 0 code;
          match Raytrace_unix.Files.read_ppm (out name) with Ok img -> img | Error (`Msg m) -> Alcotest.fail m
        in
        Helpers.check_images "--samples 1" ~expected:(render "plain.ppm" []) (render "one.ppm" [ "--samples"; "1" ]);
        let s = Raytrace.Scene.with_overrides ~width:30 ~height:20 (Helpers.load_scene "cgfs.scene") in
        Helpers.check_images "--samples 3 --adaptive 5"
          ~expected:(Helpers.image_exn ~samples:3 ~adaptive:5 s)
          (render "adaptive.ppm" [ "--samples"; "3"; "--adaptive"; "5"; "--jobs"; "2" ]);
        Helpers.check_images "--subsample"
          ~expected:(Helpers.image_exn ~subsample:true s)
          (render "sub.ppm" [ "--subsample" ]));
    Alcotest.test_case "tiles rendered with --samples 3 --adaptive 4 merge into the whole render, others do not" `Quick
      (fun () ->
        let dir = Helpers.temp_dir () in
        let out name = Filename.concat dir name in
        let scene = Helpers.scene_path "cgfs.scene" and size = [ "--width"; "30"; "--height"; "20" ] in
        let sampling = [ "--samples"; "3"; "--adaptive"; "4" ] in
        let run_ok args =
          let code, _, err = run (exe ()) args in
          Alcotest.(check int) err 0 code
        in
        let read name = match Raytrace_unix.Files.read_ppm (out name) with Ok img -> img | Error (`Msg m) -> Alcotest.fail m in
        run_ok ([ "render"; scene; "-o"; out "whole.ppm" ] @ size @ sampling);
        List.iter
          (fun i ->
            run_ok
              ([ "render"; scene; "--tile"; Printf.sprintf "%d/3" i; "-o"; out (Printf.sprintf "part-%d.ppm" i) ]
              @ size @ sampling))
          [ 1; 2; 3 ];
        run_ok [ "merge"; out "part-1.ppm"; out "part-2.ppm"; out "part-3.ppm"; "-o"; out "merged.ppm" ];
        Helpers.check_images "merged tiles" ~expected:(read "whole.ppm") (read "merged.ppm");
        run_ok ([ "render"; scene; "--tile"; "3/3"; "-o"; out "full-3.ppm"; "--samples"; "3" ] @ size);
        let code, _, err = run (exe ()) [ "merge"; out "part-1.ppm"; out "part-2.ppm"; out "full-3.ppm"; "-o"; out "bad.ppm" ] in
        Alcotest.(check int) __LOC__ 1 code;
        let expected = "with adaptive (none)" in
        if not (Astring_free.contains err expected) then Alcotest.failf "expected %S in %S" expected err);
    Alcotest.test_case "bad sampling options: one line, status 1, no output file" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let out = Filename.concat dir "never.ppm" in
        List.iter
          (fun (args, expected) ->
            let code, _, err = run (exe ()) ([ "render"; "--width"; "4"; "--height"; "4"; "-o"; out ] @ args) in
            let what = String.concat " " args in
            Alcotest.(check int) what 1 code;
            Alcotest.(check string) what ("raytrace: " ^ expected ^ "\n") err;
            Alcotest.(check bool) (what ^ ": no output file") false (Sys.file_exists out))
          [
            ([ "--samples"; "0" ], "samples must lie in [1, 64] (an N x N grid per pixel), got 0");
            ( [ "--adaptive"; "8" ],
              "adaptive sampling needs an odd number of samples >= 3, whose grid has the pixel's centre in its \
               middle (or, under a lens, any number >= 2), got 1" );
            ( [ "--samples"; "4"; "--adaptive"; "8" ],
              "adaptive sampling needs an odd number of samples >= 3, whose grid has the pixel's centre in its \
               middle (or, under a lens, any number >= 2), got 4" );
            ([ "--samples"; "3"; "--adaptive"; "300" ], "the adaptive threshold must lie in [0, 255], got 300");
            ([ "--samples"; "2"; "--subsample" ], "subsampling traces one ray per pixel: it cannot be combined with samples > 1");
            ( [ "--literal"; "--samples"; "2" ],
              "--literal traces one ray per pixel: it cannot be combined with --samples or --subsample" );
          ]);
  ]
