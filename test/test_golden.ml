(* Golden images: every scene of scenes/ at most 64 pixels wide or high,
   and a few at more samples a pixel too, checked in under test/golden/. `make golden` regenerates them with this
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

(* Scenes whose integrals (a lens's blur) want more than one ray a
   pixel to be worth looking at: also checked at [--samples n], against
   golden/NAME-samplesN.ppm. *)
let sampled = [ ("focus.scene", 4) ]

(* [img] against the golden image [file], or written there under
   RAYTRACE_WRITE_GOLDEN. *)
let golden name file img =
  match Sys.getenv_opt "RAYTRACE_WRITE_GOLDEN" with
  | Some dir -> (
      let path = Filename.concat dir file in
      match Files.write_ppm path img with
      | Ok () -> print_endline ("wrote " ^ path)
      | Error (`Msg m) -> Alcotest.fail m)
  | None -> (
      match Files.read_ppm (Filename.concat "golden" file) with
      | Error (`Msg m) -> Alcotest.failf "%s: no golden image (%s); run `make golden`" name m
      | Ok expected -> Helpers.check_images ~max_abs:1 name ~expected img)

let tests =
  [
    Alcotest.test_case "every scene matches its golden image within 1 per channel" `Quick (fun () ->
        List.iter
          (fun name ->
            let img = Helpers.image_exn (small (Helpers.load_scene name)) in
            golden name (Filename.basename (golden_path name)) img)
          (Helpers.scene_names ());
        List.iter
          (fun (name, samples) ->
            let img = Helpers.image_exn ~samples (small (Helpers.load_scene name)) in
            let file = Printf.sprintf "%s-samples%d.ppm" (Filename.remove_extension name) samples in
            golden (Printf.sprintf "%s, --samples %d" name samples) file img)
          sampled);
    Alcotest.test_case "the reference scenes are the published CGFS images, byte for byte" `Quick
      (fun () ->
        List.iter
          (fun (name, digest) ->
            let img = Helpers.image_exn (Helpers.load_scene name) in
            Alcotest.(check string) name digest (Digest.to_hex (Digest.string (Image.Ppm.to_string img))))
          cgfs_digests);
  ]
