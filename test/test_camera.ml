open Raytrace

let check = Alcotest.check Helpers.vec3

let tests =
  [
    Alcotest.test_case "the document's camera looks along +z: D = V" `Quick (fun () ->
        let v = Vec3.v 0.25 (-0.5) 1. in
        check __LOC__ v (Camera.direction Camera.default v));
    Alcotest.test_case "CGFS's camera matrix turns the view direction" `Quick (fun () ->
        (* rows (0.7071 0 -0.7071) (0 1 0) (0.7071 0 0.7071) times (0, 0, 1)
           = (-0.7071, 0, 0.7071); times (1, 0, 0) = (0.7071, 0, 0.7071) *)
        let cam = (Scene.camera Scene.cgfs_camera) in
        check __LOC__ (Vec3.v (-0.7071) 0. 0.7071) (Camera.direction cam Vec3.oz);
        check __LOC__ (Vec3.v 0.7071 0. 0.7071) (Camera.direction cam Vec3.ox));
    Alcotest.test_case "look-at along +z is the identity" `Quick (fun () ->
        match Camera.look_at ~position:Vec3.zero (Vec3.v 0. 0. 5.) with
        | Ok cam -> Alcotest.(check bool) __LOC__ true (Camera.is_identity cam.rotation)
        | Error (`Msg e) -> Alcotest.fail e);
    Alcotest.test_case "look-at sends the viewport center toward the target" `Quick (fun () ->
        (* from (3, 0, 1) toward (2, 0, 2): forward = (-1, 0, 1) / sqrt 2 *)
        match Camera.look_at ~position:(Vec3.v 3. 0. 1.) (Vec3.v 2. 0. 2.) with
        | Ok cam ->
            let s = 1. /. sqrt 2. in
            Alcotest.check (Helpers.vec3_near 1e-15) __LOC__ (Vec3.v (-.s) 0. s)
              (Camera.direction cam Vec3.oz);
            Alcotest.(check (float 1e-12)) __LOC__ 1. (Camera.determinant cam.rotation)
        | Error (`Msg e) -> Alcotest.fail e);
    Alcotest.test_case "look-at refuses degenerate input" `Quick (fun () ->
        let fails what r = Alcotest.(check bool) what true (Result.is_error r) in
        fails "target = position" (Camera.look_at ~position:Vec3.oz Vec3.oz);
        fails "up parallel to view" (Camera.look_at ~up:Vec3.oz ~position:Vec3.zero (Vec3.v 0. 0. 3.));
        fails "zero up" (Camera.look_at ~up:Vec3.zero ~position:Vec3.zero Vec3.oz));
    Alcotest.test_case "a singular rotation is rejected" `Quick (fun () ->
        let m = Camera.{ row0 = Vec3.ox; row1 = Vec3.ox; row2 = Vec3.oz } in
        Alcotest.(check bool) __LOC__ true (Result.is_error (Camera.check_rotation m)));
  ]
