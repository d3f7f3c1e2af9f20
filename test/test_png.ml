(* PNG files through camlimages: exact round trips, other programs' files,
   and damaged files reported, never crashing. *)
open Raytrace
module Png_file = Raytrace_png.Png_file
module Image_file = Raytrace_png.Image_file

let ok = function Ok x -> x | Error (`Msg m) -> Alcotest.fail m
let error = function Ok _ -> Alcotest.fail "expected an error" | Error (`Msg m) -> m
let image () = Helpers.image_exn (Scene.with_overrides ~width:23 ~height:17 Scene.cgfs)

let write_string path s =
  let oc = open_out_bin path in
  output_string oc s;
  close_out oc

let be32 s o = Int32.to_int (String.get_int32_be s o)

let tests =
  [
    Alcotest.test_case "a PNG reads back to the same bytes" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let path = Filename.concat dir "a.png" in
        let img = image () in
        ok (Png_file.write_file path img);
        Helpers.check_images __LOC__ ~expected:img (ok (Png_file.read_file path));
        Alcotest.(check (array string)) __LOC__ [| "a.png" |] (Sys.readdir dir));
    Alcotest.test_case "the file is an 8-bit RGB PNG of the image's size" `Quick (fun () ->
        let png = ok (Png_file.to_string (image ())) in
        Alcotest.(check string) __LOC__ "\137PNG\r\n\026\n" (String.sub png 0 8);
        (* IHDR: length 13, then width, height, bit depth 8, colour type 2 (RGB). *)
        Alcotest.(check string) __LOC__ "IHDR" (String.sub png 12 4);
        Alcotest.(check (list int)) __LOC__ [ 23; 17; 8; 2 ]
          [ be32 png 16; be32 png 20; Char.code png.[24]; Char.code png.[25] ]);
    Alcotest.test_case "ImageMagick's PNG of a PPM reads as the PPM's pixels" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let ppm = Filename.concat dir "a.ppm" and png = Filename.concat dir "a.png" in
        let img = image () in
        ok (Files.write_ppm ppm img);
        let code, _, err = Helpers.run "/usr/bin/convert" [ ppm; png ] in
        Alcotest.(check int) err 0 code;
        Helpers.check_images __LOC__ ~expected:img (ok (Image_file.read_file png));
        (* And ImageMagick reads ours back to the same PPM. *)
        let ours = Filename.concat dir "b.png" and back = Filename.concat dir "b.ppm" in
        ok (Png_file.write_file ours img);
        let code, _, err = Helpers.run "/usr/bin/convert" [ ours; back ] in
        Alcotest.(check int) err 0 code;
        Helpers.check_images __LOC__ ~expected:img (ok (Files.read_ppm back)));
    Alcotest.test_case "damaged PNG files are errors, not crashes" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let png = ok (Png_file.to_string (image ())) in
        let n = String.length png in
        (* libpng fails inside the pixel data on these: camlimages would
           crash (SIGSEGV) in this process. *)
        let flipped = Bytes.of_string png in
        Bytes.set flipped (n / 2) (Char.chr (Char.code png.[n / 2] lxor 0xff));
        List.iter
          (fun (name, contents, expected) ->
            let path = Filename.concat dir name in
            write_string path contents;
            Alcotest.(check string) name (path ^ expected) (error (Image_file.read_file path)))
          [
            ("truncated.png", String.sub png 0 (n / 2), ": cannot decode the PNG file: corrupt or truncated data");
            ("flipped.png", Bytes.to_string flipped, ": cannot decode the PNG file: corrupt or truncated data");
            ("header.png", String.sub png 0 20, ": not a PNG file: no IHDR header");
            ("text.png", "hello", ": not a PNG file (it lacks the PNG signature)");
          ]);
    Alcotest.test_case "the format follows the file name, PPM by default" `Quick (fun () ->
        let fmt = Alcotest.testable (fun ppf f -> Format.pp_print_string ppf (Image_file.extension f)) ( = ) in
        List.iter
          (fun (path, expected) -> Alcotest.check fmt path expected (Image_file.format_of_path path))
          [ ("a.png", Image_file.Png); ("A.PNG", Png); ("a.ppm", Ppm); ("a", Ppm); ("png", Ppm); ("a.png.ppm", Ppm) ]);
  ]
