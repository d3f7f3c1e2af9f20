(* The scene reader's fast path (Sexp_scan, and spheres read straight into
   their values) against parsexp: the same scenes, the same errors at the
   same places, whatever the text. *)
open Raytrace

let read ?limits reader text =
  match Scene_file.of_string ?limits ~file:"t.scene" ~reader text with
  | Ok v -> Ok (Scene.of_valid v)
  | Error (`Msg m) -> Error m

(* Both readers give the same scene, or the same error message. *)
let same ?limits what text =
  match (read ?limits `Fast text, read ?limits `Parsexp text) with
  | Ok a, Ok b -> if not (Scene.equal a b) then Alcotest.failf "%s: the two readers give different scenes" what
  | Error a, Error b -> Alcotest.(check string) what b a
  | Ok _, Error m -> Alcotest.failf "%s: read fast, but parsexp says %s" what m
  | Error m, Ok _ -> Alcotest.failf "%s: parsexp reads it, the fast reader says %s" what m

let corpus () =
  let dir = Filename.concat "corpus" "scene" in
  Sys.readdir dir |> Array.to_list |> List.sort String.compare
  |> List.map (fun f -> (f, In_channel_free.read (Filename.concat dir f)))

let sphere = "(sphere (center 0 -1 3) (radius 1) (color 255 0 0) (specular 500) (reflective 0.2))"

let tests =
  [
    Alcotest.test_case "every example scene and fuzzing case reads alike with and without parsexp" `Quick (fun () ->
        List.iter
          (fun n -> same n (In_channel_free.read (Helpers.scene_path n)))
          (Helpers.scene_names ());
        let cases = corpus () in
        List.iter (fun (f, text) -> same f text) cases;
        Alcotest.(check bool) "the corpus is there" true (List.length cases > 100));
    Alcotest.test_case "text the fast path leaves to parsexp reads alike" `Quick (fun () ->
        List.iter
          (fun (what, text) -> same what text)
          [
            ("carriage return and newline", sphere ^ "\r\n" ^ sphere ^ "\r\n");
            ("lone carriage return", sphere ^ "\r" ^ sphere);
            ("carriage return in a comment", "; a\rb\n" ^ sphere);
            ("block comment", "#| (sphere) |#\n" ^ sphere);
            ("sexp comment", "#; " ^ sphere ^ "\n" ^ sphere);
            ("string atom", "(sphere (center 0 0 3) (radius \"1\") (color 1 2 3))");
            ("hexadecimal float", "(sphere (center 0 0 0x3p0) (radius 1) (color 1 2 3))");
            ("underscores", "(sphere (center 0 0 1_000) (radius 1) (color 1 2 3))");
            ("nan", "(sphere (center 0 0 nan) (radius 1) (color 1 2 3))");
            ("overflow", "(sphere (center 0 0 1e999) (radius 1) (color 1 2 3))");
            ("atom then comment", "(sphere (center 0 0 3);c\n (radius 1) (color 1 2 3))");
            ("fields in another order", "(sphere (color 1 2 3) (radius 1) (center 0 0 3))");
            ("a field twice", "(sphere (center 0 0 3) (radius 1) (radius 2) (color 1 2 3))");
            ("a missing field", "(sphere (center 0 0 3) (color 1 2 3))");
            ("four coordinates", "(sphere (center 0 0 3 4) (radius 1) (color 1 2 3))");
            ("a list for a number", "(sphere (center 0 (0) 3) (radius 1) (color 1 2 3))");
            ("out of gamut", "(sphere (center 0 0 3) (radius 1) (color 256 2 3))");
            ("unclosed", sphere ^ "\n(sphere (center 0 0 3)");
            ("a stray parenthesis", sphere ^ ")\n" ^ sphere);
            ("a top-level atom", sphere ^ " sphere");
            ("deep nesting", String.make 100 '(' ^ String.make 100 ')');
            ("a hash in an atom", "(sphere (center 0 0 3) (radius 1#) (color 1 2 3))");
            ("form feed and tabs", "\012(sphere\t(center 0 0 3)\012(radius 1) (color 1 2 3))");
            ("a long plain form", "(light point (intensity 0.6) (position 2 1 0) " ^ String.make 20000 ' ' ^ ")");
            ("mixed", "(canvas (width 10) (height 10))\n#|x|#" ^ sphere ^ "\n(light ambient (intensity 0.2))\n" ^ sphere);
          ]);
    Alcotest.test_case "the sphere bound is checked by either reader at the same sphere" `Quick (fun () ->
        let limits = Limits.with_bound Limits.default `Spheres 2. in
        same ~limits "three spheres" (String.concat "\n" [ sphere; sphere; sphere ]));
    Alcotest.test_case "spheres that repeat a material share its values" `Quick (fun () ->
        (* 5 words each: center x, y, z and radius in float arrays, the
           material's index in an int array; the grid's dozen materials
           are one table. A list of records took 17. *)
        let text = Scene_file.to_string (Scene.grid 1000) in
        match Scene_file.of_string text with
        | Error (`Msg m) -> Alcotest.fail m
        | Ok v ->
            let spheres = (Scene.of_valid v).spheres in
            let words = Obj.reachable_words (Obj.repr spheres) / Spheres.length spheres in
            if words > 6 then Alcotest.failf "%d words per sphere, more than 6" words);
    Alcotest.test_case "plain forms are read without parsexp, the rest left to it" `Quick (fun () ->
        let form text =
          match Sexp_scan.form text 0 ~max_bytes:1000 with
          | sexp, e -> Ok (Sexplib0.Sexp.to_string sexp, e)
          | exception Sexp_scan.Unusual -> Error ()
        in
        let ok = Alcotest.(result (pair string int) unit) in
        Alcotest.check ok __LOC__ (Ok ("(a(b -1.5e3)c)", 16)) (form "(a (b -1.5e3) c) ; rest");
        Alcotest.check ok __LOC__ (Ok ("(a b)", 9)) (form "(a;x\r\n b)");
        Alcotest.check ok __LOC__ (Error ()) (form "(a \"b\")");
        Alcotest.check ok __LOC__ (Error ()) (form "(a #|b|#)");
        Alcotest.check ok __LOC__ (Error ()) (form "(a\rb)");
        Alcotest.check ok __LOC__ (Error ()) (form "(a b");
        Alcotest.check ok __LOC__ (Error ()) (form ("(" ^ String.make 2000 'a' ^ ")"));
        Alcotest.check ok __LOC__ (Error ()) (form (String.make 65 '(' ^ String.make 65 ')'));
        Alcotest.(check int) __LOC__ 8 (Sexp_scan.skip_blank " ; c\n\t\012 x" 0));
  ]
