

let signature = "\137PNG\r\n\026\n"
let is_png s = String.length s >= 8 && String.sub s 0 8 = signature
let ( let* ) = Result.bind

(* libpng prints to stderr, and camlimages' stubs (still the writer's)
   crash (SIGSEGV) on a file that breaks off or goes wrong after its
   header. So libpng runs in a child process, its stderr silenced,
   writing the pixels into shared memory, which becomes the image: a
   crash there becomes an error message here. *)
let in_child ~pixels ~crash f =
  let out = Parallel.shared_bytes (max 1 (3 * pixels)) in
  let message = Parallel.shared_bytes 256 in
  let work _ =
    let null = Unix.openfile "/dev/null" [ O_WRONLY ] 0 in
    Unix.dup2 null Unix.stderr;
    let tell m = String.iteri (fun i c -> if i < 255 then message.{i} <- Char.code c) m in
    match f out with
    | () -> ()
    | exception (Failure m as e) ->
        tell m;
        raise e
    | exception Out_of_memory ->
        tell "not enough memory";
        raise Out_of_memory
  in
  match Parallel.run 1 work with
  | Ok () -> Ok out
  | Error (`Msg why) ->
      let text = String.init 255 (fun i -> Char.chr message.{i}) in
      let text = match String.index_opt text '\000' with Some n -> String.sub text 0 n | None -> text in
      (* SIGKILL is what the kernel sends when memory runs out: not a
         corrupt file. *)
      let killed = String.length why >= 7 && String.sub why (String.length why - 7) 7 = "SIGKILL" in
      Error
        (if text <> "" then text
         else if killed then "the decoding process was killed by SIGKILL (out of memory?)"
         else crash)

(* In the child: the file's pixels, alpha dropped, decoded by libpng
   straight into [out] (png_stubs.c), with the transforms camlimages'
   readers ask of it: [Png.load_as_rgb24]'s, then, where it refuses the
   file (an RGB file with a transparent colour), [Png.load]'s. *)
external decode_into : string -> Image.buffer -> int -> int -> unit = "raytrace_png_decode"

let decode path ~width ~height out = decode_into path out width height

(* The most memory decoding takes, in bytes: the pixels in shared memory
   (3 bytes a pixel, which become the image) and, in the decoding
   process, libpng's rows and a pointer a row (at most 1 more a pixel). *)
let decode_bytes pixels = 4 * pixels

let be32 s o =
  (Char.code s.[o] lsl 24) lor (Char.code s.[o + 1] lsl 16) lor (Char.code s.[o + 2] lsl 8) lor Char.code s.[o + 3]

let read_file ?(limits = Limits.default) path =
  let fail m = Error (`Msg (Printf.sprintf "%s: %s" path m)) in
  let* contents = File_io.read path in
  if not (is_png contents) then fail "not a PNG file"
  else if String.length contents < 33 || String.sub contents 12 4 <> "IHDR" then fail "not a PNG file: no IHDR header"
  else
    (* The size, read here to bound the memory before libpng sees it. *)
    let width = be32 contents 16 and height = be32 contents 20 in
    (* The same bound as a PPM image's. *)
    match Limits.check_image_size limits width height with
    | Error (`Msg m) -> fail m
    | Ok () -> (
        let pixels = width * height in
        match Parallel.available_memory () with
        | Some available when decode_bytes pixels > available ->
            let gib n = Float.of_int n /. 1073741824. in
            fail
              (Printf.sprintf "a %dx%d PNG image needs %.2f GiB of memory to decode, but only %.2f GiB are available"
                 width height (gib (decode_bytes pixels)) (gib available))
        | _ -> (
            match in_child ~pixels ~crash:"corrupt or truncated data" (decode path ~width ~height) with
            | exception Failure m -> fail m
            | Ok out -> Ok (Image.of_buffer width height (Bigarray.Array1.sub out 0 (3 * pixels)))
            | Error m -> fail ("cannot decode the PNG file: " ^ m)))

let to_string img =
  let w = Image.width img and h = Image.height img in
  let data = Bytes.create (3 * w * h) in
  let buf = Image.buffer img in
  for k = 0 to (3 * w * h) - 1 do
    Bytes.unsafe_set data k (Char.unsafe_chr (Bigarray.Array1.unsafe_get buf k))
  done;
  match Filename.temp_file "raytrace" ".png" with
  | exception Sys_error e -> Error (`Msg ("cannot create a temporary PNG file: " ^ e))
  | tmp ->
      Fun.protect
        ~finally:(fun () -> try Sys.remove tmp with Sys_error _ -> ())
        (fun () ->
          let save _ = Png.save tmp [] (Images.Rgb24 (Rgb24.create_with w h [] data)) in
          match in_child ~pixels:0 ~crash:"libpng failed" save with
          | Ok _ -> File_io.read tmp
          | Error m -> Error (`Msg (Printf.sprintf "cannot encode the PNG file: %s" m)))

let write_file path img =
  let* png = to_string img in
  File_io.write_atomic path (fun oc -> output_string oc png)
