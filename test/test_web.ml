(* The web page (web/), in headless Chromium: driven by test/web/drive.js
   (playwright-core), what its canvas shows is what `raytrace render` makes
   of the same scene, byte for byte. A few browser sessions serve every
   case: [main] (the page as a visitor finds it, then keys, a drag,
   selectors, edits), [held] (frames advanced band by band), [scenes],
   [random] and [corpus] (many texts put in the editor). *)
open Raytrace

(* The source tree, whose test/web/node_modules holds playwright-core
   (make deps runs npm ci there): the tests run in _build/default/test. *)
let source_root () =
  let cwd = Sys.getcwd () in
  let marker = Filename.dir_sep ^ "_build" ^ Filename.dir_sep in
  let rec find i =
    if i + String.length marker > String.length cwd then cwd
    else if String.sub cwd i (String.length marker) = marker then String.sub cwd 0 i
    else find (i + 1)
  in
  find 0

let node_modules () = Filename.concat (source_root ()) "test/web/node_modules"
let chromium () = Option.value (Sys.getenv_opt "RAYTRACE_CHROMIUM") ~default:"/usr/bin/chromium"

(* [Some why] when the browser tests cannot run here. *)
let missing () =
  if not (Sys.file_exists (chromium ())) then Some (chromium () ^ " is not installed (make deps installs chromium)")
  else if not (Helpers.on_path "node") then Some "node is not installed (make deps installs nodejs)"
  else if not (Sys.file_exists (Filename.concat (node_modules ()) "playwright-core")) then
    Some "playwright-core is not in test/web/node_modules (make deps runs npm ci there)"
  else None

(* A check that cannot run says so, and fails under CI=true. *)
let runnable what =
  match missing () with
  | None -> true
  | Some why ->
      Helpers.skip what ~why;
      false

let page () = Option.value (Sys.getenv_opt "RAYTRACE_WEB_PAGE") ~default:"../web/index.html"

let write path text =
  let oc = open_out_bin path in
  output_string oc text;
  close_out oc

(* The position of the first [sub] in [text]. *)
let index text sub =
  let n = String.length sub in
  let rec go i =
    if i + n > String.length text then Alcotest.failf "%S not found" sub
    else if String.sub text i n = sub then i
    else go (i + 1)
  in
  go 0

