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

(* [text], read by [of_source] [window] bytes at a time from a source that
   gives at most [step] bytes a read; [opens] counts its passes. *)
let windowed ?limits ~reader ~window ~step ~opens text =
  let source () =
    incr opens;
    let r = Private.Scene_text.string_source text () in
    { r with read = (fun buf pos len -> r.read buf pos (min len step)) }
  in
  match Private.Scene_text.of_source ?limits ~file:"t.scene" ~reader ~window_bytes:window source with
  | Ok v -> Ok (Scene.of_valid v)
  | Error (`Msg m) -> Error m

(* Read a window at a time, [text] gives what it gives read whole, and
   is read once, or at most twice for an error. *)
let same_windowed ?limits what text =
  List.iter
    (fun reader ->
      let whole = read ?limits reader text in
      List.iter
        (fun (window, step) ->
          let opens = ref 0 in
          let what = Printf.sprintf "%s, %d-byte windows, %d-byte reads" what window step in
          (match (whole, windowed ?limits ~reader ~window ~step ~opens text) with
          | Ok a, Ok b -> if not (Scene.equal a b) then Alcotest.failf "%s: a different scene" what
          | Error a, Error b -> Alcotest.(check string) what a b
          | Ok _, Error m -> Alcotest.failf "%s: %s" what m
          | Error m, Ok _ -> Alcotest.failf "%s: read, but whole it is %s" what m);
          (* A syntax error is placed by the first pass; a conversion
             error by a second one. *)
          let most = match whole with Ok _ -> 1 | Error _ -> 2 in
          if !opens < 1 || !opens > most then Alcotest.failf "%s: %d passes, not 1 to %d" what !opens most)
        [ (1, 1); (5, 3); (64, 64); (4096, 1000); (1 lsl 20, 1 lsl 20) ])
    [ `Fast; `Parsexp ]

let tests =
  [
    Alcotest.test_case "every example scene and fuzzing case reads alike with and without parsexp" `Quick (fun () ->
        List.iter
          (fun n -> same n (In_channel_free.read (Helpers.scene_path n)))
          (Helpers.scene_names ());
        let cases = corpus () in
        List.iter (fun (f, text) -> same f text) cases;
        Alcotest.(check bool) "the corpus is there" true (List.length cases > 100));
    Alcotest.test_case "materials that share the fast reader's recent slots read alike" `Quick (fun () ->
        (* Reds 0, 64 and 128 hash to one slot of the reader's recent
           materials (and its pair): with a fourth material in between,
           each lookup hits either way, or misses, or evicts. *)
        let colors = [| "0 0 0"; "64 0 0"; "128 0 0"; "0 0 0"; "1 2 3"; "64 0 0"; "64 0 0"; "128 0 0" |] in
        let text =
          String.concat "\n"
            (List.init 64 (fun i ->
                 Printf.sprintf "(sphere (center %d 0 3) (radius 0.5) (color %s) (specular 10))" i
                   colors.(i mod Array.length colors)))
        in
        same "colliding materials" text;
        match read `Fast text with
        | Error m -> Alcotest.fail m
        | Ok scene ->
            Alcotest.(check int) "spheres" 64 (Private.Spheres.length (Scene.spheres scene));
            Private.Spheres.iteri
              (fun i (s : Sphere.t) ->
                let c = Printf.sprintf "%g %g %g" s.material.color.r s.material.color.g s.material.color.b in
                Alcotest.(check string) (Printf.sprintf "sphere %d's color" i) colors.(i mod Array.length colors) c)
              (Scene.spheres scene));
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
    Alcotest.test_case "a text read a window at a time is the scene, or the error, read whole" `Quick (fun () ->
        (* Windows of 1 byte and up cut every form, number, comment and
           line end somewhere; the fuzzing corpus has the errors. *)
        List.iter (fun n -> same_windowed n (In_channel_free.read (Helpers.scene_path n))) (Helpers.scene_names ());
        List.iter (fun (f, text) -> same_windowed f text) (corpus ());
        let many = String.concat "\n" (List.init 3000 (fun _ -> sphere)) in
        List.iter
          (fun (what, text) -> same_windowed what text)
          [
            ("3000 spheres, past the fast reader's lookahead", many);
            ("a comment longer than a window", "; " ^ String.make 70000 'x' ^ "\n" ^ sphere);
            ("carriage returns", String.concat "\r\n" [ sphere; "; c\r"; sphere ]);
            ("a lone carriage return", sphere ^ "\n;\r x\n" ^ sphere);
            ("an error after 3000 spheres", many ^ "\n(sphere (center 0 0 3) (radius -1) (color 1 2 3))");
            ("a syntax error after 3000 spheres", many ^ "\n(sphere (center 0 0 3)");
            ("a block comment", many ^ "\n#| " ^ String.make 70000 ')' ^ " |#\n" ^ sphere);
          ];
        let limits = Limits.with_bound Limits.default `Form_bytes 200. in
        same_windowed ~limits "a form over the form bound, after blanks" (many ^ "\n\n  ; c\n (light ambient (intensity 0.2)" ^ String.make 300 ' ' ^ ")");
        (* A source's size is not known before it is read: it is refused
           once more than the bound has been read. *)
        let limits = Limits.with_bound Limits.default `Scene_bytes 100000. in
        List.iter
          (fun window ->
            match windowed ~limits ~reader:`Fast ~window ~step:window ~opens:(ref 0) many with
            | Ok _ -> Alcotest.failf "%d-byte windows: a text over the scene bound read" window
            | Error m ->
                let prefix = "t.scene: the scene is " in
                if not (String.length m > String.length prefix && String.sub m 0 (String.length prefix) = prefix)
                then Alcotest.failf "%d-byte windows: %s" window m)
          [ 1; 4096; 1 lsl 20 ]);
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
            let spheres = (Scene.spheres (Scene.of_valid v)) in
            let words = Obj.reachable_words (Obj.repr spheres) / Private.Spheres.length spheres in
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
