(* Hostile input: the fuzzing corpus replayed, example files mutated at
   random, and the inputs that once crashed, hung or exhausted memory.
   Every input must end in a scene or one line of error ([Hostile]), and
   every resource bound must be refused up front, saying how to raise it. *)
open Raytrace

let corpus kind =
  let dir = Filename.concat "corpus" kind in
  Sys.readdir dir |> Array.to_list |> List.sort String.compare
  |> List.map (fun f -> (f, In_channel_free.read (Filename.concat dir f)))

let holds what property input =
  match property input with
  | Ok () -> ()
  | Error m ->
      let shown = if String.length input > 200 then String.sub input 0 200 ^ "..." else input in
      Alcotest.failf "%s: %s\ninput: %S" what m shown

let example_scenes () = List.map (fun n -> In_channel_free.read (Helpers.scene_path n)) (Helpers.scene_names ())

let example_ppms () =
  let img = Helpers.image_exn (Scene.with_overrides ~width:5 ~height:3 Scene.cgfs) in
  let p6 = Image.Ppm.to_string img in
  let p3 =
    let b = Buffer.create 256 in
    Buffer.add_string b "P3\n# a comment\n5 3\n255\n";
    for k = 0 to (3 * 5 * 3) - 1 do
      Buffer.add_string b (string_of_int (Image.channel img k));
      Buffer.add_char b (if k mod 3 = 2 then '\n' else ' ')
    done;
    Buffer.contents b
  in
  [ p6; p3; "P6\n1 1\n7\n\001\002\003" ]

(* A seed file, mutated by [Hostile.mutate]; printed escaped on failure. *)
let mutated seeds tokens =
  let seeds = Array.of_list seeds in
  QCheck.make ~print:String.escaped
    QCheck.Gen.(
      int_bound (Array.length seeds - 1) >>= fun i ->
      fun rand -> Hostile.mutate rand ~tokens seeds.(i))

(* The bounds of the tests: the environment's, read once by [with_env]. *)
let limits = ref Limits.default

let scene_error text =
  match Scene_file.of_string ~limits:!limits ~file:"t.scene" text with
  | Ok _ -> Alcotest.failf "accepted %S" (String.sub text 0 (min 60 (String.length text)))
  | Error (`Msg m) -> m

(* Runs [f] with environment variable [name] set to [value] and [limits]
   read from the environment as the command line reads them, then unset. *)
let with_env name value f =
  Unix.putenv name value;
  Fun.protect
    ~finally:(fun () ->
      Unix.putenv name "";
      limits := Limits.default)
    (fun () ->
      (match Limits_env.read () with Ok l -> limits := l | Error (`Msg m) -> Alcotest.fail m);
      f ())

(* A fresh directory holding the scene file [name] with [text]: both paths. *)
let scene_file name text =
  let dir = Helpers.temp_dir () in
  let path = Filename.concat dir name in
  let oc = open_out_bin path in
  output_string oc text;
  close_out oc;
  (dir, path)

let allocated f =
  let before = Gc.allocated_bytes () in
  f ();
  Gc.allocated_bytes () -. before

let spheres n =
  String.concat "\n"
    (List.init n (fun i -> Printf.sprintf "(sphere (center %d 0 5) (radius 0.5) (color 255 0 0))" i))

