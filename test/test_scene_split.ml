(* A scene read on two cores: the second half's spheres read beside
   (Private.Scene_text.read_part), used only where they are what the sequential
   read would read. The same scene (spheres, their order, the material
   table's order) and the same errors as one core, wherever the split
   falls. *)
open Raytrace

let sphere = "(sphere (center 0 -1 3) (radius 1) (color 255 0 0) (specular 500) (reflective 0.2))"

(* Scene.equal compares spheres whatever their materials' numbering;
   here the table's order counts too. *)
let same_spheres what a b =
  let n = Private.Spheres.length a in
  if Private.Spheres.length b <> n then Alcotest.failf "%s: %d spheres, not %d" what (Private.Spheres.length b) n;
  let bits x = Int64.bits_of_float x in
  for i = 0 to n - 1 do
    let same f = Int64.equal (bits (f a i)) (bits (f b i)) in
    if not (same Private.Spheres.center_x && same Private.Spheres.center_y && same Private.Spheres.center_z && same Private.Spheres.radius) then
      Alcotest.failf "%s: sphere %d differs" what i;
    if Private.Spheres.material_index a i <> Private.Spheres.material_index b i then
      Alcotest.failf "%s: sphere %d has material %d, not %d" what i (Private.Spheres.material_index b i)
        (Private.Spheres.material_index a i)
  done;
  let ma = Private.Spheres.materials a and mb = Private.Spheres.materials b in
  if Array.length ma <> Array.length mb || not (Array.for_all2 Material.equal ma mb) then
    Alcotest.failf "%s: the material tables differ (%d and %d materials)" what (Array.length ma) (Array.length mb)

let same_result what one two =
  match (one, two) with
  | Ok a, Ok b ->
      let a = Scene.of_valid a and b = Scene.of_valid b in
      if not (Scene.equal a b) then Alcotest.failf "%s: a different scene" what;
      same_spheres what (Scene.spheres a) (Scene.spheres b)
  | Error (`Msg a), Error (`Msg b) -> Alcotest.(check string) what a b
  | Ok _, Error (`Msg m) -> Alcotest.failf "%s: read on one core, but on two: %s" what m
  | Error (`Msg m), Ok _ -> Alcotest.failf "%s: read on two cores, but on one: %s" what m

(* A source of [text] whose first reader can seek, as a file's can. *)
let seekable text =
  let seeks = ref 0 in
  let first = ref None in
  let source () =
    let at = ref 0 in
    let read buf pos len =
      let k = max 0 (min len (String.length text - !at)) in
      Bytes.blit_string text !at buf pos k;
      at := !at + k;
      k
    in
    if !first = None then first := Some at;
    { Private.Scene_text.read; close = ignore }
  in
  let seek o =
    incr seeks;
    match !first with Some at -> at := o | None -> Alcotest.fail "a seek before the first read"
  in
  (source, seek, seeks)

(* The part of [text] from [from] on, read as a child would. *)
let part ?limits ~window text from =
  let r = Private.Scene_text.string_source (String.sub text from (String.length text - from)) () in
  Private.Scene_text.read_part ?limits ~window_bytes:window r ~from

let one ?limits ?(load_mesh = Raytrace_unix.Files.read_mesh) ?(file = "t.scene") ~window text =
  Private.Scene_text.of_source ?limits ~load_mesh ~file ~window_bytes:window (Private.Scene_text.string_source text)

(* [text] read with the part from [split] beside, and whether the part was
   used (the read seeked past it). *)
let two ?limits ?(load_mesh = Raytrace_unix.Files.read_mesh) ?(file = "t.scene") ?part:given ~window text split =
  let p = match given with Some p -> p | None -> part ?limits ~window text split in
  let source, seek, seeks = seekable text in
  let waited = ref 0 in
  let beside = { Private.Scene_text.split; wait = (fun () -> incr waited; Some p); append = Private.Scene_text.append_part; seek } in
  let r = Private.Scene_text.of_source ?limits ~load_mesh ~file ~window_bytes:window ~beside source in
  if !waited <> 1 then Alcotest.failf "split at %d: the part waited for %d times, not once" split !waited;
  (r, !seeks > 0)

let line_starts text =
  let l = ref [] in
  String.iteri (fun i c -> if c = '\n' && i + 1 < String.length text then l := (i + 1) :: !l) text;
  List.rev !l

(* Every line start as the split (at most [most], spread evenly), in
   windows of a few bytes and of 1 MiB: the same result as one core.
   The number of splits whose part was used. *)
let every_split ?limits ?load_mesh ?file ?(most = max_int) ?(within = (0, max_int)) what text =
  let starts = Array.of_list (List.filter (fun i -> i >= fst within && i <= snd within) (line_starts text)) in
  let n = Array.length starts in
  let picks = if n <= most then starts else Array.init most (fun k -> starts.(k * n / most)) in
  let used = ref 0 in
  List.iter
    (fun window ->
      let expected = one ?limits ?load_mesh ?file ~window text in
      Array.iter
        (fun split ->
          let r, u = two ?limits ?load_mesh ?file ~window text split in
          if u then incr used;
          same_result (Printf.sprintf "%s, split at %d, %d-byte windows" what split window) expected r)
        picks)
    [ 7; 1 lsl 20 ];
  !used

let spheres k = String.concat "\n" (List.init k (fun i -> Printf.sprintf "(sphere (center %d 0 9) (radius 0.5) (color %d 0 0))" i (i mod 7)))
let header = "(canvas (width 20) (height 20))\n(light ambient (intensity 0.2))\n"

let crafted =
  let s = spheres 6 in
  [
    ("plain spheres", header ^ s ^ "\n" ^ s);
    ("a multi-line form", header ^ s ^ "\n(sphere\n (center 1 2 3)\n (radius 1)\n (color 1 2 3))\n" ^ s);
    ("a string", header ^ s ^ "\n(sphere (center 1 2 3) (radius 1) (color 1 2 3) (pattern checker (color 1 1 1) (size \"x\n" ^ s ^ "\n\")))\n" ^ s);
    ("a string with spheres in it", header ^ s ^ "\n(light ambient (intensity 0.1))\n; \"\n" ^ s ^ "\n");
    ("line comments", header ^ s ^ "\n; (sphere (center 0 0 0) (radius 1) (color 1 1 1))\n;\n" ^ s ^ " ; end\n" ^ s);
    ("a block comment", header ^ s ^ "\n#|\n" ^ s ^ "\n|#\n" ^ s);
    ("a nested block comment", header ^ s ^ "\n#| #|\n" ^ s ^ "\n|# \n" ^ s ^ "\n|#\n" ^ s);
    ("a datum comment", header ^ s ^ "\n#;\n" ^ s ^ "\n" ^ s);
    ("a datum comment over lines", header ^ s ^ "\n#; (a\n" ^ s ^ ")\n" ^ s);
    ("just before an error", header ^ s ^ "\n(sphere (center 0 0 3) (radius -1) (color 1 2 3))\n" ^ s);
    ("an error at the end", header ^ s ^ "\n" ^ s ^ "\n(sphere (center 0 0 3) (radius 1) (colour 1 2 3))");
    ("a syntax error in the second half", header ^ s ^ "\n" ^ s ^ "\n(sphere (center 0 0 3)\n" ^ s);
    ("a stray parenthesis in the second half", header ^ s ^ "\n" ^ s ^ ")\n" ^ s);
    ("an unknown form in the second half", header ^ s ^ "\n(spere (center 0 0 3))\n" ^ s);
    ("a duplicate form in the second half", header ^ s ^ "\n(canvas (width 2))\n" ^ s);
    ("a light between spheres", header ^ s ^ "\n(light point (intensity 0.3) (position 1 1 1))\n" ^ s);
    ("CRLF lines", String.concat "\r\n" (String.split_on_char '\n' (header ^ s ^ "\n" ^ s)));
    ("a lone carriage return", header ^ s ^ "\n; \r x\n" ^ s);
    ("a patterned sphere", header ^ s ^ "\n(sphere (center 1 2 3) (radius 1) (color 1 2 3) (pattern checker (color 1 1 1) (size 1)))\n" ^ s);
    ("spheres in other field orders", header ^ s ^ "\n(sphere (color 0 0 5) (radius 1) (center 0 0 3))\n" ^ s);
    ("an overflowing number", header ^ s ^ "\n(sphere (center 0 0 1e999) (radius 1) (color 1 2 3))\n" ^ s);
    ("forms on one line", header ^ String.concat " " (List.init 12 (fun _ -> sphere)) ^ "\n" ^ s);
    ( "new materials in the second half, in no order",
      header ^ s ^ "\n"
      ^ String.concat "\n"
          (List.map
             (fun c -> Printf.sprintf "(sphere (center 0 0 9) (radius 0.5) (color %d 9 9) (specular %d))" c (c * 10))
             [ 9; 8; 9; 7; 200; 8; 1; 150 ]) );
    ("blank lines", header ^ s ^ "\n\n\n   \n\t\n" ^ s);
    ("no newline at the end", header ^ s);
  ]

let grid k = Scene_file.to_string (Scene.grid k)

let with_file text f =
  let dir = Helpers.temp_dir () in
  let path = Filename.concat dir "t.scene" in
  let oc = open_out_bin path in
  output_string oc text;
  close_out oc;
  Fun.protect ~finally:(fun () -> Sys.remove path; Unix.rmdir dir) (fun () -> f path)

let tests =
  [
    Alcotest.test_case "crafted texts read alike on two cores, wherever the split falls" `Quick (fun () ->
        List.iter (fun (what, text) -> ignore (every_split what text)) crafted);
    Alcotest.test_case "a part is used where the split falls between plain spheres" `Quick (fun () ->
        let text = header ^ spheres 40 in
        let used = every_split "plain spheres" text in
        (* Two windows, and each line start after the header's is a sphere's. *)
        let sphere_lines = 2 * 39 in
        if used < sphere_lines then Alcotest.failf "the part was used at %d splits of %d" used sphere_lines);
    Alcotest.test_case "a part decides the spheres it holds" `Quick (fun () ->
        (* A part read from another text, of the same layout but one
           colour: used, it shows in the scene. No test of sameness above
           could tell a part never used from one used well. *)
        let text = header ^ spheres 20 in
        let other = header ^ String.map (fun c -> if c = '6' then '5' else c) (spheres 20) in
        let split = List.nth (line_starts text) 4 in
        let p = part ~window:(1 lsl 20) other split in
        if Private.Scene_text.part_length p < 10 then Alcotest.failf "a part of %d spheres" (Private.Scene_text.part_length p);
        match (two ~part:p ~window:(1 lsl 20) text split, one ~window:(1 lsl 20) other) with
        | (Ok a, true), Ok b -> same_spheres "the other text's spheres" (Scene.spheres (Scene.of_valid b)) (Scene.spheres (Scene.of_valid a))
        | (_, false), _ -> Alcotest.fail "the part was not used"
        | (Error (`Msg m), _), _ | _, Error (`Msg m) -> Alcotest.fail m);
    Alcotest.test_case "without the part (its process failed or died), the read is one core's" `Quick (fun () ->
        List.iter
          (fun (what, text) ->
            let window = 1 lsl 20 in
            let expected = one ~window text in
            List.iter
              (fun split ->
                let source, seek, seeks = seekable text in
                let beside = { Private.Scene_text.split; wait = (fun () -> None); append = Private.Scene_text.append_part; seek } in
                let r = Private.Scene_text.of_source ~load_mesh:Raytrace_unix.Files.read_mesh ~file:"t.scene" ~window_bytes:window ~beside source in
                if !seeks > 0 then Alcotest.failf "%s: a seek without a part" what;
                same_result (Printf.sprintf "%s, split at %d, no part" what split) expected r)
              (line_starts text))
          crafted);
    Alcotest.test_case "the sphere bound crossed in the second half is one core's error" `Quick (fun () ->
        let text = header ^ spheres 30 in
        List.iter
          (fun bound ->
            let limits = Limits.with_bound Limits.default `Spheres (Float.of_int bound) in
            ignore (every_split ~limits (Printf.sprintf "at most %d spheres" bound) text))
          [ 5; 20; 29; 30 ]);
    Alcotest.test_case "the form bound between spheres in the second half is one core's error" `Quick (fun () ->
        (* The bound is checked at each 64 KiB of the text: the bytes since
           the last form's end, a sphere (about 50) or blanks and comments
           longer than the bound across such a point are an error, in
           either half, before or after the part's first sphere. *)
        let comment = "\n" ^ String.concat "\n" (List.init 20 (fun _ -> "; " ^ String.make 60 'c')) ^ "\n" in
        let before = Buffer.create 70000 in
        Buffer.add_string before header;
        let k = ref 0 in
        while Buffer.length before < 65536 - 700 do
          Buffer.add_string before (Printf.sprintf "(sphere (center %d 0 9) (radius 0.5) (color %d 0 0))\n" !k (!k mod 7));
          incr k
        done;
        let at = Buffer.length before in
        let text = Buffer.contents before ^ comment ^ spheres 1500 ^ comment ^ spheres 1500 in
        List.iter
          (fun bound ->
            let limits = Limits.with_bound Limits.default `Form_bytes bound in
            let what = Printf.sprintf "a form bound of %.0f bytes" bound in
            ignore (every_split ~most:40 ~limits what text);
            ignore (every_split ~within:(at - 200, at + 2000) ~limits (what ^ ", a comment across 64 KiB") text))
          [ 30.; 100.; 500.; 2000.; 1e6 ]);
    Alcotest.test_case "every example scene, the fuzzing corpus and a grid read alike on two cores" `Quick (fun () ->
        List.iter
          (fun n ->
            let file = Helpers.scene_path n in
            ignore (every_split ~most:20 ~file n (In_channel_free.read file)))
          (Helpers.scene_names ());
        let dir = Filename.concat "corpus" "scene" in
        let cases = Sys.readdir dir |> Array.to_list |> List.sort String.compare in
        Alcotest.(check bool) "the corpus is there" true (List.length cases > 100);
        List.iter (fun f -> ignore (every_split ~most:4 f (In_channel_free.read (Filename.concat dir f)))) cases;
        let used = every_split ~most:30 "grid 5000" (grid 5000) in
        if used < 50 then Alcotest.failf "the grid's part used at %d splits of 60" used);
    Alcotest.test_case "a file read on two cores is the scene read on one, from a child process" `Quick (fun () ->
        let read ?jobs ?on_part path =
          Raytrace_unix.Files.read_scene ?jobs ~split_bytes:1 ?on_part path
        in
        let text = grid 3000 in
        with_file text (fun path ->
            let sent = ref [] in
            let pid = Unix.getpid () in
            same_result "grid 3000" (read ~jobs:1 path) (read ~jobs:2 ~on_part:(fun k -> sent := k :: !sent) path);
            Alcotest.(check int) "still the parent" pid (Unix.getpid ());
            (match !sent with
            | [ k ] when k > 1000 && k < 2000 -> ()
            | l -> Alcotest.failf "the child sent parts of [%s] spheres" (String.concat "; " (List.map string_of_int l)));
            let none = ref 0 in
            ignore (read ~jobs:1 ~on_part:(fun _ -> incr none) path);
            ignore (Raytrace_unix.Files.read_scene ~jobs:2 ~on_part:(fun _ -> incr none) path);
            Alcotest.(check int) "one job, or a file under 4 MiB: no child" 0 !none);
        List.iter
          (fun (what, text) ->
            with_file text (fun path -> same_result what (read ~jobs:1 path) (read ~jobs:2 path)))
          crafted;
        (* An error's message names the file and place, as one core's. *)
        let bad = grid 3000 ^ "\n(sphere (center 0 0 3) (radius -1) (color 1 2 3))\n" in
        with_file bad (fun path ->
            match read ~jobs:2 path with
            | Ok _ -> Alcotest.fail "a bad radius read"
            | Error (`Msg m) ->
                same_result "a bad radius" (read ~jobs:1 path) (Error (`Msg m));
                let at = String.length (grid 3000) + 1 in
                let line = 1 + List.length (String.split_on_char '\n' (String.sub bad 0 at)) - 1 in
                let prefix = Printf.sprintf "%s:%d:" path line in
                if not (String.length m > String.length prefix && String.sub m 0 (String.length prefix) = prefix) then
                  Alcotest.failf "the error %S is not at %s" m prefix));
  ]
