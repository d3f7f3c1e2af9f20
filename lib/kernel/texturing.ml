open Scratch
open Tracer

let pi = 4. *. atan 1.
let two_pi = 2. *. pi

(* The mappings of Texture_map, written for the kernel: the hit point in
   locals, (u, v) into [s.tu], [s.tv]. Each formula is the one of
   Texture_map's documentation, computed with the same operations where it
   can be (a plane's unit normal is the one stored, not recomputed). *)

let[@inline] sphere_uv s cx cy cz px py pz =
  let dx = px -. cx and dy = py -. cy and dz = pz -. cz in
  let n = sqrt ((dx *. dx) +. (dy *. dy) +. (dz *. dz)) in
  if not (n > 0.) then begin
    s.tu <- 0.5;
    s.tv <- 0.5
  end
  else begin
    s.tu <- 0.5 +. (Float.atan2 dx (-.dz) /. two_pi);
    (* A rounded quotient may pass 1 in magnitude. *)
    let q = dy /. n in
    let q = if q > 1. then 1. else if q < -1. then -1. else q in
    s.tv <- 0.5 +. (Float.asin q /. pi)
  end

(* The plane's axes [e_u = unit (n x r)], [e_v = e_u x n], with the
   reference [r] of {!Texture_map.planar_axes}: [(0, 0, 1)] for a floor or
   a ceiling ([n x r = (ny, -nx, 0)]), [(0, 1, 0)] for a wall
   ([n x r = (-nz, 0, nx)]). *)
let[@inline] plane_uv (p : Prepared.t) s i px py pz size =
  let g = p.geom and o = Kind.stride * Array.unsafe_get p.at0 i in
  let nx = Array.unsafe_get g (o + 3) and ny = Array.unsafe_get g (o + 4) and nz = Array.unsafe_get g (o + 5) in
  let ay = Float.abs ny in
  let floor = ay > Float.abs nx && ay > Float.abs nz in
  let ux = if floor then ny else -.nz and uy = if floor then -.nx else 0. and uz = if floor then 0. else nx in
  let k = 1. /. sqrt ((ux *. ux) +. (uy *. uy) +. (uz *. uz)) in
  let ux = ux *. k and uy = uy *. k and uz = uz *. k in
  let vx = (uy *. nz) -. (uz *. ny) and vy = (uz *. nx) -. (ux *. nz) and vz = (ux *. ny) -. (uy *. nx) in
  let dx = px -. Array.unsafe_get g o and dy = py -. Array.unsafe_get g (o + 1) and dz = pz -. Array.unsafe_get g (o + 2) in
  s.tu <- ((dx *. ux) +. (dy *. uy) +. (dz *. uz)) /. size;
  s.tv <- ((dx *. vx) +. (dy *. vy) +. (dz *. vz)) /. size

let[@inline] fraction lo hi x = if hi > lo then (x -. lo) /. (hi -. lo) else 0.

(* The face nearest the point, the first in Texture_map's order on a tie
   (a later face wins only when strictly nearer), then its (u, v). *)
let[@inline] box_uv s g o px py pz =
  let x0 = Array.unsafe_get g o and y0 = Array.unsafe_get g (o + 1) and z0 = Array.unsafe_get g (o + 2) in
  let x1 = Array.unsafe_get g (o + 3) and y1 = Array.unsafe_get g (o + 4) and z1 = Array.unsafe_get g (o + 5) in
  let face = 0 and best = Float.abs (px -. x0) in
  let d = Float.abs (px -. x1) in
  let face = if d < best then 1 else face and best = if d < best then d else best in
  let d = Float.abs (py -. y0) in
  let face = if d < best then 2 else face and best = if d < best then d else best in
  let d = Float.abs (py -. y1) in
  let face = if d < best then 3 else face and best = if d < best then d else best in
  let d = Float.abs (pz -. z0) in
  let face = if d < best then 4 else face and best = if d < best then d else best in
  let d = Float.abs (pz -. z1) in
  let face = if d < best then 5 else face in
  let sx = fraction x0 x1 px and sy = fraction y0 y1 py and sz = fraction z0 z1 pz in
  match face with
  | 0 -> s.tu <- 1. -. sz; s.tv <- sy
  | 1 -> s.tu <- sz; s.tv <- sy
  | 2 -> s.tu <- sx; s.tv <- 1. -. sz
  | 3 -> s.tu <- sx; s.tv <- sz
  | 4 -> s.tu <- sx; s.tv <- sy
  | _ -> s.tu <- 1. -. sx; s.tv <- sy

(* A mesh triangle's (u, v) at the ray's point at [s.t] (the hit point
   as [colour_at] computes it), from the corners as the kernel stores
   them and their [vt] in the uv table. *)
let[@inline] triangle_uv (p : Prepared.t) s i =
  Triangle.texcoords_at s p.vertex (Array.unsafe_get p.at0 i) (Array.unsafe_get p.at1 i) (Array.unsafe_get p.at2 i) p.uv (6 * i)

(* {!Texture}'s lookup, on the image's bytes: the pixel coordinate of a
   texture coordinate (a NaN or infinity looks up 0; far out, [repeat]
   keeps the coordinate's fraction), then the column brought inside. *)
let[@inline] pixel_coordinate repeat (c : float) n =
  let c = if c -. c = 0. then c else 0. in
  let c = if repeat then c -. Float.floor c else if c < -1. then -1. else if c > 2. then 2. else c in
  (c *. float n) -. 0.5

let[@inline] inside repeat n i =
  if repeat then
    let r = i mod n in
    if r < 0 then r + n else r
  else if i < 0 then 0
  else if i >= n then n - 1
  else i

let[@inline] byte (x : Image.buffer) k = float (Bigarray.Array1.unsafe_get x k)

let[@inline] blend x k00 k10 k01 k11 tx ty =
  let a = byte x k00 and b = byte x k01 in
  let top = a +. (tx *. (byte x k10 -. a)) in
  let bottom = b +. (tx *. (byte x k11 -. b)) in
  top +. (ty *. (bottom -. top))

(* The texture coordinates, into [s.tu] and [s.tv], of the point
   [px, py, pz] on the surface that tracer [g]'s last hit found in slot
   [i], by [mapping] (not [planar], which takes the texture's size): a
   CSG solid's leaf's (a sphere, a box, or a mesh's triangle with its
   [vt]: Csg's [check_textures]), or the slot's own shape's. *)
let[@inline] coordinates (g : Tracer.t) i mapping px py pz =
  let p = g.p and s = g.s in
  if Array.unsafe_get p.kind i = Kind.Csg then begin
    let geom = Csg.geometry p.csg and o = Csg.surface_offset p.csg g.csg in
    (* A leaf inside transformed operands: the point in their frame, on
       the ray carried there. *)
    Csg.enter_surface_frame p.csg g.csg s;
    let t = s.t in
    let px = s.ox +. (s.dx *. t) and py = s.oy +. (s.dy *. t) and pz = s.oz +. (s.dz *. t) in
    (* A mesh's triangle: the point on that ray, read by Csg. *)
    if mapping = Prepared.uv_mapping then Csg.texcoords p.csg g.csg s;
    Csg.leave_surface_frame p.csg g.csg s;
    if mapping = Prepared.spherical then
      sphere_uv s (Array.unsafe_get geom o) (Array.unsafe_get geom (o + 1)) (Array.unsafe_get geom (o + 2)) px py pz
    else if mapping = Prepared.box_mapping then box_uv s geom o px py pz
  end
  else if mapping = Prepared.spherical then
    sphere_uv s (Array.unsafe_get p.cx i) (Array.unsafe_get p.cy i) (Array.unsafe_get p.cz i) px py pz
  else if mapping = Prepared.box_mapping then box_uv s p.geom (Kind.stride * Array.unsafe_get p.at0 i) px py pz
  else triangle_uv p s i

let[@inline never] colour_at tr m g i =
  let p = tr.p and s = g.s in
  (* The hit point as the tracer computed it, before the robust mode
     moved it off the surface. *)
  let t = s.t in
  let px = s.ox +. (s.dx *. t) and py = s.oy +. (s.dy *. t) and pz = s.oz +. (s.dz *. t) in
  let k = Array.unsafe_get p.texture_of m in
  let e = Prepared.texture_stride * k and table = p.texture_table in
  let mapping = Array.unsafe_get table (e + 3) in
  if mapping = Prepared.planar then plane_uv g.p s i px py pz (Array.unsafe_get p.texture_size k)
  else coordinates g i mapping px py pz;
  (* Texture_map.wraps: [Repeat, Clamp] on a sphere, [Clamp, Clamp] on a
     box, [Repeat, Repeat] on a plane or a mesh. *)
  let repeat_u = mapping <> Prepared.box_mapping and repeat_v = mapping = Prepared.planar || mapping = Prepared.uv_mapping in
  let w = Array.unsafe_get table (e + 1) and h = Array.unsafe_get table (e + 2) in
  let fx = pixel_coordinate repeat_u s.tu w and fy = pixel_coordinate repeat_v (1. -. s.tv) h in
  let x0 = Float.floor fx and y0 = Float.floor fy in
  let tx = fx -. x0 and ty = fy -. y0 in
  let x0 = int_of_float x0 and y0 = int_of_float y0 in
  let xa = inside repeat_u w x0 and xb = inside repeat_u w (x0 + 1) in
  let ya = inside repeat_v h y0 and yb = inside repeat_v h (y0 + 1) in
  let k00 = 3 * ((ya * w) + xa) and k10 = 3 * ((ya * w) + xb) in
  let k01 = 3 * ((yb * w) + xa) and k11 = 3 * ((yb * w) + xb) in
  let x = Array.unsafe_get p.texels (Array.unsafe_get table e) in
  Array.unsafe_set tr.red m (blend x k00 k10 k01 k11 tx ty);
  Array.unsafe_set tr.green m (blend x (k00 + 1) (k10 + 1) (k01 + 1) (k11 + 1) tx ty);
  Array.unsafe_set tr.blue m (blend x (k00 + 2) (k10 + 2) (k01 + 2) (k11 + 2) tx ty)

let colour tr i m = colour_at tr m tr i
