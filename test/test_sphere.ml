open Raytrace

let unit_sphere_at z = Helpers.sphere ~center:(Vec3.v 0. 0. z) ~radius:1. Color.white
let triple = Alcotest.(triple (float 0.) (float 0.) (float 0.))
let pair = Alcotest.(pair (float 0.) (float 0.))

let tests =
  [
    Alcotest.test_case "a = |D|^2, b = 2 <CO, D>, c = |CO|^2 - r^2 (section 6.1)" `Quick (fun () ->
        (* O = 0, D = (0, 0, 2), C = (0, 0, 3), r = 1: CO = (0, 0, -3);
           a = 4, b = 2 * (-6) = -12, c = 9 - 1 = 8 *)
        Alcotest.check triple __LOC__ (4., -12., 8.)
          (Sphere.quadratic (unit_sphere_at 3.) ~origin:Vec3.zero ~direction:(Vec3.v 0. 0. 2.)));
    Alcotest.test_case "a ray through the center meets the sphere twice" `Quick (fun () ->
        (* a = 1, b = -6, c = 8: disc = 36 - 32 = 4; t = (6 +- 2) / 2 = 4, 2 *)
        Alcotest.check pair __LOC__ (4., 2.) (Sphere.textbook_roots 1. (-6.) 8.));
    Alcotest.test_case "a ray tangent to a sphere hits it once" `Quick (fun () ->
        (* O = (1, 0, 0), D = (0, 0, 1), C = (0, 0, 3): CO = (1, 0, -3);
           a = 1, b = -6, c = 1 + 9 - 1 = 9: disc = 0, t = 3 twice *)
        let a, b, c = Sphere.quadratic (unit_sphere_at 3.) ~origin:Vec3.ox ~direction:Vec3.oz in
        Alcotest.check pair __LOC__ (3., 3.) (Sphere.textbook_roots a b c));
    Alcotest.test_case "a ray that misses has no root" `Quick (fun () ->
        (* O = (2, 0, 0): c = 4 + 9 - 1 = 12, disc = 36 - 48 < 0 *)
        let a, b, c =
          Sphere.quadratic (unit_sphere_at 3.) ~origin:(Vec3.v 2. 0. 0.) ~direction:Vec3.oz
        in
        Alcotest.check pair __LOC__ (infinity, infinity) (Sphere.textbook_roots a b c));
    Alcotest.test_case "the normal points out of the center" `Quick (fun () ->
        (* P = (0, 0, 2) on the sphere at (0, 0, 3): (P - C) / |P - C| = (0, 0, -1) *)
        Alcotest.check Helpers.vec3 __LOC__ (Vec3.v 0. 0. (-1.))
          (Sphere.normal (unit_sphere_at 3.) (Vec3.v 0. 0. 2.)));
    Alcotest.test_case "invalid materials are rejected with the field's name" `Quick (fun () ->
        let msg = function Ok _ -> "ok" | Error (`Msg m) -> m in
        Alcotest.(check string) __LOC__ "sphere radius must be > 0, got -1" (msg (Sphere.check_radius (-1.)));
        Alcotest.(check string) __LOC__ "sphere reflective must lie in [0, 1], got 1.5"
          (msg (Sphere.check_reflective 1.5));
        Alcotest.(check string) __LOC__ "sphere specular must be -1 (matte) or >= 0, got -0.5"
          (msg (Sphere.check_specular (-0.5)));
        Alcotest.(check string) __LOC__ "ok" (msg (Sphere.check_specular 0.));
        Alcotest.(check bool) __LOC__ true (Result.is_error (Sphere.check_radius nan));
        Alcotest.(check bool) __LOC__ true (Result.is_error (Sphere.check_color (Color.v 0. 256. 0.))));
  ]
