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
    Alcotest.test_case "to_rgb8 packs the bytes the renderer stores, clamped and rounded, as 0xRRGGBB" `Quick (fun () ->
        (* 300 clamps to 255 = 0xFF; 127.5 rounds to even, 128 = 0x80; NaN is 0. *)
        Alcotest.(check int) __LOC__ 0xFF8000 (Color.to_rgb8 (Color.v 300. 127.5 Float.nan));
        (* -4 clamps to 0; 1.49 rounds to 1; 254.5 rounds to even, 254 = 0xFE. *)
        Alcotest.(check int) __LOC__ 0x0001FE (Color.to_rgb8 (Color.v (-4.) 1.49 254.5));
        let c = Color.v 12.3 200.7 99.5 in
        let words = Gc.minor_words () in
        let p = Color.to_rgb8 c in
        let allocated = Gc.minor_words () -. words in
        Alcotest.(check (list int)) __LOC__
          [ Color.to_byte c.r; Color.to_byte c.g; Color.to_byte c.b ]
          [ p lsr 16; (p lsr 8) land 0xFF; p land 0xFF ];
        Alcotest.(check (float 0.)) "minor words allocated by to_rgb8" 0. allocated);
  ]
