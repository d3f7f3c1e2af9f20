type t = {
  tr : Trace.t;
  img : Image.t;
  samples : int;
  mutable size : int;  (** Block size of the current pass; [0] once finished. *)
  mutable top : int;  (** First row of the next band. *)
}

type band = { size : int; top : int; rows : int }

let coarsest = 16

let create ?(samples = 1) (scene : Scene.t) =
  if samples < 1 then invalid_arg "Progressive.create: samples < 1";
  let tr = Trace.create (Prepared.prepare scene) in
  { tr; img = Image.create scene.width scene.height; samples; size = coarsest; top = 0 }

let finished (r : t) = r.size = 0
let image r = r.img
let samples r = r.samples
let tracer r = r.tr

(* Pixel [(col, row)] was traced by a coarser pass iff both lie on its grid. *)
let traced_before size col row = size < coarsest && col mod (2 * size) = 0 && row mod (2 * size) = 0

let trace_band (r : t) =
  let width = Image.width r.img and height = Image.height r.img in
  let buffer = Image.buffer r.img and size = r.size and row = r.top in
  let gy = Canvas.y_of_row ~height row in
  if size = 1 && r.samples > 1 then
    for col = 0 to width - 1 do
      Antialias.store r.tr buffer (Canvas.x_of_column ~width col) gy ~n:r.samples (3 * ((row * width) + col))
    done
  else
    let col = ref 0 in
    while !col < width do
      if not (traced_before size !col row) then begin
        Trace.pixel r.tr (Canvas.x_of_column ~width !col) gy;
        Trace.store r.tr buffer (3 * ((row * width) + !col))
      end;
      col := !col + size
    done

let step (r : t) =
  if finished r then None
  else begin
    let height = Image.height r.img in
    trace_band r;
    let band = { size = r.size; top = r.top; rows = min r.size (height - r.top) } in
    r.top <- r.top + r.size;
    if r.top >= height then begin
      r.size <- r.size / 2;
      r.top <- 0
    end;
    Some band
  end
