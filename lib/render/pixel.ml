type t = { scene : Scene.valid; tr : Trace.t; width : int; height : int; samples : int }

let v ?skips ?(samples = 1) scene =
  let sampling =
    match Sampling.v ~samples () with
    | Ok s -> s
    | Error (`Msg m) -> invalid_arg ("Render.Pixel.v: " ^ m)
  in
  let s = Scene.view (Scene.of_valid scene) in
  let tr = Trace.create ~averaging:(Sampling.averaging sampling) (Prepared.prepare ?skips scene) in
  (* One pixel at a time, for as long as the caller likes: no work bound
     across calls (the ray tree of glass checks one at every hit). *)
  Trace.set_budget tr max_int;
  { scene; tr; width = s.width; height = s.height; samples }

let scene p = p.scene
let samples p = p.samples

(* The samples of [Trace.average], in its order (rows [j], then columns
   [i]) and each clamped as it clamps them: the same floats added in the
   same order give the same sum, so the same bytes as the render's. *)
let average p gx gy =
  let n = p.samples and tr = p.tr in
  let r = ref 0. and g = ref 0. and b = ref 0. in
  for j = 0 to n - 1 do
    for i = 0 to n - 1 do
      Trace.sample tr gx gy ~i ~j ~n;
      r := !r +. Color.clamp (Trace.red tr);
      g := !g +. Color.clamp (Trace.green tr);
      b := !b +. Color.clamp (Trace.blue tr)
    done
  done;
  let c = Float.of_int (n * n) in
  Color.v (!r /. c) (!g /. c) (!b /. c)

let color p x y =
  if x < 0 || y < 0 || x >= p.width || y >= p.height then
    invalid_arg (Printf.sprintf "Render.Pixel.color: (%d, %d) is outside the %dx%d canvas" x y p.width p.height);
  let gx = Canvas.x_of_column ~width:p.width x and gy = Canvas.y_of_row ~height:p.height y in
  if p.samples = 1 then begin
    Trace.pixel p.tr gx gy;
    Color.v (Trace.red p.tr) (Trace.green p.tr) (Trace.blue p.tr)
  end
  else average p gx gy
