open Raytrace

let v = Vec3.v
let near = Alcotest.(check (float 1e-15))

let tests =
  [
    Alcotest.test_case "diffuse is I <L,N> / (|L| |N|) (7.5)" `Quick (fun () ->
        (* L straight along N: 0.6 * 2 / (1 * 2) = 0.6 *)
        near __LOC__ 0.6 (Shading.diffuse ~intensity:0.6 ~l:(v 0. 2. 0.) ~n:Vec3.oy);
        (* 45 degrees: <L,N> = 1, |L| = sqrt 2: 1 / sqrt 2 = 0.70710678... *)
        near __LOC__ (1. /. sqrt 2.) (Shading.diffuse ~intensity:1. ~l:(v 1. 1. 0.) ~n:Vec3.oy);
        (* 60 degrees from N: cos = 0.5 *)
        near __LOC__ 0.5 (Shading.diffuse ~intensity:1. ~l:(v (sqrt 3.) 1. 0.) ~n:Vec3.oy));
    Alcotest.test_case "light from behind the surface adds nothing (7.5)" `Quick (fun () ->
        near __LOC__ 0. (Shading.diffuse ~intensity:1. ~l:(v 0. (-1.) 0.) ~n:Vec3.oy);
        near __LOC__ 0. (Shading.diffuse ~intensity:1. ~l:(v 1. 0. 0.) ~n:Vec3.oy));
    Alcotest.test_case "R = 2 <L,N> N - L (7.6)" `Quick (fun () ->
        (* L = (1, 1, 0), N = (0, 1, 0): 2 * 1 * (0, 1, 0) - (1, 1, 0) = (-1, 1, 0) *)
        Alcotest.check Helpers.vec3 __LOC__ (v (-1.) 1. 0.) (Shading.reflect (v 1. 1. 0.) Vec3.oy);
        (* a vector along the normal reflects onto itself *)
        Alcotest.check Helpers.vec3 __LOC__ (v 0. 3. 0.) (Shading.reflect (v 0. 3. 0.) Vec3.oy));
    Alcotest.test_case "specular is I (<R,V> / (|R| |V|))^s (7.6)" `Quick (fun () ->
        (* R = V up to scale: cos = 4 / (sqrt 2 sqrt 8) = 1 (up to the rounding
           of the square roots), 0.6 * 1^500 = 0.6 *)
        Alcotest.(check (float 1e-12)) __LOC__ 0.6 (Shading.specular ~intensity:0.6 ~s:500. ~r:(v (-1.) 1. 0.) ~v:(v (-2.) 2. 0.));
        (* R = (-1, 1, 0), V = (0, 1, 0): cos = 1 / sqrt 2; squared 0.5 *)
        near __LOC__ 0.5 (Shading.specular ~intensity:1. ~s:2. ~r:(v (-1.) 1. 0.) ~v:Vec3.oy);
        (* s = 0 is not matte: cos^0 = 1 *)
        near __LOC__ 1. (Shading.specular ~intensity:1. ~s:0. ~r:(v (-1.) 1. 0.) ~v:Vec3.oy));
    Alcotest.test_case "specular is zero when R points away from V (7.6)" `Quick (fun () ->
        near __LOC__ 0. (Shading.specular ~intensity:1. ~s:10. ~r:(v 0. (-1.) 0.) ~v:Vec3.oy);
        near __LOC__ 0. (Shading.specular ~intensity:1. ~s:10. ~r:Vec3.ox ~v:Vec3.oy));
  ]
