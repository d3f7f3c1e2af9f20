open Raytrace
module Cone = Private.Cone
let v = Vec3.v
let c = Cone.v ~capped:true ~base:(v (-2.9004224214628866) (-2.480337876993987) 6.388280203706662) ~top:(v (-4.065879288068379) (-1.4434785607412488) 7.965072589187158) ~radius:0.6186857690747427 ~top_radius:0.45026005432254185 (Material.v Color.white)
let sh = Shape.Primitive (Private.Shape_desc.Primitive (Cone.desc, c))
let pr name (x : Vec3.t) = Printf.printf "%s %.17g %.17g %.17g\n" name x.x x.y x.z
let refract (d : Vec3.t) (n : Vec3.t) eta =
  let d = Vec3.unit d in
  let n = if Vec3.dot n d > 0. then Vec3.neg n else n in
  let cosi = -. Vec3.dot n d in
  let k = 1. -. eta *. eta *. (1. -. cosi *. cosi) in
  if k < 0. then None else Some (Vec3.add (Vec3.smul eta d) (Vec3.smul (eta *. cosi -. sqrt k) n))
let () =
  let text = let ic = open_in_bin "/tmp/cone/q4.scene" in let t = really_input_string ic (in_channel_length ic) in close_in ic; t in
  let s = match Scene_file.of_string ~file:"q" text with Ok s -> Scene.of_valid s | Error (`Msg m) -> failwith m in
  let w = Scene.width s and h = Scene.height s in
  let cam = Scene.camera s in
  let vp = Viewport.of_canvas (Scene.viewport s) ~canvas_width:w ~canvas_height:h 0 (-3) in
  let origin = cam.position and direction = Camera.direction cam vp in
  pr "O" origin; pr "D" direction;
  let n, f = Cone.intersect c ~origin ~direction in
  Printf.printf "kernel %.17g %.17g\n" n f;
  List.iter (fun (t, nn) -> Printf.printf "literal %.17g " t; pr "n" nn) (Cone.desc.literal c ~origin ~direction);
  let p = Vec3.add origin (Vec3.smul n direction) in
  let nk = Shape.normal sh p in pr "P" p; pr "kernel normal" nk;
  match refract direction nk (1. /. 1.0438605555746818) with
  | None -> print_endline "TIR"
  | Some d2 ->
    pr "refracted" d2;
    let n2, f2 = Cone.intersect c ~origin:p ~direction:d2 in
    Printf.printf "exit kernel %.17g %.17g\n" n2 f2;
    List.iter (fun (t, nn) -> Printf.printf "exit literal %.17g " t; pr "n" nn) (Cone.desc.literal c ~origin:p ~direction:d2);
    let q = Vec3.add p (Vec3.smul f2 d2) in
    pr "Q" q; pr "kernel normal at Q" (Shape.normal sh q);
    let l = v 0.9514016072100341 0.5914358962910063 (-0.7626515484578615) in
    let nq = Shape.normal sh q in
    let nq = if Vec3.dot nq d2 > 0. then Vec3.neg nq else nq in
    Printf.printf "n.L %.17g\n" (Vec3.dot nq l);
    let r = Vec3.sub (Vec3.smul (2. *. Vec3.dot nq l) nq) l in
    Printf.printf "R.V %.17g\n" (Vec3.dot r (Vec3.neg d2));
    let a, b = Cone.intersect c ~origin:q ~direction:l in
    Printf.printf "shadow from Q: %.17g %.17g\n" a b
