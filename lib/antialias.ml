let clamp x = if x > 255. then 255. else if x > 0. then x else 0. [@@inline]

let store tr buffer gx gy ~n k =
  if n < 1 then invalid_arg "Antialias.store: n < 1";
  let r = ref 0. and g = ref 0. and b = ref 0. in
  for j = 0 to n - 1 do
    for i = 0 to n - 1 do
      Trace.sample tr gx gy ~i ~j ~n;
      r := !r +. clamp (Trace.red tr);
      g := !g +. clamp (Trace.green tr);
      b := !b +. clamp (Trace.blue tr)
    done
  done;
  let count = Float.of_int (n * n) in
  Bigarray.Array1.unsafe_set buffer k (Trace.to_byte (!r /. count));
  Bigarray.Array1.unsafe_set buffer (k + 1) (Trace.to_byte (!g /. count));
  Bigarray.Array1.unsafe_set buffer (k + 2) (Trace.to_byte (!b /. count))

let image ?(n = 3) (scene : Scene.t) =
  if n < 1 then invalid_arg "Antialias.image: n < 1";
  let tr = Trace.create (Prepared.prepare scene) in
  let img = Image.create scene.width scene.height in
  let buffer = Image.buffer img and width = scene.width and height = scene.height in
  for row = 0 to height - 1 do
    let gy = Canvas.y_of_row ~height row in
    for col = 0 to width - 1 do
      store tr buffer (Canvas.x_of_column ~width col) gy ~n (3 * ((row * width) + col))
    done
  done;
  img
