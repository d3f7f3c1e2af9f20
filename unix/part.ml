type t = {
  canvas_width : int;
  canvas_height : int;
  region : Render.Region.t;
  settings : (string * string) list;
  image : Image.t;
}

let ( let* ) = Result.bind
let msg fmt = Printf.ksprintf (fun m -> Error (`Msg m)) fmt
let magic = "raytrace-part 1"
let reserved = [ "raytrace-part"; "canvas"; "region" ]
let has_break s = String.contains s '\n' || String.contains s '\r'

let v ~canvas_width ~canvas_height ~region ~settings image =
  let bad m = invalid_arg ("Part.v: " ^ m) in
  if not (Render.Region.contains region ~width:canvas_width ~height:canvas_height) then
    bad "region outside the canvas";
  if Image.width image <> region.w || Image.height image <> region.h then bad "image size differs from the region";
  List.iteri
    (fun i (k, value) ->
      if k = "" || String.contains k ' ' || has_break k || has_break value then bad "malformed setting";
      if List.mem k reserved || List.exists (fun (k', _) -> k' = k) (List.filteri (fun j _ -> j < i) settings)
      then bad ("repeated or reserved setting " ^ k))
    settings;
  { canvas_width; canvas_height; region; settings; image }

let settings ?frame ?(samples = 1) ?adaptive ?(subsample = false) ?(renderer = "fast") ?(files = "") (scene : Scene.t) =
  (* Without files, the digest of the text alone, as parts had it before
     files were digested: such parts still merge with them. *)
  let text = Scene_file.to_string scene in
  let digest = if files = "" then Digest.string text else Digest.string (text ^ "\nfiles " ^ files) in
  [ ("depth", string_of_int (Scene.depth scene)); ("samples", string_of_int samples) ]
  @ (match adaptive with Some th -> [ ("adaptive", string_of_int th) ] | None -> [])
  @ (if subsample then [ ("subsample", "true") ] else [])
  @ [ ("renderer", renderer) ]
  @ (match frame with Some f -> [ ("frame", string_of_int f) ] | None -> [])
  @ [ ("scene", Digest.to_hex digest) ]

let comments p =
  let r = p.region in
  magic
  :: Printf.sprintf "canvas %d %d" p.canvas_width p.canvas_height
  :: Format.asprintf "region %a" Render.Region.pp_corners r
  :: List.map (fun (k, v) -> k ^ " " ^ v) p.settings

let to_string p = Image.Ppm.to_string ~comments:(comments p) p.image
let write_file path p = Files.write_ppm ~comments:(comments p) path p.image

(* "key value" -> (key, value); the value may be empty or hold spaces. *)
let split c =
  match String.index_opt c ' ' with
  | Some i -> (String.sub c 0 i, String.sub c (i + 1) (String.length c - i - 1))
  | None -> (c, "")

let ints what value =
  let words = List.filter (( <> ) "") (String.split_on_char ' ' value) in
  let decimal w = String.length w <= 9 && String.for_all (fun c -> c >= '0' && c <= '9') w in
  if List.for_all decimal words then Ok (List.map int_of_string words)
  else msg "bad %s line %S in the part's header" what value

let decode ~limits s =
  let* image = Image.Ppm.of_string ~limits s in
  match Image.Ppm.header_comments s with
  | first :: rest when first = magic -> (
      let fields = List.map split rest in
      let find k = List.assoc_opt k fields in
      let* canvas = match find "canvas" with Some v -> ints "canvas" v | None -> msg "no canvas line in the part's header" in
      let* corners = match find "region" with Some v -> ints "region" v | None -> msg "no region line in the part's header" in
      let settings = List.filter (fun (k, _) -> not (List.mem k reserved)) fields in
      let* () =
        match List.find_opt (fun (k, _) -> List.length (List.filter (fun (k', _) -> k' = k) fields) > 1) fields with
        | Some (k, _) -> msg "the part's header gives %s twice" k
        | None -> Ok ()
      in
      match (canvas, corners) with
      | [ width; height ], [ x0; y0; x1; y1 ] ->
          let* () =
            match Limits.check_canvas limits width height with
            | Ok () -> Ok ()
            | Error (`Msg m) -> msg "bad canvas in the part's header: %s" m
          in
          let* region = Render.Region.of_corners ~width ~height x0 y0 x1 y1 in
          if Image.width image <> region.w || Image.height image <> region.h then
            msg "the part's pixels are %dx%d but its region %a is %dx%d" (Image.width image) (Image.height image)
              (fun () r -> Format.asprintf "%a" Render.Region.pp_corners r) region region.w region.h
          else if List.exists (fun (k, _) -> k = "") settings then msg "an empty setting in the part's header"
          else Ok { canvas_width = width; canvas_height = height; region; settings; image }
      | [ _; _ ], _ -> msg "the part's region line needs 4 numbers: x0 y0 x1 y1"
      | _ -> msg "the part's canvas line needs 2 numbers: width height")
  | _ ->
      msg
        "not a part of a raytrace render (its header has no \"# %s\" line); render parts with raytrace render --tile or --region"
        magic

