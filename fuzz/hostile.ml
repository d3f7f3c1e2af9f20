open Raytrace

let scene_file = "fuzz.scene"
let ( let* ) = Result.bind

(* Every exception, Stack_overflow and Out_of_memory included, is a
   finding: the user would see a backtrace instead of a message. *)
let guard what f =
  match f () with
  | r -> r
  | exception e -> Error (Printf.sprintf "%s raised %s" what (Printexc.to_string e))

let one_line what m =
  if m = "" then Error (what ^ ": empty error message")
  else if String.contains m '\n' || String.contains m '\r' then
    Error (Printf.sprintf "%s: error message spans several lines: %S" what m)
  else Ok ()

let lines_of text =
  let n = ref 1 in
  String.iter (fun c -> if c = '\n' then incr n) text;
  !n

(* "fuzz.scene:L:C: message" with L a line of [text] and C >= 1, or
   "fuzz.scene: message" for the size bound. *)
let located text m =
  let prefix = scene_file ^ ":" in
  let lp = String.length prefix in
  if String.length m < lp || String.sub m 0 lp <> prefix then
    Error (Printf.sprintf "error does not start with %s: %S" prefix m)
  else
    let rest = String.sub m lp (String.length m - lp) in
    if String.length rest > 0 && rest.[0] = ' ' then Ok ()
    else
      match String.split_on_char ':' rest with
      | l :: c :: msg :: _ -> (
          match (int_of_string_opt l, int_of_string_opt c) with
          | Some l, Some c when l >= 1 && l <= lines_of text && c >= 1 && String.length msg > 1 ->
              Ok ()
          | _ -> Error (Printf.sprintf "bad location in %S (the text has %d lines)" m (lines_of text)))
      | _ -> Error (Printf.sprintf "no line:column in %S" m)

let scene text =
  guard "Scene_file.of_string" (fun () ->
      match Scene_file.of_string ~file:scene_file text with
      | Error (`Msg m) ->
          let* () = one_line "scene" m in
          located text m
      | Ok valid ->
          let s = Scene.of_valid valid in
          let* _ =
            Result.map_error (fun (`Msg m) -> "accepted a scene that fails validation: " ^ m) (Scene.validate s)
          in
          let printed = Scene_file.to_string s in
          let* () =
            match Scene_file.of_string printed with
            | Ok s' when Scene.equal s (Scene.of_valid s') -> Ok ()
            | Ok _ -> Error ("the printed scene reads back different:\n" ^ printed)
            | Error (`Msg m) -> Error (Printf.sprintf "the printed scene does not parse (%s):\n%s" m printed)
          in
          (match Result.bind (Scene.override ~width:3 ~height:2 valid) Render.image with
          | Ok _ -> Ok ()
          | Error (`Msg m) -> Error ("rendering the scene at 3x2 failed: " ^ m)))

let ppm bytes =
  let* () =
    guard "Ppm.of_string" (fun () ->
        match Ppm.of_string bytes with
        | Error (`Msg m) -> one_line "ppm" m
        | Ok img -> (
            match Ppm.of_string (Ppm.to_string img) with
            | Ok img' when Image.equal img img' -> Ok ()
            | Ok _ -> Error "the image written as P6 reads back different"
            | Error (`Msg m) -> Error ("the image written as P6 does not read back: " ^ m)))
  in
  let* () = guard "Ppm.header_comments" (fun () -> ignore (Ppm.header_comments bytes); Ok ()) in
  (* The parts that [raytrace merge] reads are PPM files too. *)
  guard "Part.of_string" (fun () ->
      match Part.of_string bytes with
      | Error (`Msg m) -> one_line "part" m
      | Ok part -> (
          match Part.of_string (Part.to_string part) with
          | Ok _ -> Ok ()
          | Error (`Msg m) -> Error ("the part written back does not read back: " ^ m)))

