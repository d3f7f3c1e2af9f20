open Raytrace

let check = Alcotest.check Helpers.color
let byte = Alcotest.(check int)

let tests =
  [
    Alcotest.test_case "clamping keeps channels in [0, 255] (section 2)" `Quick (fun () ->
        Alcotest.(check (float 0.)) __LOC__ 255. (Color.clamp 300.);
        Alcotest.(check (float 0.)) __LOC__ 0. (Color.clamp (-5.));
        Alcotest.(check (float 0.)) __LOC__ 127.25 (Color.clamp 127.25);
        Alcotest.(check (float 0.)) __LOC__ 0. (Color.clamp nan));
    Alcotest.test_case "k (r, g, b) = (k r, k g, k b) (section 2)" `Quick (fun () ->
        (* 0.5 (200, 100, 50) = (100, 50, 25) *)
        check __LOC__ (Color.v 100. 50. 25.) (Color.smul 0.5 (Color.v 200. 100. 50.));
        (* brightening is not clamped here: 2 (200, 0, 0) = (400, 0, 0) *)
        check __LOC__ (Color.v 400. 0. 0.) (Color.smul 2. (Color.v 200. 0. 0.)));
    Alcotest.test_case "adding colours adds channels" `Quick (fun () ->
        check __LOC__ (Color.v 300. 2. 3.) (Color.add (Color.v 200. 1. 1.) (Color.v 100. 1. 2.)));
    Alcotest.test_case "a mirror blends local and reflected colours (section 7.8)" `Quick (fun () ->
        (* (100, 0, 40) * (1 - 0.25) + (0, 200, 40) * 0.25 = (75, 50, 40) *)
        check __LOC__ (Color.v 75. 50. 40.)
          (Color.blend ~reflective:0.25 ~local:(Color.v 100. 0. 40.) ~reflected:(Color.v 0. 200. 40.)));
    Alcotest.test_case "to_byte clamps, then rounds half to even" `Quick (fun () ->
        byte __LOC__ 255 (Color.to_byte 300.);
        byte __LOC__ 0 (Color.to_byte (-1.));
        byte __LOC__ 0 (Color.to_byte nan);
        byte __LOC__ 0 (Color.to_byte 0.5);
        byte __LOC__ 2 (Color.to_byte 1.5);
        byte __LOC__ 2 (Color.to_byte 2.5);
        byte __LOC__ 3 (Color.to_byte 2.5000001);
        byte __LOC__ 254 (Color.to_byte 254.5);
        byte __LOC__ 255 (Color.to_byte 254.6);
        byte __LOC__ 255 (Color.to_byte 255.));
    Helpers.qcheck "Trace's copy of to_byte agrees with Color.to_byte"
      QCheck.(float_range (-10.) 300.)
      (fun x -> Trace.to_byte x = Color.to_byte x && Trace.to_byte (Float.round x +. 0.5) = Color.to_byte (Float.round x +. 0.5));
  ]