let of_string ?(limits = Limits.default) ?(file = "<string>") s =
  Result.map_error (fun (`Msg m) -> `Msg (file ^ ": " ^ m)) (decode ~limits s)

let read_file ?(limits = Limits.default) path =
  let* s = File_io.read ~check_size:(Image.Ppm.check_file_size ~limits) path in
  of_string ~limits ~file:path s

let merge parts =
  match parts with
  | [] -> msg "no parts to merge"
  | (name0, p0) :: _ ->
      let differ (name, p) =
        if p.canvas_width <> p0.canvas_width || p.canvas_height <> p0.canvas_height then
          msg "%s is a part of a %dx%d image, %s of a %dx%d one: they do not fit together" name p.canvas_width
            p.canvas_height name0 p0.canvas_width p0.canvas_height
        else
          let keys = List.sort_uniq String.compare (List.map fst (p0.settings @ p.settings)) in
          (* The scene digest last: a depth or frame that differs is the
             clearer message. *)
          let keys = List.filter (( <> ) "scene") keys @ [ "scene" ] in
          let show s k = match List.assoc_opt k s with Some v -> v | None -> "(none)" in
          match List.find_opt (fun k -> show p.settings k <> show p0.settings k) keys with
          | None -> Ok ()
          | Some "scene" ->
              msg "%s was rendered from a different scene than %s (scene digests %s and %s): they do not fit together"
                name name0 (show p.settings "scene") (show p0.settings "scene")
          | Some k ->
              msg "%s was rendered with %s %s, %s with %s %s: they do not fit together" name k (show p.settings k) name0 k
                (show p0.settings k)
      in
      let* () = List.fold_left (fun acc part -> let* () = acc in differ part) (Ok ()) parts in
      let width = p0.canvas_width and height = p0.canvas_height in
      (* One byte per pixel: covered yet? *)
      (* The canvas is within the pixel bound (checked by [decode]); its
         memory, 4 bytes a pixel, is checked too before it is taken. *)
      let bytes = 4 * width * height in
      let mib n = n / 1048576 in
      match Parallel.available_memory () with
      | Some available when bytes > available ->
          msg "merging a %dx%d image needs %d MiB of memory, but only %d MiB are available" width height (mib bytes)
            (mib available)
      | _ -> (
      match (Bytes.make (width * height) '\000', Image.create width height) with
      | exception Out_of_memory -> msg "not enough memory to merge a %dx%d image (%d MiB)" width height (mib bytes)
      | covered, image ->
      let inside (r : Render.Region.t) x y = x >= r.x && x < r.x + r.w && y >= r.y && y < r.y + r.h in
      let exception Overlap of int * int in
      let place placed (name, p) =
        let* placed = placed in
        let r = p.region in
        match
          for y = r.y to r.y + r.h - 1 do
            let row = y * width in
            for x = r.x to r.x + r.w - 1 do
              if Bytes.unsafe_get covered (row + x) <> '\000' then raise (Overlap (x, y))
            done;
            Bytes.fill covered (row + r.x) r.w '\001'
          done
        with
        | () ->
            Image.blit ~src:p.image ~dst:image ~x:r.x ~y:r.y;
            Ok ((name, p) :: placed)
        | exception Overlap (x, y) ->
            let first = fst (List.find (fun (_, q) -> inside q.region x y) placed) in
            msg "%s and %s overlap at pixel (%d, %d) (column, row): they do not fit together" first name x y
      in
      let* _ = List.fold_left place (Ok []) parts in
      let missing = ref 0 and first = ref (-1) in
      for k = (width * height) - 1 downto 0 do
        if Bytes.unsafe_get covered k = '\000' then begin
          incr missing;
          first := k
        end
      done;
      if !missing = 0 then Ok image
      else
        msg "the parts leave %d of %d pixels uncovered, the first at (%d, %d) (column, row): a part is missing"
          !missing (width * height) (!first mod width) (!first / width))
