type mapping = Spherical | Planar | Box | Uv

let mapping_name = function Spherical -> "spherical" | Planar -> "planar" | Box -> "box" | Uv -> "uv"
let all = [ Spherical; Planar; Box; Uv ]
let mapping_names = List.map mapping_name all
let mapping_of_string s = List.find_opt (fun m -> String.equal (mapping_name m) s) all

let wraps = function
  | Spherical -> (Texture.Repeat, Texture.Clamp)
  | Planar | Uv -> (Texture.Repeat, Texture.Repeat)
  | Box -> (Texture.Clamp, Texture.Clamp)

let pi = 4. *. atan 1.

let spherical ~center p =
  let d = Vec3.sub p center in
  let n = Vec3.norm d in
  if not (n > 0.) then (0.5, 0.5)
  else
    (* [atan2 x (-z)] is 0 at the front, [pi/2] to the right, [pi] at the
       back; [asin] of a rounded quotient may see [|y| / n] above 1. *)
    let u = 0.5 +. (Float.atan2 d.x (-.d.z) /. (2. *. pi)) in
    let s = Float.min 1. (Float.max (-1.) (d.y /. n)) in
    (u, 0.5 +. (Float.asin s /. pi))

let planar_axes (n : Vec3.t) =
  if not (Vec3.is_finite n && Vec3.norm2 n > 0.) then invalid_arg "Texture_map.planar_axes: normal zero or not finite";
  let ay = Float.abs n.y in
  (* A floor's reference is the depth axis; a wall's is up. The normal is
     not parallel to the reference chosen: its largest component is not
     the reference's alone. *)
  let r = if ay > Float.abs n.x && ay > Float.abs n.z then Vec3.oz else Vec3.oy in
  let n = Vec3.unit n in
  let eu = Vec3.unit (Vec3.cross n r) in
  (eu, Vec3.cross eu n)

let planar ~point ~normal ~size p =
  if not (Float.is_finite size && size > 0.) then invalid_arg "Texture_map.planar: size not finite and > 0";
  let eu, ev = planar_axes normal in
  let d = Vec3.sub p point in
  (Vec3.dot d eu /. size, Vec3.dot d ev /. size)

type face = Min_x | Max_x | Min_y | Max_y | Min_z | Max_z

let box_face ~(min : Vec3.t) ~(max : Vec3.t) (p : Vec3.t) =
  let faces =
    [
      (Min_x, Float.abs (p.x -. min.x)); (Max_x, Float.abs (p.x -. max.x));
      (Min_y, Float.abs (p.y -. min.y)); (Max_y, Float.abs (p.y -. max.y));
      (Min_z, Float.abs (p.z -. min.z)); (Max_z, Float.abs (p.z -. max.z));
    ]
  in
  (* The first of the nearest: a later face wins only when strictly nearer. *)
  fst
    (List.fold_left
       (fun (bf, bd) (f, d) -> if d < bd then (f, d) else (bf, bd))
       (List.hd faces) (List.tl faces))

let box ~(min : Vec3.t) ~(max : Vec3.t) (p : Vec3.t) =
  let s lo hi x = if hi > lo then (x -. lo) /. (hi -. lo) else 0. in
  let sx = s min.x max.x p.x and sy = s min.y max.y p.y and sz = s min.z max.z p.z in
  let face = box_face ~min ~max p in
  let u, v =
    match face with
    | Min_z -> (sx, sy)
    | Max_z -> (1. -. sx, sy)
    | Min_x -> (1. -. sz, sy)
    | Max_x -> (sz, sy)
    | Max_y -> (sx, sz)
    | Min_y -> (sx, 1. -. sz)
  in
  (face, u, v)

let barycentric a b c p =
  let e1 = Vec3.sub b a and e2 = Vec3.sub c a and d = Vec3.sub p a in
  let d11 = Vec3.dot e1 e1 and d12 = Vec3.dot e1 e2 and d22 = Vec3.dot e2 e2 in
  let dp1 = Vec3.dot d e1 and dp2 = Vec3.dot d e2 in
  let den = (d11 *. d22) -. (d12 *. d12) in
  if not (den > 0.) then (0., 0.)
  else (((d22 *. dp1) -. (d12 *. dp2)) /. den, ((d11 *. dp2) -. (d12 *. dp1)) /. den)

let interpolate ~b1 ~b2 (u0, v0) (u1, v1) (u2, v2) =
  (u0 +. (b1 *. (u1 -. u0)) +. (b2 *. (u2 -. u0)), v0 +. (b1 *. (v1 -. v0)) +. (b2 *. (v2 -. v0)))

type t = { file : string; mapping : mapping; size : float; image : Texture.t }

let v ?(size = 1.) ~file mapping image = { file; mapping; size; image }

let equal a b =
  String.equal a.file b.file && a.mapping = b.mapping && a.size = b.size && Texture.equal a.image b.image

let pp ppf t =
  Format.fprintf ppf "(texture (file %S) (mapping %s)" t.file (mapping_name t.mapping);
  if t.size <> 1. then Format.fprintf ppf " (size %s)" (Float_text.to_string t.size);
  Format.pp_print_string ppf ")"

let pp_optional ppf = function None -> () | Some t -> Format.fprintf ppf " %a" pp t

let validate ~form t =
  if Float.is_finite t.size && t.size > 0. then Ok t
  else Error (`Msg (Printf.sprintf "%s texture size must be > 0 and finite, got %s" form (Float_text.to_string t.size)))

let mapping_for = function
  | "sphere" -> Some Spherical
  | "plane" -> Some Planar
  | "box" -> Some Box
  | "mesh" -> Some Uv
  | _ -> None