let scene_tokens =
  [|
    "("; ")"; "(("; "))"; " "; "\n"; "\t"; "\r\n"; ";"; "; comment\n"; "#|"; "|#"; "#| block |#"; "#;"; "#;)"; "(#;)"; "#; #;";
    "\""; "\"str\""; "\"\\n\""; "\\"; "canvas"; "viewport"; "camera"; "background"; "recursion-depth";
    "epsilon"; "sphere"; "light"; "camera-path"; "key"; "frame"; "width"; "height"; "distance"; "position"; "rotation"; "look-at"; "up";
    "center"; "radius"; "color"; "specular"; "reflective"; "intensity"; "direction"; "ambient"; "point";
    "directional"; "spot"; "0"; "1"; "-1"; "-0"; "0.5"; "3"; "255"; "256"; "600"; "65536"; "65537"; "1e12";
    "1.0000001e12"; "1e13"; "-1e12"; "1e308"; "1e309"; "-1e309"; "4.9e-324"; "1e-320"; "0x1p-1074";
    "0x1.fffffffffffffp1023"; "nan"; "-nan"; "inf"; "-inf"; "infinity"; "1_000"; "_"; "."; "-"; "+1"; "e5";
    "9223372036854775807"; "9223372036854775808"; "-9223372036854775809"; "99999999999999999999999";
    "0.1"; "1e-3"; "0.7071"; "(center 0 0 3)"; "(radius 1)"; "(color 255 0 0)"; "(specular 500)";
    "(reflective 0.5)"; "(intensity 0.6)"; "(position 2 1 0)"; "(direction 1 4 4)"; "(look-at 0 0 1)";
    "(up 0 1 0)"; "(rotation (1 0 0) (0 1 0) (0 0 1))"; "(canvas (width 4) (height 3))";
    "(sphere (center 0 -1 3) (radius 1) (color 255 0 0) (specular 500) (reflective 0.2))";
    "(light point (intensity 0.6) (position 2 1 0))"; "(light ambient (intensity 0.2))";
    "(light directional (intensity 0.2) (direction 1 4 4))"; "(recursion-depth 64)"; "(recursion-depth 65)";
    "(epsilon 0.001)"; "(camera (position 0 0 0) (look-at 0 0 0))";
    "(camera-path (key (frame 0) (position 0 0 -1) (look-at 0 0 3)) (key (frame 48) (position 3 1 1) (look-at 0 0 3)))";
    "(key (frame 10) (position 1 0 0) (look-at 0 0 3) (up 0 1 0))"; "\xff"; "\x00"; "\xc3\xa9";
  |]

let ppm_tokens =
  [|
    "# raytrace-part 1\n"; "# canvas 4 3\n"; "# region 0 0 4 3\n"; "# region 1 1 2 2\n"; "# depth 3\n";
    "# samples 1\n"; "# scene 9e107d9d372bb6826bd81d3542a419d6\n"; "# frame 0\n";
    "P6"; "P3"; "P5"; "P1"; "P"; " "; "\n"; "\t"; "#"; "# comment\n"; "0"; "1"; "2"; "3"; "-1"; "255"; "256";
    "65535"; "65536"; "16384"; "16385"; "268435456"; "99999999999"; "1e3"; "0x10"; "\x00"; "\xff"; "\x00\x00\x00";
    "\xff\xff\xff";
  |]

let mutate rand ~tokens s =
  let int n = if n <= 0 then 0 else Random.State.int rand n in
  let edit s =
    let n = String.length s in
    let a = int (n + 1) in
    let b = a + int (n - a + 1) in
    let before = String.sub s 0 a and span = String.sub s a (b - a) and after = String.sub s b (n - b) in
    match int 8 with
    | 0 -> before ^ after
    | 1 -> before ^ String.make 1 (Char.chr (int 256)) ^ after
    | 2 ->
        if n = 0 then s
        else
          let k = int n in
          String.mapi (fun i c -> if i = k then Char.chr (int 256) else c) s
    | 3 | 4 -> before ^ tokens.(int (Array.length tokens)) ^ span ^ after
    | 5 -> before ^ span ^ span ^ after
    | 6 ->
        let depth = if int 4 = 0 then int 10000 else int 5 in
        before ^ String.make depth '(' ^ span ^ String.make (int (depth + 2)) ')' ^ after
    | _ -> String.sub s 0 a
  in
  let rec go k s = if k = 0 then s else go (k - 1) (edit s) in
  go (1 + int 8) s
