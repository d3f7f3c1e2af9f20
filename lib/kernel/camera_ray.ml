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

(* {1 The thin lens} *)

(* The lens's numbers hang off the camera sample's key by a tag of their
   own: the lights chain their index ([>= 0]) there. *)
let lens_tag = -1

(* [Sample_key.unit], written here: a float returned from another module
   is boxed, and this runs per camera ray. *)
let[@inline] unit h = Float.of_int (Sample_key.mix h) *. 0x1p-31

(* Pairs tried before the disc's centre is taken: the chance that all of
   them miss the disc is [(1 - pi/4)^32], below [1e-21]. *)
let tries = 32

(* The lens point of the camera sample whose key is [tr.key]: the first
   of the points [(2 unit (key h 2k) - 1, 2 unit (key h (2k+1)) - 1)],
   [k = 0, 1, ...], that lies inside the unit disc, scaled by the lens's
   radius: uniform over the disc. Rejection, not the concentric map: its
   sine and cosine are not correctly rounded, so native code and
   JavaScript could differ in the last bit, and the web page must give the
   same bytes; a product, a sum and a comparison are the same everywhere.
   The pinhole ray is in [s]; this moves its origin to [O + L], with
   [L = M (l_x, l_y, 0)], and its direction to [D - (d / f) L], so that it
   still meets the pinhole ray's point at [t = f / d] (the focal plane)
   and the viewport plane at [t = 1]. *)
let lens tr =
  let p = tr.p and s = tr.s in
  let cam = p.camera in
  let h = Sample_key.key tr.key lens_tag in
  let x = ref 0. and y = ref 0. and k = ref 0 in
  while !k < tries do
    let u = (2. *. unit (Sample_key.key h (2 * !k))) -. 1. in
    let v = (2. *. unit (Sample_key.key h ((2 * !k) + 1))) -. 1. in
    if (u *. u) +. (v *. v) < 1. then begin
      x := u;
      y := v;
      k := tries
    end
    else incr k
  done;
  let r = 0.5 *. cam.aperture in
  let lx = r *. !x and ly = r *. !y in
  let q = p.viewport.distance /. cam.focal_distance in
  if p.identity_rotation then begin
    s.ox <- s.ox +. lx;
    s.oy <- s.oy +. ly;
    s.dx <- s.dx -. (q *. lx);
    s.dy <- s.dy -. (q *. ly)
  end
  else begin
    let m = cam.rotation in
    let ex = (lx *. m.row0.x) +. (ly *. m.row0.y)
    and ey = (lx *. m.row1.x) +. (ly *. m.row1.y)
    and ez = (lx *. m.row2.x) +. (ly *. m.row2.y) in
    s.ox <- s.ox +. ex;
    s.oy <- s.oy +. ey;
    s.oz <- s.oz +. ez;
    s.dx <- s.dx -. (q *. ex);
    s.dy <- s.dy -. (q *. ey);
    s.dz <- s.dz -. (q *. ez)
  end

let set_lens_pixel tr col row =
  set_pixel tr col row;
  if tr.p.camera.aperture > 0. then lens tr

let set_lens_point tr =
  set_point tr;
  if tr.p.camera.aperture > 0. then lens tr
