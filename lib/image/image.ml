type buffer = (int, Bigarray.int8_unsigned_elt, Bigarray.c_layout) Bigarray.Array1.t
type t = { width : int; height : int; data : buffer }

let of_buffer width height data =
  if width < 1 || height < 1 then invalid_arg "Image.of_buffer: empty size";
  if Bigarray.Array1.dim data <> 3 * width * height then
    invalid_arg "Image.of_buffer: buffer size does not match";
  { width; height; data }

let create width height =
  if width < 1 || height < 1 then
    invalid_arg (Printf.sprintf "Image.create: size %dx%d is empty" width height);
  let data = Bigarray.Array1.create Bigarray.int8_unsigned Bigarray.c_layout (3 * width * height) in
  Bigarray.Array1.fill data 0;
  { width; height; data }

let width img = img.width
let height img = img.height
let buffer img = img.data

let check img x y fn =
  if x < 0 || y < 0 || x >= img.width || y >= img.height then
    invalid_arg
      (Printf.sprintf "Image.%s: pixel (%d, %d) outside %dx%d image" fn x y img.width img.height)

let get img x y =
  check img x y "get";
  let k = 3 * ((y * img.width) + x) in
  (img.data.{k}, img.data.{k + 1}, img.data.{k + 2})

let set img x y r g b =
  check img x y "set";
  let byte c = if c < 0 || c > 255 then invalid_arg "Image.set: channel outside [0, 255]" in
  byte r;
  byte g;
  byte b;
  let k = 3 * ((y * img.width) + x) in
  img.data.{k} <- r;
  img.data.{k + 1} <- g;
  img.data.{k + 2} <- b

let channel img k = img.data.{k}
let equal a b =
  a.width = b.width && a.height = b.height
  &&
  let n = Bigarray.Array1.dim a.data in
  let rec same k = k >= n || (a.data.{k} = b.data.{k} && same (k + 1)) in
  same 0

let copy img =
  let c = create img.width img.height in
  Bigarray.Array1.blit img.data c.data;
  c

let blit ~src ~dst ~x ~y =
  if x < 0 || y < 0 || x + src.width > dst.width || y + src.height > dst.height then
    invalid_arg "Image.blit: source does not fit in destination";
  let row_bytes = 3 * src.width in
  for row = 0 to src.height - 1 do
    Bigarray.Array1.blit
      (Bigarray.Array1.sub src.data (row * row_bytes) row_bytes)
      (Bigarray.Array1.sub dst.data (3 * (((y + row) * dst.width) + x)) row_bytes)
  done

let sub img ~x ~y ~w ~h =
  if x < 0 || y < 0 || w < 1 || h < 1 || x + w > img.width || y + h > img.height then
    invalid_arg "Image.sub: rectangle outside the image";
  let out = create w h in
  let row_bytes = 3 * w in
  for row = 0 to h - 1 do
    Bigarray.Array1.blit
      (Bigarray.Array1.sub img.data (3 * (((y + row) * img.width) + x)) row_bytes)
      (Bigarray.Array1.sub out.data (row * row_bytes) row_bytes)
  done;
  out
