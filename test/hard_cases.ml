open Raytrace
open QCheck.Gen

type case = { sphere : Sphere.t; origin : Vec3.t; direction : Vec3.t }

let pow10 lo hi = map (fun e -> 10. ** e) (float_range lo hi)

(* A uniformly random unit vector. *)
let unit_vec =
  let* z = float_range (-1.) 1. and* phi = float_range 0. (2. *. Float.pi) in
  let s = sqrt (1. -. (z *. z)) in
  return (Vec3.v (s *. cos phi) (s *. sin phi) z)

(* A unit vector orthogonal to [w]. *)
let orthogonal w =
  let+ v = unit_vec in
  let p = Vec3.cross w v in
  if Vec3.norm2 p = 0. then Vec3.unit (Vec3.cross w Vec3.ox) else Vec3.unit p

let translation =
  oneof
    [
      return Vec3.zero;
      map3 Vec3.v (float_range (-1e6) 1e6) (float_range (-1e6) 1e6) (float_range (-1e6) 1e6);
      map (Vec3.smul 1e6) unit_vec;
    ]

let sphere center radius = Helpers.sphere ~center ~radius Color.white

(* A ray from distance [ratio * r] aimed at the point at [offset * r] from
   the center, across the line of sight: offset < 1 hits, > 1 misses. *)
let aimed ~ratio ~offset =
  let* scale = pow10 (-6.) 6. and* t = translation in
  let* r = map (fun k -> scale *. k) (pow10 (-3.) 0.) in
  let* w = unit_vec in
  let* side = orthogonal w in
  let* ratio = ratio and* offset = offset and* dscale = pow10 (-3.) 3. in
  let c = Vec3.add t (Vec3.smul scale w) in
  let o = Vec3.add c (Vec3.smul (ratio *. r) w) in
  let target = Vec3.add c (Vec3.smul (offset *. r) side) in
  return { sphere = sphere c r; origin = o; direction = Vec3.smul dscale (Vec3.sub target o) }

let far_tiny = aimed ~ratio:(pow10 3. 9.) ~offset:(float_range 0. 1.2)

let grazing =
  aimed ~ratio:(pow10 0.05 4.)
    ~offset:(let* e = pow10 (-12.) (-2.) and* sign = bool in
             return (if sign then 1. +. e else 1. -. e))

(* Just above a huge sphere (the ground of the reference scene is r = 5000),
   looking in a random direction. *)
let huge =
  let* scale = pow10 (-6.) 6. and* t = translation in
  let* r = map (fun k -> scale *. k) (pow10 2. 6.) in
  let* w = unit_vec and* h = pow10 (-9.) (-1.) and* dir = unit_vec in
  let c = Vec3.add t (Vec3.smul scale w) in
  let o = Vec3.add c (Vec3.smul (r *. (1. +. h)) w) in
  (* Mostly nearly horizontal: the hard, grazing directions. *)
  let* tilt = float_range (-0.01) 0.01 in
  let horizontal = Vec3.sub dir (Vec3.smul (Vec3.dot dir w) w) in
  let d = if Vec3.norm2 horizontal = 0. then dir else Vec3.add (Vec3.unit horizontal) (Vec3.smul tilt w) in
  return { sphere = sphere c r; origin = o; direction = d }

(* From a point of the surface (rounded to floats), outward or inward. *)
let on_surface =
  let* scale = pow10 (-6.) 6. and* t = translation in
  let* r = map (fun k -> scale *. k) (pow10 (-3.) 3.) in
  let* w = unit_vec and* dir = unit_vec and* pos = pow10 (-3.) 3. in
  let c = Vec3.add t (Vec3.smul scale w) in
  return { sphere = sphere c r; origin = Vec3.add c (Vec3.smul r w); direction = Vec3.smul pos dir }

let general =
  let* scale = pow10 (-6.) 6. and* t = translation in
  let* r = map (fun k -> scale *. k) (pow10 (-2.) 1.) in
  let* w = unit_vec and* side = unit_vec and* dist = float_range 0. 10. in
  let* dscale = pow10 (-3.) 3. in
  let c = Vec3.add t (Vec3.smul scale w) in
  let o = Vec3.add c (Vec3.smul (dist *. r) side) in
  let* target = map (fun v -> Vec3.add c (Vec3.smul (2. *. r) v)) unit_vec in
  return { sphere = sphere c r; origin = o; direction = Vec3.smul dscale (Vec3.sub target o) }

let families =
  [
    ("far, tiny spheres", far_tiny);
    ("grazing rays", grazing);
    ("huge spheres, from just above", huge);
    ("rays from a surface point", on_surface);
    ("general position", general);
  ]

let pp ppf c =
  let v (p : Vec3.t) = Printf.sprintf "(%h %h %h)" p.x p.y p.z in
  Format.fprintf ppf "center %s radius %h origin %s direction %s" (v c.sphere.center)
    c.sphere.radius (v c.origin) (v c.direction)
