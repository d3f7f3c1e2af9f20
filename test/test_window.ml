(* The Graphics window, in a virtual X server: what it shows is what
   `raytrace render` writes. Runs when xvfb-run is installed. *)
open Raytrace

let on_path tool =
  List.exists
    (fun dir -> Sys.file_exists (Filename.concat dir tool))
    (String.split_on_char ':' (Option.value (Sys.getenv_opt "PATH") ~default:""))

let tools = [ "xvfb-run"; "xwd"; "xdotool"; "convert" ]

let tests =
  [
    Alcotest.test_case "a screenshot of the window equals the rendered image" `Slow (fun () ->
        if not (on_path "xvfb-run") then print_endline "skipped: xvfb-run is not installed"
        else begin
        (match List.filter (fun t -> not (on_path t)) tools with
        | [] -> ()
        | missing -> Alcotest.failf "xvfb-run is installed but not %s (make deps)" (String.concat ", " missing));
        let dir = Helpers.temp_dir () in
        List.iter
          (fun name ->
            let shot = Filename.concat dir (name ^ ".ppm") in
            let code, _, err =
              Helpers.run "xvfb-run"
                [ "-a"; "-s"; "-screen 0 1024x768x24"; "./window_screenshot.sh"; Helpers.raytrace ();
                  Helpers.scene_path name; shot ]
            in
            if code <> 0 then Alcotest.failf "%s: screenshot failed (%d): %s" name code err;
            match Ppm.read_file shot with
            | Error (`Msg m) -> Alcotest.fail m
            | Ok img ->
                Helpers.check_images ~max_abs:1 ("window of " ^ name)
                  ~expected:(Render.image_exn (Helpers.load_scene name)) img)
          [ "cgfs.scene"; "cgfs-camera.scene" ]
        end);
  ]
