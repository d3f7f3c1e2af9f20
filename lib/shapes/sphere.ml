type t = {
  center : Vec3.t;
  radius : float;
  color : Color.t;
  specular : float;
  reflective : float;
  transparency : float;
  refractive_index : float;
  fresnel : bool;
  pattern : Pattern.t option;
}
[@@deriving eq]

let error fmt = Printf.ksprintf (fun m -> Error (`Msg m)) fmt
let error_pp fmt = Format.kasprintf (fun m -> Error (`Msg m)) fmt
let matte = -1.

let v ?(specular = matte) ?(reflective = 0.) ?(transparency = 0.) ?(refractive_index = 1.) ?(fresnel = false)
    ?pattern ~center ~radius color =
  { center; radius; color; specular; reflective; transparency; refractive_index; fresnel; pattern }

let is_matte s = s.specular = matte
let num = Float_text.to_string
let check_center c = Limits.check_point "sphere center" c

let check_radius r = Limits.check_size "sphere radius" r

let check_color c =
  if Color.in_gamut c then Ok c
  else (error_pp "sphere color channels must lie in [0, 255], got %a" Color.pp c)

let specular_ok s = Float.is_finite s && (s = matte || s >= 0.)

let check_specular s =
  if specular_ok s then Ok s
  else (error "sphere specular must be -1 (matte) or >= 0, got %s" (num s))

let reflective_ok r = r >= 0. && r <= 1.

let check_reflective r =
  if reflective_ok r then Ok r
  else (error "sphere reflective must lie in [0, 1], got %s" (num r))

let check_pattern = function
  | None -> Ok None
  | Some p -> Result.map Option.some (Pattern.validate ~form:"sphere" p)
let check_transparency x =
  if x >= 0. && x <= 1. then Ok x
  else (error "sphere transparency must lie in [0, 1], got %s" (num x))

let check_refractive_index n =
  if n > 0. && Float.is_finite n then Ok n
  else (error "sphere refractive-index must be > 0 and finite, got %s" (num n))

(* Each part of a hit's colour has its own weight (local 1 - r - t): the
   sum may not exceed 1. *)
let check_split ~reflective ~transparency =
  if reflective +. transparency <= 1. then Ok ()
  else (error "sphere reflective + transparency must be <= 1, got %s + %s" (num reflective) (num transparency))

let validate s =
  let ( let* ) = Result.bind in
  let* _ = check_center s.center in
  let* _ = check_radius s.radius in
  let* _ = check_color s.color in
  let* _ = check_specular s.specular in
  let* _ = check_reflective s.reflective in
  let* _ = check_transparency s.transparency in
  let* _ = check_refractive_index s.refractive_index in
  let* () = check_split ~reflective:s.reflective ~transparency:s.transparency in
  let* _ = check_pattern s.pattern in
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

(* The optional fields print only when they differ from their defaults, as
   a scene file would write them. *)
let pp_optional_material ?(transparency = 0.) ?(refractive_index = 1.) ?(fresnel = false) ppf ~specular ~reflective =
  if specular <> matte then Format.fprintf ppf " (specular %s)" (Float_text.to_string specular);
  if reflective <> 0. then Format.fprintf ppf " (reflective %s)" (Float_text.to_string reflective);
  if transparency <> 0. then Format.fprintf ppf " (transparency %s)" (Float_text.to_string transparency);
  if refractive_index <> 1. then
    Format.fprintf ppf " (refractive-index %s)" (Float_text.to_string refractive_index);
  if fresnel then Format.pp_print_string ppf " (fresnel true)"

let pp ppf s =
  Format.fprintf ppf "(sphere (center %a) (radius %s) (color %a)" Vec3.pp_components s.center
    (Float_text.to_string s.radius) Color.pp_components s.color;
  pp_optional_material ~transparency:s.transparency ~refractive_index:s.refractive_index ~fresnel:s.fresnel ppf
    ~specular:s.specular ~reflective:s.reflective;
  Pattern.pp_optional ppf s.pattern;
  Format.pp_print_string ppf ")"

let show s = Format.asprintf "%a" pp s
