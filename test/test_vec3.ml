open Raytrace

let v = Vec3.v
let check = Alcotest.check Helpers.vec3
let checkf = Alcotest.check (Helpers.float_near 0.)

let tests =
  [
    Alcotest.test_case "add and sub are coordinate-wise" `Quick (fun () ->
        check __LOC__ (v 5. 7. 9.) (Vec3.add (v 1. 2. 3.) (v 4. 5. 6.));
        check __LOC__ (v (-3.) (-3.) (-3.)) (Vec3.sub (v 1. 2. 3.) (v 4. 5. 6.)));
    Alcotest.test_case "smul scales each coordinate" `Quick (fun () ->
        check __LOC__ (v 2. (-4.) 1.) (Vec3.smul 2. (v 1. (-2.) 0.5)));
    Alcotest.test_case "dot is the inner product" `Quick (fun () ->
        (* 1*4 + 2*5 + 3*6 = 4 + 10 + 18 = 32 *)
        checkf __LOC__ 32. (Vec3.dot (v 1. 2. 3.) (v 4. 5. 6.)));
    Alcotest.test_case "cross follows the right-hand rule of the coordinates" `Quick (fun () ->
        check __LOC__ Vec3.oz (Vec3.cross Vec3.ox Vec3.oy);
        (* (1,2,3) x (4,5,6) = (2*6-3*5, 3*4-1*6, 1*5-2*4) = (-3, 6, -3) *)
        check __LOC__ (v (-3.) 6. (-3.)) (Vec3.cross (v 1. 2. 3.) (v 4. 5. 6.)));
    Alcotest.test_case "norm is the length" `Quick (fun () ->
        (* sqrt (9 + 16 + 0) = 5 *)
        checkf __LOC__ 5. (Vec3.norm (v 3. 4. 0.));
        checkf __LOC__ 25. (Vec3.norm2 (v 3. 4. 0.)));
    Alcotest.test_case "unit has length 1" `Quick (fun () ->
        (* (3, 4, 0) / 5 = (0.6, 0.8, 0) *)
        Alcotest.check (Helpers.vec3_near 1e-15) __LOC__ (v 0.6 0.8 0.) (Vec3.unit (v 3. 4. 0.)));
    Alcotest.test_case "equal is IEEE equality" `Quick (fun () ->
        Alcotest.(check bool) __LOC__ false (Vec3.equal (v nan 0. 0.) (v nan 0. 0.));
        Alcotest.(check bool) __LOC__ true (Vec3.equal (v 0. 0. 0.) (v (-0.) 0. 0.)));
    Alcotest.test_case "pp writes scene syntax that reads back" `Quick (fun () ->
        Alcotest.(check string) __LOC__ "(1 -0.5 0.1)" (Vec3.show (v 1. (-0.5) 0.1)));
    Helpers.qcheck "Float_text.to_string reads back as the same float"
      QCheck.(float)
      (fun x -> Float.is_nan x || float_of_string (Float_text.to_string x) = x);
  ]
