type t = { samples : int; adaptive : int option; subsample : bool }

let max_samples = 64
let max_threshold = 255
let msg fmt = Printf.ksprintf (fun m -> Error (`Msg m)) fmt

let v ?(samples = 1) ?adaptive ?(subsample = false) () =
  if samples < 1 || samples > max_samples then
    msg "samples must lie in [1, %d] (an N x N grid per pixel), got %d" max_samples samples
  else
    match adaptive with
    | Some th when th < 0 || th > max_threshold ->
        msg "the adaptive threshold must lie in [0, %d], got %d" max_threshold th
    | Some _ when samples < 3 || samples land 1 = 0 ->
        msg "adaptive sampling needs an odd number of samples >= 3, whose grid has the pixel's centre in its middle, got %d"
          samples
    | _ when subsample && samples > 1 ->
        msg "subsampling traces one ray per pixel: it cannot be combined with samples > 1"
    | _ -> Ok { samples; adaptive; subsample }

let one = { samples = 1; adaptive = None; subsample = false }
let is_one s = s.samples = 1 && not s.subsample
let averaging s = s.samples > 1

let to_string s =
  let n = s.samples in
  match s.adaptive with
  | Some th -> Printf.sprintf "adaptive %dx%d t=%d" n n th
  | None -> if s.subsample then "subsampled" else Printf.sprintf "%dx%d" n n

type ints = (int64, Bigarray.int64_elt, Bigarray.c_layout) Bigarray.Array1.t

type plan = {
  s : t;
  img : Image.t;
  first : Image.buffer;  (** Adaptive: the bytes of each pixel's first ray. *)
  saved : Trace.samples;  (** Adaptive: its clamped colour. *)
  hits : ints;  (** The sphere each pixel's (first) ray hit, [-1] for none. *)
}

let plan s img ~shared =
  let pixels = Image.width img * Image.height img in
  let adaptive = s.adaptive <> None in
  let needs_hits = adaptive || s.subsample in
  (* Empty buffers need no shared memory. *)
  let bytes n =
    if shared && n > 0 then Parallel.shared_bytes n
    else Bigarray.Array1.create Bigarray.int8_unsigned Bigarray.c_layout n
  in
  let floats n =
    if shared && n > 0 then Parallel.shared_floats n
    else Bigarray.Array1.create Bigarray.float64 Bigarray.c_layout n
  in
  let ints n =
    if shared && n > 0 then Parallel.shared_ints n else Bigarray.Array1.create Bigarray.int64 Bigarray.c_layout n
  in
  (* Unused buffers are empty; every used element is written before it is read. *)
  {
    s;
    img;
    first = bytes (if adaptive then 3 * pixels else 0);
    saved = floats (if adaptive then 3 * pixels else 0);
    hits = ints (if needs_hits then pixels else 0);
  }

let passes pl = if pl.s.adaptive <> None || pl.s.subsample then 2 else 1

(* One ray per pixel, or the full grid. *)
let full pl tr r =
  let width = Image.width pl.img and height = Image.height pl.img in
  let buffer = Image.buffer pl.img and n = pl.s.samples in
  let gy = Canvas.y_of_row ~height r in
  for x = 0 to width - 1 do
    let gx = Canvas.x_of_column ~width x and k = 3 * ((r * width) + x) in
    if n = 1 then begin
      Trace.pixel tr gx gy;
      Trace.store tr buffer k
    end
    else begin
      Trace.average tr gx gy ~n;
      Trace.store_average tr buffer k ~count:(n * n)
    end
  done

let set_hit (hits : ints) p tr = Bigarray.Array1.unsafe_set hits p (Int64.of_int (Trace.hit_sphere tr))
let hit (hits : ints) p = Int64.to_int (Bigarray.Array1.unsafe_get hits p)

(* Adaptive, pass 0: each pixel's first ray, kept three ways. *)
let first_rays pl tr r =
  let width = Image.width pl.img and height = Image.height pl.img in
  let gy = Canvas.y_of_row ~height r in
  for x = 0 to width - 1 do
    let p = (r * width) + x in
    Trace.pixel tr (Canvas.x_of_column ~width x) gy;
    Trace.store tr pl.first (3 * p);
    Trace.save tr pl.saved (3 * p);
    set_hit pl.hits p tr
  done

(* Do the first rays of pixels [p] and [q] differ: another sphere, or a
   channel more than [th] apart? *)
let[@inline] apart (f : Image.buffer) th p q c =
  abs (Bigarray.Array1.unsafe_get f ((3 * p) + c) - Bigarray.Array1.unsafe_get f ((3 * q) + c)) > th

let differ pl th p q =
  hit pl.hits p <> hit pl.hits q || apart pl.first th p q 0 || apart pl.first th p q 1 || apart pl.first th p q 2

(* Adaptive, pass 1: refine the pixels that differ from a neighbour, copy
   the others' first bytes. Reads only what pass 0 wrote. *)
let refine pl th tr r =
  let width = Image.width pl.img and height = Image.height pl.img in
  let buffer = Image.buffer pl.img and n = pl.s.samples in
  let gy = Canvas.y_of_row ~height r in
  for x = 0 to width - 1 do
    let p = (r * width) + x in
    let k = 3 * p in
    if
      (x > 0 && differ pl th p (p - 1))
      || (x < width - 1 && differ pl th p (p + 1))
      || (r > 0 && differ pl th p (p - width))
      || (r < height - 1 && differ pl th p (p + width))
    then begin
      Trace.average_reusing tr pl.saved k (Canvas.x_of_column ~width x) gy ~n;
      Trace.store_average tr buffer k ~count:(n * n)
    end
    else
      for c = 0 to 2 do
        Bigarray.Array1.unsafe_set buffer (k + c) (Bigarray.Array1.unsafe_get pl.first (k + c))
      done
  done

(* Subsampling: pixel [p] from its neighbours [a] and [b], when both hit
   the same sphere; traced in full when they differ or [b] is outside. *)
let subsampled pl tr gx gy p a b ~inside =
  let ha = hit pl.hits a in
  if inside && ha = hit pl.hits b then Trace.pixel_assuming tr gx gy ha else Trace.pixel tr gx gy;
  Trace.store tr (Image.buffer pl.img) (3 * p);
  set_hit pl.hits p tr

(* Subsampling, pass 0, even rows: even columns traced, odd ones from their
   left and right neighbours. *)
let even_row pl tr r =
  let width = Image.width pl.img and height = Image.height pl.img in
  let buffer = Image.buffer pl.img in
  let gy = Canvas.y_of_row ~height r in
  let x = ref 0 in
  while !x < width do
    let p = (r * width) + !x in
    Trace.pixel tr (Canvas.x_of_column ~width !x) gy;
    Trace.store tr buffer (3 * p);
    set_hit pl.hits p tr;
    x := !x + 2
  done;
  let x = ref 1 in
  while !x < width do
    let p = (r * width) + !x in
    subsampled pl tr (Canvas.x_of_column ~width !x) gy p (p - 1) (p + 1) ~inside:(!x + 1 < width);
    x := !x + 2
  done

(* Subsampling, pass 1, odd rows: every pixel from the pixels above and
   below, written by pass 0. *)
let odd_row pl tr r =
  let width = Image.width pl.img and height = Image.height pl.img in
  let gy = Canvas.y_of_row ~height r in
  for x = 0 to width - 1 do
    let p = (r * width) + x in
    subsampled pl tr (Canvas.x_of_column ~width x) gy p (p - width) (p + width) ~inside:(r + 1 < height)
  done

let rows pl i tr ~first ~step =
  let p = Trace.prepared tr in
  if Image.width pl.img <> p.width || Image.height pl.img <> p.height then
    invalid_arg "Sampling.rows: image size differs from the canvas";
  if Trace.averaging tr <> averaging pl.s then invalid_arg "Sampling.rows: the tracer's averaging differs";
  if step < 1 then invalid_arg "Sampling.rows: step < 1";
  if i < 0 || i >= passes pl then invalid_arg "Sampling.rows: no such pass";
  let height = Image.height pl.img in
  (* Subsampling's passes work on every other row; the others on all rows.
     A plain loop: a closure per pass would show in the allocation test. *)
  let every = if pl.s.subsample then 2 else 1 in
  let r = ref ((if pl.s.subsample then i else 0) + (every * first)) in
  while !r < height do
    (match pl.s.adaptive with
    | Some _ when i = 0 -> first_rays pl tr !r
    | Some th -> refine pl th tr !r
    | None -> if not pl.s.subsample then full pl tr !r else if i = 0 then even_row pl tr !r else odd_row pl tr !r);
    r := !r + (every * step)
  done
