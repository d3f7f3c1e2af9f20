(* The README's program that builds a scene in code. *)

let tests =
  [
    Alcotest.test_case "the README example builds and renders its scene" `Quick (fun () ->
        let exe =
          match Sys.getenv_opt "RAYTRACE_EXAMPLE" with
          | Some p -> if Filename.is_relative p then Filename.concat (Sys.getcwd ()) p else p
          | None -> Alcotest.fail "RAYTRACE_EXAMPLE is not set"
        in
        let out = Filename.concat (Helpers.temp_dir ()) "hello.ppm" in
        let code, stdout, err = Helpers.run exe [ out ] in
        Alcotest.(check int) err 0 code;
        Alcotest.(check string) __LOC__ ("wrote " ^ out ^ "\n") stdout;
        match (Files.read_ppm out, Files.read_ppm "golden/hello_scene.ppm") with
        | Ok img, Ok expected -> Helpers.check_images ~max_abs:1 "hello_scene" ~expected img
        | Error (`Msg m), _ | _, Error (`Msg m) -> Alcotest.fail m);
  ]
