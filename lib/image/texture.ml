(* The channels in a bigarray, not a string: a decoder's buffer (a PNG's,
   decoded by another process into shared memory) becomes the texture
   without a copy, and the kernel's typed reads of it are inlined. *)
type t = { width : int; height : int; channels : Image.buffer }
type wrap = Repeat | Clamp

let v ~width ~height bytes =
  if width < 1 || height < 1 then invalid_arg (Printf.sprintf "Texture.v: size %dx%d is empty" width height);
  if String.length bytes <> 3 * width * height then invalid_arg "Texture.v: bytes do not match the size";
  let channels = Bigarray.Array1.create Bigarray.int8_unsigned Bigarray.c_layout (String.length bytes) in
  String.iteri (fun k c -> Bigarray.Array1.unsafe_set channels k (Char.code c)) bytes;
  { width; height; channels }

let of_image img = { width = Image.width img; height = Image.height img; channels = Image.buffer img }

let width t = t.width
let height t = t.height
let channels t = t.channels

let pixel t x y =
  if x < 0 || y < 0 || x >= t.width || y >= t.height then
    invalid_arg (Printf.sprintf "Texture.pixel: (%d, %d) outside %dx%d" x y t.width t.height);
  let k = 3 * ((y * t.width) + x) in
  let c i = float (Bigarray.Array1.get t.channels (k + i)) in
  Color.v (c 0) (c 1) (c 2)

let image t = Image.of_buffer t.width t.height t.channels
let equal a b = a.width = b.width && a.height = b.height && Image.equal (image a) (image b)
let pp ppf t = Format.fprintf ppf "<texture %dx%d>" t.width t.height

(* The column (or row) [i] of an axis of [n] pixels, brought inside. *)
let[@inline] inside wrap n i =
  match wrap with
  | Repeat ->
      let r = i mod n in
      if r < 0 then r + n else r
  | Clamp -> if i < 0 then 0 else if i >= n then n - 1 else i

(* The pixel coordinate [f] of a texture coordinate: its floor must fit an
   int whatever [f] is. Far beyond the image, [Repeat] keeps the
   fractional position of the coordinate itself ([u - floor u] is exact),
   so that [fx] stays small; a NaN or infinity becomes 0. *)
let[@inline] pixel_coordinate wrap (c : float) n =
  let c = if Float.is_finite c then c else 0. in
  let c = match wrap with Repeat -> c -. Float.floor c | Clamp -> Float.min 2. (Float.max (-1.) c) in
  (c *. float n) -. 0.5

let[@inline] byte t k = float (Bigarray.Array1.unsafe_get (t.channels : Image.buffer) k)

let lookup ~wrap_u ~wrap_v t (uv : float array) i (dst : float array) j =
  if i < 0 || i + 1 >= Array.length uv || j < 0 || j + 2 >= Array.length dst then
    invalid_arg "Texture.lookup: index outside its array";
  let fx = pixel_coordinate wrap_u (Array.unsafe_get uv i) t.width in
  let fy = pixel_coordinate wrap_v (1. -. Array.unsafe_get uv (i + 1)) t.height in
  let x0 = Float.floor fx and y0 = Float.floor fy in
  let tx = fx -. x0 and ty = fy -. y0 in
  let x0 = int_of_float x0 and y0 = int_of_float y0 in
  let xa = inside wrap_u t.width x0 and xb = inside wrap_u t.width (x0 + 1) in
  let ya = inside wrap_v t.height y0 and yb = inside wrap_v t.height (y0 + 1) in
  let k00 = 3 * ((ya * t.width) + xa) and k10 = 3 * ((ya * t.width) + xb) in
  let k01 = 3 * ((yb * t.width) + xa) and k11 = 3 * ((yb * t.width) + xb) in
  for c = 0 to 2 do
    (* [a + t (b - a)] rather than [(1 - t) a + t b]: equal neighbours
       give their value exactly, and the result stays between [a] and [b]
       (rounding is monotonic), so within [0, 255]. *)
    let a = byte t (k00 + c) and b = byte t (k01 + c) in
    let top = a +. (tx *. (byte t (k10 + c) -. a)) in
    let bottom = b +. (tx *. (byte t (k11 + c) -. b)) in
    Array.unsafe_set dst (j + c) (top +. (ty *. (bottom -. top)))
  done

let color ?(wrap_u = Repeat) ?(wrap_v = Repeat) t u v =
  let dst = [| 0.; 0.; 0. |] in
  lookup ~wrap_u ~wrap_v t [| u; v |] 0 dst 0;
  Color.v dst.(0) dst.(1) dst.(2)
