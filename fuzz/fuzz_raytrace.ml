(* The fuzz target: crowbar generators of hostile scene files and PPM
   images, checked by the properties of [Hostile]. Run by AFL++ (`make
   fuzz`), crowbar's input bytes steer the generators and coverage guides
   the search; run alone it draws random inputs (the tests do so briefly). *)

open Crowbar

let check property input = match property input with Ok () -> () | Error m -> fail m
let token tokens = map [ range (Array.length tokens) ] (fun i -> tokens.(i))

let number =
  choose
    [
      map [ int ] string_of_int;
      map [ int8 ] string_of_int;
      map [ float ] Raytrace.Float_text.to_string;
      map [ float ] (Printf.sprintf "%h");
      (* Numbers of a sensible size, so that scenes are often valid. *)
      map [ int16 ] (fun n -> Raytrace.Float_text.to_string (Float.of_int n /. 256.));
      map [ uint8 ] string_of_int;
      token Hostile.scene_tokens;
    ]

let atom = choose [ number; token Hostile.scene_tokens; bytes ]

let sexp =
  fix (fun sexp ->
      choose [ atom; map [ list sexp ] (fun l -> "(" ^ String.concat " " l ^ ")") ])

let names =
  [|
    "canvas"; "viewport"; "camera"; "background"; "recursion-depth"; "epsilon"; "sphere"; "light";
    "width"; "height"; "distance"; "position"; "rotation"; "look-at"; "up"; "center"; "radius"; "color";
    "specular"; "reflective"; "intensity"; "direction"; "ambient"; "point"; "directional";
  |]

let field =
  map [ token names; list (choose [ number; number; sexp ]) ] (fun n values ->
      "(" ^ n ^ " " ^ String.concat " " values ^ ")")

let form =
  map [ token names; option (token [| "ambient"; "point"; "directional" |]); list (choose [ field; number ]) ]
    (fun n kind fields ->
      "(" ^ n ^ (match kind with Some k -> " " ^ k | None -> "") ^ " " ^ String.concat " " fields ^ ")")

let separator = choose [ const "\n"; const " "; token [| "; c\n"; "#| b |#"; "#;"; "\r\n"; "" |] ]

let scene_text =
  map [ list (pair separator (choose [ form; form; form; sexp ])) ] (fun forms ->
      String.concat "" (List.map (fun (sep, f) -> sep ^ f) forms))

(* Deep nesting, balanced or not, around a generated form. *)
let nested =
  map [ range 100_000; range 3; scene_text ] (fun depth shape inner ->
      let opening = String.make depth '(' and closing = String.make depth ')' in
      match shape with
      | 0 -> opening ^ inner ^ closing
      | 1 -> opening ^ inner
      | _ -> "(sphere " ^ opening ^ inner ^ closing ^ ")")

let ppm_text =
  map
    [
      token Hostile.ppm_tokens; list (pair (token [| " "; "\n"; "#c\n"; "\t" |]) (choose [ number; token Hostile.ppm_tokens ]));
      bool; bytes;
    ]
    (fun magic header one_space data ->
      magic
      ^ String.concat "" (List.map (fun (sep, f) -> sep ^ f) header)
      ^ (if one_space then "\n" else "")
      ^ data)

(* A P6 image whose header is right, so that the pixel checks are reached. *)
let ppm_image =
  map [ range ~min:1 40; range ~min:1 40; range ~min:1 255; bytes ] (fun w h maxval data ->
      Printf.sprintf "P6\n%d %d\n%d\n" w h maxval ^ data)

let () =
  add_test ~name:"scene: any bytes" [ bytes ] (check Hostile.scene);
  add_test ~name:"scene: forms and fields" [ scene_text ] (check Hostile.scene);
  add_test ~name:"scene: deep nesting" [ nested ] (check Hostile.scene);
  add_test ~name:"ppm: any bytes" [ bytes ] (check Hostile.ppm);
  add_test ~name:"ppm: headers" [ ppm_text ] (check Hostile.ppm);
  add_test ~name:"ppm: P6 pixels" [ ppm_image ] (check Hostile.ppm)
