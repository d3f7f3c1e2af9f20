type t = { center : Vec3.t; axis : Vec3.t; major : float; minor : float; material : Material.t } [@@deriving eq]

let v ~center ~axis ~major ~minor material = { center; axis; major; minor; material }
let unit_axis x = Vec3.unit x.axis

let validate x =
  let ( let* ) = Result.bind in
  let* _ = Limits.check_point "torus center" x.center in
  let* _ = Limits.check_point "torus axis" x.axis in
  let* () = if Vec3.norm x.axis > 0. then Ok () else Error (`Msg "torus axis must not be zero") in
  let* _ = Limits.check_size "torus major" x.major in
  let* _ = Limits.check_size "torus minor" x.minor in
  (* A horn or spindle torus (minor >= major) crosses itself: its quartic
     has roots inside the solid, which no interval list describes. *)
  let* () =
    if x.minor < x.major then Ok ()
    else Error (`Msg (Printf.sprintf "torus minor (%s) must be less than major (%s)" (Float_text.to_string x.minor) (Float_text.to_string x.major)))
  in
  let* _ = Material.validate ~form:"torus" x.material in
  Ok x

(* The axis is stored scaled by the major radius, so that every stored
   float is of the torus's size: the robust mode's offset reads the
   largest of them as the shape's extent ([Prepared]), and a unit axis
   would make that 1 whatever the scale. *)
let store x g o =
  let a = unit_axis x in
  g.(o) <- x.center.x;
  g.(o + 1) <- x.center.y;
  g.(o + 2) <- x.center.z;
  g.(o + 3) <- a.x *. x.major;
  g.(o + 4) <- a.y *. x.major;
  g.(o + 5) <- a.z *. x.major;
  g.(o + 6) <- x.major;
  g.(o + 7) <- x.minor

let u = epsilon_float /. 2.

(* {1 The kernel's routines}

   Everything below runs per ray and allocates nothing: the helpers are
   inlined (a float they return then stays unboxed), and the loops keep
   their floats in local references, which the compiler keeps unboxed
   as they never escape. *)

let[@inline] cubic c3 c2 c1 c0 x = (((((c3 *. x) +. c2) *. x) +. c1) *. x) +. c0

(* [F(s) = (rho - R)^2 + z^2 - r^2] at the point [q + s D] of the line:
   the torus's quartic divided by [(rho + R)^2 + z^2 - r^2 > 0] (a ring
   torus), so of its sign everywhere, but computed without the quartic's
   cancellation of terms of size [(R + r)^4]: its rounding error is of
   the order [u (R + r)^2], that of [rho^2]. *)
let[@inline] field qx qy qz dx dy dz ax ay az big r s =
  let px = qx +. (s *. dx) and py = qy +. (s *. dy) and pz = qz +. (s *. dz) in
  let z = (px *. ax) +. (py *. ay) +. (pz *. az) in
  let rho2 = (px *. px) +. (py *. py) +. (pz *. pz) -. (z *. z) in
  let rho = sqrt (if rho2 > 0. then rho2 else 0.) in
  let e = rho -. big in
  (e *. e) +. ((z -. r) *. (z +. r))

