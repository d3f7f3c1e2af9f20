open Raytrace

let pair () =
  let a = Image.create 2 1 and b = Image.create 2 1 in
  Image.set a 0 0 10 20 30;
  Image.set b 0 0 10 22 30;
  (a, b)

let stats a b = match Image.Diff.compare a b with Ok d -> d | Error (`Msg m) -> Alcotest.fail m

let tests =
  [
    Alcotest.test_case "identical images differ nowhere" `Quick (fun () ->
        let a, _ = pair () in
        let d = stats a a in
        Alcotest.(check (list int)) __LOC__ [ 2; 0; 0; 0 ] [ d.pixels; d.differing; d.differing_gt1; d.max_abs ];
        Alcotest.(check (float 0.)) __LOC__ infinity d.psnr);
    Alcotest.test_case "one channel off by 2 in a 2 x 1 image" `Quick (fun () ->
        let a, b = pair () in
        let d = stats a b in
        (* 6 channels, one differs by 2: mean 2 / 6; MSE 4 / 6;
           PSNR = 10 log10 (65025 / (2/3)) = 10 log10 97537.5 = 49.8917 dB *)
        Alcotest.(check (list int)) __LOC__ [ 2; 1; 1; 2 ] [ d.pixels; d.differing; d.differing_gt1; d.max_abs ];
        Alcotest.(check (float 1e-12)) __LOC__ (2. /. 6.) d.mean_abs;
        Alcotest.(check (float 1e-4)) __LOC__ 49.8917 d.psnr;
        Alcotest.(check (float 0.)) __LOC__ 0.5 (Image.Diff.share_within d));
    Alcotest.test_case "a difference of 1 is within 1" `Quick (fun () ->
        let a = Image.create 1 1 and b = Image.create 1 1 in
        Image.set b 0 0 1 1 1;
        let d = stats a b in
        Alcotest.(check (list int)) __LOC__ [ 1; 0; 1 ] [ d.differing; d.differing_gt1; d.max_abs ]);
    Alcotest.test_case "four pixels off by 0, 1, 4 and 255" `Quick (fun () ->
        let a = Image.create 2 2 and b = Image.create 2 2 in
        Image.set a 0 0 7 7 7;
        Image.set b 0 0 7 7 7;
        Image.set b 1 0 1 0 0;
        Image.set a 0 1 10 20 30;
        Image.set b 0 1 13 20 26;
        Image.set b 1 1 0 255 0;
        let d = stats a b in
        (* Channel differences 0 0 0 | 1 0 0 | 3 0 4 | 0 255 0: three pixels
           differ, two by more than 1, the largest by 255.
           mean = (1 + 3 + 4 + 255) / 12 = 263 / 12 = 21.916667
           MSE = (1 + 9 + 16 + 65025) / 12 = 65051 / 12 = 5420.916667
           PSNR = 10 log10 (65025 / 5420.916667) = 10 log10 11.995203 = 10.790076 dB
           within 1: 2 of 4 pixels. *)
        Alcotest.(check (list int)) __LOC__ [ 4; 3; 2; 255 ] [ d.pixels; d.differing; d.differing_gt1; d.max_abs ];
        Alcotest.(check (float 1e-9)) __LOC__ (263. /. 12.) d.mean_abs;
        Alcotest.(check (float 1e-6)) __LOC__ 10.790076 d.psnr;
        Alcotest.(check (float 0.)) __LOC__ 0.5 (Image.Diff.share_within d));
    Alcotest.test_case "images of different sizes cannot be compared" `Quick (fun () ->
        match Image.Diff.compare (Image.create 2 1) (Image.create 1 2) with
        | Ok _ -> Alcotest.fail "compared"
        | Error (`Msg m) -> Alcotest.(check string) __LOC__ "image sizes differ: 2x1 and 1x2" m);
  ]