let read_text path = match File_io.read path with Ok t -> t | Error (`Msg m) -> Alcotest.fail m
let cgfs_text () = read_text (Helpers.scene_path "cgfs.scene")

(* The default scene with the red sphere's radius made negative. *)
let broken_text () =
  let text = cgfs_text () in
  let good = "(radius 1)    (color 255 0 0)" in
  let i = index text good in
  String.sub text 0 i ^ "(radius -1)   (color 255 0 0)" ^ String.sub text (i + String.length good) (String.length text - i - String.length good)

let typed_sphere = "\n(sphere (center 0 1.2 3.5) (radius 0.4) (color 255 255 255) (specular 50))\n"

(* Runs drive.js on the page through [steps] in a fresh directory, which
   then holds what it saw. *)
let drive ?(hash = "") steps =
  let dir = Helpers.temp_dir () in
  let env = Array.append [| "NODE_PATH=" ^ node_modules () |] (Unix.environment ()) in
  let t0 = Unix.gettimeofday () in
  let code, _, err = Helpers.run ~env "node" ([ "web/drive.js"; page () ^ hash; dir ] @ List.map (fun s -> s dir) steps) in
  if code <> 0 then Alcotest.failf "the browser session failed (%d): %s" code err;
  Printf.printf "browser session: %.1f s\n%!" (Unix.gettimeofday () -. t0);
  dir

let step s _ = s
let file_step verb name text dir =
  let path = Filename.concat dir name in
  write path text;
  verb ^ ":" ^ path

let main =
  lazy
    (drive
       [
         step "wait";
         step "shot:first";
         step "download:first";
         step "savekey:first-key";
         step "keys:Shift+D,Shift+Q,ArrowUp,=";
         step "shot:moved";
         step "drag:300,300,30,-20";
         step "shot:dragged";
         step "select:size=400x300";
         step "select:samples=2";
         step "wait";
         step "shot:sized";
         (fun dir -> file_step "edit" "broken.scene" (broken_text ()) dir);
         step "shot:broken";
         (fun dir -> file_step "edit" "cgfs.scene" (cgfs_text ()) dir);
         step ("type:" ^ typed_sphere);
         step "wait";
         step "shot:typed";
       ])

let held = lazy (drive ~hash:"#hold" [ step "advance:38"; step "shot:coarse"; step "release"; step "probe:progress"; step "shot:final" ])

(* A CSG union of 16384 spheres: `raytrace render` draws it; JavaScript's
   smaller stack ran out on it with an empty error line. *)
let csg_text () = Helpers.csg_spiral 16384

(* The reference scene at 16384 x 16384 pixels. *)
let huge_text () =
  let text = cgfs_text () in
  let from = "(canvas (width 600) (height 600))" in
  let i = index text from in
  String.sub text 0 i ^ "(canvas (width 16384) (height 16384))"
  ^ String.sub text (i + String.length from) (String.length text - i - String.length from)

(* Hostile scenes, each put in the editor while the one before renders:
   glass whose rows take seconds (the page asked every 100 ms meanwhile),
   a canvas of 16384 x 16384, a CSG of 16384 spheres, a glass pixel of
   seconds at depth 28. *)
let hostile =
  lazy
    (drive
       [
         step "wait";
         (fun dir -> file_step "set" "glass.scene" (Helpers.glass_planes ~width:300 ~height:200 ~depth:20) dir);
         step "answers:glass";
         (fun dir -> file_step "set" "huge.scene" (huge_text ()) dir);
         step "shot:huge";
         (* A quick frame ends the glass one: the CSG, if refused, leaves
            it on the page. *)
         (fun dir -> file_step "set" "cgfs.scene" (cgfs_text ()) dir);
         step "wait";
         (fun dir -> file_step "set" "csg.scene" (csg_text ()) dir);
         step "wait";
         step "shot:csg";
         (fun dir -> file_step "set" "deep.scene" (Helpers.glass_planes ~width:1 ~height:1 ~depth:28) dir);
         step "wait";
         step "shot:deep";
       ])

(* Every example scene, small (the size chosen fits the viewport as a
   resized window does), with 2 x 2 samples: shots named after the scenes. *)
let scenes =
  lazy
    (drive
       (step "select:size=200x200"
       :: step "select:samples=2"
       :: List.concat_map
            (fun name ->
              [
                (fun dir -> file_step "set" name (read_text (Helpers.scene_path name)) dir);
                step "wait";
                step ("shot:" ^ Filename.remove_extension name);
              ])
            (Helpers.scene_names ())))

(* Random scenes of the property tests' generators, fixed seed: small
   canvases, every light and material, both modes, and crowds that the
   bounding volume hierarchy serves. *)
let random_scenes =
  lazy
    (let rand = Random.State.make [| 16 |] in
     List.init 40 (fun _ -> QCheck.Gen.generate1 ~rand Gen_scene.gen)
     @ List.init 10 (fun _ -> QCheck.Gen.generate1 ~rand Gen_scene.crowd))

let random =
  lazy
    (drive
       (List.concat
          (List.mapi
             (fun i scene ->
               [
                 (fun dir -> file_step "set" (Printf.sprintf "r%d.txt" i) (Scene_file.to_string scene) dir);
                 step "wait";
                 step (Printf.sprintf "shot:r%d" i);
               ])
             (Lazy.force random_scenes))))

(* The scene files of the fuzzing corpus (test/corpus/scene), as the
   editor holds them. *)
let corpus_files () =
  let dir = "corpus/scene" in
  Sys.readdir dir |> Array.to_list |> List.sort compare |> List.map (Filename.concat dir)

let corpus =
  lazy
    (drive
       [
         (fun dir ->
           file_step "parse" "list"
             (String.concat "\n" (List.map (Filename.concat (Sys.getcwd ())) (corpus_files ())))
             dir);
       ])

(* [("scene:L:C", rest)] of a located message. *)
let split_location m =
  match String.split_on_char ':' m with
  | file :: line :: col :: rest -> (String.concat ":" [ file; line; col ], String.concat ":" rest)
  | _ -> (m, "")

(* The page's message differs from raytrace's in the two ways docs/web.md
   gives: an integer beyond 31 bits (JavaScript's OCaml ints have 32), and
   an error whose location search ran out of JavaScript's smaller stack,
   placed at 1:1 as raytrace places it when its own stack runs out. *)
let documented_difference ~native ~page =
  let nloc, nrest = split_location native and ploc, prest = split_location page in
  let beyond_31_bits =
    let marker = ": expected an integer, got " in
    let n = String.length marker in
    let rec find i = if i + n > String.length prest then None else if String.sub prest i n = marker then Some (i + n) else find (i + 1) in
    match find 0 with
    | Some j -> (
        nloc = ploc
        &&
        match int_of_string_opt (String.sub prest j (String.length prest - j)) with
        | Some k -> k > 0x7fff_ffff || k < -0x8000_0000
        | None -> false)
    | None -> false
  in
  beyond_31_bits || (ploc = "scene:1:1" && nrest = prest)

let read_image path = match Files.read_ppm path with Ok img -> img | Error (`Msg m) -> Alcotest.fail m
let shot dir name = read_image (Filename.concat dir (name ^ ".ppm"))

