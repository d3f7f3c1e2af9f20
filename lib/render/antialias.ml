(* The sums stay in the tracer (Trace.average): no float crosses a module
   boundary per sample, and its early stop is exact for averaged samples. *)
let store tr buffer gx gy ~n k =
  if n < 1 then invalid_arg "Antialias.store: n < 1";
  if n = 1 then begin
    Trace.pixel tr gx gy;
    Trace.store tr buffer k
  end
  else begin
    if not (Trace.averaging tr) then invalid_arg "Antialias.store: the tracer does not average";
    Trace.average tr gx gy ~n;
    Trace.store_average tr buffer k ~count:(n * n)
  end

let image ?(n = 3) valid =
  if n < 1 then invalid_arg "Antialias.image: n < 1";
  let tr = Trace.create ~averaging:(n > 1) (Prepared.prepare valid) in
  let scene = Scene.view (Scene.of_valid valid) in
  let img = Image.create scene.width scene.height in
  let buffer = Image.buffer img and width = scene.width and height = scene.height in
  for row = 0 to height - 1 do
    let gy = Canvas.y_of_row ~height row in
    for col = 0 to width - 1 do
      store tr buffer (Canvas.x_of_column ~width col) gy ~n (3 * ((row * width) + col))
    done;
    Trace.check_budget tr
  done;
  img
