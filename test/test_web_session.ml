(* The web page's state (web/session.ml) and key names (web/key.ml),
   natively: what the page decides, without a browser. *)
open Raytrace
module Session = Raytrace_web.Session
module Key = Raytrace_web.Key

(* A clock that advances by one second each time it is read. *)
let ticking () =
  let t = ref 0. in
  fun () ->
    t := !t +. 1.;
    !t

let cgfs_text () = match File_io.read (Helpers.scene_path "cgfs.scene") with Ok t -> t | Error (`Msg m) -> Alcotest.fail m

let session ?(now = ticking ()) text =
  match Session.v ~now text with Ok p -> p | Error (`Msg m) -> Alcotest.fail m

let ok = function Ok () -> () | Error (`Msg m) -> Alcotest.fail m

let finish p =
  while not (Session.finished p) do
    ignore (Session.step p ~until:infinity)
  done;
  Session.image p

(* A small picture of the scene, so that frames are quick. *)
let small p = ok (Session.set_size p (Some (60, 40)))

(* The example scene [name] in a session, made small, finishes with the
   picture raytrace render makes of the session's scene; the session is
   returned for more checks. *)
let renders_as_cli name =
  let text = match File_io.read (Helpers.scene_path name) with Ok t -> t | Error (`Msg m) -> Alcotest.fail m in
  let p = session text in
  small p;
  let expected = Helpers.image_exn (Session.view p).scene in
  Helpers.check_images name ~expected (finish p);
  p

let glass ~width ~height ~depth = session ~now:Unix.gettimeofday (Helpers.glass_planes ~width ~height ~depth)