(* `raytrace render` of the scene text [text] with [samples]. *)
let native ?(samples = 1) text =
  let dir = Helpers.temp_dir () in
  let scene = Filename.concat dir "shown.scene" and out = Filename.concat dir "native.ppm" in
  write scene text;
  (* The textures that the page holds built in, beside the scene, where
     the command line reads them. *)
  List.iter (fun (name, contents) -> write (Filename.concat dir name) contents) Raytrace_web.Example_textures.files;
  let code, _, err =
    Helpers.run (Helpers.raytrace ()) [ "render"; scene; "--samples"; string_of_int samples; "-o"; out ]
  in
  if code <> 0 then Alcotest.failf "raytrace render failed: %s" err;
  read_image out

let json dir name = read_text (Filename.concat dir (name ^ ".json"))

(* The string value of [field] in the page's state, as drive.js writes it
   (JSON.stringify of strings without quotes or backslashes inside). *)
let json_string dir name field =
  let j = json dir name in
  let key = Printf.sprintf "\"%s\": \"" field in
  let i = index j key + String.length key in
  String.sub j i (String.index_from j i '"' - i)

let shown dir name = read_text (Filename.concat dir (name ^ ".scene"))
let with_browser what f = if runnable what then f ()

let tests =
  [
    Alcotest.test_case "the page's picture is raytrace render's of the default scene, byte for byte" `Slow
      (fun () ->
        with_browser "web: default scene" (fun () ->
            let dir = Lazy.force main in
            Helpers.check_images __LOC__ ~expected:(native (cgfs_text ())) (shot dir "first");
            Alcotest.(check string) __LOC__ (Scene_file.to_string Scene.cgfs) (shown dir "first")));
    Alcotest.test_case "the frame time is on the page" `Slow (fun () ->
        with_browser "web: frame time" (fun () ->
            let dir = Lazy.force main in
            let frame = json_string dir "first" "frame" in
            Printf.printf "first frame: %s\n" frame;
            Printf.printf "after keys: %s\n" (json_string dir "moved" "frame");
            let prefix = "600 x 600, 1 sample per pixel: " in
            Alcotest.(check string) __LOC__ prefix (String.sub frame 0 (String.length prefix))));
    Alcotest.test_case "the download link and the key s give the canvas's picture as PNG" `Slow (fun () ->
        with_browser "web: download" (fun () ->
            let dir = Lazy.force main in
            List.iter
              (fun name ->
                match Raytrace_png.Png_file.read_file (Filename.concat dir (name ^ ".png")) with
                | Error (`Msg m) -> Alcotest.fail m
                | Ok png -> Helpers.check_images name ~expected:(shot dir "first") png)
              [ "first"; "first-key" ]));
    Alcotest.test_case "keys move and turn the camera as in the window, and the picture follows" `Slow (fun () ->
        with_browser "web: keys" (fun () ->
            let dir = Lazy.force main in
            let keys = View.[ Key 'D'; Key 'Q'; Key arrow_up; Key '=' ] in
            let view = List.fold_left (fun v i -> fst (View.handle v i)) (View.v (Helpers.valid Scene.cgfs)) keys in
            Alcotest.(check string) __LOC__ (Scene_file.to_string view.scene) (shown dir "moved");
            let moved = shot dir "moved" in
            Alcotest.(check bool) "the picture changed" false (Image.equal moved (shot dir "first"));
            Helpers.check_images __LOC__ ~expected:(native (shown dir "moved")) moved));
    Alcotest.test_case "dragging turns the camera as in the window" `Slow (fun () ->
        with_browser "web: drag" (fun () ->
            let dir = Lazy.force main in
            (* The pointer moved 30 pixels right and 20 up. *)
            let before = match Scene_file.of_string (shown dir "moved") with Ok s -> s | Error (`Msg m) -> Alcotest.fail m in
            let view, _ = View.handle (View.v before) (View.Drag (30, 20)) in
            Alcotest.(check string) __LOC__ (Scene_file.to_string view.scene) (shown dir "dragged");
            Helpers.check_images __LOC__ ~expected:(native (shown dir "dragged")) (shot dir "dragged")));
    Alcotest.test_case "size and samples chosen: raytrace render --samples of the scene shown" `Slow (fun () ->
        with_browser "web: size and samples" (fun () ->
            let dir = Lazy.force main in
            let sized = shot dir "sized" in
            Alcotest.(check (pair int int)) __LOC__ (400, 300) (Image.width sized, Image.height sized);
            Helpers.check_images __LOC__ ~expected:(native ~samples:2 (shown dir "sized")) sized));
    Alcotest.test_case "every example scene is raytrace render's, byte for byte" `Slow (fun () ->
        with_browser "web: example scenes" (fun () ->
            let dir = Lazy.force scenes in
            List.iter
              (fun name ->
                let shot_name = Filename.remove_extension name in
                Helpers.check_images name ~expected:(native ~samples:2 (shown dir shot_name)) (shot dir shot_name))
              (Helpers.scene_names ())));
    Alcotest.test_case "random scenes are the renderer's, byte for byte" `Slow (fun () ->
        with_browser "web: random scenes" (fun () ->
            let dir = Lazy.force random in
            List.iteri
              (fun i scene ->
                let name = Printf.sprintf "r%d" i in
                Alcotest.(check string) name (Scene_file.to_string scene) (shown dir name);
                Helpers.check_images name ~expected:(Helpers.image_exn scene) (shot dir name))
              (Lazy.force random_scenes)));
    Alcotest.test_case "a broken scene shows file:line:column under the editor, the picture stays" `Slow
      (fun () ->
        with_browser "web: errors" (fun () ->
            let dir = Lazy.force main in
            let error = json_string dir "broken" "error" in
            (* raytrace render names the same line, column and fault. *)
            let scene = Filename.concat (Helpers.temp_dir ()) "broken.scene" in
            write scene (broken_text ());
            let code, _, err = Helpers.run (Helpers.raytrace ()) [ "render"; scene; "-o"; scene ^ ".ppm" ] in
            Alcotest.(check int) "raytrace render fails" 1 code;
            let expected = "scene" ^ String.sub err (String.length ("raytrace: " ^ scene)) (String.length err - String.length ("raytrace: " ^ scene) - 1) in
            Alcotest.(check string) __LOC__ expected error;
            Alcotest.(check string) __LOC__ "scene:14:" (String.sub error 0 9);
            Helpers.check_images __LOC__ ~expected:(shot dir "sized") (shot dir "broken")));
    Alcotest.test_case "every scene of the fuzzing corpus gets raytrace's message, or a documented variant" `Slow (fun () ->
        with_browser "web: corpus" (fun () ->
            let dir = Lazy.force corpus in
            let differ = ref 0 and known = ref 0 in
            List.iteri
              (fun i file ->
                let page_text = read_text (Filename.concat dir (Printf.sprintf "parse-%d.txt" i)) in
                let page_error = read_text (Filename.concat dir (Printf.sprintf "parse-%d.err" i)) in
                let native = match Scene_file.of_string ~file:"scene" page_text with Ok _ -> "" | Error (`Msg m) -> m in
                if native <> page_error then begin
                  if documented_difference ~native ~page:page_error then incr known else incr differ;
                  Printf.printf "%s:\n  native: %s\n  page:   %s\n" file native page_error
                end)
              (corpus_files ());
            Printf.printf "%d files, %d messages differ as docs/web.md says\n" (List.length (corpus_files ())) !known;
            Alcotest.(check int) "messages that differ" 0 !differ));
    Alcotest.test_case "text typed into the editor is rendered" `Slow (fun () ->
        with_browser "web: typing" (fun () ->
            let dir = Lazy.force main in
            let text = shown dir "typed" in
            let scene = match Helpers.of_string text with Ok s -> s | Error (`Msg m) -> Alcotest.fail m in
            Alcotest.(check int) "spheres" 5 (Private.Spheres.length (Scene.spheres scene));
            Alcotest.(check string) "typed error cleared" "" (json_string dir "typed" "error");
            Helpers.check_images __LOC__ ~expected:(native ~samples:2 text) (shot dir "typed")));
    Alcotest.test_case "coarse blocks come first: after the first pass, 16 x 16 blocks of the image" `Slow
      (fun () ->
        with_browser "web: coarse blocks" (fun () ->
            let dir = Lazy.force held in
            let full = native (cgfs_text ()) and coarse = shot dir "coarse" in
            let expected = Image.create 600 600 in
            for y = 0 to 599 do
              for x = 0 to 599 do
                let r, g, b = Image.get full (16 * (x / 16)) (16 * (y / 16)) in
                Image.set expected x y r g b
              done
            done;
            Helpers.check_images __LOC__ ~expected coarse;
            Helpers.check_images __LOC__ ~expected:full (shot dir "final")));
    Alcotest.test_case "the page answers within a fraction of a second while glass rows take seconds" `Slow (fun () ->
        with_browser "web: glass" (fun () ->
            let dir = Lazy.force hostile in
            let answers =
              List.map
                (fun l ->
                  match String.split_on_char ' ' l with
                  | [ ms; finished; slice ] -> (int_of_string ms, finished, float_of_string slice)
                  | _ -> Alcotest.failf "answers.txt: %S" l)
                (String.split_on_char '\n' (String.trim (read_text (Filename.concat dir "glass.txt"))))
            in
            let slowest = List.fold_left (fun m (ms, _, _) -> max m ms) 0 answers in
            let _, _, slice = List.nth answers (List.length answers - 1) in
            Printf.printf "answers in %s ms; longest slice %.3f s\n"
              (String.concat " " (List.map (fun (ms, _, _) -> string_of_int ms) answers)) slice;
            (* Before, a slice was a band of seconds (docs/faults.md). *)
            Alcotest.(check bool) "every answer while the frame was traced" true
              (List.for_all (fun (_, f, _) -> f = "false") answers);
            Alcotest.(check bool) (Printf.sprintf "the slowest answer within 1 s (%d ms)" slowest) true (slowest < 1000);
            Alcotest.(check bool)
              (Printf.sprintf "slices within a pixel's bound (%.3f s)" slice)
              true
              (slice < Raytrace_web.Session.max_pixel_seconds +. 0.1)));
    Alcotest.test_case "a 16384 x 16384 canvas is refused with a positioned line, at once" `Slow (fun () ->
        with_browser "web: huge canvas" (fun () ->
            let dir = Lazy.force hostile in
            Alcotest.(check string) __LOC__
              "scene:5:1: canvas 16384x16384 has 268435456 pixels, more than the limit of 16777216 (the page's bound: \
               raytrace render draws larger canvases)"
              (json_string dir "huge" "error")));
    Alcotest.test_case "a CSG of 16384 spheres is raytrace render's picture, or one positioned line" `Slow (fun () ->
        with_browser "web: big CSG" (fun () ->
            let dir = Lazy.force hostile in
            match json_string dir "csg" "error" with
            | "" -> Helpers.check_images __LOC__ ~expected:(native (csg_text ())) (shot dir "csg")
            | error ->
                (* The library's passes over the tree are too deep for
                   JavaScript's stack: docs/web.md. *)
                Printf.printf "the page says: %s\n" error;
                Alcotest.(check string) __LOC__
                  "scene:1:1: scene too deeply nested for the browser: its stack ran out (raytrace render renders it)"
                  error));
    Alcotest.test_case "a pixel that takes seconds stops the frame with a positioned line" `Slow (fun () ->
        with_browser "web: slow pixel" (fun () ->
            let dir = Lazy.force hostile in
            let expected =
              Printf.sprintf
                "scene:1:1: one pixel takes more than %g s to trace, too long for the page to stay responsive: the \
                 frame stops here (raytrace render renders it)"
                Raytrace_web.Session.max_pixel_seconds
            in
            Alcotest.(check string) "the line" expected (json_string dir "deep" "error");
            Alcotest.(check string) "stopped" expected (json_string dir "deep" "stopped")));
    Alcotest.test_case "the page answers while it traces a frame" `Slow (fun () ->
        with_browser "web: responsive" (fun () ->
            let dir = Lazy.force held in
            let lines = String.split_on_char '\n' (String.trim (read_text (Filename.concat dir "progress.txt"))) in
            let unfinished = List.sort_uniq compare (List.filter (fun l -> String.sub l 0 5 = "false") lines) in
            Printf.printf "%d answers, %d while tracing, at different stages\n" (List.length lines) (List.length unfinished);
            Alcotest.(check bool) "at least 3 answers at different stages of the frame" true (List.length unfinished >= 3)));
  ]
