(* Checker patterns: the scene syntax, the cell a point on a boundary
   belongs to, object coordinates for boxes and meshes, anti-aliasing by
   the samples, the oracle, and no allocation. *)
open Raytrace

let light = "(light ambient (intensity 1))"
let scene_exn text = match Helpers.of_string text with Ok s -> s | Error (`Msg m) -> Alcotest.fail m

let error text =
  match Helpers.of_string ~file:"p.scene" text with
  | Ok _ -> Alcotest.failf "accepted: %s" text
  | Error (`Msg m) -> m

(* Lit by an ambient light of intensity 1 alone, every pixel of an object
   is its colour or its pattern's, exactly. *)
let light_grey = (200, 200, 200) and dark = (50, 50, 50)

(* The floor y = -1, on a boundary of the cells of side 1. *)
let floor_scene ~camera ~epsilon =
  scene_exn
    (Printf.sprintf
       "(canvas (width 64) (height 64)) (camera %s) %s\n\
        (plane (point 0 -1 0) (normal 0 1 0) (color 200 200 200) (pattern checker (color 50 50 50) (size 1))) %s"
       camera
       (match epsilon with Some e -> Printf.sprintf "(epsilon %g)" e | None -> "")
       light)

(* Each pixel whose exact hit on y = -1 lies farther than [margin] from a
   cell boundary in x and z is checked against the cell [y_cell] (the
   side the camera is on) by the rule floor (x) + floor (z) + y_cell odd:
   the pattern's colour. Returns the pixels checked and those wrong. *)
let check_floor (s : Scene.t) img ~y_cell =
  let checked = ref 0 and wrong = ref 0 in
  let o = (Scene.camera s).position in
  for gx = Canvas.min_x (Scene.width s) to Canvas.max_x (Scene.width s) do
    for gy = Canvas.min_y (Scene.height s) to Canvas.max_y (Scene.height s) do
      let v = Viewport.of_canvas (Scene.viewport s) ~canvas_width:(Scene.width s) ~canvas_height:(Scene.height s) gx gy in
      let d = Camera.direction (Scene.camera s) v in
      let t = (-1. -. o.y) /. d.y in
      if t > 1. && t < 1e3 then begin
        let x = o.x +. (t *. d.x) and z = o.z +. (t *. d.z) in
        let away u = Float.abs (u -. Float.round u) > 1e-6 in
        if away x && away z then begin
          incr checked;
          let odd = (int_of_float (Float.floor x) + int_of_float (Float.floor z) + y_cell) land 1 = 1 in
          let expected = if odd then dark else light_grey in
          let got = Image.get img (Canvas.column ~width:(Scene.width s) gx) (Canvas.row ~height:(Scene.height s) gy) in
          if got <> expected then incr wrong
        end
      end
    done
  done;
  (!checked, !wrong)

let colours img =
  let seen = Hashtbl.create 16 in
  for y = 0 to Image.height img - 1 do
    for x = 0 to Image.width img - 1 do
      Hashtbl.replace seen (Image.get img x y) ()
    done
  done;
  seen

let tests =
  [
    Alcotest.test_case "a checker made by Pattern.checker reads back its colour and size" `Quick (fun () ->
        let c = Color.v 1. 2. 3. in
        let p = Pattern.checker ~size:0.25 c in
        Alcotest.(check bool) "colour" true (Color.equal c (Pattern.color p));
        Alcotest.(check (float 0.)) "size" 0.25 (Pattern.size p);
        Alcotest.(check bool) "equal to itself, not to another size" true
          (Pattern.equal p (Pattern.checker ~size:0.25 c) && not (Pattern.equal p (Pattern.checker ~size:0.5 c))));
    Alcotest.test_case "a pattern prints as it reads, and a scene reads back equal" `Quick (fun () ->
        let text =
          "(sphere (center 0 0 4) (radius 1) (color 255 0 0) (pattern checker (color 0 0 255) (size 0.25)))\n\
           (plane (point 0 -1 0) (normal 0 1 0) (color 200 200 200) (reflective 0.5) (pattern checker (color 20 20 20) (size 1)))\n\
           (box (min -1 -1 3) (max 1 1 5) (color 0 0 255) (pattern checker (color 1 2 3) (size 2)))"
        in
        let s = scene_exn text in
        let printed = Scene.show s in
        List.iter
          (fun field ->
            if not (Astring_free.contains printed field) then Alcotest.failf "%S not in:\n%s" field printed)
          [
            "(color 255 0 0) (pattern checker (color 0 0 255) (size 0.25)))";
            "(reflective 0.5) (pattern checker (color 20 20 20) (size 1)))";
            "(pattern checker (color 1 2 3) (size 2)))";
          ];
        let again = scene_exn printed in
        Alcotest.(check bool) "read back equal" true (Scene.equal s again));
    Alcotest.test_case "bad patterns are one error naming file:line:column" `Quick (fun () ->
        List.iter
          (fun (text, expected) ->
            let m = error text in
            if not (Astring_free.contains m expected) then Alcotest.failf "%S: got %S, expected %S" text m expected)
          [
            ( "(sphere (center 0 0 4) (radius 1) (color 1 1 1)\n (pattern checker (color 0 0 0) (size 0)))",
              "p.scene:2:39: sphere pattern size must be > 0, got 0" );
            ( "(plane (point 0 0 0) (normal 0 1 0) (color 1 1 1) (pattern checker (color 0 0 0) (size -1)))",
              "p.scene:1:88: plane pattern size must be > 0, got -1" );
            ("(box (min 0 0 0) (max 1 1 1) (color 1 1 1) (pattern checker (size 1)))", "box pattern checker is missing its (color ...) field");
            ("(box (min 0 0 0) (max 1 1 1) (color 1 1 1) (pattern checker (color 0 0 0)))", "box pattern checker is missing its (size ...) field");
            ( "(sphere (center 0 0 4) (radius 1) (color 1 1 1) (pattern checker (color 300 0 0) (size 1)))",
              "sphere pattern color channels must lie in [0, 255]" );
            ("(sphere (center 0 0 4) (radius 1) (color 1 1 1) (pattern cheker (color 0 0 0) (size 1)))", "p.scene:1:58: unknown sphere pattern cheker");
            ("(sphere (center 0 0 4) (radius 1) (color 1 1 1) (pattern))", "sphere pattern: expected a kind");
            ( "(sphere (center 0 0 4) (radius 1) (color 1 1 1) (pattern checker (color 0 0 0) (size 1) (size 2)))",
              "duplicate sphere pattern checker field size" );
          ]);
    Alcotest.test_case "a floor on a cell boundary shows the cells of the side the camera is on" `Quick (fun () ->
        List.iter
          (fun (what, camera, y_cell) ->
            List.iter
              (fun epsilon ->
                let s = floor_scene ~camera ~epsilon in
                let img = Helpers.image_exn s in
                let checked, wrong = check_floor s img ~y_cell in
                let what = Printf.sprintf "%s, %s" what (if epsilon = None then "robust" else "epsilon") in
                if checked < 500 then Alcotest.failf "%s: only %d pixels checked" what checked;
                if wrong > 0 then Alcotest.failf "%s: %d of %d floor pixels in the wrong cell" what wrong checked)
              [ None; Some 0.001 ])
          [
            (* y = -1 + e: floor -1; y = -1 - e: floor -2. *)
            ("seen from above", "(position 0.37 0.5 0.21)", -1);
            ("seen from below", "(position 0.37 -2.5 0.21)", -2);
            ("seen from far above, looking down", "(position 100.37 50.5 100.21) (look-at 100.87 -1 103)", -1);
          ]);
    Alcotest.test_case "samples anti-alias the cell edges: edge pixels take values in between" `Quick (fun () ->
        let s = floor_scene ~camera:"(position 0.37 0.5 0.21)" ~epsilon:None in
        let one = colours (Helpers.image_exn s) in
        Hashtbl.iter
          (fun c () ->
            if c <> light_grey && c <> dark && c <> (0, 0, 0) then
              let r, g, b = c in
              Alcotest.failf "one sample per pixel: colour %d %d %d is neither cell's" r g b)
          one;
        let img = Helpers.image_exn ~samples:3 s in
        let between = ref 0 in
        for y = 0 to Image.height img - 1 do
          for x = 0 to Image.width img - 1 do
            let r, g, b = Image.get img x y in
            if r = g && g = b && r > 50 && r < 200 then incr between
          done
        done;
        if !between < 20 then Alcotest.failf "3x3 samples: only %d edge pixels in between" !between);
    Alcotest.test_case "a mesh's cells are in its file's coordinates, before scale and translate" `Quick
      (fun () ->
        (* A quad of side 2 at z = 0, placed at scale 2 and translate
           (2, 2, 4): cells of side 0.5 in the file are cells of side 1 in
           the world, shifted by (2, 2, 4) cells, an even sum: the picture
           of the placed triangles with cells of side 1 in world
           coordinates. In world coordinates, cells of 0.5 would differ. *)
        let positions = [| -1.; -1.; 0.; 1.; -1.; 0.; 1.; 1.; 0.; -1.; 1.; 0. |] in
        let triangles = [| 0; 1; 2; 0; 2; 3 |] in
        let material size = Material.v ~pattern:(Pattern.checker ~size (Color.v 50. 50. 50.)) (Color.v 200. 200. 200.) in
        let mesh =
          match
            Mesh.v ~scale:2. ~translate:(Vec3.v 2. 2. 4.) ~positions ~triangles ~normals:[||]
              ~triangle_normals:[| -1; -1; -1; -1; -1; -1 |] (material 0.5)
          with
          | Ok m -> m
          | Error (`Msg m) -> Alcotest.fail m
        in
        let world size = List.init 2 (fun k -> (let t = Mesh.triangle mesh k in Shape.Triangle (Triangle.v t.v0 t.v1 t.v2 (material size)))) in
        let scene shapes =
          Helpers.scene ~width:64 ~height:64 ~camera:(Camera.v (Vec3.v 2.1 2.2 0.)) ~lights:[ Light.ambient 1. ] ~spheres:[]
            ~shapes ()
        in
        let m = Helpers.image_exn (scene [ Shape.Mesh mesh ]) in
        Helpers.check_images "mesh against world triangles" ~expected:(Helpers.image_exn (scene (world 1.))) m;
        if Image.equal m (Helpers.image_exn (scene (world 0.5))) then Alcotest.fail "the mesh's cells are the world's");
    Alcotest.test_case "a box's cells start at its min corner" `Quick (fun () ->
        (* The same box and camera, moved together by (0.3, 0.1, 0.7): the
           cells move with the box, and the picture stays (but for a few
           pixels on cell edges, where the moved rays round otherwise). *)
        let scene (dx, dy, dz) =
          scene_exn
            (Printf.sprintf
               "(canvas (width 64) (height 64)) (camera (position %g %g %g) (look-at %g %g %g))\n\
                (box (min %g %g %g) (max %g %g %g) (color 200 200 200) (pattern checker (color 50 50 50) (size 0.25))) %s"
               (dx -. 1.) (dy +. 1.7) (dz -. 0.5) (dx +. 0.5) (dy +. 0.5) (dz +. 4.5) dx dy (dz +. 4.) (dx +. 1.)
               (dy +. 1.) (dz +. 5.) light)
        in
        let a = Helpers.image_exn (scene (0., 0., 0.)) and b = Helpers.image_exn (scene (0.3, 0.1, 0.7)) in
        Alcotest.(check bool) "both cells' colours are seen" true
          (Hashtbl.mem (colours a) light_grey && Hashtbl.mem (colours a) dark);
        Helpers.check_images ~min_share:0.99 "box moved with the camera" ~expected:a b);
    Alcotest.test_case "random scenes with patterns in the document's mode render as the oracle does" `Quick
      (fun () ->
        let rand = Random.State.make [| 14 |] in
        let scenes = QCheck.Gen.generate ~rand ~n:80 Gen_scene.gen in
        List.iteri
          (fun i (s : Scene.t) ->
            let s = Gen_scene.with_patterns rand (Scene.with_overrides ~epsilon:(Some 0.001) s) in
            let expected = Private.Literal.render (Helpers.valid s) in
            Helpers.check_images (Printf.sprintf "scene %d:\n%s" i (Scene.show s)) ~expected (Helpers.image_exn s))
          scenes);
    Alcotest.test_case "with patterns, switching the skips off changes no byte" `Quick (fun () ->
        (* The early stop of reflections bounds every colour a ray can
           return: the patterns' second colours count. *)
        let rand = Random.State.make [| 41 |] in
        let scenes = QCheck.Gen.generate ~rand ~n:60 Gen_scene.gen in
        List.iteri
          (fun i (s : Scene.t) ->
            let s = Gen_scene.with_patterns rand s in
            Helpers.check_images (Printf.sprintf "scene %d:\n%s" i (Scene.show s))
              ~expected:(Helpers.image_exn ~skips:false s) (Helpers.image_exn s))
          scenes);
    Alcotest.test_case "a faint mirror shows a black wall's white cells: the early stop counts them" `Quick
      (fun () ->
        (* Behind the camera, the wall z = -1, black with white cells, seen
           only in a mirror of reflectivity 0.02: 0.02 * 255 = 5.1 per
           channel, which an early stop that took the wall's colour for the
           brightest would drop. *)
        let s =
          scene_exn
            "(canvas (width 48) (height 48)) (sphere (center 0 0 3) (radius 1) (color 0 0 0) (reflective 0.02))\n\
             (plane (point 0 0 -1) (normal 0 0 1) (color 0 0 0) (pattern checker (color 255 255 255) (size 0.5)))\n\
             (light ambient (intensity 1))"
        in
        let img = Helpers.image_exn s in
        Alcotest.(check bool) "the white cells are seen" true (Hashtbl.mem (colours img) (5, 5, 5));
        Helpers.check_images "skips on and off" ~expected:(Helpers.image_exn ~skips:false s) img);
    Alcotest.test_case "tracing a patterned scene allocates nothing per pixel" `Quick (fun () ->
        List.iter
          (fun epsilon ->
            let s = Scene.with_overrides ~epsilon (Scene.with_overrides ~width:64 ~height:64 (Helpers.load_scene "checker.scene")) in
            match Helpers.render ~samples:2 s with
            | Ok (_, stats) -> Alcotest.(check (float 0.)) __LOC__ 0. stats.minor_words
            | Error (`Msg m) -> Alcotest.fail m)
          [ None; Some 0.001 ]);
  ]
