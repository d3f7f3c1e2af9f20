(* Work and memory without a bound (issue 29): the estimate is an upper
   bound of the ray tree, the work is counted and checked often enough
   that no render passes its budget by more than a pixel's work, and what
   a scene makes the program allocate is counted before it is allocated. *)
open Raytrace

(* A fresh directory holding the files [(name, text)]: the directory. *)
let files contents =
  let dir = Helpers.temp_dir () in
  List.iter
    (fun (name, text) ->
      let oc = open_out_bin (Filename.concat dir name) in
      output_string oc text;
      close_out oc)
    contents;
  dir

let env vars = Array.append (Array.of_list vars) (Unix.environment ())

let contains s sub =
  let n = String.length sub in
  let rec at i = i + n <= String.length s && (String.sub s i n = sub || at (i + 1)) in
  at 0

let one_line what err =
  Alcotest.(check bool)
    (what ^ ": one line starting with raytrace: " ^ err)
    true
    (String.length err > 10
    && String.sub err 0 10 = "raytrace: "
    && List.length (String.split_on_char '\n' err) = 2
    && not (contains err "internal error" || contains err "exception"))

(* Four glass planes that reflect half and let half through: every hit
   spawns two rays, 2^41 - 1 rays per pixel at depth 40. *)
let glass_planes ~depth =
  Printf.sprintf "(canvas (width 16) (height 16))\n(recursion-depth %d)\n%s(light ambient (intensity 0.2))\n\
                  (light point (intensity 0.6) (position 2 1 0))\n"
    depth
    (String.concat ""
       (List.init 4 (fun i ->
            Printf.sprintf
              "(plane (point 0 0 %d) (normal 0 0 -1) (color 255 255 255) (transparency 0.5) (reflective 0.5) \
               (refractive-index 1.5))\n"
              (i + 2))))

(* 2000 concentric spheres around the camera: every ray meets every one
   of them, which no hierarchy can avoid; the estimate says 16 x 11 = 176
   tests a ray, the truth is 2000 and more. *)
let concentric ~width ~height =
  Printf.sprintf "(canvas (width %d) (height %d)) (camera (position 0 0 0)) (recursion-depth 0)\n\
                  (light ambient (intensity 1))\n%s"
    width height
    (String.concat ""
       (List.init 2000 (fun i ->
            Printf.sprintf "(sphere (center 0 0 0) (radius %s) (color 255 0 0))\n"
              (Float_text.to_string (10. +. (Float.of_int i *. 1e-5))))))

(* The count in "the render was stopped after N intersection tests". *)
let stopped_after err =
  let prefix = "raytrace: the render was stopped after " in
  let n = String.length prefix in
  if String.length err > n && String.sub err 0 n = prefix then
    Scanf.sscanf (String.sub err n (String.length err - n)) "%d " Fun.id
  else Alcotest.failf "not a stopped render: %s" err

