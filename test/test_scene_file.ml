open Raytrace

let scene = Alcotest.testable Scene.pp Scene.equal

let parse text =
  match Helpers.of_string ~file:"t.scene" text with
  | Ok s -> s
  | Error (`Msg m) -> Alcotest.failf "unexpected error: %s" m

let error text =
  match Helpers.of_string ~file:"t.scene" text with
  | Ok _ -> Alcotest.failf "expected an error for %S" text
  | Error (`Msg m) -> m

(* Each bad input, and the exact message: file:line:column (1-based) and
   what was expected. *)
(* The forms of the described kinds ({!Private.Primitives}) follow csg's in
   the messages that list the forms: a new kind's name joins them there. *)
let described_forms = String.concat "" (List.map (fun (Private.Shape_desc.Any d) -> ", " ^ d.name) Private.Primitives.all)

let bad_inputs =
  [
    ("(material glass (color 1 1 1))\n(material glass (color 2 2 2))",
     "t.scene:2:11: material glass is defined twice (first at 1:11); a name may be defined only once");
    ("(sphere (center 0 0 3) (radius 1) (material glass))\n(material glass (color 1 1 1))",
     "t.scene:1:45: unknown material glass: no (material glass ...) form comes before it");
    ("(material glass (color 1 1 1))\n(box (min 0 0 3) (max 1 1 4) (material glas))",
     "t.scene:2:40: unknown material glas; defined before it: glass (did you mean glass?)");
    ("(material glass (color 1 1 1) (transparency 2))", "t.scene:1:45: material glass transparency must lie in [0, 1], got 2");
    ("(material glass (color 1 1 1) (reflective 0.5))\n(sphere (center 0 0 3) (radius 1) (material glass) (transparency 0.6))",
     "t.scene:2:66: sphere reflective + transparency must be <= 1, got 0.5 + 0.6");
    ("(material glass (specular 10))", "t.scene:1:1: material glass is missing its (color ...) field");
    ("(material glass (color 1 1 1) (material metal))",
     "t.scene:1:32: unknown material glass field material; expected color, specular, reflective, transparency, refractive-index, fresnel, pattern or texture");
    ("(material (color 1 1 1))", "t.scene:1:1: material: expected its name first, e.g. (material glass (color 230 230 255) (transparency 0.9))");
    ("(sphere (center 0 0 3) (radius 1) (material 1 2))",
     "t.scene:1:35: sphere material: expected the name of a material, e.g. (material glass)");
    ("(sphere (center 0 0 3) (radius 1) (color 1 2 3)", "t.scene:1:48: syntax error: unclosed parentheses at end of input");
    ("(sphere (center 0 0 3) (radius -1) (color 1 2 3))", "t.scene:1:32: sphere radius must be > 0, got -1");
    ("(sphere (center 0 0 3) (radius 1) (color 1 2 3) (reflective 1.5))",
     "t.scene:1:61: sphere reflective must lie in [0, 1], got 1.5");
    ("(sphere (center 0 0 3) (radius 1) (color 1 2 3) (reflectiv 0.5))",
     "t.scene:1:50: unknown sphere field reflectiv; expected center, radius, material, color, specular, reflective, transparency, refractive-index, fresnel, pattern or texture (did you mean reflective?)");
     ("(sphere (center 0 0 3) (radius 1) (color 1 2 3) (transparency 1.5))",
      "t.scene:1:63: sphere transparency must lie in [0, 1], got 1.5");
     ("(sphere (center 0 0 3) (radius 1) (color 1 2 3) (reflective 0.6) (transparency 0.5))",
      "t.scene:1:80: sphere reflective + transparency must be <= 1, got 0.6 + 0.5");
     ("(sphere (center 0 0 3) (radius 1) (color 1 2 3) (refractive-index 0))",
      "t.scene:1:67: sphere refractive-index must be > 0 and finite, got 0");
     ("(sphere (center 0 0 3) (radius 1) (color 1 2 3) (fresnel yes))",
      "t.scene:1:58: sphere fresnel: expected true or false");
     ("(box (min 0 0 3) (max 1 1 4) (color 1 2 3) (transparency 0.7) (reflective 0.7))",
      "t.scene:1:58: box reflective + transparency must be <= 1, got 0.7 + 0.7");
     ("(plane (point 0 0 0) (normal 0 1 0) (color 1 2 3) (refractive-index -1.5))",
      "t.scene:1:69: plane refractive-index must be > 0 and finite, got -1.5");
    ("(sphere (center 0 nan 3) (radius 1) (color 1 2 3))", "t.scene:1:19: sphere center must be a finite number, got nan");
    ("(sphere (center 0 0 3) (radius inf) (color 1 2 3))", "t.scene:1:32: sphere radius must be a finite number, got inf");
    ("(sphere (center 0 0) (radius 1) (color 1 2 3))", "t.scene:1:9: sphere center takes 3 numbers (x y z), got 2 values");
    ("(sphere (center 0 0 3) (color 1 2 3))", "t.scene:1:1: sphere is missing its (radius ...) field");
    ("(sphere (center 0 0 3) (radius 1) (color 300 2 3))",
     "t.scene:1:35: sphere color channels must lie in [0, 255], got (300 2 3)");
    ("(sphere (center 0 0 3) (radius 1) (radius 2) (color 1 2 3))",
     "t.scene:1:36: duplicate sphere field radius (first given at 1:25)");
    ("(sphere (center 0 0 3) (radius one) (color 1 2 3))", "t.scene:1:32: sphere radius: expected a number, got one");
    ("(light point (intensity 0.6))", "t.scene:1:1: light point is missing its (position ...) field");
    ("(light spots (intensity 0.6))", "t.scene:1:8: unknown light kind spots; expected ambient, point, directional, area, sphere or spot (did you mean spot?)");
    ("(light directional (intensity 0.2) (direction 0 0 0))",
     "t.scene:1:36: directional light direction must not be the zero vector (its length must be at least 1e-30)");
    ("(light ambient (intensity -1))", "t.scene:1:27: light intensity must lie in [0, 1e6], got -1");
    ("(light ambient (intensity 0.2) (position 1 2 3))",
     "t.scene:1:33: unknown light ambient field position; expected intensity");
    ("(canvas (width 600) (height 60.5))", "t.scene:1:29: canvas height: expected an integer, got 60.5");
    ("(canvas (width 0))", "t.scene:1:16: canvas width must lie in [1, 65536], got 0");
    ("(canvas (width 65536) (height 65536))", "t.scene:1:1: canvas 65536x65536 has 4294967296 pixels, more than the limit of 268435456 (set RAYTRACE_MAX_PIXELS to raise it)");
    ("(recursion-depth -1)", "t.scene:1:18: recursion depth must be >= 0, got -1");
    ("(epsilon 0.001)\n(epsilon 0.01)", "t.scene:2:2: duplicate epsilon form (first given at 1:2); it may appear only once");
    ( "(spere (center 0 0 3))",
      "t.scene:1:2: unknown form spere; expected material, canvas, viewport, camera, camera-path, background, recursion-depth, epsilon, sphere, plane, triangle, box, mesh, csg"
      ^ described_forms ^ ", transform, define, use or light (did you mean sphere?)" );
    ("sphere", "t.scene:1:1: expected a form in parentheses such as (sphere ...), got sphere");
    ( "()",
      "t.scene:1:1: empty form (); expected one of material, canvas, viewport, camera, camera-path, background, recursion-depth, epsilon, sphere, plane, triangle, box, mesh, csg"
      ^ described_forms ^ ", transform, define, use or light" );
    ("(camera (look-at 0 0 0))", "t.scene:1:9: the camera looks at its own position");
    ("(camera (rotation (1 0 0) (1 0 0) (0 0 1)))",
     "t.scene:1:9: camera rotation must be invertible, but its rows are (nearly) linearly dependent");
    ("(camera (rotation (1 0 0) (0 1 0) (0 0 1)) (look-at 0 0 1))",
     "t.scene:1:44: camera takes either (rotation ...) or (look-at ...), not both");
    ("(viewport (distance 0))", "t.scene:1:21: viewport distance must be > 0, got 0");
    ("(background 0 0)", "t.scene:1:1: background takes 3 numbers (r g b), got 2 values");
    ("\"a\nb\"", "t.scene:1:1: expected a form in parentheses such as (sphere ...), got \"a\\nb\"");
    ("(sphere (center 0 0 3) (radius 1e-31) (color 1 2 3))", "t.scene:1:32: sphere radius must be at least 1e-30, got 1e-31");
    ("(light point (intensity 1e7) (position 0 0 0))", "t.scene:1:25: light intensity must lie in [0, 1e6], got 10000000");
    ("(sphere (center 1e13 0 0) (radius 1) (color 1 2 3))",
     "t.scene:1:9: sphere center must be finite and at most 1e12 in magnitude, got 10000000000000");
    ("(camera-path)", "t.scene:1:1: camera-path needs at least one (key (frame N) (position x y z) (look-at x y z))");
    ("(camera-path (key (frame 0) (position 0 0 0)))", "t.scene:1:14: camera-path key is missing its (look-at ...) field");
    ("(camera-path (key (frame 0) (position 0 0 0) (look-at 0 0 1) (fov 2)))",
     "t.scene:1:63: unknown camera-path key field fov; expected frame, position, look-at or up");
    ("(camera-path (key (frame -2) (position 0 0 0) (look-at 0 0 1)))",
     "t.scene:1:26: camera-path key frame must lie in [0, 1000000], got -2");
    ("(camera-path (key (frame 1.5) (position 0 0 0) (look-at 0 0 1)))",
     "t.scene:1:26: camera-path key frame: expected an integer, got 1.5");
    ("(camera-path (key (frame 0) (position 0 0 1) (look-at 0 0 1)))",
     "t.scene:1:14: the camera looks at its own position");
    ("(camera-path (key (frame 0) (position 0 0 0) (look-at 0 0 1) (up 0 0 1)))",
     "t.scene:1:14: the camera's up vector is zero or parallel to its view direction");
    ("(camera-path (key (frame 0) (position 0 0 nan) (look-at 0 0 1)))",
     "t.scene:1:43: camera-path key position must be a finite number, got nan");
    ("(camera-path\n (key (frame 5) (position 0 0 0) (look-at 0 0 1))\n (key (frame 3) (position 0 0 0) (look-at 0 0 1)))",
     "t.scene:3:2: camera-path keys must come in increasing frame order, but frame 3 follows frame 5");
    ("(camera-path\n (key (frame 0) (position 0 0 0) (look-at 0 0 2))\n (key (frame 2) (position 0 0 4) (look-at 0 0 2)))",
     "t.scene:3:2: at frame 1, between the keys of frames 0 and 2, the camera looks at its own position");
    ("(camera-path (frame 0))", "t.scene:1:14: camera-path: expected a keyframe (key (frame N) (position x y z) (look-at x y z))");
  ]

(* Mesh files for the tests, by path: the text of each, read by Obj_file
   as Scene_file.read_mesh would read the file. *)
let meshes =
  [
    ("dir/quad.obj", "# a unit square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\ns off\nf 1//1 2//1 3//1 4//1\n");
    ("dir/bad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 9\n");
  ]

let load_mesh path =
  match List.assoc_opt path meshes with
  | Some text -> Mesh.Obj.of_string ~name:path ~max_vertices:100 ~max_triangles:100 text
  | None -> Error (`Msg (Printf.sprintf "cannot read mesh file: %s: No such file or directory" path))

let with_mesh text = Result.map Scene.of_valid (Scene_file.of_string ~load_mesh ~file:"dir/t.scene" text)

let tests =
  [
    Alcotest.test_case "scenes/cgfs.scene is the built-in reference scene" `Quick (fun () ->
        Alcotest.check scene __LOC__ Scene.cgfs (Helpers.load_scene "cgfs.scene"));
    Alcotest.test_case "scenes/cgfs-camera.scene is the camera demo" `Quick (fun () ->
        Alcotest.check scene __LOC__ Scene.cgfs_camera (Helpers.load_scene "cgfs-camera.scene"));
    Alcotest.test_case "every scene in scenes/ loads" `Quick (fun () ->
        List.iter (fun name -> ignore (Helpers.load_scene name)) (Helpers.scene_names ()));
    Alcotest.test_case "omitted forms take the document's values" `Quick (fun () ->
        let s = parse "(light ambient (intensity 1))" in
        Alcotest.(check (pair int int)) __LOC__ (600, 600) ((Scene.width s), (Scene.height s));
        Alcotest.(check int) __LOC__ 3 (Scene.depth s);
        Alcotest.(check bool) __LOC__ true (Viewport.equal (Scene.viewport s) Viewport.default);
        Alcotest.(check bool) __LOC__ true (Camera.equal (Scene.camera s) Camera.default);
        Alcotest.(check (option (float 0.))) __LOC__ None (Scene.epsilon s);
        Alcotest.check Helpers.color __LOC__ Color.black (Scene.background s));
    Alcotest.test_case "specular and reflective default to matte and 0" `Quick (fun () ->
        let s = parse "(sphere (center 0 0 3) (radius 1) (color 1 2 3))" in
        match Private.Spheres.to_list (Scene.spheres s) with
        | [ sp ] ->
            Alcotest.(check (float 0.)) __LOC__ (-1.) sp.material.specular;
            Alcotest.(check (float 0.)) __LOC__ 0. sp.material.reflective
        | _ -> Alcotest.fail "one sphere expected");
    Alcotest.test_case "the optical fields default to opaque, index 1, no Fresnel, and print only when set" `Quick
      (fun () ->
        let plain = "(sphere (center 0 0 3) (radius 1) (color 1 2 3))" in
        (match Helpers.scene_spheres (parse plain) with
        | [ sp ] ->
            Alcotest.(check (float 0.)) __LOC__ 0. sp.material.transparency;
            Alcotest.(check (float 0.)) __LOC__ 1. sp.material.refractive_index;
            Alcotest.(check bool) __LOC__ false sp.material.fresnel;
            Alcotest.(check string) "a sphere without them prints as before" plain (Sphere.show sp)
        | _ -> Alcotest.fail "one sphere expected");
        let glass =
          "(sphere (center 0 0 3) (radius 1) (color 1 2 3) (reflective 0.1) (transparency 0.9) (refractive-index 1.5) (fresnel true))"
        in
        (match Helpers.scene_spheres (parse glass) with
        | [ sp ] -> Alcotest.(check string) "a glass sphere prints its fields" glass (Sphere.show sp)
        | _ -> Alcotest.fail "one sphere expected");
        let box = "(box (min 0 0 3) (max 1 1 4) (color 1 2 3) (transparency 1) (refractive-index 1.33))" in
        match Scene.shapes (parse box) with
        | [ sh ] -> Alcotest.(check string) "a glass box prints its fields" box (Shape.show sh)
        | _ -> Alcotest.fail "one shape expected");
    Alcotest.test_case "a named material is defined once and used by any object; inline fields override it" `Quick
      (fun () ->
        let text =
          "(material glass (color 230 230 255) (transparency 0.9) (refractive-index 1.5) (fresnel true))\n\
           (material checked (color 200 200 200) (pattern checker (color 20 20 20) (size 0.5)))\n\
           (sphere (center 0 0 3) (radius 1) (material glass))\n\
           (plane (point 0 -1 0) (normal 0 1 0) (material checked) (specular 50))\n\
           (box (min 1 0 4) (max 2 1 5) (material glass) (transparency 0.5) (reflective 0.3) (color 1 2 3))\n\
           (light ambient (intensity 1))"
        in
        let glass = Material.v ~transparency:0.9 ~refractive_index:1.5 ~fresnel:true (Color.v 230. 230. 255.) in
        let checked = Material.v ~pattern:(Pattern.checker ~size:0.5 (Color.v 20. 20. 20.)) (Color.v 200. 200. 200.) in
        let expected =
          [
            Shape.Sphere (Sphere.v ~center:(Vec3.v 0. 0. 3.) ~radius:1. glass);
            Shape.Plane (Plane.v ~point:(Vec3.v 0. (-1.) 0.) ~normal:(Vec3.v 0. 1. 0.) (Material.update ~specular:50. checked));
            Shape.Box
              (Box.v ~min:(Vec3.v 1. 0. 4.) ~max:(Vec3.v 2. 1. 5.)
                 (Material.update ~transparency:0.5 ~reflective:0.3 ~color:(Color.v 1. 2. 3.) glass));
          ]
        in
        List.iter
          (fun reader ->
            match Scene_file.of_string ~reader ~file:"t.scene" text with
            | Error (`Msg m) -> Alcotest.fail m
            | Ok v ->
                let s = Scene.of_valid v in
                Alcotest.(check (list (testable Shape.pp Shape.equal))) __LOC__ expected (Scene.objects s);
                (* The names are gone once read: the scene prints each
                   object's fields, and reads back equal. *)
                Alcotest.check scene "round trip" s (parse (Scene.show s)))
          [ `Fast; `Parsexp ]);
    Alcotest.test_case "Scene_file.located gives the error's file, line and column beside its message" `Quick (fun () ->
        let text = "(light ambient (intensity 1))\n(sphere (center 0 0 3) (radius -1) (color 1 1 1))" in
        (match Scene_file.located ~file:"t.scene" text with
        | Ok _ -> Alcotest.fail "accepted"
        | Error e ->
            Alcotest.(check (list string)) __LOC__
              [ "t.scene"; "2"; "32"; "sphere radius must be > 0, got -1" ]
              [ e.file; string_of_int e.line; string_of_int e.column; e.message ];
            Alcotest.(check string) "the message of_string gives" (error text) (Scene_file.error_message e));
        let limits = Limits.with_bound Limits.default `Scene_bytes 10. in
        match Scene_file.located ~limits ~file:"t.scene" text with
        | Ok _ -> Alcotest.fail "accepted"
        | Error e -> Alcotest.(check (pair int int)) "a whole-text error has no line" (0, 0) (e.line, e.column));
    Alcotest.test_case "comments of every kind are ignored" `Quick (fun () ->
        let s =
          parse
            "; line\n#| block |#\n#;(sphere (center 0 0 0))\n(recursion-depth 2) ; trailing\n"
        in
        Alcotest.(check int) __LOC__ 2 (Scene.depth s);
        Alcotest.(check int) __LOC__ 0 (Private.Spheres.length (Scene.spheres s)));
    Alcotest.test_case "a UTF-8 byte order mark at the start reads as blanks, in both readers and in windows" `Quick
      (fun () ->
        let bom = "\xef\xbb\xbf" in
        let text = "(canvas (width 8) (height 6))\n(sphere (center 0 0 3) (radius 1) (color 1 2 3))\n" in
        let read ?(window_bytes = 1 lsl 20) reader t =
          Result.map Scene.of_valid
            (Private.Scene_text.of_source ~file:"t.scene" ~reader ~window_bytes (Private.Scene_text.string_source t))
        in
        List.iter
          (fun (what, reader, window_bytes) ->
            match (read ~window_bytes reader text, read ~window_bytes reader (bom ^ text)) with
            | Ok a, Ok b -> Alcotest.check scene what a b
            | _, Error (`Msg m) | Error (`Msg m), _ -> Alcotest.failf "%s: %s" what m)
          [ ("fast", `Fast, 1 lsl 20); ("parsexp", `Parsexp, 1 lsl 20); ("fast, 2-byte windows", `Fast, 2);
            ("fast, 1-byte windows", `Fast, 1) ];
        (* Columns count the mark's 3 bytes, in both readers. *)
        List.iter
          (fun reader ->
            match read reader (bom ^ "(sphere)") with
            | Ok _ -> Alcotest.fail "accepted"
            | Error (`Msg m) -> Alcotest.(check string) __LOC__ "t.scene:1:4: sphere is missing its (center ...) field" m)
          [ `Fast; `Parsexp ];
        (* Elsewhere, the bytes are an atom like any other. *)
        Alcotest.(check bool) __LOC__ true (Result.is_error (read `Fast (" " ^ bom ^ text))));
    Alcotest.test_case "look-at builds the camera" `Quick (fun () ->
        let s = parse "(camera (position 3 0 1) (look-at 2 0 2) (up 0 1 0))" in
        let d = Camera.direction (Scene.camera s) Vec3.oz in
        let k = 1. /. sqrt 2. in
        Alcotest.check (Helpers.vec3_near 1e-15) __LOC__ (Vec3.v (-.k) 0. k) d);
    Alcotest.test_case "bad input gets one located line" `Quick (fun () ->
        List.iter
          (fun (text, expected) -> Alcotest.(check string) (String.escaped text) expected (error text))
          bad_inputs);
    Alcotest.test_case "errors are one line and never raise" `Quick (fun () ->
        List.iter
          (fun (text, _) -> Alcotest.(check bool) text false (String.contains (error text) '\n'))
          bad_inputs);
    Alcotest.test_case "a missing file is an error naming it" `Quick (fun () ->
        match Helpers.read_scene "no/such.scene" with
        | Ok _ -> Alcotest.fail "loaded a missing file"
        | Error (`Msg m) -> Alcotest.(check string) __LOC__ "no/such.scene: No such file or directory" m);
    Alcotest.test_case "printing the reference scenes reads back equal" `Quick (fun () ->
        List.iter
          (fun s -> Alcotest.check scene __LOC__ s (parse (Scene_file.to_string s)))
          [ Scene.cgfs; Scene.cgfs_camera ]);
    Alcotest.test_case "a camera-path gives keys; without a camera form, stills are its first frame" `Quick (fun () ->
        let s =
          parse
            "(camera-path (key (frame 2) (position 0 1 -2) (look-at 0 0 4))\n\
             (key (frame 10) (position 1 1 -2) (look-at 0 0 4) (up 0 1 0.5)))"
        in
        match (Scene.camera_path s) with
        | None -> Alcotest.fail "no camera path"
        | Some p ->
            Alcotest.(check (list int)) __LOC__ [ 2; 10 ] (List.map (fun (k : Camera.Path.key) -> k.frame) (Camera.Path.keys p));
            Alcotest.check Helpers.vec3 __LOC__ (Vec3.v 0. 1. 0.5) (List.nth (Camera.Path.keys p) 1).up;
            Alcotest.check Helpers.vec3 __LOC__ Vec3.oy (List.hd (Camera.Path.keys p)).up;
            (match Camera.look_at ~position:(Vec3.v 0. 1. (-2.)) (Vec3.v 0. 0. 4.) with
            | Ok c -> Alcotest.(check bool) __LOC__ true (Camera.equal c (Scene.camera s))
            | Error (`Msg m) -> Alcotest.fail m);
            let with_camera = parse "(camera (position 0 0 -1))\n(camera-path (key (frame 0) (position 0 0 0) (look-at 0 0 1)))" in
            Alcotest.check Helpers.vec3 __LOC__ (Vec3.v 0. 0. (-1.)) (Scene.camera with_camera).position);
    Alcotest.test_case "a scene with a camera path prints and parses back equal" `Quick (fun () ->
        let s = Helpers.load_scene "orbit.scene" in
        Alcotest.(check bool) __LOC__ true (Option.is_some (Scene.camera_path s));
        Alcotest.check scene __LOC__ s (parse (Scene_file.to_string s)));
    Helpers.qcheck ~count:300 "any valid scene prints and parses back equal" Gen_scene.arbitrary
      (fun s ->
        match Helpers.of_string (Scene_file.to_string s) with
        | Ok s' -> Scene.equal s s'
        | Error (`Msg m) -> QCheck.Test.fail_report m);
    Helpers.qcheck ~count:300 "Scene.show of any valid scene parses back equal, as Scene_file.to_string's text"
      Gen_scene.arbitrary (fun s ->
        let text = Scene.show s in
        if text <> Scene_file.to_string s then QCheck.Test.fail_report "Scene.show differs from Scene_file.to_string";
        if text <> Format.asprintf "%a" Scene.pp s then QCheck.Test.fail_report "Scene.show differs from Scene.pp";
        match Scene_file.of_string text with
        | Ok v -> Scene.equal s (Scene.of_valid v)
        | Error (`Msg m) -> QCheck.Test.fail_report m);
    (* The parts' printers are the scene's: each part's [show] is its form
       in the scene's text. *)
    Helpers.qcheck ~count:300 "the parts of a scene print as their forms in Scene.show" Gen_scene.arbitrary (fun s ->
        let text = Scene.show s in
        let lines = String.split_on_char '\n' text in
        let has_line what form =
          if not (List.mem form lines) then QCheck.Test.fail_reportf "%s prints %S, not a line of:\n%s" what form text
        in
        has_line "Viewport.show" (Viewport.show (Scene.viewport s));
        has_line "Camera.show" (Camera.show (Scene.camera s));
        Private.Spheres.iter (fun x -> has_line "Sphere.show" (Sphere.show x)) (Scene.spheres s);
        List.iter (fun x -> has_line "Shape.show" (Shape.show x)) (Scene.shapes s);
        List.iter (fun x -> has_line "Light.show" (Light.show x)) (Scene.lights s);
        Option.iter
          (fun p ->
            let form = Camera.Path.show p in
            let n = String.length form and t = String.length text in
            let rec found i = i + n <= t && (String.sub text i n = form || found (i + 1)) in
            if not (found 0) then QCheck.Test.fail_reportf "Camera.Path.show prints %S, not in:\n%s" form text)
          (Scene.camera_path s);
        true);
      Alcotest.test_case "the new shapes read with their fields and defaults" `Quick (fun () ->
        let s =
          parse
            "(plane (point 0 -1 0) (normal 0 2 0) (color 1 2 3))\n\
             (triangle (vertices (-1 0 4) (1 0 4) (0 1.5 4)) (color 4 5 6) (specular 10))\n\
             (box (min -1 -1 3) (max 1 1 5) (color 7 8 9) (reflective 0.5))"
        in
        match (Scene.shapes s) with
        | [ Shape.Plane p; Shape.Triangle t; Shape.Box b ] ->
            Alcotest.(check (float 0.)) "plane normal as given" 2. p.normal.y;
            Alcotest.(check (float 0.)) "plane matte" Sphere.matte p.material.specular;
            Alcotest.(check (float 0.)) "triangle vertex" 1.5 t.v2.y;
            Alcotest.(check (float 0.)) "triangle specular" 10. t.material.specular;
            Alcotest.(check (float 0.)) "box reflective" 0.5 b.material.reflective
        | _ -> Alcotest.fail "expected a plane, a triangle and a box");
    Alcotest.test_case "bad shapes get one located line" `Quick (fun () ->
        List.iter
          (fun (text, expected) -> Alcotest.(check string) text expected (error text))
          [
            ("(plane (point 0 0 0) (normal 0 0 0) (color 1 2 3))", "t.scene:1:22: plane normal must not be zero, got (0 0 0)");
            ("(plane (point 0 0 0) (color 1 2 3))", "t.scene:1:1: plane is missing its (normal ...) field");
            ("(triangle (vertices (0 0 0) (1 1 1) (2 2 2)) (color 1 2 3))",
             "t.scene:1:11: triangle vertices must not lie on a line, got (0 0 0) (1 1 1) (2 2 2)");
            ("(triangle (vertices (0 0 0) (1 1 1)) (color 1 2 3))",
             "t.scene:1:11: triangle vertices takes 3 vertices, e.g. (-1 0 4) (1 0 4) (0 1.5 4), got 2 values");
            ("(box (min 0 0 0) (max 1 0 1) (color 1 2 3))",
             "t.scene:1:18: box min must be below max on every axis, got (0 0 0) and (1 0 1)");
            ("(box (min 0 0 0) (max 1 1 1) (color 1 2 300))", "t.scene:1:30: box color channels must lie in [0, 255], got (1 2 300)");
            ("(box (min 0 0 0) (max 1 1 1) (color 1 2 3) (reflective 2))", "t.scene:1:56: box reflective must lie in [0, 1], got 2");
          ]);
    Alcotest.test_case "a mesh is read relative to the scene file, placed by scale then translate" `Quick (fun () ->
        match with_mesh "(mesh (file \"quad.obj\") (color 1 2 3) (scale 2) (translate 10 0 0) (smooth true))" with
        | Error (`Msg m) -> Alcotest.fail m
        | Ok s -> (
            match (Scene.shapes s) with
            | [ Shape.Mesh m ] ->
                Alcotest.(check string) "source as given" "quad.obj" m.source;
                Alcotest.(check int) "fan-triangulated" 2 (Mesh.triangle_count m);
                (* vertex 3 (1 1 0) -> 2 * (1 1 0) + (10 0 0) = (12 2 0) *)
                Alcotest.(check (float 0.)) "x" 12. m.positions.(6);
                Alcotest.(check (float 0.)) "y" 2. m.positions.(7);
                Alcotest.(check int) "skipped: the comment and s" 2 m.skipped;
                Alcotest.(check bool) "smooth" true m.smooth
            | _ -> Alcotest.fail "expected one mesh"));
    Alcotest.test_case "a bad mesh file or form is one located line" `Quick (fun () ->
        List.iter
          (fun (text, expected) ->
            match with_mesh text with
            | Ok _ -> Alcotest.failf "expected an error for %S" text
            | Error (`Msg m) -> Alcotest.(check string) text expected m)
          [
            ("(mesh (file \"bad.obj\") (color 1 2 3))",
             "dir/t.scene:1:7: dir/bad.obj:4:7: vertex index 9 is out of range: 3 vertices defined so far");
            ("(mesh (file \"none.obj\") (color 1 2 3))",
             "dir/t.scene:1:7: cannot read mesh file: dir/none.obj: No such file or directory");
            ("(mesh (color 1 2 3))", "dir/t.scene:1:1: mesh is missing its (file ...) field");
            ("(mesh (file \"quad.obj\") (color 1 2 3) (scale 0))", "dir/t.scene:1:46: mesh scale must be > 0, got 0");
            ("(mesh (file \"quad.obj\") (color 1 2 3) (smooth yes))", "dir/t.scene:1:47: mesh smooth: expected true or false");
          ];
        (* Without a loader, text names no file it can read. *)
        match Scene_file.of_string ~file:"t.scene" "(mesh (file \"quad.obj\") (color 1 2 3))" with
        | Ok _ -> Alcotest.fail "a mesh without a loader"
        | Error (`Msg m) ->
            Alcotest.(check string) "no loader"
              "t.scene:1:7: cannot read mesh file quad.obj: this scene was given as text, with no way to read files" m);
  ]
