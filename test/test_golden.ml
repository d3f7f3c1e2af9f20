(* Golden images: every scene of scenes/ at most 64 pixels wide or high,
   checked in under test/golden/. `make golden` regenerates them with this
   very code (RAYTRACE_WRITE_GOLDEN names the directory to write to): only
   after a deliberate change of the pictures, said in the commit. *)
open Raytrace

(* The scene's canvas shrunk to fit 64 x 64, keeping its aspect ratio. *)
let small (s : Scene.t) =
  let longest = max (Scene.width s) (Scene.height s) in
  let fit n = max 1 (n * 64 / longest) in
  Scene.with_overrides ~width:(fit (Scene.width s)) ~height:(fit (Scene.height s)) s

let golden_path name = Filename.concat "golden" (Filename.remove_extension name ^ ".ppm")

(* MD5 of the C reference's 600 x 600 renders (../shared/reference/cref.c),
   which are byte-identical to the published CGFS demo images
   raytracer-05 and raytracer-06. *)
let cgfs_digests =
  [ ("cgfs.scene", "78688d9454e67a720258aed697ea3e68"); ("cgfs-camera.scene", "e018b05b9fbde13b6e12bcdc2776645d") ]

let tests =
  [
    Alcotest.test_case "every scene matches its golden image within 1 per channel" `Quick (fun () ->
        List.iter
          (fun name ->
            let img = Helpers.image_exn (small (Helpers.load_scene name)) in
            match Sys.getenv_opt "RAYTRACE_WRITE_GOLDEN" with
            | Some dir -> (
                let path = Filename.concat dir (Filename.basename (golden_path name)) in
                match Files.write_ppm path img with
                | Ok () -> print_endline ("wrote " ^ path)
                | Error (`Msg m) -> Alcotest.fail m)
            | None -> (
                match Files.read_ppm (golden_path name) with
                | Error (`Msg m) -> Alcotest.failf "%s: no golden image (%s); run `make golden`" name m
                | Ok expected -> Helpers.check_images ~max_abs:1 name ~expected img))
          (Helpers.scene_names ()));
    Alcotest.test_case "the reference scenes are the published CGFS images, byte for byte" `Quick
      (fun () ->
        List.iter
          (fun (name, digest) ->
            let img = Helpers.image_exn (Helpers.load_scene name) in
            Alcotest.(check string) name digest (Digest.to_hex (Digest.string (Image.Ppm.to_string img))))
          cgfs_digests);
  ]
