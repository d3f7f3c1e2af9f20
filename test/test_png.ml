(* PNG files, written through camlimages, read through libpng: exact
   round trips, other programs' files and every layout read as camlimages
   reads them, and damaged files reported, never crashing. *)
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

(* camlimages' own reading of the file [path] as 8-bit RGB, alpha
   dropped, as this project read PNG files before it decoded them with
   libpng itself (png_stubs.c): [Png.load_as_rgb24], or [Png.load] where
   that refuses the file; [None] for a layout neither gives as RGB. Only
   on well-formed files: camlimages crashes on damaged ones. *)
let camlimages_rgb path =
  let image (b : Rgb24.t) =
    let img = Image.create b.width b.height in
    for y = 0 to b.height - 1 do
      let row = Rgb24.get_scanline b y in
      for x = 0 to b.width - 1 do
        let c k = Char.code (Bytes.get row ((3 * x) + k)) in
        Image.set img x y (c 0) (c 1) (c 2)
      done
    done;
    Some img
  in
  match Png.load_as_rgb24 path [] with
  | Images.Rgb24 b -> image b
  | _ -> None
  | exception Failure _ -> (
      match Png.load path [] with Images.Rgba32 b -> image (Rgb24.of_rgba32 b) | Images.Rgb24 b -> image b | _ -> None)

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
    Alcotest.test_case "every PNG layout reads as camlimages reads it" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let ppm = Filename.concat dir "a.ppm" in
        ok (Files.write_ppm ppm (image ()));
        (* An alpha channel that runs from 0 to 1 left to right. *)
        let alpha = [ "-alpha"; "set"; "-channel"; "A"; "-fx"; "i/w"; "+channel" ] in
        let corner = [ "-transparent"; "rgb(0,0,0)"; "-fill"; "black"; "-draw"; "point 0,0" ] in
        List.iter
          (fun (name, args, format) ->
            let path = Filename.concat dir name in
            let code, _, err = Helpers.run "/usr/bin/convert" ((ppm :: args) @ [ format ^ path ]) in
            Alcotest.(check int) err 0 code;
            match (camlimages_rgb path, Image_file.read_file path) with
            | Some expected, Ok img -> Helpers.check_images name ~expected img
            | None, Error (`Msg m) ->
                Alcotest.(check string) name (path ^ ": cannot decode the PNG file: unsupported PNG layout") m
            | Some _, Error (`Msg m) -> Alcotest.failf "%s: camlimages reads it, this reader: %s" name m
            | None, Ok _ -> Alcotest.failf "%s: camlimages refuses it, this reader does not" name)
          [
            ("rgb8.png", [], "PNG24:");
            ("rgb16.png", [ "-depth"; "16" ], "PNG48:");
            ("rgba8.png", alpha, "PNG32:");
            ("rgba16.png", alpha @ [ "-depth"; "16" ], "PNG64:");
            ("gray8.png", [ "-colorspace"; "Gray"; "-define"; "png:color-type=0"; "-define"; "png:bit-depth=8" ], "");
            ("gray16.png", [ "-colorspace"; "Gray"; "-depth"; "16"; "-define"; "png:color-type=0" ], "");
            ("gray1.png", [ "-monochrome" ], "");
            ("gray-alpha.png", alpha @ [ "-colorspace"; "Gray"; "-define"; "png:color-type=4" ], "");
            ("palette.png", [ "-colors"; "50" ], "PNG8:");
            ("interlaced.png", [ "-interlace"; "PNG" ], "PNG24:");
            ("interlaced-rgba.png", alpha @ [ "-interlace"; "PNG" ], "PNG32:");
            (* A transparent colour (tRNS): load_as_rgb24 refuses the RGB
               file and Png.load reads it; neither reads the palette one. *)
            ("rgb-transparent.png", corner @ [ "-define"; "png:color-type=2"; "-define"; "png:bit-depth=8" ], "");
            ("palette-transparent.png", corner @ [ "-colors"; "50"; "-define"; "png:format=png8" ], "");
          ]);
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
