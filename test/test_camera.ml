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
      Alcotest.test_case "a pinhole has no focus: its focal distance is 1 whatever is given" `Quick (fun () ->
        let c = Camera.v ~focal_distance:7. Vec3.zero in
        Alcotest.(check (float 0.)) __LOC__ 1. (Camera.focal_distance c);
        Alcotest.(check bool) __LOC__ true (Camera.equal c Camera.default);
        Alcotest.(check bool) __LOC__ false (Camera.has_lens c));
    Alcotest.test_case "look-at focuses on its target unless told otherwise" `Quick (fun () ->
        (* |(3, 4, 0) - 0| = 5. *)
        (match Camera.look_at ~aperture:0.1 ~position:Vec3.zero (Vec3.v 3. 4. 0.) with
        | Ok c -> Alcotest.(check (float 0.)) __LOC__ 5. (Camera.focal_distance c)
        | Error (`Msg m) -> Alcotest.fail m);
        match Camera.look_at ~aperture:0.1 ~focal_distance:2. ~position:Vec3.zero (Vec3.v 3. 4. 0.) with
        | Ok c -> Alcotest.(check (float 0.)) __LOC__ 2. (Camera.focal_distance c)
        | Error (`Msg m) -> Alcotest.fail m);
    Alcotest.test_case "a lens camera prints as a camera form that reads back" `Quick (fun () ->
        let rotation = Camera.{ row0 = Vec3.v 0.7071 0. (-0.7071); row1 = Vec3.oy; row2 = Vec3.v 0.7071 0. 0.7071 } in
        List.iter
          (fun c ->
            let text = Camera.show c in
            let read = Scene.camera (Helpers.parse_ok text) in
            if not (Camera.equal c read) then Alcotest.failf "%s read back as %s" text (Camera.show read))
          [
            Camera.v ~aperture:0.25 ~focal_distance:6.5 (Vec3.v 0. 1. (-2.));
            Camera.v ~rotation ~aperture:0.1 ~focal_distance:1. (Vec3.v 3. 0. 1.);
            Camera.v ~aperture:0.1 ~focal_distance:0.1 Vec3.zero;
            Camera.v ~aperture:0.1 ~focal_distance:2. ~lens_sampling:Camera.Uniform Vec3.zero;
            Camera.v ~rotation ~aperture:0.3 ~focal_distance:4. ~lens_sampling:Camera.Stratified (Vec3.v 3. 0. 1.);
            Camera.v (Vec3.v 1. 2. 3.);
          ]);
    Alcotest.test_case "a lens is stratified unless (lens-sampling uniform); a pinhole has nothing to sample" `Quick
      (fun () ->
        let sampling text = Camera.lens_sampling (Scene.camera (Helpers.parse_ok text)) in
        Alcotest.(check bool) __LOC__ true
          (sampling "(camera (position 0 0 -1) (look-at 0 0 4) (aperture 0.2))" = Camera.Stratified);
        Alcotest.(check bool) __LOC__ true
          (sampling "(camera (aperture 0.2) (focal-distance 3) (lens-sampling uniform))" = Camera.Uniform);
        Alcotest.(check bool) __LOC__ true
          (sampling "(camera (aperture 0.2) (focal-distance 3) (lens-sampling stratified))" = Camera.Stratified);
        (* Printed only when uniform: the default reads back as itself. *)
        Alcotest.(check string) __LOC__ "(camera (position 0 0 0) (aperture 0.2) (focal-distance 3))"
          (Camera.show (Camera.v ~aperture:0.2 ~focal_distance:3. Vec3.zero));
        Alcotest.(check string) __LOC__ "(camera (position 0 0 0) (aperture 0.2) (focal-distance 3) (lens-sampling uniform))"
          (Camera.show (Camera.v ~aperture:0.2 ~focal_distance:3. ~lens_sampling:Camera.Uniform Vec3.zero));
        (* A pinhole's is the default, whatever is given: two pinholes are equal. *)
        Alcotest.(check bool) __LOC__ true
          (Camera.equal Camera.default (Camera.v ~lens_sampling:Camera.Uniform Vec3.zero));
        Alcotest.(check string) __LOC__
          "t.scene:1:58: camera lens-sampling: expected stratified or uniform, got unifrom (did you mean uniform?)"
          (Helpers.parse_error "(camera (aperture 0.2) (focal-distance 3) (lens-sampling unifrom))");
        Alcotest.(check string) __LOC__ "t.scene:2:2: camera (lens-sampling ...) needs an (aperture ...) above 0"
          (Helpers.parse_error "(camera (position 0 0 0)\n (lens-sampling uniform))");
        Alcotest.(check string) __LOC__ "t.scene:1:22: camera (lens-sampling ...) needs an (aperture ...) above 0"
          (Helpers.parse_error "(camera (aperture 0) (lens-sampling stratified))"));
    Alcotest.test_case "an aperture is 0 or a size; a focal distance a size" `Quick (fun () ->
        let bad r = Alcotest.(check bool) __LOC__ true (Result.is_error r) in
        let good r = Alcotest.(check bool) __LOC__ true (Result.is_ok r) in
        good (Camera.check_aperture 0.);
        good (Camera.check_aperture 0.5);
        bad (Camera.check_aperture (-0.5));
        bad (Camera.check_aperture Float.nan);
        bad (Camera.check_aperture Float.infinity);
        bad (Camera.check_focal_distance 0.);
        bad (Camera.check_focal_distance (-1.));
        bad (Camera.validate (Camera.v ~aperture:0.5 ~focal_distance:Float.nan Vec3.zero)));
    Alcotest.test_case "scene text: a lens without a focus or a target is refused where it is written" `Quick
      (fun () ->
        let m = Helpers.parse_error "(camera (position 0 0 0)\n (aperture 0.2))" in
        Alcotest.(check string) __LOC__
          "t.scene:2:2: camera (aperture ...) needs a (focal-distance ...), or a (look-at ...) target to focus on" m;
        (* The number as the scene text writes numbers (shortest exact),
           not %g's rounding: 0x1p-1074 was "4.94066e-324" and the bound
           "1e+12", where every other message says 5e-324 and 1e12. *)
        let m = Helpers.parse_error "(camera (aperture 0x1p-1074) (focal-distance 1))" in
        Alcotest.(check string) __LOC__ "t.scene:1:19: camera aperture must be 0 or in [1e-30, 1e12], got 5e-324" m;
        let m = Helpers.parse_error "(camera (aperture -0.30000001) (focal-distance 1))" in
        Alcotest.(check string) __LOC__ "t.scene:1:19: camera aperture must be 0 or in [1e-30, 1e12], got -0.30000001" m;
        let m = Helpers.parse_error "(camera (aperture 0.2) (focal-distance 0))" in
        Alcotest.(check string) __LOC__ "t.scene:1:40: camera focal-distance must be > 0, got 0" m;
        let c = Scene.camera (Helpers.parse_ok "(camera (position 0 0 -1) (look-at 0 0 4) (aperture 0.2))") in
        (* Focused on the target, 5 away. *)
        Alcotest.(check (float 0.)) __LOC__ 5. (Camera.focal_distance c));
  ]
