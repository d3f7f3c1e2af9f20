

(* [Float_scan.of_string s] against [float_of_string]: the same bits, or
   NaN where OCaml's reader refuses [s] and where [s] has characters
   outside the decimal grammar (OCaml also reads "nan", "0x1p3", "1_0"). *)
let agrees s =
  let ours = Float_scan.of_string s in
  let decimal_chars = String.for_all (fun c -> (c >= '0' && c <= '9') || String.contains "+-.eE" c) s in
  match float_of_string_opt s with
  | Some x when decimal_chars -> Int64.equal (Int64.bits_of_float x) (Int64.bits_of_float ours)
  | _ -> Float.is_nan ours

let digits n = QCheck.Gen.(string_size ~gen:(char_range '0' '9') (int_bound n))

(* Decimals of every shape: sign, integer and fraction digits (up to 25,
   beyond the 2^53 of the fast path), exponents around both ends of the
   float range and around the fast path's 10^22. *)
let decimal =
  QCheck.Gen.(
    map
      (fun (((sign, whole), (dot, frac)), (e, exp)) ->
        sign ^ whole ^ (if dot then "." ^ frac else "") ^ if e then Printf.sprintf "e%d" exp else "")
      (pair
         (pair (pair (oneofl [ ""; "-"; "+" ]) (digits 25)) (pair bool (digits 25)))
         (pair bool (oneof [ int_range (-30) 30; int_range (-350) 330 ]))))

let edge_cases =
  [
    "0"; "-0"; "+0"; "0.0"; "-0.0e5"; ".5"; "5."; "-.5e-3"; "1"; "1e22"; "1e23"; "1e-22"; "1e-23";
    "9007199254740992"; "9007199254740993"; "9007199254740993e-5"; "9007199254740991.5";
    "0.1"; "0.3"; "3.14159265358979323846"; "123456789012345678901234567890";
    "4.9e-324"; "2.4703282292062328e-324"; "2.4703282292062327e-324"; "2.2250738585072014e-308";
    "2.2250738585072011e-308"; "1.7976931348623157e308"; "1.7976931348623158e308";
    "1.7976931348623159e308"; "1e400"; "-1e400"; "1e-400"; "0e999999999999999999999";
    "1e99999999999999999999"; "1e-99999999999999999999"; "00000000000000000000000001.5";
    "1.00000000000000000000000000"; "0.000000000000000000000000001";
    (* Not decimals of the grammar: NaN. *)
    ""; "-"; "+"; "."; "-."; "e5"; "1e"; "1e+"; "1.5.5"; "nan"; "inf"; "-inf"; "infinity";
    "0x1p3"; "1_000"; "1 "; " 1"; "1f"; "--1"; "1e5.5";
  ]

let tests =
  [
    Alcotest.test_case "edge-case decimals read as float_of_string reads them, bit for bit" `Quick (fun () ->
        List.iter (fun s -> Alcotest.(check bool) s true (agrees s)) edge_cases);
    Alcotest.test_case "strings outside the decimal grammar are NaN" `Quick (fun () ->
        List.iter
          (fun s -> Alcotest.(check bool) s true (Float.is_nan (Float_scan.of_string s)))
          [ ""; "."; "e5"; "1e"; "nan"; "inf"; "0x1p3"; "1_000"; " 1"; "1 " ]);
    Helpers.qcheck ~count:20_000 "random decimals read as float_of_string reads them"
      (QCheck.make ~print:Fun.id decimal) agrees;
    Helpers.qcheck ~count:20_000 "every float printed with %.17g, %.15g, %g or %f reads back as float_of_string"
      QCheck.(pair (oneofl [ "%.17g"; "%.15g"; "%g"; "%f"; "%.3e" ]) float)
      (fun (fmt, x) ->
        let s = Printf.sprintf (Scanf.format_from_string fmt "%f") x in
        agrees s);
    Helpers.qcheck ~count:20_000 "17-digit decimals next to a midpoint between two floats read as float_of_string"
      (* The hardest inputs of the 17-digit path: the exact midpoint
         between a float and the next, cut to 17 digits, then moved by a
         unit of the last digit or not; exponents of 10 from -21 to 6. *)
      QCheck.(
        make ~print:Fun.id
          Gen.(
            map
              (fun (x, delta) ->
                let x = Float.abs x in
                let mid = x +. ((Float.succ x -. x) /. 2.) in
                let s = Printf.sprintf "%.16e" mid in
                (* "d.dddddddddddddddde+XX": the 17 digits as an integer. *)
                let digits, exp = Scanf.sscanf s "%1[0-9].%16[0-9]e%d" (fun a b e -> (a ^ b, e)) in
                let n = Int64.add (Int64.of_string digits) (Int64.of_int delta) in
                Printf.sprintf "%Lde%d" n (exp - 16))
              (pair (float_range 1e-5 1e22) (int_range (-2) 2))))
      agrees;
    Helpers.qcheck ~count:5_000 "17-digit decimals exactly halfway between two floats round to even"
      (* Between 2^52 and 2^53 floats are the integers: n + 0.5 is a tie,
         17 digits with e = -1, whose correction is inexact (a division by
         10): the path must see the tie and leave it to float_of_string. *)
      QCheck.(
        make ~print:Fun.id
          Gen.(map (fun n -> Printf.sprintf "%d.5" ((1 lsl 52) + n)) (int_bound ((1 lsl 52) - 1))))
      agrees;
    Helpers.qcheck ~count:20_000 "17-digit mantissas with exponents from -22 to 22 read as float_of_string"
      QCheck.(
        make ~print:Fun.id
          Gen.(
            map
              (fun (n, e) -> Printf.sprintf "%Lde%d" n e)
              (pair (map Int64.of_int (int_range 9007199254740993 99999999999999999)) (int_range (-22) 22))))
      agrees;
    Helpers.qcheck ~count:5_000 "scan reads the longest decimal at a point, as into reads it"
      (* Texts of decimal characters and a few others: from every point,
         [scan] stops where [into] (hence [float_of_string]) reads the
         same bits, and no longer piece reads as a number. *)
      QCheck.(make ~print:Fun.id Gen.(string_size ~gen:(oneofl [ '0'; '1'; '9'; '.'; 'e'; 'E'; '-'; '+'; ' '; ')'; 'x' ]) (int_bound 14)))
      (fun s ->
        let b = Bytes.of_string s and n = String.length s in
        let a = [| 0. |] and c = [| 0. |] in
        let bits x = Int64.bits_of_float x in
        let ok = ref true in
        for i = 0 to n do
          let e = Float_scan.scan b i n a 0 in
          if e = i then (if not (Float.is_nan a.(0)) then ok := false)
          else begin
            Float_scan.into b i e c 0;
            if Float.is_nan c.(0) || not (Int64.equal (bits a.(0)) (bits c.(0))) then ok := false
          end;
          for e' = max (i + 1) (e + 1) to n do
            Float_scan.into b i e' c 0;
            if not (Float.is_nan c.(0)) then ok := false
          done
        done;
        !ok);
    Alcotest.test_case "scan stops before an exponent marker without digits, and at its bound" `Quick (fun () ->
        let b = Bytes.of_string "12.5e+x 3e7) .e4 -" and a = [| 0. |] in
        Alcotest.(check int) __LOC__ 4 (Float_scan.scan b 0 18 a 0);
        Alcotest.(check (float 0.)) __LOC__ 12.5 a.(0);
        Alcotest.(check int) __LOC__ 11 (Float_scan.scan b 8 18 a 0);
        Alcotest.(check (float 0.)) __LOC__ 3e7 a.(0);
        Alcotest.(check int) __LOC__ 9 (Float_scan.scan b 8 9 a 0);
        Alcotest.(check (float 0.)) __LOC__ 3. a.(0);
        Alcotest.(check int) __LOC__ 13 (Float_scan.scan b 13 18 a 0);
        Alcotest.(check bool) __LOC__ true (Float.is_nan a.(0));
        Alcotest.(check int) __LOC__ 17 (Float_scan.scan b 17 18 a 0);
        match Float_scan.scan b 0 19 a 0 with
        | _ -> Alcotest.fail "out of bounds accepted"
        | exception Invalid_argument _ -> ());
    Alcotest.test_case "to_float reads only the bytes between its bounds" `Quick (fun () ->
        let b = Bytes.of_string "v 12.5e1 7" in
        Alcotest.(check (float 0.)) __LOC__ 125. (Float_scan.to_float b 2 8);
        Alcotest.(check (float 0.)) __LOC__ 12. (Float_scan.to_float b 2 4);
        Alcotest.(check bool) __LOC__ true (Float.is_nan (Float_scan.to_float b 2 2));
        match Float_scan.to_float b 5 20 with
        | _ -> Alcotest.fail "out of bounds accepted"
        | exception Invalid_argument _ -> ());
    Alcotest.test_case "into stores the number at its index, and allocates nothing for a simple decimal" `Quick
      (fun () ->
        let b = Bytes.of_string "-0.4 2000 12.5e1 0.30000000000000004" in
        let a = Array.make 3 7. in
        Float_scan.into b 10 16 a 1;
        Alcotest.(check (list (float 0.))) __LOC__ [ 7.; 125.; 7. ] (Array.to_list a);
        Float_scan.into b 17 36 a 2;
        Alcotest.(check bool) __LOC__ true (Int64.equal (Int64.bits_of_float a.(2)) (Int64.bits_of_float 0.30000000000000004));
        (match Float_scan.into b 0 4 a 3 with
        | () -> Alcotest.fail "an index out of the array accepted"
        | exception Invalid_argument _ -> ());
        (* The reader's fast path reads every coordinate of a million
           spheres this way: no word per number. *)
        let before = Gc.minor_words () in
        for _ = 1 to 1000 do
          Float_scan.into b 0 4 a 0;
          Float_scan.into b 5 9 a 1
        done;
        let words = Gc.minor_words () -. before in
        Alcotest.(check (list (float 0.))) __LOC__ [ -0.4; 2000. ] [ a.(0); a.(1) ];
        if words > 100. then Alcotest.failf "2000 numbers read allocated %.0f words" words);
  ]
