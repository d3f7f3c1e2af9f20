open Raytrace

let check = Alcotest.check Helpers.vec3

let tests =
  [
    Alcotest.test_case "V = (Gx Vw / Gw, Gy Vh / Gh, d) (section 3)" `Quick (fun () ->
        (* 150 * 1 / 600 = 0.25; -300 * 1 / 600 = -0.5; d = 1 *)
        check __LOC__ (Vec3.v 0.25 (-0.5) 1.)
          (Viewport.of_canvas Viewport.default ~canvas_width:600 ~canvas_height:600 150 (-300));
        (* 100 * 2 / 400 = 0.5; 30 * 3 / 200 = 0.45; d = 1.5 *)
        check __LOC__ (Vec3.v 0.5 0.45 1.5)
          (Viewport.of_canvas
             (Viewport.v ~width:2. ~height:3. ~distance:1.5)
             ~canvas_width:400 ~canvas_height:200 100 30));
    Alcotest.test_case "the document's viewport sees about 53 degrees" `Quick (fun () ->
        (* 2 atan (0.5 / 1) = 53.13 degrees *)
        let vp = Viewport.default in
        let fov = 2. *. atan (vp.width /. 2. /. vp.distance) *. 180. /. Float.pi in
        Alcotest.(check (float 0.01)) __LOC__ 53.13 fov);
  ]
