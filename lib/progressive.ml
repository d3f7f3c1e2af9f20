type t = {
  tr : Trace.t;
  img : Image.t;
  samples : int;
  passes : (int * int) array;  (** Block size and samples per pixel of each pass. *)
  mutable pass : int;  (** Index of the current pass; [Array.length passes] once finished. *)
  mutable top : int;  (** First row of the next band. *)
}

type band = { size : int; top : int; rows : int }

let coarsest = 16

(* 2 x 2 blocks would cost as much to draw as single pixels (one request
   per block), for little preview: the pass after 4 is the full one. *)
let passes samples =
  let plain = [ (16, 1); (8, 1); (4, 1); (1, 1) ] in
  Array.of_list (if samples = 1 then plain else plain @ [ (1, samples) ])

let create ?(samples = 1) (scene : Scene.t) =
  if samples < 1 then invalid_arg "Progressive.create: samples < 1";
  let tr = Trace.create (Prepared.prepare scene) in
  { tr; img = Image.create scene.width scene.height; samples; passes = passes samples; pass = 0; top = 0 }

let finished (r : t) = r.pass >= Array.length r.passes
let image r = r.img
let samples r = r.samples
let tracer r = r.tr

let trace_band (r : t) =
  let width = Image.width r.img and height = Image.height r.img in
  let buffer = Image.buffer r.img and row = r.top in
  let size, n = r.passes.(r.pass) in
  let gy = Canvas.y_of_row ~height row in
  if n > 1 then
    for col = 0 to width - 1 do
      Antialias.store r.tr buffer (Canvas.x_of_column ~width col) gy ~n (3 * ((row * width) + col))
    done
  else
    (* The grid of the previous one-sample pass holds every pixel traced
       so far: the block sizes divide each other. *)
    let prev = if r.pass = 0 then 0 else fst r.passes.(r.pass - 1) in
    let row_done = prev > 0 && row mod prev = 0 in
    let col = ref 0 in
    while !col < width do
      if not (row_done && !col mod prev = 0) then begin
        Trace.pixel r.tr (Canvas.x_of_column ~width !col) gy;
        Trace.store r.tr buffer (3 * ((row * width) + !col))
      end;
      col := !col + size
    done

let step (r : t) =
  if finished r then None
  else begin
    let height = Image.height r.img in
    let size = fst r.passes.(r.pass) in
    trace_band r;
    let band = { size; top = r.top; rows = min size (height - r.top) } in
    r.top <- r.top + size;
    if r.top >= height then begin
      r.pass <- r.pass + 1;
      r.top <- 0
    end;
    Some band
  end
