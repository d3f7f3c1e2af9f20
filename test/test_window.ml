(* The Graphics window, in a virtual X server: driven by keys and the
   pointer (test/window_session.sh), what it shows is what the headless
   renderer makes of the same view. Runs when xvfb-run is installed. *)
open Raytrace

let tools = [ "xvfb-run"; "xwd"; "xdotool"; "convert" ]

let available () =
  if not (Helpers.on_path "xvfb-run") then begin
    Helpers.skip "window" ~why:"xvfb-run is not installed (make deps installs it)";
    false
  end
  else
    match Helpers.missing tools with
    | [] -> true
    | missing -> Alcotest.failf "xvfb-run is installed but not %s (make deps)" (String.concat ", " missing)

(* Runs the window on a copy of scenes/[name] in a fresh directory (where
   [s] saves) through [steps]; the directory then holds the screenshots. *)
let session ?(view_args = "") ?(first_frame = true) ?(screen = "1024x768") ?(edit = Fun.id) name steps =
  let dir = Helpers.temp_dir () in
  let scene = Filename.concat dir name in
  (match File_io.read (Helpers.scene_path name) with
  | Ok text ->
      let oc = open_out_bin scene in
      output_string oc (edit text);
      close_out oc
  | Error (`Msg m) -> Alcotest.fail m);
  New_scenes.copy_models dir;
  let env =
    Array.append [| "VIEW_ARGS=" ^ view_args; "FIRST_FRAME=" ^ if first_frame then "yes" else "no" |] (Unix.environment ())
  in
  let code, _, err =
    Helpers.run ~env "xvfb-run"
      ([ "-a"; "-s"; "-screen 0 " ^ screen ^ "x24"; "./window_session.sh"; Helpers.raytrace (); scene; dir ] @ steps)
  in
  if code <> 0 then Alcotest.failf "%s: the window session failed (%d): %s" name code err;
  dir

let read path = match Files.read_ppm path with Ok img -> img | Error (`Msg m) -> Alcotest.fail m
let shot dir name = read (Filename.concat dir (name ^ ".ppm"))

let contains text s =
  let n = String.length s in
  let rec go i = i + n <= String.length text && (String.sub text i n = s || go (i + 1)) in
  go 0

let text path = match File_io.read path with Ok t -> t | Error (`Msg m) -> Alcotest.fail m

let views inputs view = List.fold_left (fun v i -> fst (View.handle v i)) view inputs
let keys cs = List.map (fun c -> View.Key c) cs

(* [text] with the canvas of scenes/cgfs.scene made [w x h]. *)
let with_canvas w h text =
  let from = "(canvas (width 600) (height 600))" in
  let n = String.length from in
  let rec find i =
    if i + n > String.length text then Alcotest.fail "cgfs.scene has no 600x600 canvas"
    else if String.sub text i n = from then i
    else find (i + 1)
  in
  let i = find 0 in
  String.sub text 0 i
  ^ Printf.sprintf "(canvas (width %d) (height %d))" w h
  ^ String.sub text (i + n) (String.length text - i - n)

let tests =
  [
    Alcotest.test_case "q quits within a fraction of a second while a glass pixel takes seconds" `Slow (fun () ->
        if available () then begin
          (* The window used to read its keys between bands of pixels:
             q waited for the band, seconds here. *)
          (* At depth 30 a pixel takes seconds; a canvas this small
             keeps the render within the work bound however the estimate
             counts the tree. *)
          let glass _ = Helpers.glass_planes ~width:8 ~height:8 ~depth:30 in
          let dir = session ~first_frame:false ~edit:glass "cgfs.scene" [ "quit:1" ] in
          let seconds = float_of_string (String.trim (text (Filename.concat dir "quit.seconds"))) in
          Printf.printf "q pressed after 1 s of tracing: the window closed in %.3f s\n" seconds;
          Alcotest.(check bool) (Printf.sprintf "closed within 0.5 s (%.3f s)" seconds) true (seconds < 0.5)
        end);
    Alcotest.test_case "quitting with q never crashes, whatever the canvas size" `Slow (fun () ->
        if available () then
          (* 1x2 and 7x8 crashed (SIGSEGV, status 139) on q: the frame's
             Graphics images were freed by the GC after close_graph. *)
          List.iter
            (fun (w, h) ->
              (* window_session.sh fails unless the window exits with 0 on q *)
              let dir = session ~screen:"1280x1024" ~edit:(with_canvas w h) "cgfs.scene" [ "shot:window" ] in
              Alcotest.(check (pair int int))
                (Printf.sprintf "the window of a %dx%d canvas" w h)
                (w, h)
                (let img = shot dir "window" in
                 (Image.width img, Image.height img)))
            [ (1, 2); (7, 8); (2, 1); (333, 334); (1001, 701) ]);
    Alcotest.test_case "a canvas larger than the X screen is one line, not a crash" `Slow (fun () ->
        if available () then begin
          let dir = Helpers.temp_dir () in
          let scene = Filename.concat dir "big.scene" in
          (match File_io.read (Helpers.scene_path "cgfs.scene") with
          | Ok text ->
              let oc = open_out_bin scene in
              output_string oc (with_canvas 800 800 text);
              close_out oc
          | Error (`Msg m) -> Alcotest.fail m);
          let code, out, err =
            Helpers.run "xvfb-run" [ "-a"; "-s"; "-screen 0 640x480x24"; Helpers.raytrace (); "view"; scene ]
          in
          Alcotest.(check int) ("exit status 3 (no window): " ^ err) 3 code;
          Alcotest.(check string) "nothing on stdout" "" out;
          Alcotest.(check (list string)) "one line"
            [
              "raytrace: cannot open a window (the X screen is 640x480 pixels, too small for the 800x800 canvas); to \
               render without a display, use: raytrace render " ^ Filename.quote scene ^ " -o out.ppm";
            ]
            (List.filter (fun l -> l <> "") (String.split_on_char '\n' err))
        end);
    Alcotest.test_case "a screenshot of the window equals the rendered image" `Slow (fun () ->
        if available () then
          List.iter
            (fun name ->
              let dir = session name [ "shot:window" ] in
              Helpers.check_images ("window of " ^ name)
                ~expected:(Helpers.image_exn (Helpers.load_scene name)) (shot dir "window"))
            ([ "cgfs.scene"; "cgfs-camera.scene" ] @ New_scenes.names));
    Alcotest.test_case "keys, the pointer and resizing change the picture as the headless render shows it" `Slow
      (fun () ->
        if available () then begin
          (* Two workers: the full-resolution passes go through them, and
             an antialiased 600 x 600 frame takes long enough (over 0.1 s)
             for a key 30 ms later to come in the middle of it. *)
          let dir =
            session ~view_args:"--jobs 2" "cgfs.scene"
              [
                "frame:a,a"; "keys:Left"; "shot:left"; "title:left"; "resize:320x240"; "shot:small"; "keys:W,E,plus";
                "shot:moved"; "keys:a"; "shot:aa"; "press:h"; "keys:r"; "shot:help"; "press:h"; "keys:a";
                "drag:160,120,24,-16"; "shot:drag"; "save:D,s"; "shot:final";
              ]
          in
          let start = View.v (Helpers.valid (Helpers.load_scene "cgfs.scene")) in
          let left = views (keys [ View.arrow_left ]) start in
          let small = views [ View.Resize (320, 240) ] left in
          let moved = views (keys [ 'W'; 'E'; '+' ]) small in
          let aa = views (keys [ 'a' ]) moved in
          let aa_image = Antialias.image ~n:(View.samples aa) (Helpers.valid aa.scene) in
          (* xdotool moves the pointer 16 pixels up: +16 in Graphics' y *)
          let drag = views (keys [ 'a' ] @ [ View.Drag (24, 16) ]) aa in
          let final = views (keys [ 'D' ]) drag in
          (* The second a came while the antialiased frame of the first was
             being traced: that frame was dropped, never finished. The only
             antialiased frames are those of a and r at 320 x 240. *)
          let log = text (Filename.concat dir "log") in
          let lines = String.split_on_char '\n' log in
          Alcotest.(check (list string)) "the antialiased frames" [ "320x240"; "320x240" ]
            (List.filter_map
               (fun l ->
                 match String.split_on_char ' ' l with
                 | "raytrace:" :: "drawn" :: size :: "antialiased" :: _ -> Some size
                 | _ -> None)
               lines);
          let check what (view : View.t) =
            let expected = if View.samples view = 1 then Helpers.image_exn view.scene else aa_image in
            Helpers.check_images ("window after " ^ what) ~expected (shot dir what)
          in
          check "left" left;
          check "moved" moved;
          check "small" small;
          check "aa" aa;
          check "drag" drag;
          check "final" final;
          Alcotest.(check bool) "the left arrow changed the picture" false
            (Image.equal (Helpers.image_exn start.scene) (shot dir "left"));
          Alcotest.(check (pair int int)) "the resized window's picture" (320, 240)
            (Image.width (shot dir "small"), Image.height (shot dir "small"));
          (* The help box covers the top left; below it the picture is intact. *)
          let help = shot dir "help" in
          Alcotest.(check bool) "the help is drawn" false (Image.equal help aa_image);
          Helpers.check_images "the picture below the help"
            ~expected:(Image.sub aa_image ~x:0 ~y:170 ~w:320 ~h:70)
            (Image.sub help ~x:0 ~y:170 ~w:320 ~h:70);
          let title = text (Filename.concat dir "left.title") in
          List.iter
            (fun s -> Alcotest.(check bool) ("title has " ^ s ^ ": " ^ title) true (contains title s))
            [ "raytrace: cgfs.scene - 600x600 in "; " M rays/s"; "h: help" ];
          (* s, pressed right after D, saved the frame that D asked for and
             its scene; the command line renders that scene to the same
             picture. *)
          let ppm = Filename.concat dir "cgfs-1.ppm" and scene = Filename.concat dir "cgfs-1.scene" in
          Alcotest.(check bool) ("the window says where it saved: " ^ log) true (contains log ("saved " ^ ppm));
          Helpers.check_images "the saved image" ~expected:(shot dir "final") (read ppm);
          let out = Filename.concat dir "headless.ppm" in
          let code, _, err = Helpers.run (Helpers.raytrace ()) [ "render"; scene; "-o"; out ] in
          if code <> 0 then Alcotest.failf "raytrace render %s: %s" scene err;
          Helpers.check_images "raytrace render of the saved scene" ~expected:(read out) (shot dir "final")
        end);
  ]
