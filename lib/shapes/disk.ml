type t = { center : Vec3.t; normal : Vec3.t; radius : float; material : Material.t } [@@deriving eq]

let v ~center ~normal ~radius material = { center; normal; radius; material }

let validate d =
  let ( let* ) = Result.bind in
  let* _ = Limits.check_point "disk center" d.center in
  let* _ = Limits.check_point "disk normal" d.normal in
  let* _ = Limits.check_size "disk radius" d.radius in
  let n = Vec3.norm d.normal in
  let* () =
    if n >= Limits.min_size && Float.is_finite n then Ok ()
    else Error (`Msg (Format.asprintf "disk normal must not be zero, got %a" Vec3.pp d.normal))
  in
  let* _ = Material.validate ~form:"disk" d.material in
  Ok d

(* The normal as given, scaled by a power of two (exactly) so that its
   largest coordinate lies in [1/4, 1/2), as a plane's: the root does not
   depend on its length, a ray parallel to the disk is so to the normal
   the roots are found with, and the stored floats' largest magnitude
   (which bounds the hit point's rounding) is the centre's or the
   radius's, not a constant. *)
let store d g o =
  g.(o) <- d.center.x;
  g.(o + 1) <- d.center.y;
  g.(o + 2) <- d.center.z;
  let _, e = Float.frexp (Float.max (Float.abs d.normal.x) (Float.max (Float.abs d.normal.y) (Float.abs d.normal.z))) in
  let k = Float.ldexp 1. (-e - 1) in
  g.(o + 3) <- d.normal.x *. k;
  g.(o + 4) <- d.normal.y *. k;
  g.(o + 5) <- d.normal.z *. k;
  g.(o + 6) <- d.radius

(* The plane's root [<C - O, N> / <D, N>], as [Plane.roots] finds it, and
   the point's offset from the centre [(O - C) + t D], inside the circle
   or not. *)
let[@inline never] roots (s : Scratch.t) g o =
  let nx = Array.unsafe_get g (o + 3) and ny = Array.unsafe_get g (o + 4) and nz = Array.unsafe_get g (o + 5) in
  let den = (s.dx *. nx) +. (s.dy *. ny) +. (s.dz *. nz) in
  let fx = s.ox -. Array.unsafe_get g o and fy = s.oy -. Array.unsafe_get g (o + 1) and fz = s.oz -. Array.unsafe_get g (o + 2) in
  let t = -.((fx *. nx) +. (fy *. ny) +. (fz *. nz)) /. den in
  let px = fx +. (t *. s.dx) and py = fy +. (t *. s.dy) and pz = fz +. (t *. s.dz) in
  let r = Array.unsafe_get g (o + 6) in
  if den <> 0. && (px *. px) +. (py *. py) +. (pz *. pz) <= r *. r then begin
    s.near <- t;
    s.far <- t;
    true
  end
  else begin
    s.near <- infinity;
    s.far <- infinity;
    false
  end

(* The unit normal: one square root per hit, not a stored constant. *)
let[@inline never] normal (s : Scratch.t) g o =
  let nx = Array.unsafe_get g (o + 3) and ny = Array.unsafe_get g (o + 4) and nz = Array.unsafe_get g (o + 5) in
  let inv = 1. /. sqrt ((nx *. nx) +. (ny *. ny) +. (nz *. nz)) in
  s.nx <- nx *. inv;
  s.ny <- ny *. inv;
  s.nz <- nz *. inv

(* The executable specification's crossing, from the definition: the
   point of the line in the disk's plane (through the centre, across the
   unit normal) whose distance from the centre is at most the radius. *)
let literal d ~origin ~direction =
  let open Vec3 in
  let n = unit d.normal in
  let dn = dot direction n in
  if dn = 0. then []
  else
    let t = dot (sub d.center origin) n /. dn in
    let off = sub (add origin (smul t direction)) d.center in
    if norm off <= d.radius then [ (t, n) ] else []

(* Along axis [i], a circle of radius [r] across [n] reaches
   [r sqrt ((n_j^2 + n_k^2) / |n|^2)] from its centre (no cancellation: a
   sum of squares over a sum of squares, each within a few [u] relatively
   of its exact value, the normal's coordinates rounded or not); [32 u]
   more covers the rounding. *)
let rim_extent r (n : Vec3.t) =
  let x2 = n.x *. n.x and y2 = n.y *. n.y and z2 = n.z *. n.z in
  let n2 = x2 +. y2 +. z2 in
  let e a b = r *. sqrt ((a +. b) /. n2) *. (1. +. (32. *. epsilon_float)) in
  Vec3.v (e y2 z2) (e x2 z2) (e x2 y2)

(* The box of the circle, outward by an ulp after the one rounding of
   each sum: a disk across an axis is flat along it. *)
let bounds d =
  let e = rim_extent d.radius d.normal in
  let lo x e = Float.pred (x -. e) and hi x e = Float.succ (x +. e) in
  ( Vec3.v (lo d.center.x e.x) (lo d.center.y e.y) (lo d.center.z e.z),
    Vec3.v (hi d.center.x e.x) (hi d.center.y e.y) (hi d.center.z e.z) )

let pp ppf d =
  Format.fprintf ppf "(disk (center %a) (normal %a) (radius %s) %a)" Vec3.pp_components d.center Vec3.pp_components
    d.normal (Float_text.to_string d.radius) Material.pp d.material

let show d = Format.asprintf "%a" pp d

let desc =
  {
    Shape_desc.name = "disk";
    kind = Kind.Disk;
    witness = Shape_desc.witness ();
    fields = [ ("center", Point); ("normal", Point); ("radius", Number) ];
    read = (fun r m -> v ~center:(r.point "center") ~normal:(r.point "normal") ~radius:(r.number "radius") m);
    validate;
    material = (fun d -> d.material);
    closed = (fun _ -> false);
    bounds;
    store;
    pp;
    equal;
    literal;
  }
