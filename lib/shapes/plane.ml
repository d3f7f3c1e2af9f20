type t = { point : Vec3.t; normal : Vec3.t; material : Material.t } [@@deriving eq]

let v ~point ~normal material = { point; normal; material }

let validate p =
  let ( let* ) = Result.bind in
  let* _ = Limits.check_point "plane point" p.point in
  let* _ = Limits.check_point "plane normal" p.normal in
  let n = Vec3.norm p.normal in
  let* () =
    if n >= Limits.min_size && Float.is_finite n then Ok ()
    else Error (`Msg (Format.asprintf "plane normal must not be zero, got %a" Vec3.pp p.normal))
  in
  let* _ = Material.validate ~form:"plane" p.material in
  Ok p

(* The normal as given, scaled by a power of two (exactly) so that its
   largest coordinate lies in [1/4, 1/2), is the one the roots are found
   with: the root does not depend on the normal's length, and a ray
   exactly parallel to the plane is so to this normal, not always to the
   rounded unit one (which shading uses). Below the unit normal's
   largest coordinate (at least 1 / sqrt 3), it leaves the shape's
   extent as it was. *)
let store p g o =
  let n = Vec3.unit p.normal in
  g.(o) <- p.point.x;
  g.(o + 1) <- p.point.y;
  g.(o + 2) <- p.point.z;
  g.(o + 3) <- n.x;
  g.(o + 4) <- n.y;
  g.(o + 5) <- n.z;
  let _, e = Float.frexp (Float.max (Float.abs p.normal.x) (Float.max (Float.abs p.normal.y) (Float.abs p.normal.z))) in
  let k = Float.ldexp 1. (-e - 1) in
  g.(o + 6) <- p.normal.x *. k;
  g.(o + 7) <- p.normal.y *. k;
  g.(o + 8) <- p.normal.z *. k

let[@inline never] roots (s : Scratch.t) g o =
  let nx = Array.unsafe_get g (o + 6) and ny = Array.unsafe_get g (o + 7) and nz = Array.unsafe_get g (o + 8) in
  let den = (s.dx *. nx) +. (s.dy *. ny) +. (s.dz *. nz) in
  if den = 0. then begin
    s.near <- infinity;
    s.far <- infinity;
    false
  end
  else begin
    let num =
      ((Array.unsafe_get g o -. s.ox) *. nx)
      +. ((Array.unsafe_get g (o + 1) -. s.oy) *. ny)
      +. ((Array.unsafe_get g (o + 2) -. s.oz) *. nz)
    in
    let t = num /. den in
    s.near <- t;
    s.far <- t;
    true
  end

let[@inline never] normal (s : Scratch.t) g o =
  s.nx <- Array.unsafe_get g (o + 3);
  s.ny <- Array.unsafe_get g (o + 4);
  s.nz <- Array.unsafe_get g (o + 5)

let intersect p ~origin ~direction =
  let g = Array.make 9 0. and s = Scratch.create () in
  store p g 0;
  Scratch.set_ray s origin direction;
  if roots s g 0 then s.near else infinity

let pp ppf p =
  Format.fprintf ppf "(plane (point %a) (normal %a) %a)" Vec3.pp_components p.point Vec3.pp_components p.normal
    Material.pp p.material

let show p = Format.asprintf "%a" pp p
