(* The window's state and keys, without a window. *)
open Raytrace

let cgfs = View.v (Helpers.valid Scene.cgfs)
let vec = Alcotest.check (Helpers.vec3_near 1e-12)

let press view keys =
  List.fold_left (fun (v, _) c -> View.handle v (View.Key c)) (view, View.Nothing) keys

let effect =
  Alcotest.testable
    (fun ppf e ->
      Format.pp_print_string ppf
        View.(match e with Nothing -> "Nothing" | Render -> "Render" | Redraw -> "Redraw" | Save -> "Save" | Quit -> "Quit"))
    ( = )

let position (v : View.t) = (Scene.camera v.scene).position
let forward (v : View.t) = Camera.direction (Scene.camera v.scene) Vec3.oz

let tests =
  [
    Alcotest.test_case "moving and turning keep the camera's lens" `Quick (fun () ->
        let s = Helpers.parse_ok "(camera (position 0 1 -2) (look-at 0 0 6) (aperture 0.3) (focal-distance 7.5))" in
        let v, _ = press (View.v (Helpers.valid s)) [ View.arrow_up; 'E'; 'D'; View.arrow_down ] in
        let c = Scene.camera v.scene in
        Alcotest.(check (pair (float 0.) (float 0.))) __LOC__ (0.3, 7.5) (Camera.aperture c, Camera.focal_distance c));
    Alcotest.test_case "a new view shows the scene as loaded" `Quick (fun () ->
        Alcotest.(check bool) __LOC__ true (Scene.equal cgfs.scene Scene.cgfs);
        Alcotest.(check int) __LOC__ 1 (View.samples cgfs);
        Alcotest.(check bool) __LOC__ false cgfs.help);
    Alcotest.test_case "the up arrow and W move forward by half the viewport distance" `Quick (fun () ->
        (* d = 1: the step is 0.5 along +z *)
        List.iter
          (fun k ->
            let v, e = press cgfs [ k ] in
            Alcotest.check effect __LOC__ View.Render e;
            vec __LOC__ (Vec3.v 0. 0. 0.5) (position v))
          [ View.arrow_up; 'W' ]);
    Alcotest.test_case "each arrow and its letter move the camera along its axes" `Quick (fun () ->
        List.iter
          (fun (keys, expected) -> vec __LOC__ expected (position (fst (press cgfs keys))))
          [
            ([ View.arrow_down ], Vec3.v 0. 0. (-0.5));
            ([ 'S' ], Vec3.v 0. 0. (-0.5));
            ([ View.arrow_left ], Vec3.v (-0.5) 0. 0.);
            ([ 'A' ], Vec3.v (-0.5) 0. 0.);
            ([ View.arrow_right; 'D' ], Vec3.v 1. 0. 0.);
          ]);
    Alcotest.test_case "moving follows a turned camera's own view direction" `Quick (fun () ->
        (* CGFS camera at (3, 0, 1): its view axis M (0, 0, 1) = (-0.7071, 0,
           0.7071), unit (-1/sqrt 2, 0, 1/sqrt 2); 0.5 along it adds
           (-0.353553, 0, 0.353553) *)
        let v, _ = press (View.v (Helpers.valid Scene.cgfs_camera)) [ 'W' ] in
        let h = 0.5 /. sqrt 2. in
        vec __LOC__ (Vec3.v (3. -. h) 0. (1. +. h)) (position v);
        Alcotest.(check bool) __LOC__ true (Camera.equal_rotation (Scene.camera v.scene).rotation (Scene.camera Scene.cgfs_camera).rotation));
    Alcotest.test_case "the step scales with the scene" `Quick (fun () ->
        let big = (Scene.with_overrides ~viewport:(Viewport.v ~width:1000. ~height:1000. ~distance:1000.) Scene.cgfs) in
        vec __LOC__ (Vec3.v 0. 0. 500.) (position (fst (press (View.v (Helpers.valid big)) [ 'W' ]))));
    Alcotest.test_case "lower-case w, d and e are not moves: letters that move need Shift" `Quick (fun () ->
        vec __LOC__ Vec3.zero (position (fst (press cgfs [ 'w'; 'd'; 'e' ]))));
    Alcotest.test_case "E turns right by 5 degrees, Q back" `Quick (fun () ->
        (* R_y(5 deg) (0, 0, 1) = (sin 5, 0, cos 5) = (0.0871557, 0, 0.9961947) *)
        let v, e = press cgfs [ 'E' ] in
        Alcotest.check effect __LOC__ View.Render e;
        Alcotest.check (Helpers.vec3_near 1e-7) __LOC__ (Vec3.v 0.0871557 0. 0.9961947) (forward v);
        vec __LOC__ Vec3.zero (position v);
        let back, _ = press v [ 'Q' ] in
        vec __LOC__ Vec3.oz (forward back);
        List.iter (fun k -> vec __LOC__ (forward v) (forward (fst (press cgfs [ k ])))) [ '>'; '.' ];
        List.iter (fun k -> vec __LOC__ (forward (fst (press cgfs [ 'Q' ]))) (forward (fst (press cgfs [ k ])))) [ '<'; ',' ]);
    Alcotest.test_case "72 turns of 5 degrees make a full circle" `Quick (fun () ->
        let v, _ = press cgfs (List.init 72 (fun _ -> '<')) in
        let m = (Scene.camera v.scene).rotation in
        vec __LOC__ Vec3.ox m.row0;
        vec __LOC__ Vec3.oy m.row1;
        vec __LOC__ Vec3.oz m.row2);
    Alcotest.test_case "a drag turns so that the picture follows the pointer" `Quick (fun () ->
        (* 600 x 600, V_w = V_h = d = 1: one pixel is 1/600 rad; 60 pixels
           right turn left by 0.1 rad: forward (sin -0.1, 0, cos 0.1) =
           (-0.0998334, 0, 0.9950042); 60 pixels up tilt down by 0.1 rad *)
        let right, e = View.handle cgfs (View.Drag (60, 0)) in
        Alcotest.check effect __LOC__ View.Render e;
        Alcotest.check (Helpers.vec3_near 1e-7) __LOC__ (Vec3.v (-0.0998334) 0. 0.9950042) (forward right);
        let up, _ = View.handle cgfs (View.Drag (0, 60)) in
        Alcotest.check (Helpers.vec3_near 1e-7) __LOC__ (Vec3.v 0. (-0.0998334) 0.9950042) (forward up);
        Alcotest.check effect __LOC__ View.Nothing (snd (View.handle cgfs (View.Drag (0, 0)))));
    Alcotest.test_case "tilting keeps the camera's right axis horizontal" `Quick (fun () ->
        let v = View.((Scene.camera cgfs.scene) |> pitch 0.3 |> yaw 0.7) in
        Alcotest.(check (float 1e-15)) __LOC__ 0. (Camera.direction v Vec3.ox).y;
        Alcotest.(check (float 1e-12)) __LOC__ 1. (Camera.determinant v.rotation));
    Alcotest.test_case "+ and - change the depth within its bounds" `Quick (fun () ->
        let v, e = press cgfs [ '+' ] in
        Alcotest.check effect __LOC__ View.Render e;
        Alcotest.(check int) __LOC__ 4 (Scene.depth v.scene);
        Alcotest.(check int) __LOC__ 5 (Scene.depth (fst (press v [ '=' ])).scene);
        Alcotest.(check int) __LOC__ 0 (Scene.depth (fst (press cgfs [ '-'; '_'; '-' ])).scene);
        let v, e = press cgfs [ '-'; '-'; '-'; '-' ] in
        Alcotest.check effect __LOC__ View.Nothing e;
        Alcotest.(check int) __LOC__ 0 (Scene.depth v.scene);
        let deep = View.v (Helpers.valid (Scene.with_overrides ~depth:Limits.max_depth Scene.cgfs)) in
        Alcotest.check effect __LOC__ View.Nothing (snd (press deep [ '+' ])));
    Alcotest.test_case "a toggles antialiasing, h the help" `Quick (fun () ->
        let v, e = press cgfs [ 'a' ] in
        Alcotest.check effect __LOC__ View.Render e;
        Alcotest.(check int) __LOC__ 3 (View.samples v);
        Alcotest.(check int) __LOC__ 1 (View.samples (fst (press v [ 'a' ])));
        let v, e = press cgfs [ 'h' ] in
        Alcotest.check effect __LOC__ View.Redraw e;
        Alcotest.(check bool) __LOC__ true v.help;
        Alcotest.(check bool) __LOC__ false (fst (press v [ 'h' ])).help);
    Alcotest.test_case "r renders, s saves, q and Escape quit, other keys do nothing" `Quick (fun () ->
        List.iter
          (fun (k, e) -> Alcotest.check effect (Printf.sprintf "key %C" k) e (snd (press cgfs [ k ])))
          [ ('r', View.Render); ('s', Save); ('q', Quit); ('\027', Quit); ('x', Nothing); (' ', Nothing) ]);
    Alcotest.test_case "a move beyond the coordinate limit is refused" `Quick (fun () ->
        let far = (Scene.with_overrides ~camera:(Camera.v (Vec3.v Limits.max_coordinate 0. 0.)) Scene.cgfs) in
        let v, e = press (View.v (Helpers.valid far)) [ 'D' ] in
        Alcotest.check effect __LOC__ View.Nothing e;
        vec __LOC__ (Vec3.v Limits.max_coordinate 0. 0.) (position v));
    Alcotest.test_case "a wider or taller window sees more, with square pixels" `Quick (fun () ->
        let fit w h = View.fit Scene.cgfs ~width:w ~height:h in
        let check w h (vw, vh) =
          let vp = fit w h in
          Alcotest.(check (pair (float 1e-15) (float 1e-15))) (Printf.sprintf "%dx%d" w h) (vw, vh) (vp.width, vp.height);
          Alcotest.(check (float 0.)) __LOC__ 1. vp.distance
        in
        (* k = max (600 / w) (600 / h); V_w' = k w / 600, V_h' = k h / 600 *)
        check 1200 600 (2., 1.);
        check 600 1200 (1., 2.);
        check 300 300 (1., 1.);
        check 900 600 (1.5, 1.);
        check 400 300 (4. /. 3., 1.);
        Alcotest.(check bool) __LOC__ true (Viewport.equal (Scene.viewport Scene.cgfs) (fit 600 600)));
    Helpers.qcheck "after any resize, pixels keep their shape and the first view stays inside"
      QCheck.(pair (int_range 1 3000) (int_range 1 3000))
      (fun (w, h) ->
        let base = (Scene.with_overrides ~width:640 ~height:480 ~viewport:(Viewport.v ~width:2. ~height:1. ~distance:1.) Scene.cgfs) in
        let vp = View.fit base ~width:w ~height:h in
        let aspect (vp : Viewport.t) w h = vp.width /. Float.of_int w /. (vp.height /. Float.of_int h) in
        Float.abs (aspect vp w h -. aspect (Scene.viewport base) 640 480) <= 1e-12 *. aspect (Scene.viewport base) 640 480
        && vp.width >= 2. *. (1. -. 1e-15)
        && vp.height >= 1. *. (1. -. 1e-15)
        && (Float.abs (vp.width -. 2.) <= 1e-15 *. 2. || Float.abs (vp.height -. 1.) <= 1e-15));
    Alcotest.test_case "a resize renders at the new size, the same size does nothing" `Quick (fun () ->
        let v, e = View.handle cgfs (View.Resize (400, 300)) in
        Alcotest.check effect __LOC__ View.Render e;
        Alcotest.(check (pair int int)) __LOC__ (400, 300) ((Scene.width v.scene), (Scene.height v.scene));
        Alcotest.(check (float 1e-15)) __LOC__ (4. /. 3.) (Scene.viewport v.scene).width;
        Alcotest.check effect __LOC__ View.Nothing (snd (View.handle v (View.Resize (400, 300))));
        Alcotest.check effect __LOC__ View.Nothing (snd (View.handle v (View.Resize (0, 300))));
        let back, _ = View.handle v (View.Resize (600, 600)) in
        Alcotest.(check bool) __LOC__ true (Scene.equal back.scene Scene.cgfs));
    Alcotest.test_case "s saves beside the scene under the first free number" `Quick (fun () ->
        let taken = [ "scenes/x-1.ppm"; "scenes/x-2.scene" ] in
        let exists f = List.mem f taken in
        Alcotest.(check (pair string string)) __LOC__ ("scenes/x-3.ppm", "scenes/x-3.scene")
          (View.save_paths ~scene_file:(Some "scenes/x.scene") ~exists);
        Alcotest.(check (pair string string)) __LOC__ ("./cgfs-1.ppm", "./cgfs-1.scene")
          (View.save_paths ~scene_file:None ~exists));
    Alcotest.test_case "the title names the scene, then the last frame's time and speed" `Quick (fun () ->
        Alcotest.(check string) __LOC__ "raytrace: cgfs.scene - h: help" (View.title ~name:"cgfs.scene" ());
        Alcotest.(check string) __LOC__ "raytrace: cgfs.scene - 600x600 in 0.125 s, 16.3 M rays/s - h: help"
          (View.title ~name:"cgfs.scene" ~frame:(600, 600, 0.125, 16.3e6) ()));
    Alcotest.test_case "the help lists every key and the current state" `Quick (fun () ->
        let text = String.concat "\n" (View.help_lines (fst (press cgfs [ '+'; 'a' ]))) in
        let has s =
          let n = String.length s in
          let rec go i = i + n <= String.length text && (String.sub text i n = s || go (i + 1)) in
          Alcotest.(check bool) s true (go 0)
        in
        List.iter has [ "arrows"; "W A S D"; "drag"; "depth (now 4)"; "(now on)"; "save"; "quit"; "camera at 0 0 0" ]);
  ]
