type t = { scene : Scene.valid; tr : Trace.t; width : int; height : int }

let v ?skips scene =
  let s = Scene.of_valid scene in
  let tr = Trace.create (Prepared.prepare ?skips scene) in
  (* One pixel at a time, for as long as the caller likes: no work bound
     across calls (the ray tree of glass checks one at every hit). *)
  Trace.set_budget tr max_int;
  { scene; tr; width = s.width; height = s.height }

let scene p = p.scene

let color p x y =
  if x < 0 || y < 0 || x >= p.width || y >= p.height then
    invalid_arg (Printf.sprintf "Pixel.color: (%d, %d) is outside the %dx%d canvas" x y p.width p.height);
  Trace.pixel p.tr (Canvas.x_of_column ~width:p.width x) (Canvas.y_of_row ~height:p.height y);
  Color.v (Trace.red p.tr) (Trace.green p.tr) (Trace.blue p.tr)
