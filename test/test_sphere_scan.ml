(* The scene reader's layout path for spheres (Sphere_scan.layout) against
   its general path (Sphere_scan.general): wherever the layout reads a
   form, the general reader reads the same fields, values and end; the
   layout reads every form in the one-space layout, and leaves every
   other form (other blanks, comments, odd numbers, unknown or repeated
   fields, a form too near the end of the text) to the general one. *)
open Raytrace.Private

(* A number token, and whether it is a decimal that a space or a
   parenthesis ends and that reads as a finite float. *)
let numbers =
  [
    ("0", true); ("-499.5", true); ("2000", true); ("0.4", true); ("+5", true); (".5", true); ("5.", true);
    ("-0", true); ("1e3", true); ("2.5E-3", true); ("1e+2", true); ("0.30000000000000004", true);
    ("123456789012345678901234", true); ("9007199254740993", true); ("1e-400", true); ("1e400", false);
    ("nan", false); ("inf", false); ("1e", false); ("1.5.5", false); ("--1", false); ("1_0", false);
    ("0x10", false); ("", false); ("1a", false); ("-", false); (".", false);
  ]

let names = [| "center"; "radius"; "color"; "specular"; "reflective" |]
let arity = [| 3; 1; 3; 1; 1 |]

(* A blank between two tokens, and whether it is the layout's. *)
let blanks = [ (" ", true); ("  ", false); ("\t", false); ("\n", false); (" ;c\n", false); ("\r\n", false) ]

type form = { text : string; layout : bool }

let gen_form =
  let open QCheck.Gen in
  let blank = frequency [ (12, return (" ", true)); (1, oneofl blanks) ] in
  let number = frequency [ (8, oneofl (List.filter snd numbers)); (1, oneofl numbers) ] in
  let field =
    frequency [ (12, int_bound 4 >|= fun c -> (names.(c), c, true)); (1, oneofl [ ("centre", 0, false); ("colour", 2, false); ("radiu", 1, false) ]) ]
  in
  let one =
    field >>= fun (name, c, known) ->
    frequency [ (12, return 0); (1, return 1) ] >>= fun extra ->
    list_repeat (arity.(c) + extra) (pair blank number) >>= fun values ->
    pair blank (oneofl [ ("(", true); ("( ", false) ]) >|= fun ((sep, sep_ok), (opening, open_ok)) ->
    let body = String.concat "" (List.map (fun ((b, _), (n, _)) -> b ^ n) values) in
    let ok =
      known && sep_ok && open_ok && List.length values = arity.(c)
      && List.for_all (fun ((_, b), (_, n)) -> b && n) values
    in
    (c, sep ^ opening ^ name ^ body ^ ")", ok)
  in
  list_size (int_range 0 6) one >>= fun fields ->
  pair (oneofl [ ("(sphere", true); ("( sphere", false); ("(spheres", false) ]) (oneofl [ (")", true); (" )", false) ])
  >>= fun ((head, head_ok), (close, close_ok)) ->
  let cs = List.map (fun (c, _, _) -> c) fields in
  let unique = List.length (List.sort_uniq compare cs) = List.length cs in
  let text = head ^ String.concat "" (List.map (fun (_, t, _) -> t) fields) ^ close in
  return { text; layout = head_ok && close_ok && unique && List.for_all (fun (_, _, ok) -> ok) fields }

let bits x = Int64.bits_of_float x

(* The general reader's fields, or [None] where it refuses the form. *)
let general s =
  let f = Sphere_scan.create () in
  match Sphere_scan.general f s 0 with
  | e -> Some (e, f.seen, Array.copy f.values)
  | exception Sexp_scan.Unusual -> None

let agrees { text; layout } =
  (* Padded past the layout's margin, and not. *)
  let padded = text ^ String.make 16 ' ' in
  let f = Sphere_scan.create () in
  let e = Sphere_scan.layout f padded 0 in
  let same =
    e = -1
    ||
    match general padded with
    | Some (e', seen, values) ->
        e = e' && seen = f.seen
        && List.for_all
             (fun c ->
               seen land (1 lsl c) = 0
               || List.for_all (fun v -> Int64.equal (bits values.(v)) (bits f.values.(v)))
                    (List.init arity.(c) (fun k -> [| 0; 3; 4; 7; 8 |].(c) + k)))
             [ 0; 1; 2; 3; 4 ]
    | None -> false
  in
  if not same then QCheck.Test.fail_reportf "the layout read %S differently" text;
  if layout && e <> String.length text then QCheck.Test.fail_reportf "the layout did not read %S" text;
  if (not layout) && e <> -1 then QCheck.Test.fail_reportf "the layout read %S, which is not in the layout" text;
  (* Too near the end of the text: always the general reader's. *)
  Sphere_scan.layout f text 0 = -1
  && (* read = layout, else general *)
  (match (Sphere_scan.read (Sphere_scan.create ()) padded 0, general padded) with
   | r, Some (e', _, _) -> r = e'
   | _, None -> false
   | exception Sexp_scan.Unusual -> general padded = None)

let tests =
  [
    Helpers.qcheck ~count:20_000 "the layout reads the one-space sphere forms as the general reader does, and no others"
      (QCheck.make ~print:(fun f -> f.text) gen_form)
      agrees;
    Alcotest.test_case "a sphere without its opening parenthesis is not a sphere: an error at its first byte" `Quick
      (fun () ->
        (* main's fast path read "x sphere (...))" as a sphere, where
           parsexp's reader refuses the atom x. *)
        let text = "(light ambient (intensity 1))\nx sphere (center 0 0 3) (radius 1) (color 255 0 0))\n" in
        (match Sphere_scan.general (Sphere_scan.create ()) text 30 with
        | _ -> Alcotest.fail "read as a sphere"
        | exception Sexp_scan.Unusual -> ());
        List.iter
          (fun reader ->
            match Raytrace.Scene_file.of_string ~file:"x.scene" ~reader text with
            | Ok _ -> Alcotest.fail "accepted"
            | Error (`Msg m) ->
                Alcotest.(check string) __LOC__ "x.scene:2:1: expected a form in parentheses such as (sphere ...), got x" m)
          [ `Fast; `Parsexp ]);
    Alcotest.test_case "the layout reads a generated grid line, and a line with a comment is left to the general reader" `Quick
      (fun () ->
        let line = "(sphere (center -499.5 -0.6 2000) (radius 0.4) (color 0 255 0) (specular 10) (reflective 0.2))" in
        let pad = line ^ "\n(sphere (center 1 2 3) (radius 1) (color 1 1 1))\n" in
        let f = Sphere_scan.create () in
        Alcotest.(check int) __LOC__ (String.length line) (Sphere_scan.layout f pad 0);
        Alcotest.(check int) __LOC__ 31 f.seen;
        Alcotest.(check (list (float 0.))) __LOC__ [ -499.5; -0.6; 2000.; 0.4; 0.; 255.; 0.; 10.; 0.2 ] (Array.to_list f.values);
        let commented = "(sphere (center 1 2 3) ; the first\n (radius 1) (color 1 1 1))" ^ String.make 20 ' ' in
        Alcotest.(check int) __LOC__ (-1) (Sphere_scan.layout f commented 0);
        Alcotest.(check int) __LOC__ (String.length commented - 20) (Sphere_scan.read f commented 0));
  ]
