type t = { v0 : Vec3.t; v1 : Vec3.t; v2 : Vec3.t; material : Material.t } [@@deriving eq]

let v v0 v1 v2 material = { v0; v1; v2; material }

let validate tri =
  let ( let* ) = Result.bind in
  let* _ = Limits.check_point "triangle vertex" tri.v0 in
  let* _ = Limits.check_point "triangle vertex" tri.v1 in
  let* _ = Limits.check_point "triangle vertex" tri.v2 in
  let n = Vec3.norm (Vec3.cross (Vec3.sub tri.v1 tri.v0) (Vec3.sub tri.v2 tri.v0)) in
  let* () =
    if n > 0. && Float.is_finite n && Float.is_finite (1. /. n) then Ok ()
    else
      Error
        (`Msg
          (Format.asprintf "triangle vertices must not lie on a line, got %a %a %a" Vec3.pp tri.v0
             Vec3.pp tri.v1 Vec3.pp tri.v2))
  in
  let* _ = Material.validate ~form:"triangle" tri.material in
  Ok tri

let store tri g o =
  let put k (p : Vec3.t) =
    g.(o + k) <- p.x;
    g.(o + k + 1) <- p.y;
    g.(o + k + 2) <- p.z
  in
  put 0 tri.v0;
  put 3 tri.v1;
  put 6 tri.v2

(* Coordinate [axis] of the vertex at [o], relative to the ray origin. *)
let[@inline] rel g o axis origin = Array.unsafe_get g (o + axis) -. origin

(* The shear of the ray whose direction's coordinates on the axes kx, ky,
   kz are [dkx], [dky], [dkz], and its origin's. *)
let[@inline] put (s : Scratch.t) dkx dky dkz okx oky okz =
  s.sx <- dkx /. dkz;
  s.sy <- dky /. dkz;
  s.sz <- 1. /. dkz;
  s.okx <- okx;
  s.oky <- oky;
  s.okz <- okz

let[@inline] axes ~kx ~ky ~kz = kz lor (kx lsl 2) lor (ky lsl 4)

(* The ray's shear on the axes kx, ky, kz, its direction's coordinates on
   them [dkx], [dky], [dkz] and its origin's: kx and ky swapped when
   D.kz < 0, so that the winding is kept. *)
let[@inline] on_axes s ~kx ~ky ~kz dkx dky dkz okx oky okz =
  if dkz < 0. then begin
    put s dky dkx dkz oky okx okz;
    axes ~kx:ky ~ky:kx ~kz
  end
  else begin
    put s dkx dky dkz okx oky okz;
    axes ~kx ~ky ~kz
  end

(* Woop, Benthin and Wald, JCGT 2(1), 2013, section 3, in double precision
   throughout. kz is the largest axis of D, and kx, ky follow it. *)
let[@inline never] shear (s : Scratch.t) =
  let dx = s.dx and dy = s.dy and dz = s.dz in
  let ax = Float.abs dx and ay = Float.abs dy and az = Float.abs dz in
  if ax > ay && ax > az then on_axes s ~kx:1 ~ky:2 ~kz:0 dy dz dx s.oy s.oz s.ox
  else if (not (ax > ay)) && ay > az then on_axes s ~kx:2 ~ky:0 ~kz:1 dz dx dy s.oz s.ox s.oy
  else on_axes s ~kx:0 ~ky:1 ~kz:2 dx dy dz s.ox s.oy s.oz

let axis_x axes = (axes lsr 2) land 3
let axis_y axes = axes lsr 4
let axis_z axes = axes land 3

let[@inline] hit (s : Scratch.t) g o0 o1 o2 kx ky kz =
  let sx = s.sx and sy = s.sy in
  let okx = s.okx and oky = s.oky and okz = s.okz in
  let az_ = rel g o0 kz okz and bz_ = rel g o1 kz okz and cz_ = rel g o2 kz okz in
  let ax_ = rel g o0 kx okx -. (sx *. az_) and ay_ = rel g o0 ky oky -. (sy *. az_) in
  let bx_ = rel g o1 kx okx -. (sx *. bz_) and by_ = rel g o1 ky oky -. (sy *. bz_) in
  let cx_ = rel g o2 kx okx -. (sx *. cz_) and cy_ = rel g o2 ky oky -. (sy *. cz_) in
  let u = (cx_ *. by_) -. (cy_ *. bx_) in
  let v = (ax_ *. cy_) -. (ay_ *. cx_) in
  (* Two edge functions of opposite signs already decide a miss: the
     test below would find one below 0 and one above, whatever [w]. A
     product below 0 has factors of opposite signs, neither 0 nor NaN (one
     that underflows to 0 leaves the decision to the test below). *)
  (not (u *. v < 0.))
  &&
  let w = (bx_ *. ay_) -. (by_ *. ax_) in
  (not ((u < 0. || v < 0. || w < 0.) && (u > 0. || v > 0. || w > 0.)))
  &&
  let det = u +. v +. w in
  (not (det = 0.))
  && begin
       let sz = s.sz in
       s.near <- ((u *. (sz *. az_)) +. (v *. (sz *. bz_)) +. (w *. (sz *. cz_))) /. det;
       true
     end

(* The sign of the edge function [qx py - qy px] of the edge [p -> q]
   whose computed value is 0, for the point [(e, e^2)] of the ray's plane,
   [e > 0] infinitely small: the exact value first (the computed one is 0,
   so the rounded products are equal and the exact value is the difference
   of their rounding errors, which [fma] gives exactly), then [qy - py],
   then [px - qx], the terms of [e] and [e^2]. Swapping [p] and [q] negates
   each step, rounding included: the two triangles of an edge disagree. *)
let[@inline never] tie_sign px py qx qy =
  let e = Float.fma qx py (-.(qx *. py)) -. Float.fma qy px (-.(qy *. px)) in
  if e > 0. then 1
  else if e < 0. then -1
  else
    let dy = qy -. py in
    if dy > 0. then 1
    else if dy < 0. then -1
    else
      let dx = px -. qx in
      if dx > 0. then 1 else if dx < 0. then -1 else 0

let[@inline] sign_of e px py qx qy = if e > 0. then 1 else if e < 0. then -1 else tie_sign px py qx qy

let[@inline never] crosses_at (s : Scratch.t) g o0 o1 o2 kx ky kz =
  let sx = s.sx and sy = s.sy in
  let okx = s.okx and oky = s.oky and okz = s.okz in
  let az_ = rel g o0 kz okz and bz_ = rel g o1 kz okz and cz_ = rel g o2 kz okz in
  let ax_ = rel g o0 kx okx -. (sx *. az_) and ay_ = rel g o0 ky oky -. (sy *. az_) in
  let bx_ = rel g o1 kx okx -. (sx *. bz_) and by_ = rel g o1 ky oky -. (sy *. bz_) in
  let cx_ = rel g o2 kx okx -. (sx *. cz_) and cy_ = rel g o2 ky oky -. (sy *. cz_) in
  let u = (cx_ *. by_) -. (cy_ *. bx_) in
  let v = (ax_ *. cy_) -. (ay_ *. cx_) in
  let crossed =
    (not (u *. v < 0.))
    &&
    let w = (bx_ *. ay_) -. (by_ *. ax_) in
    let su = sign_of u bx_ by_ cx_ cy_ in
    su <> 0
    && su = sign_of v cx_ cy_ ax_ ay_
    && su = sign_of w ax_ ay_ bx_ by_
    && begin
         let sz = s.sz in
         let det = u +. v +. w in
         (* All three of one sign, none computed above 0 against it: [det]
            is 0 only if all three are computed 0, a triangle seen edge on
            or too small to resolve, whose depth is then its corners'. *)
         s.near <-
           (if det = 0. then sz *. ((az_ +. bz_ +. cz_) /. 3.)
            else ((u *. (sz *. az_)) +. (v *. (sz *. bz_)) +. (w *. (sz *. cz_))) /. det);
         true
       end
  in
  if crossed then s.far <- s.near
  else begin
    s.near <- infinity;
    s.far <- infinity
  end;
  crossed

let crosses s g o =
  let axes = shear s in
  crosses_at s g o (o + 3) (o + 6) (axis_x axes) (axis_y axes) (axis_z axes)

let[@inline never] roots_at (s : Scratch.t) g o0 o1 o2 kx ky kz =
  if hit s g o0 o1 o2 kx ky kz then begin
    s.far <- s.near;
    true
  end
  else begin
    s.near <- infinity;
    s.far <- infinity;
    false
  end

let roots s g o =
  let axes = shear s in
  roots_at s g o (o + 3) (o + 6) (axis_x axes) (axis_y axes) (axis_z axes)

let[@inline never] normal_at (s : Scratch.t) g o0 o1 o2 =
  let e1x = g.(o1) -. g.(o0) and e1y = g.(o1 + 1) -. g.(o0 + 1) and e1z = g.(o1 + 2) -. g.(o0 + 2) in
  let e2x = g.(o2) -. g.(o0) and e2y = g.(o2 + 1) -. g.(o0 + 1) and e2z = g.(o2 + 2) -. g.(o0 + 2) in
  let nx = (e1y *. e2z) -. (e1z *. e2y) and ny = (e1z *. e2x) -. (e1x *. e2z) and nz = (e1x *. e2y) -. (e1y *. e2x) in
  let inv = 1. /. sqrt ((nx *. nx) +. (ny *. ny) +. (nz *. nz)) in
  s.nx <- nx *. inv;
  s.ny <- ny *. inv;
  s.nz <- nz *. inv

(* Barycentric coordinates of P in the triangle by the normal equations of
   P - v0 = b1 e1 + b2 e2; then the corners' normals weighted by them. *)
let normal s g o = normal_at s g o (o + 3) (o + 6)

let[@inline never] smooth_normal_at (s : Scratch.t) g o0 o1 o2 vn k0 k1 k2 =
  let x0 = g.(o0) and y0 = g.(o0 + 1) and z0 = g.(o0 + 2) in
  let e1x = g.(o1) -. x0 and e1y = g.(o1 + 1) -. y0 and e1z = g.(o1 + 2) -. z0 in
  let e2x = g.(o2) -. x0 and e2y = g.(o2 + 1) -. y0 and e2z = g.(o2 + 2) -. z0 in
  let wx = s.px -. x0 and wy = s.py -. y0 and wz = s.pz -. z0 in
  let d00 = (e1x *. e1x) +. (e1y *. e1y) +. (e1z *. e1z) in
  let d01 = (e1x *. e2x) +. (e1y *. e2y) +. (e1z *. e2z) in
  let d11 = (e2x *. e2x) +. (e2y *. e2y) +. (e2z *. e2z) in
  let d20 = (wx *. e1x) +. (wy *. e1y) +. (wz *. e1z) in
  let d21 = (wx *. e2x) +. (wy *. e2y) +. (wz *. e2z) in
  let den = (d00 *. d11) -. (d01 *. d01) in
  let b1 = ((d11 *. d20) -. (d01 *. d21)) /. den and b2 = ((d00 *. d21) -. (d01 *. d20)) /. den in
  let b0 = 1. -. b1 -. b2 in
  let nx = (b0 *. vn.(k0)) +. (b1 *. vn.(k1)) +. (b2 *. vn.(k2)) in
  let ny = (b0 *. vn.(k0 + 1)) +. (b1 *. vn.(k1 + 1)) +. (b2 *. vn.(k2 + 1)) in
  let nz = (b0 *. vn.(k0 + 2)) +. (b1 *. vn.(k1 + 2)) +. (b2 *. vn.(k2 + 2)) in
  let l = sqrt ((nx *. nx) +. (ny *. ny) +. (nz *. nz)) in
  if l > 0. && l < infinity then begin
    let inv = 1. /. l in
    s.nx <- nx *. inv;
    s.ny <- ny *. inv;
    s.nz <- nz *. inv;
    true
  end
  else false

let smooth_normal s g o vn k0 k1 k2 = smooth_normal_at s g o (o + 3) (o + 6) vn k0 k1 k2

(* The point's barycentric weights on the corners as stored
   (Texture_map.barycentric's formula), then the corners' [vt] blended
   ({!Texture_map.interpolate}). The point is read from [s], not passed:
   a float argument across modules is boxed where they are not inlined
   (the dev profile). *)
let[@inline] texcoords_at (s : Scratch.t) v o0 o1 o2 uv j =
  let t = s.t in
  let px = s.ox +. (s.dx *. t) and py = s.oy +. (s.dy *. t) and pz = s.oz +. (s.dz *. t) in
  let ax = Array.unsafe_get v o0 and ay = Array.unsafe_get v (o0 + 1) and az = Array.unsafe_get v (o0 + 2) in
  let e1x = Array.unsafe_get v o1 -. ax and e1y = Array.unsafe_get v (o1 + 1) -. ay and e1z = Array.unsafe_get v (o1 + 2) -. az in
  let e2x = Array.unsafe_get v o2 -. ax and e2y = Array.unsafe_get v (o2 + 1) -. ay and e2z = Array.unsafe_get v (o2 + 2) -. az in
  let dx = px -. ax and dy = py -. ay and dz = pz -. az in
  let d11 = (e1x *. e1x) +. (e1y *. e1y) +. (e1z *. e1z) and d12 = (e1x *. e2x) +. (e1y *. e2y) +. (e1z *. e2z) in
  let d22 = (e2x *. e2x) +. (e2y *. e2y) +. (e2z *. e2z) in
  let dp1 = (dx *. e1x) +. (dy *. e1y) +. (dz *. e1z) and dp2 = (dx *. e2x) +. (dy *. e2y) +. (dz *. e2z) in
  let den = (d11 *. d22) -. (d12 *. d12) in
  let b1 = if den > 0. then ((d22 *. dp1) -. (d12 *. dp2)) /. den else 0. in
  let b2 = if den > 0. then ((d11 *. dp2) -. (d12 *. dp1)) /. den else 0. in
  let u0 = Array.unsafe_get uv j and v0 = Array.unsafe_get uv (j + 1) in
  s.tu <- u0 +. (b1 *. (Array.unsafe_get uv (j + 2) -. u0)) +. (b2 *. (Array.unsafe_get uv (j + 4) -. u0));
  s.tv <- v0 +. (b1 *. (Array.unsafe_get uv (j + 3) -. v0)) +. (b2 *. (Array.unsafe_get uv (j + 5) -. v0))

let intersect tri ~origin ~direction =
  let g = Array.make 9 0. and s = Scratch.create () in
  store tri g 0;
  Scratch.set_ray s origin direction;
  if roots s g 0 then s.near else infinity

let crossing tri ~origin ~direction =
  let g = Array.make 9 0. and s = Scratch.create () in
  store tri g 0;
  Scratch.set_ray s origin direction;
  if crosses s g 0 then s.near else infinity

let pp ppf t =
  Format.fprintf ppf "(triangle (vertices (%a) (%a) (%a)) %a)" Vec3.pp_components t.v0 Vec3.pp_components t.v1
    Vec3.pp_components t.v2 Material.pp t.material

let show t = Format.asprintf "%a" pp t
