open Raytrace

let q = Q.of_float
let qv (v : Vec3.t) = (q v.x, q v.y, q v.z)
let dot (ax, ay, az) (bx, by, bz) = Q.(add (add (mul ax bx) (mul ay by)) (mul az bz))
let sub (ax, ay, az) (bx, by, bz) = Q.(sub ax bx, sub ay by, sub az bz)
let add (ax, ay, az) (bx, by, bz) = Q.(add ax bx, add ay by, add az bz)
let scale k (x, y, z) = Q.(mul k x, mul k y, mul k z)

let line_distance2 (s : Sphere.t) ~origin ~direction =
  let f = sub (qv origin) (qv s.center) and d = qv direction in
  let b = dot f d in
  Q.(sub (dot f f) (div (mul b b) (dot d d)))

let surface_distance (s : Sphere.t) ~origin ~direction t =
  let pc = add (sub (qv origin) (qv s.center)) (scale (q t) (qv direction)) in
  let pc2 = dot pc pc in
  let g = Q.(sub pc2 (mul (q s.radius) (q s.radius))) in
  Float.abs (Q.to_float g) /. (sqrt (Q.to_float pc2) +. s.radius)
