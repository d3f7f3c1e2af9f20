let header ?(comments = []) img =
  let comment c =
    if String.contains c '\n' || String.contains c '\r' then
      invalid_arg "Ppm.to_string: a comment contains a line break";
    "# " ^ c ^ "\n"
  in
  Printf.sprintf "P6\n%s%d %d\n255\n" (String.concat "" (List.map comment comments)) (Image.width img)
    (Image.height img)

(* The buffer's bytes are copied 8 at a time: byte by byte, the copy was
   most of the time of writing an image (docs/performance.md, "Numbers
   moved out of the library's comments"). The compiler's primitives read and
   write the 64-bit words unboxed, both little-endian, so the bytes keep
   their order; [copy] checks the bounds once for all of them. *)
external unsafe_get64 : Image.buffer -> int -> int64 = "%caml_bigstring_get64u"
external unsafe_set64 : Bytes.t -> int -> int64 -> unit = "%caml_bytes_set64u"

(* [copy src i dst j len] copies [src.{i .. i + len - 1}] to [dst] at [j]. *)
let copy (src : Image.buffer) i dst j len =
  if i < 0 || j < 0 || len < 0 || i + len > Bigarray.Array1.dim src || j + len > Bytes.length dst then
    invalid_arg "Ppm.copy";
  let words = len / 8 in
  for w = 0 to words - 1 do
    unsafe_set64 dst (j + (8 * w)) (unsafe_get64 src (i + (8 * w)))
  done;
  for k = 8 * words to len - 1 do
    Bytes.unsafe_set dst (j + k) (Char.unsafe_chr (Bigarray.Array1.unsafe_get src (i + k)))
  done

let to_string ?comments img =
  let data = Image.buffer img in
  let h = header ?comments img in
  let n = Bigarray.Array1.dim data in
  let b = Bytes.create (String.length h + n) in
  Bytes.blit_string h 0 b 0 (String.length h);
  copy data 0 b (String.length h) n;
  Bytes.unsafe_to_string b

(* In chunks: writing a large image costs 64 KiB, not a copy of it. *)
let output_rows oc img ~first ~stop =
  if first < 0 || stop > Image.height img || first > stop then invalid_arg "Ppm.output_rows";
  let data = Image.buffer img and row = 3 * Image.width img in
  let n = stop * row in
  let chunk = Bytes.create (min (n - (first * row)) 65536) in
  let k = ref (first * row) in
  while !k < n do
    let len = min (Bytes.length chunk) (n - !k) in
    copy data !k chunk 0 len;
    output oc chunk 0 len;
    k := !k + len
  done

let output ?comments oc img =
  output_string oc (header ?comments img);
  output_rows oc img ~first:0 ~stop:(Image.height img)

exception Bad of string

let bad fmt = Printf.ksprintf (fun m -> raise (Bad m)) fmt
let is_space c = c = ' ' || c = '\t' || c = '\n' || c = '\r' || c = '\011' || c = '\012'

(* The token at or after [pos], skipping whitespace and comments: its text,
   where it starts, and the position just after it; [None] at the end. *)
let rec token s pos =
  let n = String.length s in
  if pos >= n then None
  else if is_space s.[pos] then token s (pos + 1)
  else if s.[pos] = '#' then
    match String.index_from_opt s pos '\n' with Some nl -> token s (nl + 1) | None -> None
  else
    let stop = ref pos in
    while !stop < n && (not (is_space s.[!stop])) && s.[!stop] <> '#' do
      incr stop
    done;
    Some (String.sub s pos (!stop - pos), pos, !stop)

(* A decimal number: digits only, so "-1" or "0x10" are refused. *)
let number ~at_end what s pos =
  match token s pos with
  | None -> at_end ()
  | Some (tok, start, next) -> (
      let digits = tok <> "" && String.for_all (fun c -> c >= '0' && c <= '9') tok in
      match if digits && String.length tok <= 9 then int_of_string_opt tok else None with
      | Some v -> (v, start, next)
      | None -> bad "%s: expected a decimal number at byte %d, got %S" what start tok)

let decode ~limits s =
  let in_header () = bad "unexpected end of file in the header" in
  let magic = if String.length s >= 3 && is_space s.[2] then String.sub s 0 2 else "" in
  let binary =
    match magic with
    | "P6" -> true
    | "P3" -> false
    | _ -> bad "not a PPM file: it must start with P6 or P3 and a whitespace"
  in
  let w, _, pos = number ~at_end:in_header "width" s 2 in
  let h, _, pos = number ~at_end:in_header "height" s pos in
  let maxval, _, pos = number ~at_end:in_header "maxval" s pos in
  (match Limits.check_image_size limits w h with Ok () -> () | Error (`Msg m) -> bad "%s" m);
  if maxval < 1 || maxval > 255 then bad "maxval must lie in [1, 255], got %d" maxval;
  let n = 3 * w * h in
  let start = pos + 1 in
  (* Checked before allocating, so a lying header cannot ask for memory. *)
  if binary then begin
    if pos >= String.length s || not (is_space s.[pos]) then
      bad "missing whitespace after maxval at byte %d" pos;
    let avail = String.length s - start in
    if avail < n then bad "pixel data is truncated: %d of %d bytes" avail n;
    if avail > n then bad "%d bytes of unexpected data after the pixels" (avail - n)
  end
  else if String.length s - pos < (2 * n) - 1 then bad "pixel data is truncated: fewer than %d samples" n;
  let img = Image.create w h in
  let data = Image.buffer img in
  let scale v = if maxval = 255 then v else ((v * 255) + (maxval / 2)) / maxval in
  if binary then
    for k = 0 to n - 1 do
      let v = Char.code (String.unsafe_get s (start + k)) in
      if v > maxval then bad "sample %d at byte %d exceeds maxval %d" v (start + k) maxval;
      Bigarray.Array1.unsafe_set data k (scale v)
    done
  else begin
    let pos = ref pos in
    for k = 0 to n - 1 do
      let truncated () = bad "pixel data is truncated: %d of %d samples" k n in
      let v, start, next = number ~at_end:truncated "sample" s !pos in
      if v > maxval then bad "sample %d at byte %d exceeds maxval %d" v start maxval;
      Bigarray.Array1.unsafe_set data k (scale v);
      pos := next
    done;
    match token s !pos with
    | Some (_, start, _) -> bad "unexpected data after the pixels at byte %d" start
    | None -> ()
  end;
  img

let of_string ?(limits = Limits.default) s = match decode ~limits s with img -> Ok img | exception Bad m -> Error (`Msg m)

(* The header's room: a P6 header of comments may take 1 MiB
   ([check_file_size]); past that the whole file is read as before. *)
let header_room = 1048576 + 4096

(* [n] bytes of [s] from [o] into [b] from [k]. *)
let blit_string s o (b : Image.buffer) k n =
  for i = 0 to n - 1 do
    Bigarray.Array1.unsafe_set b (k + i) (Char.code (String.unsafe_get s (o + i)))
  done

(* [n] bytes of [ic] into [b] from [k], through a chunk of 64 KiB: the
   channel reads no bigarray. *)
let input_channels ic (b : Image.buffer) k n =
  let chunk = Bytes.create (min n 65536) in
  let rec go k n =
    if n > 0 then begin
      let m = min n (Bytes.length chunk) in
      really_input ic chunk 0 m;
      blit_string (Bytes.unsafe_to_string chunk) 0 b k m;
      go (k + m) (n - m)
    end
  in
  go k n

(* A P6 file's pixels read straight into the texture's channels: the file's
   first [header_room] bytes (or all of it), then the rest of its pixels
   into the bigarray that becomes the texture. Only the texture is held,
   not the file's text as well ([of_string]: twice the pixels). The
   checks and their messages are [decode]'s, in its order; a P3 file, or
   a header that does not end within the room, is read whole and decoded
   by [decode]. *)
let texture_of_channel ?(limits = Limits.default) ic ~length =
  let whole prefix =
    let rest = really_input_string ic (length - String.length prefix) in
    let img = decode ~limits (prefix ^ rest) in
    Texture.of_image img
  in
  let read () =
    let prefix = really_input_string ic (min length header_room) in
    let in_header () = raise Exit in
    let binary = String.length prefix >= 3 && String.sub prefix 0 2 = "P6" && is_space prefix.[2] in
    match
      if not binary then None
      else
        let w, _, pos = number ~at_end:in_header "width" prefix 2 in
        let h, _, pos = number ~at_end:in_header "height" prefix pos in
        let maxval, _, pos = number ~at_end:in_header "maxval" prefix pos in
        (* The maxval's token may go on past the room: not its end. *)
        if pos >= String.length prefix && String.length prefix < length then None else Some (w, h, maxval, pos)
    with
    | exception Exit -> whole prefix
    | None -> whole prefix
    | Some (w, h, maxval, pos) ->
        (match Limits.check_image_size limits w h with Ok () -> () | Error (`Msg m) -> bad "%s" m);
        if maxval < 1 || maxval > 255 then bad "maxval must lie in [1, 255], got %d" maxval;
        let n = 3 * w * h in
        let start = pos + 1 in
        if pos >= length || not (is_space prefix.[pos]) then bad "missing whitespace after maxval at byte %d" pos;
        let avail = length - start in
        if avail < n then bad "pixel data is truncated: %d of %d bytes" avail n;
        if avail > n then bad "%d bytes of unexpected data after the pixels" (avail - n);
        let b = Bigarray.Array1.create Bigarray.int8_unsigned Bigarray.c_layout n in
        let have = String.length prefix - start in
        blit_string prefix start b 0 have;
        input_channels ic b have (n - have);
        if maxval < 255 then
          for k = 0 to n - 1 do
            let v = Bigarray.Array1.unsafe_get b k in
            if v > maxval then bad "sample %d at byte %d exceeds maxval %d" v (start + k) maxval;
            Bigarray.Array1.unsafe_set b k (((v * 255) + (maxval / 2)) / maxval)
          done;
        Texture.of_image (Image.of_buffer w h b)
  in
  match read () with
  | t -> Ok t
  | exception Bad m -> Error (`Msg m)
  | exception End_of_file -> Error (`Msg "the file ended before its length: was it written to while read?")

(* A P6 image at the pixel bound, with room for a long commented header;
   anything larger is refused before it is read. *)
let check_file_size ?(limits = Limits.default) n =
  let pixels = Limits.bound limits `Pixels in
  let most = (3. *. pixels) +. 1048576. in
  if Float.of_int n <= most then Ok n
  else
    Error
      (`Msg (Printf.sprintf "the file is %d bytes, more than a PPM image of at most %.0f pixels can be (%.0f bytes; set %s to raise the limit)"
         n pixels most (Limits.variable `Pixels)))

(* The comments between the magic number and the maxval: the header ends
   after three numbers. *)
let header_comments s =
  let n = String.length s in
  let rec scan pos numbers acc =
    if numbers = 3 || pos >= n then List.rev acc
    else if is_space s.[pos] then scan (pos + 1) numbers acc
    else if s.[pos] = '#' then
      let stop = match String.index_from_opt s pos '\n' with Some nl -> nl | None -> n in
      let text = String.sub s (pos + 1) (stop - pos - 1) in
      let text = if String.length text > 0 && text.[0] = ' ' then String.sub text 1 (String.length text - 1) else text in
      let text =
        if String.length text > 0 && text.[String.length text - 1] = '\r' then String.sub text 0 (String.length text - 1)
        else text
      in
      scan stop numbers (text :: acc)
    else
      let stop = ref pos in
      while !stop < n && (not (is_space s.[!stop])) && s.[!stop] <> '#' do
        incr stop
      done;
      scan !stop (numbers + 1) acc
  in
  if n >= 2 && (String.sub s 0 2 = "P6" || String.sub s 0 2 = "P3") then scan 2 0 [] else []
