(* Sample keys: pinned numbers (the js check holds the web build to the
   same ones), ranges, and the evenness that stratified sampling promises. *)
open Raytrace.Private

let check_int = Alcotest.(check int)

let tests =
  [
    Alcotest.test_case "sample keys are pinned" `Quick (fun () ->
        (* The values test/js/js_check.ml prints on both builds. *)
        check_int __LOC__ 2061196236 (Sample_key.pixel ~col:0 ~row:0 ~sample:0);
        check_int __LOC__ 580295973 (Sample_key.pixel ~col:1 ~row:0 ~sample:0);
        check_int __LOC__ 671359358 (Sample_key.pixel ~col:(-300) ~row:299 ~sample:15);
        check_int __LOC__ 1414110600 (Sample_key.pixel ~col:1_000_000 ~row:(-7) ~sample:4095);
        Alcotest.(check (float 0.)) __LOC__ 0x1.77ed457p-1 (Sample_key.unit 1414110600));
    Alcotest.test_case "keys and units stay in their ranges" `Quick (fun () ->
        for i = -5000 to 5000 do
          let h = Sample_key.key (i * 7919) i in
          if h < 0 || h >= 1 lsl 31 then Alcotest.failf "key %d out of range: %d" i h;
          let u = Sample_key.unit h in
          if not (u >= 0. && u < 1.) then Alcotest.failf "unit %d out of range: %h" i u
        done);
    Alcotest.test_case "a stratum's point lies in its stratum" `Quick (fun () ->
        List.iter
          (fun n ->
            for h = 0 to 200 do
              for i = 0 to n - 1 do
                let x = Sample_key.stratum h ~n i in
                let lo = Float.of_int i /. Float.of_int n and hi = Float.of_int (i + 1) /. Float.of_int n in
                if not (x >= lo && x <= hi && x < 1.) then
                  Alcotest.failf "stratum %d of %d, key %d: %h outside [%h, %h]" i n h x lo hi
              done
            done)
          [ 1; 2; 3; 4; 7; 16; 64 ]);
    Alcotest.test_case "units are spread evenly" `Quick (fun () ->
        (* 100,000 consecutive pixels' keys in 10 bins: each bin should hold
           10,000 +- 3 sqrt(9,000) ~ 285 if the numbers are uniform. *)
        let bins = Array.make 10 0 in
        for col = 0 to 99_999 do
          let u = Sample_key.unit (Sample_key.pixel ~col ~row:3 ~sample:0) in
          let b = Float.to_int (u *. 10.) in
          bins.(b) <- bins.(b) + 1
        done;
        Array.iteri (fun b c -> if abs (c - 10_000) > 400 then Alcotest.failf "bin %d holds %d of 100000" b c) bins);
    Alcotest.test_case "neighbouring keys differ in about half their bits" `Quick (fun () ->
        (* Avalanche: the keys of samples s and s+1 of one pixel differ in
           15.5 of 31 bits on average if mixed well. *)
        let total = ref 0 in
        let rec pop x = if x = 0 then 0 else (x land 1) + pop (x lsr 1) in
        for s = 0 to 9_999 do
          total := !total + pop (Sample_key.pixel ~col:5 ~row:5 ~sample:s lxor Sample_key.pixel ~col:5 ~row:5 ~sample:(s + 1))
        done;
        let mean = Float.of_int !total /. 10_000. in
        if Float.abs (mean -. 15.5) > 0.5 then Alcotest.failf "mean differing bits %.2f" mean);
    Alcotest.test_case "Sample_key.permute is a permutation of [0, n), another for another key" `Quick (fun () ->
        List.iter
          (fun n ->
            let image h = List.init n (fun k -> Sample_key.permute h ~n k) in
            let a = image 17 and b = image 18 in
            Alcotest.(check (list int)) (Printf.sprintf "n = %d" n) (List.init n Fun.id) (List.sort compare a);
            if n >= 8 && a = b then Alcotest.failf "n = %d: keys 17 and 18 give the same permutation" n)
          [ 1; 2; 3; 8; 9; 24; 25; 48; 63; 64; 1000; 4095; 4096 ];
        Alcotest.check_raises "k = n" (Invalid_argument "Sample_key.permute: k outside [0, n)") (fun () ->
            ignore (Sample_key.permute 0 ~n:4 4)));
  ]