let tests =
  [
    Alcotest.test_case "every scene of the fuzzing corpus is a scene or one located line" `Quick (fun () ->
        let files = corpus "scene" in
        if List.length files < 20 then Alcotest.failf "only %d files in corpus/scene" (List.length files);
        List.iter (fun (f, text) -> holds f Hostile.scene text) files);
    Alcotest.test_case "every image of the fuzzing corpus is an image or one line" `Quick (fun () ->
        let files = corpus "ppm" in
        if List.length files < 10 then Alcotest.failf "only %d files in corpus/ppm" (List.length files);
        List.iter (fun (f, bytes) -> holds f Hostile.ppm bytes) files);
    Helpers.qcheck ~count:400 "mutated example scenes are scenes or one located line"
      (mutated (example_scenes ()) Hostile.scene_tokens)
      (fun text ->
        (* With the example textures, so that the mutants of globe.scene
           reach the textured renderer. *)
        let files = List.map (fun f -> (f, In_channel_free.read (Helpers.scene_path f))) [ "earth.ppm"; "tiles.ppm" ] in
        holds "mutated scene" (Hostile.scene ~files) text;
        true);
    Helpers.qcheck ~count:300
      "random scenes of every form (meshes, CSG, glass, patterns) render within their work budget or fail with one located line"
      (QCheck.make
         ~print:(fun (text, meshes) ->
           text ^ String.concat "" (List.map (fun (n, t) -> Printf.sprintf "\n--- %s\n%s" n t) meshes))
         Hostile.random_scene)
      (fun (text, meshes) ->
        (match Hostile.scene ~files:meshes text with Ok () -> () | Error m -> Alcotest.failf "%s\ninput:\n%s" m text);
        true);
    Helpers.qcheck ~count:400 "mutated images are images or one line"
      (mutated (example_ppms ()) Hostile.ppm_tokens)
      (fun bytes -> holds "mutated image" Hostile.ppm bytes; true);
    Alcotest.test_case "a million nested parentheses are one error, not a stack overflow" `Quick (fun () ->
        let n = 1_000_000 and m = 100_000 in
        List.iter
          (fun text -> holds "deep nesting" Hostile.scene text)
          [
            String.make n '(' ^ String.make n ')';
            String.make m '(';
            "(sphere " ^ String.make m '(' ^ String.make m ')' ^ ")";
            "(camera (rotation (1 0 0) (0 1 0) " ^ String.make m '(' ^ String.make m ')' ^ "))";
            String.concat "" (List.init m (fun _ -> "()"));
          ]);
    Alcotest.test_case "a sexp comment with nothing to comment is a syntax error, not an assertion" `Quick
      (fun () ->
        (* parsexp v0.15's CST parser raises Assert_failure on these (found
           by the crowbar target); the plain parser's message is used. *)
        List.iter
          (fun (text, expected) -> Alcotest.(check string) text expected (scene_error text))
          [
            ("(#;)", "t.scene:1:4: syntax error: unterminated sexp comment");
            ("(sphere (center 0 0 3) (radius #;) (color 1 2 3))", "t.scene:1:34: syntax error: unterminated sexp comment");
            ("(light ambient\n  (intensity 1) #; ; why\n)", "t.scene:3:1: syntax error: unterminated sexp comment");
          ]);
    Alcotest.test_case "texture forms and files gone wrong are one located line" `Quick (fun () ->
        (* Kept here rather than in corpus/scene, whose files the web
           suite also gives the page, which holds textures of its own. *)
        let files =
          [ ("t.ppm", "P6\n2 1\n255\n\001\002\003\004\005\006"); ("empty.ppm", ""); ("truncated.ppm", "P6\n4 4\n255\n\001");
            ("huge.ppm", "P6\n99999 99999\n255\n"); ("wrong.ppm", "v 0 0 0\n") ]
        in
        let sphere t = "(sphere (center 0 0 3) (radius 1) (color 1 2 3) (texture " ^ t ^ "))" in
        List.iter
          (fun text -> holds "texture" (Hostile.scene ~files) text)
          ([ "(box (min -1 -1 2) (max 1 1 4) (color 1 2 3) (texture (file \"t.ppm\") (mapping spherical)))";
             "(cylinder (base 0 0 3) (top 0 1 3) (radius 1) (color 1 2 3) (texture (file \"t.ppm\") (mapping planar)))";
             "(plane (point 0 -1 0) (normal 0 1 0) (color 1 2 3) (pattern checker (color 0 0 0) (size 1)) (texture (file \"t.ppm\") (mapping planar)))";
             "(plane (point 0 -1 0) (normal 0 1 0) (color 1 2 3) (texture (file \"t.ppm\") (mapping planar) (size 1e-30)))";
             "(csg union (sphere (center 0 0 3) (radius 1) (color 1 2 3) (texture (file \"t.ppm\") (mapping spherical))) (sphere (center 0 0 4) (radius 1) (color 1 2 3)))";
             "(transform ((translate 0 0 3)) (box (min -1 -1 -1) (max 1 1 1) (color 1 1 1)) (color 1 2 3) (texture (file \"t.ppm\") (mapping box)))";
           ]
          @ List.map sphere
              [ "(file \"t.ppm\") (mapping spherical)"; "(file \"t.ppm\") (mapping spherical) (size 2)"; "(file \"t.ppm\")";
                "(mapping spherical)"; "(file \"\") (mapping spherical)"; "(file \"missing.ppm\") (mapping spherical)";
                "(file \"empty.ppm\") (mapping spherical)"; "(file \"truncated.ppm\") (mapping spherical)";
                "(file \"huge.ppm\") (mapping spherical)"; "(file \"wrong.ppm\") (mapping spherical)";
                "(file t.ppm) (mapping cubic)"; "(file \"t.ppm\") (mapping spherical) (file \"t.ppm\")"; "" ]));
    Alcotest.test_case "a file name or a loader's message with a line break is one line" `Quick (fun () ->
        (* Found by mutating globe.scene: a texture's (or a mesh's) file
           name holding a newline made a two-line message, with the
           library's own loader (no files) and with any loader that names
           the file, as the web page's does. *)
        let texture = "(sphere (center 0 0 3) (radius 1) (color 1 2 3) (texture (file \"a\nb.ppm\") (mapping spherical)))" in
        let mesh = "(mesh (file \"a\nb.obj\") (color 1 2 3))" in
        let read ?load_mesh ?load_texture text =
          match Scene_file.of_string ?load_mesh ?load_texture ~file:"t.scene" text with
          | Ok _ -> Alcotest.failf "accepted %S" text
          | Error (`Msg m) -> m
        in
        Alcotest.(check string) __LOC__
          "t.scene:1:58: cannot read texture file a\\nb.ppm: this scene was given as text, with no way to read files"
          (read texture);
        Alcotest.(check string) __LOC__
          "t.scene:1:7: cannot read mesh file a\\nb.obj: this scene was given as text, with no way to read files" (read mesh);
        let refuse name = Error (`Msg (Printf.sprintf "cannot read %s:\r\n\tno\000" name)) in
        Alcotest.(check string) __LOC__ "t.scene:1:58: cannot read a\\nb.ppm:\\r\\n\\tno\\x00"
          (read ~load_texture:refuse texture);
        Alcotest.(check string) __LOC__ "t.scene:1:7: cannot read a\\nb.obj:\\r\\n\\tno\\x00" (read ~load_mesh:refuse mesh));
    Alcotest.test_case "the textures of a scene count against the pixel bound together" `Quick (fun () ->
        (* Each texture file is within the pixel bound, but the scene keeps
           every texture it reads: without a bound on their sum, a scene of
           many big texture files held them all (a file at the bound is
           805 MB of pixels). They count as the meshes' triangles do. *)
        let image = "P6\n3 3\n255\n" ^ String.make 27 '\100' in
        let load_texture name =
          if List.mem name [ "a.ppm"; "b.ppm" ] then Result.map Image.Texture.of_image (Image.Ppm.of_string image)
          else Error (`Msg ("cannot read texture file: " ^ name))
        in
        let limits = Limits.with_bound Limits.default `Pixels 10. in
        let sphere file =
          Printf.sprintf "(sphere (center 0 0 3) (radius 1) (color 1 2 3) (texture (file %S) (mapping spherical)))" file
        in
        let read text = Scene_file.of_string ~limits ~load_texture ~file:"t.scene" ("(canvas (width 1) (height 1))\n" ^ text) in
        (* One file used twice is read once: 9 pixels. *)
        (match read (sphere "a.ppm" ^ "\n" ^ sphere "a.ppm") with
        | Ok _ -> ()
        | Error (`Msg m) -> Alcotest.failf "one texture of 9 pixels, used twice, refused: %s" m);
        match read (sphere "a.ppm" ^ "\n" ^ sphere "b.ppm") with
        | Ok _ -> Alcotest.fail "two textures of 9 pixels accepted under a bound of 10"
        | Error (`Msg m) ->
            Alcotest.(check string) __LOC__
              "t.scene:3:58: texture b.ppm brings the scene's textures to 18 pixels in all, more than the limit of 10 \
               (set RAYTRACE_MAX_PIXELS to raise it)"
              m);
    Alcotest.test_case "a megabyte-long unknown name costs no more memory than its text" `Quick (fun () ->
        (* The suggestion for a misspelt name once computed an edit distance
           table of 2 MB x 15 cells for this input (500 MB; 2.4 GB and 51 s
           for a 10 MB name). *)
        let text = "(" ^ String.make 2_000_000 'x' ^ ")" in
        let bytes = allocated (fun () -> ignore (scene_error text)) in
        if bytes > 64e6 then Alcotest.failf "parsing allocated %.0f MB" (bytes /. 1e6);
        Alcotest.(check string) __LOC__ "t.scene:1:2: unknown form"
          (String.sub (scene_error text) 0 (String.length "t.scene:1:2: unknown form")));
    Alcotest.test_case "an image header cannot ask for more memory than the pixel bound" `Quick (fun () ->
        let bytes = allocated (fun () -> ignore (Image.Ppm.of_string "P6\n16384 16384\n255\n\000")) in
        if bytes > 1e6 then Alcotest.failf "decoding a lying header allocated %.0f bytes" bytes;
        match Image.Ppm.of_string "P6\n99999 99999\n255\n" with
        | Ok _ -> Alcotest.fail "accepted"
        | Error (`Msg m) ->
            Alcotest.(check string) __LOC__
              "image 99999x99999 has 9999800001 pixels, more than the limit of 268435456 (set \
               RAYTRACE_MAX_PIXELS to raise it)"
              m);
    Alcotest.test_case "resource bounds are refused with the variable that raises them" `Quick (fun () ->
        Alcotest.(check string) __LOC__
          "t.scene:1:1: canvas 65536x8192 has 536870912 pixels, more than the limit of 268435456 (set \
           RAYTRACE_MAX_PIXELS to raise it)"
          (scene_error "(canvas (width 65536) (height 8192))");
        Alcotest.(check string) __LOC__
          "t.scene:1:18: recursion depth 65 is too deep, more than the limit of 64 (set \
           RAYTRACE_MAX_DEPTH to raise it)"
          (scene_error "(recursion-depth 65)");
        with_env "RAYTRACE_MAX_SPHERES" "3" (fun () ->
            Alcotest.(check string) __LOC__
              "t.scene:4:1: the scene has 4 spheres, more than the limit of 3 (set \
               RAYTRACE_MAX_SPHERES to raise it)"
              (scene_error (spheres 4));
            (* Boxes, or spheres after another shape, are objects, not spheres. *)
            let box = "(box (min 0 0 0) (max 1 1 1) (color 1 2 3))\n" in
            Alcotest.(check string) __LOC__
              "t.scene:4:1: the scene has 4 objects, more than the limit of 3 (set RAYTRACE_MAX_SPHERES to raise it)"
              (scene_error (String.concat "" (List.init 4 (fun _ -> box))));
            Alcotest.(check string) __LOC__
              "t.scene:4:1: the scene has 4 objects, more than the limit of 3 (set RAYTRACE_MAX_SPHERES to raise it)"
              (scene_error (box ^ spheres 3));
            (* And a scene built in code, checked by Scene.validate. *)
            match Helpers.of_string (box ^ box) with
            | Error (`Msg m) -> Alcotest.fail m
            | Ok s -> (
                match Scene.validate ~limits:(Limits.with_bound Limits.default `Spheres 1.) s with
                | Ok _ -> Alcotest.fail "two boxes within a bound of 1"
                | Error (`Msg m) ->
                    Alcotest.(check string) __LOC__
                      "the scene has 2 objects, more than the limit of 1 (set RAYTRACE_MAX_SPHERES to raise it)" m));
        with_env "RAYTRACE_MAX_LIGHTS" "1" (fun () ->
            Alcotest.(check string) __LOC__
              "t.scene:1:30: the scene has 2 lights, more than the limit of 1 (set \
               RAYTRACE_MAX_LIGHTS to raise it)"
              (scene_error "(light ambient (intensity 1))(light ambient (intensity 1))"));
        with_env "RAYTRACE_MAX_SCENE_BYTES" "1000" (fun () ->
            Alcotest.(check string) __LOC__
              "t.scene: the scene is 1002 bytes long, more than the limit of 1000 (set \
               RAYTRACE_MAX_SCENE_BYTES to raise it)"
              (scene_error (";" ^ String.make 1000 'x' ^ "\n"))));
    Alcotest.test_case "a raised bound lets the scene through" `Quick (fun () ->
        with_env "RAYTRACE_MAX_DEPTH" "1_000" (fun () ->
            match Helpers.of_string ~limits:!limits "(recursion-depth 1000)" with
            | Ok s -> Alcotest.(check int) __LOC__ 1000 (Scene.depth s)
            | Error (`Msg m) -> Alcotest.fail m);
        with_env "RAYTRACE_MAX_PIXELS" "1e9" (fun () ->
            match Helpers.of_string ~limits:!limits "(canvas (width 65536) (height 8192))" with
            | Ok s -> Alcotest.(check int) __LOC__ 8192 (Scene.height s)
            | Error (`Msg m) -> Alcotest.fail m));
    Alcotest.test_case "a malformed bound is an error that names the variable" `Quick (fun () ->
        Unix.putenv "RAYTRACE_MAX_DEPTH" "lots";
        Fun.protect
          ~finally:(fun () -> Unix.putenv "RAYTRACE_MAX_DEPTH" "")
          (fun () ->
            match Limits_env.read () with
            | Ok _ -> Alcotest.fail "accepted"
            | Error (`Msg m) ->
                Alcotest.(check string) __LOC__ "RAYTRACE_MAX_DEPTH must be a positive integer, got \"lots\"" m));
    Alcotest.test_case "a render that would take years is refused before it starts" `Quick (fun () ->
        (* 65536 x 4096 = 268435456 pixels x 4 rays (depth 3, reflective
           spheres) x 4 spheres x (1 + 2 shadow-casting lights) = 1.288e10
           tests: within 1e12. 1024 samples per pixel: 1.319e13, beyond. *)
        let big = Scene.with_overrides ~width:65536 ~height:4096 Scene.cgfs in
        Alcotest.(check bool) __LOC__ true (Scene.check_work (Helpers.valid big) = Ok ());
        (match Scene.check_work ~samples:1024 (Helpers.valid big) with
        | Ok () -> Alcotest.fail "1024 samples accepted"
        | Error (`Msg m) ->
            Alcotest.(check string) __LOC__
              "the render needs about 1.32e+13 intersection tests (268435456 pixels x \
               1024 samples x 4 rays x 4 objects per ray x (1 + 2 lights)), more than the limit of \
               1000000000000 (set RAYTRACE_MAX_WORK to raise it)"
              m);
        (* 400 spheres: a hierarchy of ceil (log2 400) = 9 levels, at most
           16 x 9 = 144 objects per ray; depth 64: 65 rays.
           268435456 x 65 x 144 x 3 = 7.54e12. *)
        let crowded =
          Scene.with_overrides ~depth:64 ~objects:(List.concat (List.init 100 (fun _ -> Scene.objects Scene.cgfs))) big
        in
        match Helpers.render crowded with
        | Ok _ -> Alcotest.fail "rendered"
        | Error (`Msg m) ->
            Alcotest.(check string) __LOC__
              "the render needs about 7.54e+12 intersection tests (268435456 pixels x 1 \
               samples x 65 rays x 144 objects per ray x (1 + 2 lights)), more than the limit of \
               1000000000000 (set RAYTRACE_MAX_WORK to raise it)"
              m);
    Alcotest.test_case "a scene that defeats the hierarchy is stopped once its tests pass the work bound" `Slow
      (fun () ->
        (* 20000 concentric spheres of radii 1 to 1.2 (identical ones would
           share one slot of the tracer's table, Prepared.n_scene_objects):
           no split separates them, and a ray
           that meets their box tests all 20000. The estimate: 32 x 32
           pixels x 1 ray x 16 log2 20000 = 16 x 15 spheres = 245760 tests,
           within 1e6. Done: about 130 pixels hit the sphere, 2.6e6 tests. *)
        let dir, scene =
          scene_file "coincident.scene"
            ("(canvas (width 32) (height 32)) (viewport (width 1) (height 1) (distance 1))\n\
              (camera (position 0 0 0)) (background 0 0 0) (recursion-depth 0)\n\
              (light ambient (intensity 1))\n"
            ^ String.concat ""
                (List.init 20000 (fun i ->
                     Printf.sprintf "(sphere (center 0 0 5) (radius %s) (color 255 0 0) (specular -1) (reflective 0))\n"
                       (Float_text.to_string (1. +. (Float.of_int i *. 1e-5))))))
        in
        let out = Filename.concat dir "out.ppm" in
        let env = Array.append [| "RAYTRACE_MAX_WORK=1e6" |] (Unix.environment ()) in
        List.iter
          (fun args ->
            let what = String.concat " " args in
            let code, _, err = Helpers.run ~env (Helpers.raytrace ()) ([ "render"; scene; "-o"; out ] @ args) in
            Alcotest.(check int) (what ^ ": exit status: " ^ err) 1 code;
            let prefix = "raytrace: the render was stopped after " in
            let suffix =
              " intersection tests (objects, CSG leaves and boxes of the hierarchies), more than the limit of 1000000 (set RAYTRACE_MAX_WORK \
               to raise it)\n"
            in
            let ends_with s e =
              String.length s >= String.length e && String.sub s (String.length s - String.length e) (String.length e) = e
            in
            Alcotest.(check bool) (what ^ ": one line: " ^ err) true
              (String.length err > String.length prefix
              && String.sub err 0 (String.length prefix) = prefix
              && ends_with err suffix
              && List.length (String.split_on_char '\n' err) = 2);
            Alcotest.(check bool) (what ^ ": no output") false (Sys.file_exists out))
          [
            [ "--jobs"; "1" ]; [ "--jobs"; "2" ]; [ "--literal" ]; [ "--jobs"; "2"; "--tile"; "1/2" ];
            [ "--jobs"; "1"; "--samples"; "2" ]; [ "--jobs"; "2"; "--subsample" ];
          ];
        (* Raised, the same scene renders. *)
        let env = Array.append [| "RAYTRACE_MAX_WORK=1e8" |] (Unix.environment ()) in
        let code, _, err = Helpers.run ~env (Helpers.raytrace ()) [ "render"; scene; "-o"; out; "--jobs"; "2" ] in
        Alcotest.(check int) ("a raised bound renders: " ^ err) 0 code);
    Alcotest.test_case "a light's huge sample counts are refused at once, in one line, without output" `Quick (fun () ->
        (* 4096 x 4096 samples of an area light, or 4096 of a sphere light on
           a glass scene, at the default bounds: the work estimate refuses
           them before any pixel (the command must end within seconds). *)
        let texts =
          [
            "(sphere (center 0 0 3) (radius 1) (color 200 100 50))\n\
             (light area (intensity 0.5) (corner -1 3 4) (edge1 2 0 0) (edge2 0 0 2) (samples 4096 4096) (adaptive true))";
            "(recursion-depth 8) (sphere (center 0 0 3) (radius 1) (color 200 100 50) (transparency 0.5) (reflective 0.4))\n\
             (light sphere (intensity 0.5) (position 0 3 0) (radius 1) (samples 4096))";
          ]
        in
        List.iter
          (fun text ->
            let dir, scene = scene_file "s.scene" text in
            let out = Filename.concat dir "out.ppm" in
            let t0 = Unix.gettimeofday () in
            let code, _, err = Helpers.run (Helpers.raytrace ()) [ "render"; scene; "-o"; out; "--samples"; "8" ] in
            Alcotest.(check int) ("exit status: " ^ err) 1 code;
            let prefix = "raytrace: the render needs about " in
            Alcotest.(check bool) ("one line: " ^ err) true
              (String.length err > String.length prefix
              && String.sub err 0 (String.length prefix) = prefix
              && List.length (String.split_on_char '\n' err) = 2);
            Alcotest.(check bool) "no output" false (Sys.file_exists out);
            let seconds = Unix.gettimeofday () -. t0 in
            if seconds > 5. then Alcotest.failf "refused after %.1f s" seconds)
          texts);
    Alcotest.test_case "the progressive render stops at the work bound too" `Quick (fun () ->
        (* 2000 concentric spheres (not identical: those share a slot), 16 x 16 pixels: estimate 256 x 16 x 11
           x (1 + 2 lights) = 135168 tests, within 2e5; a pixel that sees
           the sphere alone does 2000 x 3. *)
        let sphere = Private.Spheres.get (Scene.spheres Scene.cgfs) 0 in
        let scene =
          Helpers.with_objects
            ~spheres:(List.init 2000 (fun i -> Sphere.v ~center:sphere.center ~radius:(sphere.radius +. (Float.of_int i *. 1e-5)) sphere.material))
            (Scene.with_overrides ~width:16 ~height:16 ~depth:0 Scene.cgfs)
        in
        with_env "RAYTRACE_MAX_WORK" "200000" (fun () ->
            let valid = Helpers.valid scene in
            Alcotest.(check bool) "the estimate lets it through" true (Scene.check_work ~limits:!limits valid = Ok ());
            let r = Progressive.create ~limits:!limits valid in
            let rec go () = match Progressive.step ~rows:4 r with Some _ -> go () | None -> () in
            go ();
            Alcotest.(check bool) "finished" true (Progressive.finished r);
            match Progressive.stopped r with
            | None -> Alcotest.fail "the render went to its end"
            | Some m ->
                Alcotest.(check bool) ("names the variable: " ^ m) true
                  (String.length m > 30 && String.sub m (String.length m - 35) 35 = "(set RAYTRACE_MAX_WORK to raise it)")));
    Alcotest.test_case "the oracle follows a million reflections without overflowing the stack" `Slow (fun () ->
        (* Two convex mirrors face each other on the z axis; the middle
           pixel's ray bounces between them until the depth runs out. The
           recursive oracle died of Stack_overflow at this depth. *)
        let dir, scene =
          scene_file "mirrors.scene"
          "(canvas (width 3) (height 3)) (viewport (width 1) (height 1) (distance 1))\n\
           (camera (position 0 0 0)) (background 0 0 0) (recursion-depth 1000000)\n\
           (sphere (center 0 0 -1001) (radius 998) (color 255 0 0) (specular -1) (reflective 0.999))\n\
           (sphere (center 0 0 1001) (radius 998) (color 0 255 0) (specular -1) (reflective 0.999))\n\
           (light ambient (intensity 0.2))\n"
        in
        let env = Array.append [| "RAYTRACE_MAX_DEPTH=1000000" |] (Unix.environment ()) in
        let render args name =
          let out = Filename.concat dir name in
          let code, _, err = Helpers.run ~env (Helpers.raytrace ()) ([ "render"; scene; "-o"; out ] @ args) in
          Alcotest.(check int) (String.concat " " args ^ ": " ^ err) 0 code;
          match Files.read_ppm out with Ok img -> img | Error (`Msg m) -> Alcotest.fail m
        in
        Helpers.check_images "the oracle's image is the renderer's" ~expected:(render [ "--jobs"; "1" ] "fast.ppm")
          (render [ "--literal" ] "literal.ppm"));
    Alcotest.test_case "rays per pixel have a bound that --samples meets" `Quick (fun () ->
        let check_samples n = Result.map_error (fun (`Msg m) -> m) (Limits.check_samples Limits.default n) in
        Alcotest.(check (result int string)) __LOC__ (Ok 4096) (check_samples 4096);
        Alcotest.(check (result int string)) __LOC__
          (Error "4097 samples per pixel are too many, more than the limit of 4096 (set RAYTRACE_MAX_SAMPLES to raise it)")
          (check_samples 4097);
        (* --samples 8 is an 8 x 8 grid: 64 rays a pixel, beyond a bound of 50. *)
        with_env "RAYTRACE_MAX_SAMPLES" "50" (fun () ->
            match Helpers.render ~limits:!limits ~samples:8 (Scene.with_overrides ~width:4 ~height:4 Scene.cgfs) with
            | Ok _ -> Alcotest.fail "rendered"
            | Error (`Msg m) ->
                Alcotest.(check string) __LOC__
                  "64 samples per pixel are too many, more than the limit of 50 (set RAYTRACE_MAX_SAMPLES to raise it)" m);
        Alcotest.(check (result int string)) __LOC__ (Error "samples per pixel must be >= 1, got 0") (check_samples 0));
    Alcotest.test_case "the work estimate is the product of its factors" `Quick (fun () ->
        (* 600 * 600 pixels * 4 samples * (3 + 1) rays * 4 spheres * (1 + 2) = 69120000 *)
        Alcotest.(check (float 0.)) __LOC__ 69120000.
          (Limits.work ~pixels:360000 ~samples:4 ~depth:3 ~spheres:4 ~lights:2 ());
        (* 100000 spheres: 2^17 = 131072 >= 100000, so 16 x 17 = 272 per ray;
           1000 * 1 * 1 * 272 * 1 = 272000 *)
        Alcotest.(check (float 0.)) __LOC__ 272000.
          (Limits.work ~pixels:1000 ~samples:1 ~depth:0 ~spheres:100_000 ~lights:0 ()));
  ]
