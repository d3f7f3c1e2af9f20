type format = Ppm | Png

let format_of_path path =
  if Filename.check_suffix (String.lowercase_ascii path) ".png" then Png else Ppm

let extension = function Ppm -> ".ppm" | Png -> ".png"

let write_file path img =
  match format_of_path path with Png -> Png_file.write_file path img | Ppm -> Files.write_ppm path img

let read_file ?(limits = Limits.default) path =
  match File_io.read ~check_size:(Image.Ppm.check_file_size ~limits) path with
  | Error e -> Error e
  | Ok contents when Png_file.is_png contents -> Png_file.read_file ~limits path
  | Ok _ when format_of_path path = Png -> Error (`Msg (path ^ ": not a PNG file (it lacks the PNG signature)"))
  | Ok contents -> (
      match Image.Ppm.of_string ~limits contents with
      | Ok img -> Ok img
      | Error (`Msg m) -> Error (`Msg (path ^ ": " ^ m)))

(* The first bytes of [path], at most [n]. *)
let first_bytes path n =
  match open_in_bin path with
  | exception Sys_error e -> Error (`Msg e)
  | ic ->
      Fun.protect
        ~finally:(fun () -> close_in_noerr ic)
        (fun () ->
          let b = Bytes.create n in
          let rec fill k = if k = n then k else match input ic b k (n - k) with 0 -> k | r -> fill (k + r) in
          match fill 0 with k -> Ok (Bytes.sub_string b 0 k) | exception Sys_error e -> Error (`Msg e))

let read_texture ?(limits = Limits.default) path =
  match first_bytes path 8 with
  | Error e -> Error e
  | Ok first when Png_file.is_png first -> Result.map Image.Texture.of_image (Png_file.read_file ~limits path)
  | Ok _ when format_of_path path = Png -> Error (`Msg (path ^ ": not a PNG file (it lacks the PNG signature)"))
  | Ok _ -> Files.read_ppm_texture ~limits path