let tests =
  [
    Alcotest.test_case "the estimate counts the ray tree of glass that reflects and refracts" `Quick (fun () ->
        (* 16 x 16 pixels x (2^41 - 1) rays x 4 planes x (1 + 1 light):
           256 x 2199023255551 x 4 x 2 = 4.5e15, beyond 1e12. Counted
           linearly in the depth it was 256 x 41 x 4 x 2 = 83968 tests, and
           the render ran for hours. *)
        let scene = Helpers.of_string (glass_planes ~depth:40) |> Result.get_ok in
        (match Scene.check_work (Helpers.valid scene) with
        | Ok () -> Alcotest.fail "accepted"
        | Error (`Msg m) ->
            Alcotest.(check string) __LOC__
              "the render needs about 4.5e+15 intersection tests (256 pixels x 1 samples x \
               2199023255551 rays (a tree of depth 40: a hit on glass that reflects may spawn two rays) x 4 \
               objects per ray x (1 + 1 lights)), more than the limit of 1000000000000 (set RAYTRACE_MAX_WORK \
               to raise it)"
              m);
        (* 2^(d+1) - 1 rays for a tree, d + 1 for a chain. *)
        Alcotest.(check (float 0.)) __LOC__ 31. (Limits.rays_per_sample ~depth:4 ~split:true);
        Alcotest.(check (float 0.)) __LOC__ 5. (Limits.rays_per_sample ~depth:4 ~split:false);
        (* 600 x 600 x 4 samples x 15 rays x 4 spheres x (1 + 2) *)
        Alcotest.(check (float 0.)) __LOC__ 259200000.
          (Limits.work ~split:true ~pixels:360000 ~samples:4 ~depth:3 ~spheres:4 ~lights:2 ());
        (* Glass without a mirror or the Fresnel term refracts or reflects,
           never both: a chain, as are mirrors alone. *)
        let chain =
          Helpers.of_string
            "(canvas (width 16) (height 16)) (recursion-depth 40)\n\
             (sphere (center 0 0 3) (radius 1) (color 255 255 255) (transparency 0.9) (refractive-index 1.5))\n\
             (light ambient (intensity 1))"
          |> Result.get_ok
        in
        Alcotest.(check bool) __LOC__ true (Scene.check_work (Helpers.valid chain) = Ok ()));
    Alcotest.test_case "a CSG solid's leaves count in the estimate, each tested by every ray that meets it" `Quick
      (fun () ->
        (* 1000 x 1000 pixels x 1 ray x (1 object + 3 leaves) x (1 + 1
           light) = 8e6, beyond 3e6; counted as one object it was 2e6. *)
        let scene =
          Helpers.of_string
            "(canvas (width 1000) (height 1000)) (recursion-depth 0)\n\
             (csg union (sphere (center 0 0 3) (radius 1) (color 255 0 0))\n\
             \  (csg difference (sphere (center 1 0 3) (radius 1) (color 255 0 0)) (box (min 0 0 0) (max 1 1 1) (color 1 2 3))))\n\
             (light point (intensity 1) (position 0 0 0))"
          |> Result.get_ok
        in
        let limits = Limits.with_bound Limits.default `Work 3e6 in
        match Scene.check_work ~limits (Helpers.valid scene) with
        | Ok () -> Alcotest.fail "accepted"
        | Error (`Msg m) ->
            Alcotest.(check string) __LOC__
              "the render needs about 8e+06 intersection tests (1000000 pixels x 1 samples x 1 rays x 4 \
               objects per ray (with 3 leaves of CSG solids) x (1 + 1 lights)), more than the limit of 3000000 (set \
               RAYTRACE_MAX_WORK to raise it)"
              m);
    Alcotest.test_case "a transparent scene's depth counts in the estimate" `Quick (fun () ->
        (* Transparent, not reflective: the refracted rays bounce too.
           100 x 100 pixels x 65 rays x 1 x 1 = 650000, beyond 600000;
           counted at depth 0 it was 10000. *)
        let scene =
          Helpers.of_string
            "(canvas (width 100) (height 100)) (recursion-depth 64)\n\
             (sphere (center 0 0 3) (radius 1) (color 255 255 255) (transparency 0.9) (refractive-index 1.5))\n\
             (light ambient (intensity 1))"
          |> Result.get_ok
        in
        let limits = Limits.with_bound Limits.default `Work 600000. in
        Alcotest.(check bool) __LOC__ true (Result.is_error (Scene.check_work ~limits (Helpers.valid scene))));
    Alcotest.test_case "a render the estimate refuses says so in one line, at once" `Quick (fun () ->
        let dir = files [ ("glass.scene", glass_planes ~depth:40) ] in
        let out = Filename.concat dir "out.ppm" in
        let t0 = Unix.gettimeofday () in
        let code, _, err = Helpers.run (Helpers.raytrace ()) [ "render"; Filename.concat dir "glass.scene"; "-o"; out ] in
        Alcotest.(check int) ("exit status: " ^ err) 1 code;
        one_line "refused" err;
        Alcotest.(check bool) "no output" false (Sys.file_exists out);
        Alcotest.(check bool) "at once" true (Unix.gettimeofday () -. t0 < 10.);
        (* The window too, before it opens (with or without a display). *)
        let code, _, err =
          Helpers.run ~env:(env [ "DISPLAY=" ]) (Helpers.raytrace ()) [ "view"; Filename.concat dir "glass.scene" ]
        in
        Alcotest.(check int) ("view: exit status: " ^ err) 1 code;
        one_line "view" err;
        Alcotest.(check bool) ("view: names the bound: " ^ err) true (contains err "RAYTRACE_MAX_WORK"));
    Alcotest.test_case "a depth of max_int is refused in one line, never an internal error" `Quick (fun () ->
        (* With the depth bound raised as far as it goes: the estimate
           saturates (2^(max_int + 1) rays is infinity, not an overflow),
           and a tracer's storage per level has a fixed bound. *)
        let depth = string_of_int max_int in
        let dir =
          files
            [
              ("glass.scene", glass_planes ~depth:1);
              ( "matte.scene",
                "(canvas (width 4) (height 4)) (sphere (center 0 0 3) (radius 1) (color 255 0 0))\n\
                 (light ambient (intensity 1))" );
            ]
        in
        let out = Filename.concat dir "out.ppm" in
        List.iter
          (fun (scene, args) ->
            let what = String.concat " " (scene :: args) in
            let code, _, err =
              Helpers.run
                ~env:(env [ "RAYTRACE_MAX_DEPTH=" ^ depth; "RAYTRACE_MAX_WORK=1e300" ])
                (Helpers.raytrace ())
                ([ "render"; Filename.concat dir scene; "-o"; out ] @ args)
            in
            Alcotest.(check int) (what ^ ": exit status: " ^ err) 1 code;
            one_line what err)
          [ ("glass.scene", [ "--depth"; depth ]); ("matte.scene", [ "--depth"; depth ]) ];
        (* Two facing mirrors and a glass ball: the ray tree of a scene
           with transparency is followed by recursion, whose stack (8 MiB)
           overflowed at about 20000 levels. *)
        let mirrors =
          "(canvas (width 3) (height 3)) (camera (position 0 0 0)) (recursion-depth 25000)\n\
           (sphere (center 0 0 -1001) (radius 998) (color 255 0 0) (reflective 1))\n\
           (sphere (center 0 0 1001) (radius 998) (color 0 255 0) (reflective 1))\n\
           (sphere (center 100 100 100) (radius 1) (color 0 255 0) (transparency 0.5))\n\
           (light ambient (intensity 0.2))\n"
        in
        let dir = files [ ("mirrors.scene", mirrors) ] in
        let code, _, err =
          Helpers.run ~env:(env [ "RAYTRACE_MAX_DEPTH=1000000" ]) (Helpers.raytrace ())
            [ "render"; Filename.concat dir "mirrors.scene"; "-o"; Filename.concat dir "out.ppm" ]
        in
        Alcotest.(check int) ("deep glass: exit status: " ^ err) 1 code;
        Alcotest.(check string) __LOC__
          "raytrace: recursion depth 25000 is too deep for a scene with transparent objects: their ray tree is \
           followed by recursion, at most 4096 levels\n"
          err;
        Alcotest.(check bool) __LOC__ true
          (Limits.work ~split:true ~pixels:1 ~samples:1 ~depth:max_int ~spheres:1 ~lights:0 () = infinity);
        Alcotest.(check bool) __LOC__ true
          (Limits.work ~pixels:1 ~samples:1 ~depth:max_int ~spheres:1 ~lights:0 () > 4e18);
        (* A scene where nothing reflects keeps no storage for its depth. *)
        let matte =
          Helpers.with_objects
            ~spheres:(List.map (fun s -> Helpers.with_sphere_material s (Material.update ~reflective:0.)) (Helpers.scene_spheres Scene.cgfs))
            (Scene.with_overrides ~depth:(1 lsl 20) Scene.cgfs)
        in
        let limits = Limits.with_bound Limits.default `Depth (Float.of_int (1 lsl 20)) in
        match Scene.validate ~limits matte with
        | Error (`Msg m) -> Alcotest.fail m
        | Ok valid -> Alcotest.(check int) __LOC__ 0 (Prepared.prepare valid).depth);
    Alcotest.test_case "a render stops within a pixel's work of its budget, even on one wide row" `Slow (fun () ->
        (* 65536 x 2 pixels: the estimate, 131072 x 176 = 2.3e7 tests,
           lets it through a budget of 3e7; each pixel does about 2000
           tests, 2.6e8 in all. Checked once a row, the first row ran to
           1.3e8 before the check. *)
        let budget = 30_000_000 in
        let dir = files [ ("wide.scene", concentric ~width:65536 ~height:2) ] in
        let scene = Filename.concat dir "wide.scene" and out = Filename.concat dir "out.ppm" in
        List.iter
          (fun args ->
            let what = String.concat " " args in
            let code, _, err =
              Helpers.run ~env:(env [ "RAYTRACE_MAX_WORK=" ^ string_of_int budget ]) (Helpers.raytrace ())
                ([ "render"; scene; "-o"; out ] @ args)
            in
            Alcotest.(check int) (what ^ ": exit status: " ^ err) 1 code;
            one_line what err;
            let n = stopped_after err in
            Alcotest.(check bool)
              (Printf.sprintf "%s: stopped after %d tests, within 1.05 x %d" what n budget)
              true
              (n > budget && Float.of_int n <= 1.05 *. Float.of_int budget);
            Alcotest.(check bool) (what ^ ": no output") false (Sys.file_exists out))
          [
            [ "--jobs"; "1" ]; [ "--jobs"; "2" ]; [ "--jobs"; "1"; "--subsample" ]; [ "--jobs"; "2"; "--subsample" ];
            [ "--jobs"; "2"; "--tile"; "1/2" ];
          ]);
    Alcotest.test_case "every sampling mode and the progressive renderer stop within a pixel's work" `Quick
      (fun () ->
        (* 4096 x 1 pixels: 4096 x 9 samples x 176 = 6.5e6 estimated; the
           truth 4096 x 9 x 2000 = 7.4e7. One ray a pixel (or half of one,
           subsampled): 720896 estimated, about 8e6 (4e6) done. The worst
           pixel does 9 x 2000 tests and a few boxes. *)
        let valid = Helpers.valid (Result.get_ok (Helpers.of_string (concentric ~width:4096 ~height:1))) in
        let within what budget n =
          Alcotest.(check bool)
            (Printf.sprintf "%s: stopped after %d tests, budget %d" what n budget)
            true
            (n > budget && n <= budget + 30_000)
        in
        List.iter
          (fun (what, budget, samples, adaptive, subsample) ->
            let limits = Limits.with_bound Limits.default `Work (Float.of_int budget) in
            match Render.image ~limits ~samples ?adaptive ~subsample valid with
            | Ok _ -> Alcotest.failf "%s: rendered" what
            | Error (`Msg m) -> within what budget (stopped_after ("raytrace: " ^ m ^ "\n")))
          [
            ("one ray", 2_000_000, 1, None, false); ("3 x 3", 6_600_000, 3, None, false);
            ("adaptive", 6_600_000, 3, Some 0, false); ("subsampled", 2_000_000, 1, None, true);
          ];
        let budget = 2_000_000 in
        let limits = Limits.with_bound Limits.default `Work (Float.of_int budget) in
        let r = Progressive.create ~limits valid in
        let rec go () = match Progressive.step ~rows:1 r with Some _ -> go () | None -> () in
        go ();
        match Progressive.stopped r with
        | None -> Alcotest.fail "the progressive render went to its end"
        | Some m -> (
            within "progressive" budget (stopped_after ("raytrace: " ^ m ^ "\n"));
            (* The window's workers share the budget: 512 x 8 pixels, the
               full-resolution rows traced by 2 workers, 4 rows a step. *)
            let valid = Helpers.valid (Result.get_ok (Helpers.of_string (concentric ~width:512 ~height:8))) in
            let workers = Progressive_workers.v ~jobs:2 ~width:512 ~height:8 in
            let r = Progressive.create ~limits ~workers valid in
            let rec go () = match Progressive.step ~rows:4 r with Some _ -> go () | None -> () in
            go ();
            match Progressive.stopped r with
            | None -> Alcotest.fail "the progressive render with workers went to its end"
            | Some m -> within "progressive, 2 workers" budget (stopped_after ("raytrace: " ^ m ^ "\n"))));
    Alcotest.test_case "the triangles of every mesh form count against a bound before they are made" `Quick
      (fun () ->
        (* A file of 2 triangles named 6 times: 12 triangles, beyond a
           bound of 10 at the sixth form (line 7), whose copy is not made. *)
        let obj = "v 0 0 3\nv 1 0 3\nv 0 1 3\nv 1 1 3\nf 1 2 3\nf 2 4 3\n" in
        let scene =
          "(canvas (width 4) (height 4))\n"
          ^ String.concat "" (List.init 6 (fun _ -> "(mesh (file \"m.obj\") (color 255 0 0))\n"))
          ^ "(light ambient (intensity 1))\n"
        in
        let dir = files [ ("m.obj", obj); ("s.scene", scene) ] in
        let path = Filename.concat dir "s.scene" and out = Filename.concat dir "out.ppm" in
        let code, _, err =
          Helpers.run ~env:(env [ "RAYTRACE_MAX_TRIANGLES=10" ]) (Helpers.raytrace ()) [ "render"; path; "-o"; out ]
        in
        Alcotest.(check int) ("exit status: " ^ err) 1 code;
        Alcotest.(check string) __LOC__
          (Printf.sprintf
             "raytrace: %s:7:1: the scene's meshes have 12 triangles in all, more than the limit of 10 (set \
              RAYTRACE_MAX_TRIANGLES to raise it)\n"
             path)
          err;
        let code, _, err =
          Helpers.run ~env:(env [ "RAYTRACE_MAX_TRIANGLES=12" ]) (Helpers.raytrace ()) [ "render"; path; "-o"; out ]
        in
        Alcotest.(check int) ("within the bound: " ^ err) 0 code;
        (* The library's check of a scene made in OCaml. *)
        match Helpers.read_scene path with
        | Error (`Msg m) -> Alcotest.fail m
        | Ok s -> (
            let limits = Limits.with_bound Limits.default `Triangles 11. in
            match Scene.validate ~limits s with
            | Ok _ -> Alcotest.fail "validated"
            | Error (`Msg m) ->
                Alcotest.(check string) __LOC__
                  "the scene's meshes have 12 triangles in all, more than the limit of 11 (set \
                   RAYTRACE_MAX_TRIANGLES to raise it)"
                  m));
      Alcotest.test_case "random scenes of every form, with their mesh files on disk, render or fail in one line" `Quick
      (fun () ->
        (* The command line end to end (files, workers, the budget shared
           by 2 jobs): an image, or one line and status 1, never an
           internal error or a render far past its budget. *)
        let rand = Random.State.make [| 29 |] in
        for i = 1 to 24 do
          let text, meshes = Hostile.random_scene rand in
          let dir = files (("s.scene", text) :: meshes) in
          let out = Filename.concat dir "out.ppm" in
          let jobs = string_of_int (1 + (i mod 2)) in
          let code, _, err =
            Helpers.run ~env:(env [ "RAYTRACE_MAX_WORK=1000000" ]) (Helpers.raytrace ())
              [ "render"; Filename.concat dir "s.scene"; "-o"; out; "--jobs"; jobs; "--quiet" ]
          in
          let what = Printf.sprintf "scene %d (--jobs %s): %s\n%s" i jobs err text in
          if code = 0 then Alcotest.(check bool) (what ^ ": an image") true (Sys.file_exists out)
          else begin
            Alcotest.(check int) (what ^ ": exit status") 1 code;
            one_line what err;
            Alcotest.(check bool) (what ^ ": no output") false (Sys.file_exists out);
            if contains err "the render was stopped after" then
              Alcotest.(check bool) (what ^ ": near its budget") true (stopped_after err <= 1_100_000)
          end
        done);
  ]
