open Scratch
open Tracer

(* The direction of the camera ray through viewport point [(vx, vy, vz)],
   turned by the camera's matrix [m] unless it is the identity. *)
let[@inline] set_direction s identity (m : Camera.rotation) vx vy vz =
  if identity then begin
    s.dx <- vx;
    s.dy <- vy;
    s.dz <- vz
  end
  else begin
    s.dx <- (vx *. m.row0.x) +. (vy *. m.row0.y) +. (vz *. m.row0.z);
    s.dy <- (vx *. m.row1.x) +. (vy *. m.row1.y) +. (vz *. m.row1.z);
    s.dz <- (vx *. m.row2.x) +. (vy *. m.row2.y) +. (vz *. m.row2.z)
  end

(* The camera ray through viewport point [(vx, vy, d)], in [s]. *)
let[@inline] through tr vx vy =
  let p = tr.p and s = tr.s in
  let cam = p.camera in
  set_direction s p.identity_rotation cam.rotation vx vy p.viewport.distance;
  s.ox <- cam.position.x;
  s.oy <- cam.position.y;
  s.oz <- cam.position.z;
  s.t_min <- 1.;
  s.t_max <- infinity

let[@inline] set_pixel tr col row =
  let p = tr.p in
  through tr (Array.unsafe_get p.column_vx col) (Array.unsafe_get p.row_vy row)

let set_point tr =
  let p = tr.p and s = tr.s in
  let vp = p.viewport in
  (* Viewport point (section 3), multiplied before dividing as written. *)
  let vx = s.gx *. vp.width /. Float.of_int p.width in
  let vy = s.gy *. vp.height /. Float.of_int p.height in
  through tr vx vy
