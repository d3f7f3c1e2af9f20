(* The document's algorithm (Literal) on scenes small enough to compute by
   hand. *)
open Raytrace

let near = Alcotest.(check (float 1e-12))
let sphere ?(specular = Sphere.matte) ?(reflective = 0.) ?(color = Color.white) center radius =
  Sphere.v ~specular ~reflective ~center ~radius color

let scene ?(background = Color.black) ?(depth = 3) spheres lights =
  Scene.v ~background ~depth ~epsilon:0.001 ~spheres ~lights ()

(* A unit sphere at the origin, seen at its top point P = (0, 1, 0), N = (0, 1, 0). *)
let ball = sphere Vec3.zero 1.
let top = Vec3.oy

let lighting ?(specular = Sphere.matte) ?(view = Vec3.oy) s =
  Literal.compute_lighting s ~epsilon:0.001 ~point:top ~normal:Vec3.oy ~view ~specular

let tests =
  [
    Alcotest.test_case "the closest of several hits wins (section 6.1)" `Quick (fun () ->
        let near_s = sphere (Vec3.v 0. 0. 3.) 1. and far_s = sphere (Vec3.v 0. 0. 10.) 1. in
        match
          Literal.closest_intersection [ far_s; near_s ] ~origin:Vec3.zero ~direction:Vec3.oz
            ~t_min:1. ~t_max:infinity
        with
        | Some (s, t) ->
            (* roots of the near sphere: 2 and 4; the far one: 9 and 11 *)
            Alcotest.(check bool) __LOC__ true (s == near_s);
            near __LOC__ 2. t
        | None -> Alcotest.fail "no hit");
    Alcotest.test_case "hits outside (t_min, t_max) are not seen" `Quick (fun () ->
        let s = sphere (Vec3.v 0. 0. 3.) 1. in
        let hit ~t_min ~t_max =
          Option.map snd
            (Literal.closest_intersection [ s ] ~origin:Vec3.zero ~direction:Vec3.oz ~t_min ~t_max)
        in
        (* roots 2 and 4: the range is open at both ends *)
        Alcotest.(check (option (float 0.))) __LOC__ (Some 4.) (hit ~t_min:2. ~t_max:infinity);
        Alcotest.(check (option (float 0.))) __LOC__ None (hit ~t_min:4. ~t_max:infinity);
        Alcotest.(check (option (float 0.))) __LOC__ None (hit ~t_min:0. ~t_max:2.));
    Alcotest.test_case "ambient light lights every point equally (7.3)" `Quick (fun () ->
        near __LOC__ 0.2 (lighting (scene [ ball ] [ Light.ambient 0.2 ])));
    Alcotest.test_case "intensities add up (7.4)" `Quick (fun () ->
        (* ambient 0.2 + point light straight above: L = (0, 3, 0) - (0, 1, 0)
           = (0, 2, 0), 0.6 * 2 / (1 * 2) = 0.6: total 0.8 *)
        near __LOC__ 0.8
          (lighting (scene [ ball ] [ Light.ambient 0.2; Light.point 0.6 (Vec3.v 0. 3. 0.) ])));
    Alcotest.test_case "a light below the horizon adds nothing diffuse" `Quick (fun () ->
        near __LOC__ 0. (lighting (scene [ ball ] [ Light.directional 0.5 (Vec3.v 1. 0. 0.) ])));
    Alcotest.test_case "specular adds I cos^s for shiny spheres only (7.6)" `Quick (fun () ->
        (* light along (1, 1, 0) from P: diffuse 1 / sqrt 2; R = (-1, 1, 0);
           V = (-1, 1, 0): cos = 1, so specular adds 1: 1 + 1 / sqrt 2 *)
        let s = scene [ ball ] [ Light.directional 1. (Vec3.v 1. 1. 0.) ] in
        let view = Vec3.v (-1.) 1. 0. in
        near __LOC__ (1. +. (1. /. sqrt 2.)) (lighting ~specular:100. ~view s);
        near __LOC__ (1. /. sqrt 2.) (lighting ~view s));
    Alcotest.test_case "a sphere between point and light casts a shadow (7.7)" `Quick (fun () ->
        (* blocker at (0, 2, 0), r = 0.5: the shadow ray (0,1,0) + t (0,2,0)
           meets it at y = 1.5, t = 0.25, inside (0.001, 1) *)
        let blocker = sphere (Vec3.v 0. 2. 0.) 0.5 in
        near __LOC__ 0.2
          (lighting (scene [ ball; blocker ] [ Light.ambient 0.2; Light.point 0.6 (Vec3.v 0. 3. 0.) ])));
    Alcotest.test_case "an object beyond a point light casts no shadow, beyond a directional one does"
      `Quick (fun () ->
        (* blocker at (0, 5, 0), r = 0.5: first hit at y = 4.5, t = (4.5 - 1) / 2
           = 1.75 > 1 for the point light at (0, 3, 0); for the directional
           light L = (0, 1, 0), t = 3.5 < infinity *)
        let blocker = sphere (Vec3.v 0. 5. 0.) 0.5 in
        near __LOC__ 0.6 (lighting (scene [ ball; blocker ] [ Light.point 0.6 (Vec3.v 0. 3. 0.) ]));
        near __LOC__ 0. (lighting (scene [ ball; blocker ] [ Light.directional 0.6 Vec3.oy ])));
    Alcotest.test_case "the surface does not shadow itself thanks to epsilon (7.7)" `Quick (fun () ->
        (* the shadow ray starts on the sphere: its root t = 0 must not count *)
        near __LOC__ 1. (lighting (scene [ ball ] [ Light.directional 1. Vec3.oy ])));
    Alcotest.test_case "a mirror blends its colour with what it reflects (7.8)" `Quick (fun () ->
        (* ray along +z hits the sphere at (0, 0, 2) head-on, local colour
           (200, 100, 0) * ambient 1; the mirror ray goes back to the camera
           side and sees the background (0, 0, 255):
           (200, 100, 0) * 0.5 + (0, 0, 255) * 0.5 = (100, 50, 127.5) *)
        let s =
          scene ~background:(Color.v 0. 0. 255.)
            [ sphere ~reflective:0.5 ~color:(Color.v 200. 100. 0.) (Vec3.v 0. 0. 3.) 1. ]
            [ Light.ambient 1. ]
        in
        let trace depth =
          Literal.trace_ray s ~epsilon:0.001 ~origin:Vec3.zero ~direction:Vec3.oz ~t_min:1.
            ~t_max:infinity ~depth
        in
        Alcotest.check Helpers.color __LOC__ (Color.v 100. 50. 127.5) (trace 3);
        (* with no recursion left, only the local colour *)
        Alcotest.check Helpers.color __LOC__ (Color.v 200. 100. 0.) (trace 0));
    Alcotest.test_case "rendering visits exactly w x h pixels (section 8)" `Quick (fun () ->
        let s = { (scene [] [ Light.ambient 1. ]) with width = 7; height = 4; background = Color.v 1. 2. 3. } in
        let img = Literal.render (Helpers.valid s) in
        Alcotest.(check (pair int int)) __LOC__ (7, 4) (Image.width img, Image.height img);
        Alcotest.(check (triple int int int)) __LOC__ (1, 2, 3) (Image.get img 6 3));
    Alcotest.test_case "what is above the camera lands in the top rows" `Quick (fun () ->
        (* 4 x 4 canvas: rows 0..3 are canvas y = 1, 0, -1, -2, rays
           (V_x, y / 4, 1). A ceiling sphere (center (0, 101, 10), r = 100,
           lowest point y = 1) is met by the rays with y / 4 = 0.25 (at
           z = 10 they are at y = 2.5, inside it) and by none with y <= 0. *)
        let s =
          { (scene [ sphere (Vec3.v 0. 101. 10.) 100. ] [ Light.ambient 1. ]) with width = 4; height = 4 }
        in
        let img = Literal.render (Helpers.valid s) in
        let white = (255, 255, 255) and black = (0, 0, 0) in
        List.iter
          (fun (row, expected) ->
            for x = 0 to 3 do
              Alcotest.(check (triple int int int)) (Printf.sprintf "row %d" row) expected (Image.get img x row)
            done)
          [ (0, white); (1, black); (2, black); (3, black) ]);
  ]