let tests =
  [
    Alcotest.test_case "a big CSG traced in slices, paused between and inside pixels, is raytrace render's picture" `Quick
      (fun () ->
        let text = Helpers.csg_spiral 16384 in
        let p = session ~now:Unix.gettimeofday text in
        let expected = match Helpers.of_string text with Ok s -> Helpers.image_exn s | Error (`Msg m) -> Alcotest.fail m in
        let slices = ref 0 in
        while not (Session.finished p) do
          incr slices;
          ignore (Session.step p ~until:(Unix.gettimeofday () +. 0.0005))
        done;
        Printf.printf "%d slices\n" !slices;
        Alcotest.(check (option string)) "no line" None (Session.stopped p);
        Helpers.check_images __LOC__ ~expected (Session.image p));
    Alcotest.test_case "a slice ends soon after its deadline, inside a band of glass that takes a second" `Quick (fun () ->
        (* The first band: 38 pixels of deep glass, far longer than the slice. *)
        let p = glass ~width:600 ~height:2 ~depth:22 in
        let t0 = Unix.gettimeofday () in
        let bands = Session.step p ~until:(t0 +. 0.02) in
        let t = Unix.gettimeofday () -. t0 in
        Printf.printf "a slice of 20 ms took %.3f s, %d bands\n" t (List.length bands);
        Alcotest.(check bool) (Printf.sprintf "within 0.2 s (%.3f s)" t) true (t < 0.2);
        Alcotest.(check int) "the band is not finished" 0 (List.length bands);
        Alcotest.(check bool) "the frame goes on" false (Session.finished p);
        (* It goes on where it paused: the picture is raytrace render's. *)
        let p = glass ~width:40 ~height:3 ~depth:12 in
        let slices = ref 0 in
        while not (Session.finished p) do
          incr slices;
          ignore (Session.step p ~until:(Unix.gettimeofday () +. 0.002))
        done;
        Printf.printf "%d slices of 2 ms\n" !slices;
        let scene = match Helpers.of_string (Session.shown_text p) with Ok s -> s | Error (`Msg m) -> Alcotest.fail m in
        Helpers.check_images __LOC__ ~expected:(Helpers.image_exn scene) (Session.image p));
    Alcotest.test_case "a pixel that takes seconds stops the frame with a positioned line" `Quick (fun () ->
        (* The page's clock runs 50 times as fast as the wall's, so that the
           pixel takes "seconds" on any machine: this one traces it in about
           half a second of wall time, the page's bound. *)
        let t0 = Unix.gettimeofday () in
        let now () = t0 +. (50. *. (Unix.gettimeofday () -. t0)) in
        let p = session ~now (Helpers.glass_planes ~width:1 ~height:1 ~depth:28) in
        ignore (Session.step p ~until:(now () +. 0.02));
        let t = Unix.gettimeofday () -. t0 in
        Printf.printf "stopped after %.3f s\n" t;
        Alcotest.(check bool) (Printf.sprintf "within a second (%.3f s)" t) true (t < 1.);
        Alcotest.(check bool) "finished" true (Session.finished p);
        Alcotest.(check (option string)) "the line"
          (Some
             "scene:1:1: one pixel takes more than 0.5 s to trace, too long for the page to stay responsive: the frame \
              stops here (raytrace render renders it)")
          (Session.stopped p);
        Alcotest.(check bool) "no frame statistics" true (Session.last_frame p = None));
    Alcotest.test_case "a canvas beyond 4096 x 4096 is refused with the page's bound, positioned" `Quick (fun () ->
        let p = session (cgfs_text ()) in
        small p;
        let huge = Helpers.glass_planes ~width:16384 ~height:16384 ~depth:1 in
        (match Session.edit p huge with
        | Ok () -> Alcotest.fail "a 16384 x 16384 canvas was accepted"
        | Error (`Msg m) ->
            Alcotest.(check string) __LOC__
              "scene:1:1: canvas 16384x16384 has 268435456 pixels, more than the limit of 16777216 (the page's bound: \
               raytrace render draws larger canvases)"
              m);
        (match Session.edit p (Helpers.glass_planes ~width:4096 ~height:4096 ~depth:1) with
        | Ok () -> ()
        | Error (`Msg m) -> Alcotest.failf "4096 x 4096 was refused: %s" m);
        Alcotest.(check (pair int int)) "the size chosen stays" (60, 40)
          (Scene.width (Session.view p).scene, Scene.height (Session.view p).scene));
    Alcotest.test_case "the finished picture of the default text is raytrace render's" `Quick (fun () ->
        let p = session (cgfs_text ()) in
        Helpers.check_images __LOC__ ~expected:(Helpers.image_exn Scene.cgfs) (finish p);
        Alcotest.(check string) __LOC__ (Scene_file.to_string Scene.cgfs) (Session.shown_text p));
    Alcotest.test_case "the textured globe renders as raytrace render's, its textures built in; another texture file is refused at its name" `Quick
      (fun () ->
        let p = renders_as_cli "globe.scene" in
        (* The built-in images are the checked-in files. *)
        List.iter
          (fun (name, contents) ->
            match File_io.read (Helpers.scene_path name) with
            | Ok t -> Alcotest.(check string) name t contents
            | Error (`Msg m) -> Alcotest.fail m)
          Raytrace_web.Example_textures.files;
        match Session.edit p {|(sphere (center 0 0 3) (radius 1) (color 1 1 1) (texture (file "moon.png") (mapping spherical)))|} with
        | Ok () -> Alcotest.fail "a texture the page does not have was accepted"
        | Error (`Msg m) ->
            Alcotest.(check string) __LOC__
              "scene:1:58: cannot read texture file moon.png: the page reads no files; its textures are the example scenes' earth.ppm and tiles.ppm"
              m);
    Alcotest.test_case "the textured die (textures on CSG operands and on a use's own material) renders as raytrace render's" `Quick
      (fun () ->
        ignore (renders_as_cli "textured-die.scene"));
    Alcotest.test_case "a step traces at least one band and stops at its deadline" `Quick (fun () ->
        let p = session (cgfs_text ()) in
        (* The ticking clock passes [until] at the first reading after a band. *)
        let bands = Session.step p ~until:0. in
        Alcotest.(check int) "one band" 1 (List.length bands);
        Alcotest.(check int) "a block of 16 first" 16 (List.hd bands).size;
        let bands = Session.step p ~until:infinity in
        Alcotest.(check bool) "until the end" true (Session.finished p);
        Alcotest.(check int) "every band counted" (1 + List.length bands) (Session.bands p);
        match Session.last_frame p with
        | None -> Alcotest.fail "no frame statistics"
        | Some f ->
            Alcotest.(check (pair int int)) "size" (600, 600) (f.width, f.height);
            Alcotest.(check int) "slices" 2 f.slices);
    Alcotest.test_case "a broken text is a scene:line:column error and the picture stays" `Quick (fun () ->
        let p = session (cgfs_text ()) in
        small p;
        let before = Image.copy (finish p) in
        let text = cgfs_text () ^ "(sphere (center 0 0 3) (radius 0) (color 1 2 3))\n" in
        (match Session.edit p text with
        | Ok () -> Alcotest.fail "a zero radius was accepted"
        | Error (`Msg m) -> Alcotest.(check string) __LOC__ "scene:22:32: sphere radius must be > 0, got 0" m);
        Alcotest.(check bool) "still finished" true (Session.finished p);
        Helpers.check_images __LOC__ ~expected:before (Session.image p));
    Alcotest.test_case "an edit keeps the size and samples chosen, and resets the camera" `Quick (fun () ->
        let p = session (cgfs_text ()) in
        small p;
        ok (Session.set_samples p 2);
        ignore (Session.input p (View.Key 'D'));
        ok (Session.edit p (Scene_file.to_string Scene.cgfs_camera));
        let shown = (Session.view p).scene in
        Alcotest.(check (pair int int)) "size" (60, 40) (Scene.width shown, Scene.height shown);
        Alcotest.(check int) "samples" 2 (Session.samples p);
        Alcotest.(check bool) "camera of the text" true (Camera.equal (Scene.camera Scene.cgfs_camera) (Scene.camera shown));
        Helpers.check_images __LOC__ ~expected:(Helpers.image_exn ~samples:2 shown) (finish p));
    Alcotest.test_case "keys change the view as in the window; a is 3 x 3 samples or 1" `Quick (fun () ->
        let p = session (cgfs_text ()) in
        small p;
        let keys = View.[ Key 'D'; Key 'Q'; Key arrow_up; Key '+'; Key 'a' ] in
        List.iter (fun k -> Alcotest.(check bool) "renders" true (Session.input p k = View.Render)) keys;
        let view =
          List.fold_left (fun v k -> fst (View.handle v k)) (Session.view (session (cgfs_text ()))) (View.Resize (60, 40) :: keys)
        in
        Alcotest.(check string) __LOC__ (Scene_file.to_string view.scene) (Session.shown_text p);
        Alcotest.(check int) "antialiased" 3 (Session.samples p);
        Helpers.check_images __LOC__ ~expected:(Helpers.image_exn ~samples:3 view.scene) (finish p);
        ignore (Session.input p (View.Key 'a'));
        Alcotest.(check int) "one sample again" 1 (Session.samples p);
        Alcotest.(check bool) "h only redraws" true (Session.input p (View.Key 'h') = View.Redraw);
        Alcotest.(check bool) "unbound keys do nothing" true (Session.input p (View.Key 'x') = View.Nothing));
    Alcotest.test_case "samples chosen set the antialiasing flag; sizes keep the camera; bad ones are refused" `Quick (fun () ->
        let p = session (cgfs_text ()) in
        ok (Session.set_samples p 4);
        Alcotest.(check bool) "flag on" true (Session.view p).antialias;
        ok (Session.set_samples p 1);
        Alcotest.(check bool) "flag off" false (Session.view p).antialias;
        let refused what r = Alcotest.(check bool) what true (Result.is_error r) in
        refused "0 samples" (Session.set_samples p 0);
        refused "65 samples" (Session.set_samples p 65);
        refused "0 wide" (Session.set_size p (Some (0, 10)));
        refused "too wide" (Session.set_size p (Some (65537, 10)));
        Alcotest.(check (option (pair int int))) "size unchanged" None (Session.size p);
        ignore (Session.input p (View.Key 'D'));
        let moved = (Scene.camera (Session.view p).scene) in
        small p;
        ok (Session.set_size p None);
        let shown = (Session.view p).scene in
        Alcotest.(check (pair int int)) "the scene's canvas again" (600, 600) (Scene.width shown, Scene.height shown);
        Alcotest.(check bool) "its viewport" true (Viewport.equal (Scene.viewport Scene.cgfs) (Scene.viewport shown));
        Alcotest.(check bool) "the camera moved stays" true (Camera.equal moved (Scene.camera shown)));
    Alcotest.test_case "browser key names are the window's characters" `Quick (fun () ->
        List.iter
          (fun (name, expected) -> Alcotest.(check (option char)) name expected (Key.to_char name))
          [
            ("ArrowLeft", Some View.arrow_left);
            ("ArrowUp", Some View.arrow_up);
            ("ArrowRight", Some View.arrow_right);
            ("ArrowDown", Some View.arrow_down);
            ("Escape", Some '\027');
            ("D", Some 'D');
            ("a", Some 'a');
            ("+", Some '+');
            ("Shift", None);
            ("F1", None);
            ("\xc3\xa9", None);
            ("", None);
          ]);
  ]