(* Its derivative along the line; [0] on the axis, where it has none (a
   ring torus's surface is far from it: the caller then bisects). *)
let[@inline] field_slope qx qy qz dx dy dz ax ay az big s =
  let px = qx +. (s *. dx) and py = qy +. (s *. dy) and pz = qz +. (s *. dz) in
  let z = (px *. ax) +. (py *. ay) +. (pz *. az) and za = (dx *. ax) +. (dy *. ay) +. (dz *. az) in
  let rho2 = (px *. px) +. (py *. py) +. (pz *. pz) -. (z *. z) in
  if rho2 <= 0. then 0.
  else
    let rho = sqrt rho2 in
    let pd = (px *. dx) +. (py *. dy) +. (pz *. dz) in
    2. *. ((((rho -. big) /. rho) *. (pd -. (z *. za))) +. (z *. za))

(* The root of [F] in [a, b], where [F] changes sign ([fa = F a]): Newton
   steps kept inside the bracket, bisection otherwise, until the bracket
   is at most [4 tol] wide; a step shorter than [tol] is lengthened to
   [tol], so that it crosses the root and the bracket closes. *)
let[@inline] refine qx qy qz dx dy dz ax ay az big r a b fa tol =
  let lo = ref a and hi = ref b and x = ref (0.5 *. (a +. b)) and n = ref 0 and go = ref true in
  let neg_lo = fa < 0. in
  while !go do
    let fx = field qx qy qz dx dy dz ax ay az big r !x in
    if fx = 0. then begin
      lo := !x;
      hi := !x;
      go := false
    end
    else begin
      if fx < 0. = neg_lo then lo := !x else hi := !x;
      let width = !hi -. !lo and mid = 0.5 *. (!lo +. !hi) in
      if width <= 4. *. tol || !n >= 200 || mid <= !lo || mid >= !hi then go := false
      else begin
        incr n;
        let slope = field_slope qx qy qz dx dy dz ax ay az big !x in
        let step = if slope = 0. then infinity else fx /. slope in
        let step = if Float.abs step < tol then Float.copy_sign tol step else step in
        let next = !x -. step in
        x := if next > !lo && next < !hi then next else mid
      end
    end
  done;
  0.5 *. (!lo +. !hi)

(* The root of the cubic [G'] (or of any cubic [k3..k0]) in [a, b], where
   it changes sign: bisection, enough for the few critical points. *)
let[@inline] cubic_root k3 k2 k1 k0 a b tol =
  let lo = ref a and hi = ref b and go = ref true in
  let neg_lo = cubic k3 k2 k1 k0 a < 0. in
  while !go do
    let mid = 0.5 *. (!lo +. !hi) in
    if !hi -. !lo <= tol || mid <= !lo || mid >= !hi then go := false
    else if cubic k3 k2 k1 k0 mid < 0. = neg_lo then lo := mid
    else hi := mid
  done;
  0.5 *. (!lo +. !hi)

(* The line [O + t D] is [q + s D] with [t = t0 + s], [q] the point of the
   line nearest the centre: near the torus [s] is small and [q] is as
   exact as [O] allows, whatever the ray's length (no cancellation of
   [t]'s). The torus lies within its bounding sphere, [|s| <= h]; there
   the quartic [G(s)] (leading coefficient [|D|^4]) has at most three
   critical points, the roots of the cubic [G'], found between the roots
   of the quadratic [G'']. Between two critical points [G] is monotone:
   at most one root, bracketed and refined on [F] (see [field]). *)
let[@inline never] roots (s : Scratch.t) g o =
  let cx = Array.unsafe_get g o and cy = Array.unsafe_get g (o + 1) and cz = Array.unsafe_get g (o + 2) in
  let big = Array.unsafe_get g (o + 6) and r = Array.unsafe_get g (o + 7) in
  let inv = 1. /. big in
  let ax = Array.unsafe_get g (o + 3) *. inv and ay = Array.unsafe_get g (o + 4) *. inv and az = Array.unsafe_get g (o + 5) *. inv in
  let dx = s.dx and dy = s.dy and dz = s.dz in
  let wx = s.ox -. cx and wy = s.oy -. cy and wz = s.oz -. cz in
  let dd = (dx *. dx) +. (dy *. dy) +. (dz *. dz) in
  let t0 = -.((wx *. dx) +. (wy *. dy) +. (wz *. dz)) /. dd in
  let qx = wx +. (t0 *. dx) and qy = wy +. (t0 *. dy) and qz = wz +. (t0 *. dz) in
  let qq = (qx *. qx) +. (qy *. qy) +. (qz *. qz) in
  (* The bounding sphere, grown by a few rounding errors: a ray grazing
     the outer equator grazes it too. *)
  let outer = (big +. r) *. (1. +. (64. *. u)) in
  let found = ref false in
  if qq < outer *. outer then begin
    let h = sqrt (((outer *. outer) -. qq) /. dd) in
    let tol = u *. (Float.abs t0 +. h) in
    let qd = (qx *. dx) +. (qy *. dy) +. (qz *. dz) in
    let qa = (qx *. ax) +. (qy *. ay) +. (qz *. az) and da = (dx *. ax) +. (dy *. ay) +. (dz *. az) in
    let e = qq +. ((big -. r) *. (big +. r)) and b4 = 4. *. big *. big in
    let c4 = dd *. dd and c3 = 4. *. dd *. qd in
    let c2 = (4. *. qd *. qd) +. (2. *. dd *. e) -. (b4 *. (dd -. (da *. da))) in
    let c1 = (4. *. qd *. e) -. (2. *. b4 *. (qd -. (qa *. da))) in
    (* [G''/2 = 6 c4 s^2 + 3 c3 s + c2]: its roots split [-h, h] where
       [G'] is monotone. *)
    let k2 = 6. *. c4 and k1 = 3. *. c3 in
    let disc = (k1 *. k1) -. (4. *. k2 *. c2) in
    let lo = -.h in
    let m1 = ref lo and m2 = ref lo in
    if disc > 0. then begin
      let qm = -0.5 *. (k1 +. Float.copy_sign (sqrt disc) k1) in
      let x0 = qm /. k2 and x1 = if qm = 0. then 0. else c2 /. qm in
      let a0 = Float.min x0 x1 and a1 = Float.max x0 x1 in
      m1 := Float.max lo (Float.min h a0);
      m2 := Float.max lo (Float.min h a1)
    end;
    (* The critical points of [G]: a root of [G' = 4 c4 s^3 + 3 c3 s^2 +
       2 c2 s + c1] on each of the up to three pieces where it is
       monotone, in order. *)
    let j3 = 4. *. c4 and j2 = 3. *. c3 and j1 = 2. *. c2 in
    let crit1 = ref nan and crit2 = ref nan and crit3 = ref nan in
    let ga = cubic j3 j2 j1 c1 lo and gm1 = cubic j3 j2 j1 c1 !m1 in
    let gm2 = cubic j3 j2 j1 c1 !m2 and gh = cubic j3 j2 j1 c1 h in
    if (ga < 0.) <> (gm1 < 0.) then crit1 := cubic_root j3 j2 j1 c1 lo !m1 tol;
    if (gm1 < 0.) <> (gm2 < 0.) then crit2 := cubic_root j3 j2 j1 c1 !m1 !m2 tol;
    if (gm2 < 0.) <> (gh < 0.) then crit3 := cubic_root j3 j2 j1 c1 !m2 h tol;
    (* The pieces between [-h], the critical points and [h], in order,
       with [F] at each end (a missing critical point repeats the last:
       an empty piece). *)
    let x1 = if Float.is_finite !crit1 then !crit1 else lo in
    let x2 = if Float.is_finite !crit2 then !crit2 else x1 in
    let x3 = if Float.is_finite !crit3 then !crit3 else x2 in
    let f0 = field qx qy qz dx dy dz ax ay az big r lo and f1 = field qx qy qz dx dy dz ax ay az big r x1 in
    let f2 = field qx qy qz dx dy dz ax ay az big r x2 and f3 = field qx qy qz dx dy dz ax ay az big r x3 in
    let f4 = field qx qy qz dx dy dz ax ay az big r h in
    (* Roots alternate entries and exits ([F > 0] outside); the first
       interval of the solid whose exit lies beyond [s.t_min] is the
       answer. *)
    let enter = ref lo in
    for k = 0 to 3 do
      if not !found then begin
        let a = if k = 0 then lo else if k = 1 then x1 else if k = 2 then x2 else x3 in
        let b = if k = 0 then x1 else if k = 1 then x2 else if k = 2 then x3 else h in
        let fa = if k = 0 then f0 else if k = 1 then f1 else if k = 2 then f2 else f3 in
        let fb = if k = 0 then f1 else if k = 1 then f2 else if k = 2 then f3 else f4 in
        if (fa <= 0.) <> (fb <= 0.) then begin
          let x = refine qx qy qz dx dy dz ax ay az big r a b fa tol in
          if fa > 0. then enter := x
          else begin
            let t_exit = t0 +. x in
            if t_exit > s.t_min then begin
              s.near <- t0 +. !enter;
              s.far <- t_exit;
              found := true
            end
          end
        end
      end
    done
  end;
  if not !found then begin
    s.near <- infinity;
    s.far <- infinity
  end;
  !found

(* The outward normal at the hit point: the direction from the nearest
   point of the core circle (radius [R] about the axis) to the point. *)
let[@inline never] normal (s : Scratch.t) g o =
  let big = Array.unsafe_get g (o + 6) in
  let inv = 1. /. big in
  let ax = Array.unsafe_get g (o + 3) *. inv and ay = Array.unsafe_get g (o + 4) *. inv and az = Array.unsafe_get g (o + 5) *. inv in
  let vx = s.px -. Array.unsafe_get g o and vy = s.py -. Array.unsafe_get g (o + 1) and vz = s.pz -. Array.unsafe_get g (o + 2) in
  let z = (vx *. ax) +. (vy *. ay) +. (vz *. az) in
  let rx = vx -. (z *. ax) and ry = vy -. (z *. ay) and rz = vz -. (z *. az) in
  let rho = sqrt ((rx *. rx) +. (ry *. ry) +. (rz *. rz)) in
  let k = if rho > 0. then big /. rho else 0. in
  let nx = vx -. (k *. rx) and ny = vy -. (k *. ry) and nz = vz -. (k *. rz) in
  let l = sqrt ((nx *. nx) +. (ny *. ny) +. (nz *. nz)) in
  if l > 0. then begin
    s.nx <- nx /. l;
    s.ny <- ny /. l;
    s.nz <- nz /. l
  end
  else begin
    s.nx <- ax;
    s.ny <- ay;
    s.nz <- az
  end

(* {1 The executable specification's crossings}

   From the definition, by another method than the kernel's: the torus
   is the set of points at distance [minor] from its core circle, and
   [d(P) = sqrt ((rho - major)^2 + z^2) - minor] is the exact signed
   distance to its surface ([rho] from the axis, [z] along it). Marching
   along the line by [|d| / |D|] never steps over the surface (sphere
   tracing); each change of side is then bisected. Points are taken
   from the center, [(O - C) + t D], and a side counts only where [d] is
   beyond its rounding error: the surface's own noise makes no
   crossings. *)
let literal x ~origin ~direction =
  let open Vec3 in
  let a = unit_axis x in
  let w = sub origin x.center in
  let from_center t = add w (smul t direction) in
  let dist t =
    let v = from_center t in
    let z = dot v a in
    let rho = norm (sub v (smul z a)) in
    sqrt (((rho -. x.major) *. (rho -. x.major)) +. (z *. z)) -. x.minor
  in
  let outward t =
    let v = from_center t in
    let radial = sub v (smul (dot v a) a) in
    let rho = norm radial in
    let core = if rho > 0. then smul (x.major /. rho) radial else zero in
    unit (sub v core)
  in
  let len = norm direction and size = x.major +. x.minor in
  let noise = 2. *. epsilon_float *. (norm w +. size) in
  (* The line within the sphere of radius [2 size]: the torus lies in the
     one of radius [size]. *)
  let b = dot w direction /. (len *. len) in
  let foot = sub w (smul b direction) in
  let reach = (4. *. size *. size) -. dot foot foot in
  if reach <= 0. then []
  else begin
    let half = sqrt reach /. len in
    let t_start = -.b -. half and t_end = -.b +. half in
    (* A crossing between [t_out] (outside) and [t_in] (inside). *)
    let bisect t_out t_in =
      let rec go t_out t_in n =
        let m = 0.5 *. (t_out +. t_in) in
        if n = 0 || m = t_out || m = t_in then m else if dist m > 0. then go m t_in (pred n) else go t_out m (pred n)
      in
      go t_out t_in 200
    in
    (* Steps of at least [1e-9 size]: a pair of crossings closer than
       that is a graze deeper than no rounding band notices. *)
    let floor_step = Float.max (1e-9 *. size) noise /. len in
    (* [outside] is the side last seen beyond the noise, at [t_side]. *)
    let rec march t d outside t_side acc n =
      if t >= t_end || n = 0 then List.rev acc
      else
        let step = Float.max (Float.abs d /. len) (Float.max floor_step (8. *. epsilon_float *. Float.abs t)) in
        let t' = Float.min t_end (t +. step) in
        let d' = dist t' in
        if Float.abs d' <= noise then march t' d' outside t_side acc (pred n)
        else if d' > 0. = outside then march t' d' outside t' acc (pred n)
        else
          let c = if outside then bisect t_side t' else bisect t' t_side in
          march t' d' (not outside) t' ((c, outward c) :: acc) (pred n)
    in
    march t_start (dist t_start) true t_start [] 1_000_000
  end

let bounds x =
  let a = unit_axis x in
  let reach c = (x.major *. sqrt (Float.max 0. (1. -. (c *. c))) +. x.minor) *. (1. +. (16. *. u)) in
  let lo c e = Float.pred (c -. reach e) and hi c e = Float.succ (c +. reach e) in
  (Vec3.v (lo x.center.x a.x) (lo x.center.y a.y) (lo x.center.z a.z), Vec3.v (hi x.center.x a.x) (hi x.center.y a.y) (hi x.center.z a.z))

let pp ppf x =
  Format.fprintf ppf "(torus (center %a) (axis %a) (major %s) (minor %s) %a)" Vec3.pp_components x.center Vec3.pp_components
    x.axis (Float_text.to_string x.major) (Float_text.to_string x.minor) Material.pp x.material

let desc =
  {
    Shape_desc.name = "torus";
    kind = Kind.Torus;
    witness = Shape_desc.witness ();
    fields = [ ("center", Point); ("axis", Point); ("major", Number); ("minor", Number) ];
    read =
      (fun f m -> v ~center:(f.point "center") ~axis:(f.point "axis") ~major:(f.number "major") ~minor:(f.number "minor") m);
    validate;
    material = (fun x -> x.material);
    closed = (fun _ -> true);
    bounds;
    store;
    pp;
    equal;
    literal;
  }
