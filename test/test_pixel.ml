(* The one-pixel path (Pixel) and the one-call path (render_string) give
   the renderer's pixels. *)
open Raytrace

let image v = match Render.image v with Ok (img, _) -> img | Error (`Msg m) -> Alcotest.fail m

(* [None] if every pixel of [p] is [img]'s, else the first that is not. *)
let first_difference p img =
  let s = Scene.of_valid (Render.Pixel.scene p) in
  let found = ref None in
  for y = 0 to (Scene.height s) - 1 do
    for x = 0 to (Scene.width s) - 1 do
      let c = Render.Pixel.color p x y in
      let mine = (Color.to_byte c.r, Color.to_byte c.g, Color.to_byte c.b) in
      if !found = None && mine <> Image.get img x y then found := Some (x, y)
    done
  done;
  !found

let tests =
  [
    Helpers.qcheck ~count:100 "a pixel's colour is the renderer's pixel, with an epsilon and in the robust mode"
      Gen_scene.arbitrary (fun s ->
        List.for_all
          (fun epsilon ->
            let v = Helpers.valid (Scene.with_overrides ~epsilon s) in
            let p = Render.Pixel.v v in
            match first_difference p (image v) with
            | None -> true
            | Some (x, y) -> QCheck.Test.fail_reportf "pixel (%d, %d) differs" x y)
          [ (Scene.epsilon s); Some 0.001; Some Scene.document_epsilon; None ]);
    Alcotest.test_case "the reference scenes' pixels, one at a time, are their images" `Quick (fun () ->
        List.iter
          (fun s ->
            let v = Helpers.valid (Scene.with_overrides ~width:64 ~height:48 s) in
            Alcotest.(check (option (pair int int))) __LOC__ None (first_difference (Render.Pixel.v v) (image v)))
          [ Scene.cgfs; Scene.cgfs_camera; (Scene.with_overrides ~epsilon:None Scene.cgfs) ]);
    Alcotest.test_case "a pixel outside the canvas is a programmer error naming the function" `Quick (fun () ->
        let p = Render.Pixel.v (Helpers.valid (Scene.with_overrides ~width:4 ~height:3 Scene.cgfs)) in
        Alcotest.check_raises __LOC__ (Invalid_argument "Render.Pixel.color: (4, 0) is outside the 4x3 canvas")
          (fun () -> ignore (Render.Pixel.color p 4 0)));
    Alcotest.test_case "render_string renders scene text in one call, or says what is wrong" `Quick (fun () ->
        let text = Scene_file.to_string (Scene.with_overrides ~width:32 ~height:24 Scene.cgfs) in
        (match render_string text with
        | Ok img -> Helpers.check_images __LOC__ ~expected:(image (Helpers.valid (Scene.with_overrides ~width:32 ~height:24 Scene.cgfs))) img
        | Error (`Msg m) -> Alcotest.fail m);
        match render_string ~file:"x.scene" "(sphere (center 0 0 3) (radius -1) (color 1 2 3))" with
        | Ok _ -> Alcotest.fail "rendered an invalid scene"
        | Error (`Msg m) -> Alcotest.(check string) __LOC__ "x.scene:1:32: sphere radius must be > 0, got -1" m);
    Alcotest.test_case "render_file renders a scene file in one call, or says what is wrong" `Quick (fun () ->
        (match Files.render_file ~jobs:2 (Helpers.scene_path "cgfs-camera.scene") with
        | Ok img -> Helpers.check_images __LOC__ ~expected:(image (Helpers.valid Scene.cgfs_camera)) img
        | Error (`Msg m) -> Alcotest.fail m);
        match Files.render_file "no/such.scene" with
        | Ok _ -> Alcotest.fail "rendered a missing file"
        | Error (`Msg m) -> Alcotest.(check string) __LOC__ "no/such.scene: No such file or directory" m);
    Alcotest.test_case "the version is dune-project's, and the command prints it" `Quick (fun () ->
        let project = In_channel_free.read "../dune-project" in
        let declared = Scanf.sscanf (List.find (fun l -> String.length l > 9 && String.sub l 0 9 = "(version ") (String.split_on_char '\n' project)) "(version %s@)" Fun.id in
        Alcotest.(check string) __LOC__ declared version;
        let code, out, _ = Helpers.run (Helpers.raytrace ()) [ "--version" ] in
        Alcotest.(check (pair int string)) __LOC__ (0, version ^ "\n") (code, out));
    Alcotest.test_case "sampling settings from a user are errors, not exceptions" `Quick (fun () ->
        match Render.image ~samples:2 ~adaptive:3 (Helpers.valid Scene.cgfs) with
        | Ok _ -> Alcotest.fail "rendered"
        | Error (`Msg m) ->
            Alcotest.(check string) __LOC__
              "adaptive sampling needs an odd number of samples >= 3, whose grid has the pixel's centre in its middle (or, \
               under a lens, any number >= 2), got 2" m);
    Alcotest.test_case "with samples, a pixel's colour is Render.image's pixel with the same samples (cgfs.scene)" `Quick
      (fun () ->
        let cgfs = Helpers.valid (Helpers.load_scene "cgfs.scene") in
        (* Every pixel of a 48 x 36 canvas, an even and an odd grid. *)
        let small = match Scene.override ~width:48 ~height:36 cgfs with Ok v -> v | Error (`Msg m) -> Alcotest.fail m in
        List.iter
          (fun samples ->
            let img = match Render.image ~samples small with Ok (i, _) -> i | Error (`Msg m) -> Alcotest.fail m in
            match first_difference (Render.Pixel.v ~samples small) img with
            | None -> ()
            | Some (x, y) -> Alcotest.failf "%dx%d samples: pixel (%d, %d) differs" samples samples x y)
          [ 2; 3 ];
        (* A few pixels of the full canvas, on the spheres' edges and
           reflections, against Render.image of the whole image. *)
        let samples = 4 in
        let img = match Render.image ~samples cgfs with Ok (i, _) -> i | Error (`Msg m) -> Alcotest.fail m in
        let p = Render.Pixel.v ~samples cgfs in
        List.iter
          (fun (x, y) ->
            let c = Render.Pixel.color p x y in
            let rgb = Color.to_rgb8 c in
            Alcotest.(check (triple int int int))
              (Printf.sprintf "pixel (%d, %d)" x y)
              (Image.get img x y)
              (rgb lsr 16, (rgb lsr 8) land 0xFF, rgb land 0xFF))
          [ (0, 0); (300, 300); (250, 320); (380, 250); (430, 300); (200, 400); (599, 599) ]);
    Alcotest.test_case "Render.Pixel.v refuses a grid of 0 or more than Render.Sampling.max_samples samples" `Quick (fun () ->
        let v = Helpers.valid (Helpers.load_scene "cgfs.scene") in
        List.iter
          (fun samples ->
            match Render.Pixel.v ~samples v with
            | _ -> Alcotest.failf "accepted %d samples" samples
            | exception Invalid_argument _ -> ())
          [ 0; Render.Sampling.max_samples + 1 ];
        Alcotest.(check int) __LOC__ 5 (Render.Pixel.samples (Render.Pixel.v ~samples:5 v)));
  ]
