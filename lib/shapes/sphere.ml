type t = { center : Vec3.t; radius : float; material : Material.t } [@@deriving eq]

let matte = Material.matte
let v ~center ~radius material = { center; radius; material }
let center s = s.center
let radius s = s.radius
let material s = s.material
let is_matte s = Material.is_matte s.material
let check_center c = Limits.check_point "sphere center" c
let check_radius r = Limits.check_size "sphere radius" r
let check_color c = Material.check_color ~form:"sphere" c
let check_specular x = Material.check_specular ~form:"sphere" x
let check_reflective x = Material.check_reflective ~form:"sphere" x
let check_transparency x = Material.check_transparency ~form:"sphere" x
let check_refractive_index x = Material.check_refractive_index ~form:"sphere" x
let check_split ~reflective ~transparency = Material.check_split ~form:"sphere" ~reflective ~transparency

let validate s =
  let ( let* ) = Result.bind in
  let* _ = check_center s.center in
  let* _ = check_radius s.radius in
  let* _ = Material.validate ~form:"sphere" s.material in
  Ok s

let extent s = Float.max (Float.abs s.center.x) (Float.max (Float.abs s.center.y) (Float.abs s.center.z)) +. s.radius

let quadratic s ~origin ~direction =
  let co = Vec3.sub origin s.center in
  let a = Vec3.dot direction direction in
  let b = 2. *. Vec3.dot co direction in
  let c = Vec3.dot co co -. (s.radius *. s.radius) in
  (a, b, c)

let textbook_roots a b c =
  let discriminant = (b *. b) -. (4. *. a *. c) in
  if discriminant < 0. then (infinity, infinity)
  else
    let sq = sqrt discriminant in
    ((-.b +. sq) /. (2. *. a), (-.b -. sq) /. (2. *. a))

(* The textbook b is 2 <CO, D>; here b = <CO, D>, so the roots are
   (-b +- sqrt (b^2 - a c)) / a and b^2 - a c = a (r^2 - |l|^2). *)
let roots s ~origin ~direction:d =
  let f = Vec3.sub origin s.center in
  let a = Vec3.dot d d in
  let b = Vec3.dot f d in
  let k = b *. (1. /. a) in
  let l = Vec3.sub f (Vec3.smul k d) in
  let l2 = Vec3.dot l l and r2 = s.radius *. s.radius in
  if l2 > r2 then (infinity, infinity)
  else
    let len = sqrt l2 in
    let sq = sqrt (a *. ((s.radius -. len) *. (s.radius +. len))) in
    let q = -.(b +. Float.copy_sign sq b) in
    if q = 0. then (0., 0.)
    else
      let t0 = (Vec3.dot f f -. r2) /. q and t1 = q /. a in
      if t0 <= t1 then (t0, t1) else (t1, t0)

let normal s p =
  let n = Vec3.sub p s.center in
  Vec3.smul (1. /. Vec3.norm n) n

let pp ppf s =
  Format.fprintf ppf "(sphere (center %a) (radius %s) %a)" Vec3.pp_components s.center
    (Float_text.to_string s.radius) Material.pp s.material

let show s = Format.asprintf "%a" pp s
