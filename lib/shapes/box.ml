type t = { min : Vec3.t; max : Vec3.t; material : Material.t } [@@deriving eq]

let v ~min ~max material = { min; max; material }

let validate b =
  let ( let* ) = Result.bind in
  let* _ = Limits.check_point "box min" b.min in
  let* _ = Limits.check_point "box max" b.max in
  let* () =
    if b.min.x < b.max.x && b.min.y < b.max.y && b.min.z < b.max.z then Ok ()
    else
      Error (`Msg (Format.asprintf "box min must be below max on every axis, got %a and %a" Vec3.pp b.min Vec3.pp b.max))
  in
  let* _ = Material.validate ~form:"box" b.material in
  Ok b

let store b g o =
  g.(o) <- b.min.x;
  g.(o + 1) <- b.min.y;
  g.(o + 2) <- b.min.z;
  g.(o + 3) <- b.max.x;
  g.(o + 4) <- b.max.y;
  g.(o + 5) <- b.max.z

(* Narrows [s.near, s.far] to the slab [lo, hi] of one axis, for the ray
   coordinate [o + t d]; [false] if the ray misses the slab. *)
let[@inline] slab (s : Scratch.t) lo hi o d =
  if d = 0. then lo <= o && o <= hi
  else begin
    let t0 = (lo -. o) /. d and t1 = (hi -. o) /. d in
    let enter = if t0 < t1 then t0 else t1 and exit = if t0 < t1 then t1 else t0 in
    if enter > s.near then s.near <- enter;
    if exit < s.far then s.far <- exit;
    true
  end

let[@inline never] roots (s : Scratch.t) g o =
  s.near <- neg_infinity;
  s.far <- infinity;
  if
    slab s (Array.unsafe_get g o) (Array.unsafe_get g (o + 3)) s.ox s.dx
    && slab s (Array.unsafe_get g (o + 1)) (Array.unsafe_get g (o + 4)) s.oy s.dy
    && slab s (Array.unsafe_get g (o + 2)) (Array.unsafe_get g (o + 5)) s.oz s.dz
    && s.near <= s.far
  then true
  else begin
    s.near <- infinity;
    s.far <- infinity;
    false
  end

(* The index of the smallest of [a0 .. a5], the first of equals. *)
let[@inline] smallest (a0 : float) a1 a2 a3 a4 a5 =
  let f01 = if a1 < a0 then 1 else 0 in
  let m01 = if a1 < a0 then a1 else a0 in
  let f23 = if a3 < a2 then 3 else 2 in
  let m23 = if a3 < a2 then a3 else a2 in
  let f45 = if a5 < a4 then 5 else 4 in
  let m45 = if a5 < a4 then a5 else a4 in
  if m23 < m01 then if m45 < m23 then f45 else f23 else if m45 < m01 then f45 else f01

let[@inline never] normal (s : Scratch.t) g o =
  let face =
    smallest
      (Float.abs (s.px -. g.(o)))
      (Float.abs (s.px -. g.(o + 3)))
      (Float.abs (s.py -. g.(o + 1)))
      (Float.abs (s.py -. g.(o + 4)))
      (Float.abs (s.pz -. g.(o + 2)))
      (Float.abs (s.pz -. g.(o + 5)))
  in
  let sign = if face land 1 = 0 then -1. else 1. in
  let axis = face lsr 1 in
  s.nx <- (if axis = 0 then sign else 0.);
  s.ny <- (if axis = 1 then sign else 0.);
  s.nz <- (if axis = 2 then sign else 0.)

(* An axis's entry and exit parameters, as [slab] finds them; an axis
   along which the ray does not move bounds nothing. *)
let[@inline] entry lo hi o d =
  if d = 0. then neg_infinity
  else
    let t0 = (lo -. o) /. d and t1 = (hi -. o) /. d in
    if t0 < t1 then t0 else t1

let[@inline] exit lo hi o d =
  if d = 0. then infinity
  else
    let t0 = (lo -. o) /. d and t1 = (hi -. o) /. d in
    if t0 < t1 then t1 else t0

let[@inline never] hit_normal (s : Scratch.t) g o =
  let ex = entry (Array.unsafe_get g o) (Array.unsafe_get g (o + 3)) s.ox s.dx in
  let ey = entry (Array.unsafe_get g (o + 1)) (Array.unsafe_get g (o + 4)) s.oy s.dy in
  let ez = entry (Array.unsafe_get g (o + 2)) (Array.unsafe_get g (o + 5)) s.oz s.dz in
  let xx = exit (Array.unsafe_get g o) (Array.unsafe_get g (o + 3)) s.ox s.dx in
  let xy = exit (Array.unsafe_get g (o + 1)) (Array.unsafe_get g (o + 4)) s.oy s.dy in
  let xz = exit (Array.unsafe_get g (o + 2)) (Array.unsafe_get g (o + 5)) s.oz s.dz in
  (* As [roots] narrows: a later axis replaces an earlier one only if
     strictly beyond it, so the first axis of equals decides. *)
  let y_in = ey > ex in
  let near_xy = if y_in then ey else ex in
  let z_in = ez > near_xy in
  let near = if z_in then ez else near_xy in
  let y_out = xy < xx in
  let far_xy = if y_out then xy else xx in
  let z_out = xz < far_xy in
  (* The root at or before the entry (the line touching an edge has
     [near = far]) enters; the other leaves. *)
  let entering = s.near <= near in
  let axis =
    if entering then if z_in then 2 else if y_in then 1 else 0 else if z_out then 2 else if y_out then 1 else 0
  in
  let d = if axis = 0 then s.dx else if axis = 1 then s.dy else s.dz in
  let sign = if (d > 0.) = entering then -1. else 1. in
  s.nx <- (if axis = 0 then sign else 0.);
  s.ny <- (if axis = 1 then sign else 0.);
  s.nz <- (if axis = 2 then sign else 0.)

let intersect b ~origin ~direction =
  let g = Array.make 6 0. and s = Scratch.create () in
  store b g 0;
  Scratch.set_ray s origin direction;
  if roots s g 0 then (s.near, s.far) else (infinity, infinity)

let pp ppf b =
  Format.fprintf ppf "(box (min %a) (max %a) %a)" Vec3.pp_components b.min Vec3.pp_components b.max Material.pp
    b.material

let show b = Format.asprintf "%a" pp b
