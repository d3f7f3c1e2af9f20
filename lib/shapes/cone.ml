type t = { base : Vec3.t; top : Vec3.t; radius : float; top_radius : float; capped : bool; material : Material.t }
[@@deriving eq]

let v ?(capped = true) ~base ~top ~radius ~top_radius material = { base; top; radius; top_radius; capped; material }

(* A radius is 0 (a point) or a size the limits allow: the squares of a
   smaller one would underflow. *)
let check_radius what r =
  if r = 0. then Ok r
  else
    match Limits.check_size what r with
    | Ok r -> Ok r
    | Error (`Msg m) -> Error (`Msg (m ^ ", or 0 for a point"))

let validate c =
  let ( let* ) = Result.bind in
  let* _ = Limits.check_point "cone base" c.base in
  let* _ = Limits.check_point "cone top" c.top in
  let* _ = check_radius "cone radius" c.radius in
  let* _ = check_radius "cone top-radius" c.top_radius in
  let* () =
    if c.radius = 0. && c.top_radius = 0. then Error (`Msg "cone radius and top-radius must not both be 0")
    else Ok ()
  in
  let* () =
    let h = Vec3.norm (Vec3.sub c.top c.base) in
    if h >= Limits.min_size && Float.is_finite h then Ok ()
    else
      Error
        (`Msg (Format.asprintf "cone base and top must be apart, got %a and %a" Vec3.pp c.base Vec3.pp c.top))
  in
  let* _ = Material.validate ~form:"cone" c.material in
  Ok c

let store c g o =
  g.(o) <- c.base.x;
  g.(o + 1) <- c.base.y;
  g.(o + 2) <- c.base.z;
  g.(o + 3) <- c.top.x;
  g.(o + 4) <- c.top.y;
  g.(o + 5) <- c.top.z;
  g.(o + 6) <- c.radius;
  g.(o + 7) <- c.top_radius;
  g.(o + 8) <- (if c.capped then 1. else 0.)

(* Float.min and Float.max are not inlined here: a call would box. *)
let[@inline] fmin (x : float) y = if x < y then x else y
let[@inline] fmax (x : float) y = if x > y then x else y

(* The surfaces a root is on, as [solve] tells them. *)
let side = 0
let base_cap = 1
let top_cap = 2

(* The roots: see the .mli for the method and its bound. Every float is
   a local [let] (unboxed); the two crossings go out through [s] and
   which surface each is on as the int result ([near_surface + 3
   far_surface], 9 more for a line tangent to the side, or [-1] for a
   miss), so the routine allocates nothing.
   Inlined in [roots] and [normal] alone: the normal is the surface's
   that gave the root kept, not the one nearest the point, which at a
   rim is either (a ray in a cap's plane crosses the side there, and
   never the cap). *)
let[@inline] solve (s : Scratch.t) g o =
  let bx = Array.unsafe_get g o and by = Array.unsafe_get g (o + 1) and bz = Array.unsafe_get g (o + 2) in
  let ax = Array.unsafe_get g (o + 3) -. bx and ay = Array.unsafe_get g (o + 4) -. by and az = Array.unsafe_get g (o + 5) -. bz in
  let r0 = Array.unsafe_get g (o + 6) and dr = Array.unsafe_get g (o + 7) -. Array.unsafe_get g (o + 6) in
  let capped = Array.unsafe_get g (o + 8) > 0. in
  let dx = s.dx and dy = s.dy and dz = s.dz in
  let hh = (ax *. ax) +. (ay *. ay) +. (az *. az) in
  (* The origin moved along the ray to its closest approach to the base:
     the coefficients below then have the cone's scale, not the ray's
     length, and a far origin loses no digits of them. *)
  let fx = s.ox -. bx and fy = s.oy -. by and fz = s.oz -. bz in
  let tc = -.((fx *. dx) +. (fy *. dy) +. (fz *. dz)) /. ((dx *. dx) +. (dy *. dy) +. (dz *. dz)) in
  let wx = fx +. (tc *. dx) and wy = fy +. (tc *. dy) and wz = fz +. (tc *. dz) in
  let wa = (wx *. ax) +. (wy *. ay) +. (wz *. az) and da = (dx *. ax) +. (dy *. ay) +. (dz *. az) in
  (* The slab between the caps' planes: [0 <= (w + tau D).a <= |a|^2]. *)
  let slab_lo = if da = 0. then (if 0. <= wa && wa <= hh then neg_infinity else infinity) else fmin (-.wa /. da) ((hh -. wa) /. da) in
  let slab_hi = if da = 0. then (if 0. <= wa && wa <= hh then infinity else neg_infinity) else fmax (-.wa /. da) ((hh -. wa) /. da) in
  (* The side: [|p + tau q|^2 = (rho0 + tau rhod)^2], [p], [q] the
     parts of [w], [D] across the axis, [rho] the radius at the point's
     height; [A tau^2 + 2 B tau + C = 0]. *)
  let kw = wa /. hh and kd = da /. hh in
  let px = wx -. (kw *. ax) and py = wy -. (kw *. ay) and pz = wz -. (kw *. az) in
  let qx = dx -. (kd *. ax) and qy = dy -. (kd *. ay) and qz = dz -. (kd *. az) in
  let rho0 = r0 +. (dr *. kw) and rhod = dr *. kd in
  let a = (qx *. qx) +. (qy *. qy) +. (qz *. qz) -. (rhod *. rhod) in
  let b = (px *. qx) +. (py *. qy) +. (pz *. qz) -. (rho0 *. rhod) in
  let pp = (px *. px) +. (py *. py) +. (pz *. pz) in
  let c = pp -. (rho0 *. rho0) in
  (* The side's two roots [lo <= hi] (none: [nan], which no comparison
     keeps), and the part of the line inside the (double) cone, [in_lo,
     in_hi]: between the roots where [A > 0]; where [A < 0] the
     half-line on the nappe whose radius is positive, the only one the
     slab holds. No tuples: each float is its own [let]. *)
  let disc = (b *. b) -. (a *. c) in
  let disc = if a < 0. && disc < 0. then 0. else disc in
  let qq = -.(b +. Float.copy_sign (sqrt disc) b) in
  (* A double root (a clamped discriminant among them) is [-B / A]:
     [C / q] would divide [C]'s noise by [B]'s. *)
  let t0 = if a = 0. then -.c /. (2. *. b) else if disc = 0. then -.b /. a else c /. qq in
  let t1 = if a = 0. then t0 else if disc = 0. then -.b /. a else qq /. a in
  (* Near a double root (a line by the apex, or grazing the side) the
     roots move by the square root of [C]'s error, which has the scale of
     the point the coefficients were found at: so they are found again
     from the middle of the chord, where the side's residual is small
     and exact to that point's own rounding; [A] and [rhod] depend on the
     direction alone. Only for a chord whose middle is near the slab: a
     far one (a line almost along the side) is no better a reference.
     Where [A > 0] and the first discriminant is negative within a bound
     of its rounding ([C]'s, of the scale of [|p|^2], [rho0^2] and the
     moved origin's [|w|^2], times [A], and [B^2]'s), from [-B / A], the
     line's closest approach to the side: a tangent line's first
     discriminant is noise of either sign. (The bound is found only for
     such lines: most lines that miss are not solved again.) *)
  let mid = if a > 0. && disc < 0. then -.b /. a else 0.5 *. (t0 +. t1) in
  let width = slab_hi -. slab_lo in
  let refine =
    a <> 0.
    && slab_lo -. width <= mid
    && mid <= slab_hi +. width
    && (disc >= 0.
       || disc
          >= -.(64. *. epsilon_float
               *. ((a *. (pp +. (rho0 *. rho0) +. (wx *. wx) +. (wy *. wy) +. (wz *. wz))) +. (b *. b))))
  in
  let mid = if refine then mid else 0. in
  let wx = wx +. (mid *. dx) and wy = wy +. (mid *. dy) and wz = wz +. (mid *. dz) in
  let kw = ((wx *. ax) +. (wy *. ay) +. (wz *. az)) /. hh in
  let px = wx -. (kw *. ax) and py = wy -. (kw *. ay) and pz = wz -. (kw *. az) in
  let rho0 = r0 +. (dr *. kw) in
  let b2 = (px *. qx) +. (py *. qy) +. (pz *. qz) -. (rho0 *. rhod) in
  let c2 = (px *. px) +. (py *. py) +. (pz *. pz) -. (rho0 *. rho0) in
  let disc2_raw = (b2 *. b2) -. (a *. c2) in
  (* [C2]'s rounding: the point's coordinates, each within a few [u |w|]
     of the line's, times [2 |p|], and [rho0]'s, within a few [u (|r0| +
     |dr|)], times [2 rho0]. A discriminant within [A] times it of 0 is a
     tangent line's (a double root): its point's residual is at most that
     bound, within [16 u (|w| + |r0| + |dr|)] of the side. *)
  let tangent =
    refine && a > 0. && disc2_raw < 0.
    && disc2_raw
       >= -.(a *. 16. *. epsilon_float
            *. (Float.abs px +. Float.abs py +. Float.abs pz +. Float.abs rho0)
            *. (Float.abs wx +. Float.abs wy +. Float.abs wz +. Float.abs r0 +. Float.abs dr))
  in
  let disc2 = if tangent then 0. else fmax 0. disc2_raw in
  let qq2 = -.(b2 +. Float.copy_sign (sqrt disc2) b2) in
  let u0 = if disc2 = 0. then -.b2 /. a else c2 /. qq2 and u1 = if disc2 = 0. then -.b2 /. a else qq2 /. a in
  let lo = if refine then mid +. fmin u0 u1 else fmin t0 t1 and hi = if refine then mid +. fmax u0 u1 else fmax t0 t1 in
  (* No root where [A > 0] and the discriminant is negative: the second
     one's sign when it was found again (the first is noise for a line
     by the apex, where a tangent point -B / A would lie off the surface
     by more than the bound), beyond the tangent line's tolerance. *)
  let none = a > 0. && if refine then disc2_raw < 0. && not tangent else disc < 0. in
  let in_lo =
    if a > 0. then if none then infinity else lo
    else if a < 0. then if rhod > 0. then hi else neg_infinity
    else if b = 0. then if c <= 0. then neg_infinity else infinity
    else if b > 0. then neg_infinity
    else lo
  in
  let in_hi =
    if a > 0. then if none then neg_infinity else hi
    else if a < 0. then if rhod > 0. then infinity else lo
    else if b = 0. then if c <= 0. then infinity else neg_infinity
    else if b > 0. then lo
    else infinity
  in
  (* An open cone: the side's roots within the slab. *)
  let lo_in = (not none) && slab_lo <= lo && lo <= slab_hi and hi_in = (not none) && slab_lo <= hi && hi <= slab_hi in
  let near =
    if capped then fmax slab_lo in_lo else if lo_in then lo else if hi_in then hi else infinity
  in
  let far =
    if capped then fmin slab_hi in_hi else if hi_in then hi else if lo_in then lo else neg_infinity
  in
  if near <= far then begin
    s.near <- tc +. near;
    s.far <- tc +. far;
    (* A cap's plane decides a crossing only where it is strictly beyond
       the side's (the first of equals is the side, as [literal] sorts
       them); a ray along the caps' planes ([da = 0]) crosses neither. *)
    let near_surface = if capped && slab_lo > in_lo then if da > 0. then base_cap else top_cap else side in
    let far_surface = if capped && slab_hi < in_hi then if da > 0. then top_cap else base_cap else side in
    (* A double root of the side is a tangent line's: [normal] turns its
       normal off the ray (9 more). *)
    near_surface + (3 * far_surface) + if lo = hi then 9 else 0
  end
  else -1

let[@inline never] roots (s : Scratch.t) g o =
  if solve s g o >= 0 then true
  else begin
    s.near <- infinity;
    s.far <- infinity;
    false
  end

(* The surface nearest the point alone (a root [solve] did not find
   again): the side, a cap, or the first of equally near ones. *)
let[@inline] nearest_surface (s : Scratch.t) g o =
  let bx = Array.unsafe_get g o and by = Array.unsafe_get g (o + 1) and bz = Array.unsafe_get g (o + 2) in
  let ax = Array.unsafe_get g (o + 3) -. bx and ay = Array.unsafe_get g (o + 4) -. by and az = Array.unsafe_get g (o + 5) -. bz in
  let r0 = Array.unsafe_get g (o + 6) and dr = Array.unsafe_get g (o + 7) -. Array.unsafe_get g (o + 6) in
  let capped = Array.unsafe_get g (o + 8) > 0. in
  let hh = (ax *. ax) +. (ay *. ay) +. (az *. az) in
  let h = sqrt hh in
  let wx = s.px -. bx and wy = s.py -. by and wz = s.pz -. bz in
  let wa = (wx *. ax) +. (wy *. ay) +. (wz *. az) in
  let kw = wa /. hh in
  let px = wx -. (kw *. ax) and py = wy -. (kw *. ay) and pz = wz -. (kw *. az) in
  let radial = sqrt ((px *. px) +. (py *. py) +. (pz *. pz)) in
  let slope = dr /. h in
  (* Distances to the side (along its normal) and to the caps' planes. *)
  let off_side = Float.abs (radial -. (r0 +. (dr *. kw))) /. sqrt (1. +. (slope *. slope)) in
  let off_base = Float.abs wa /. h and off_top = Float.abs (wa -. hh) /. h in
  if (not capped) || (off_side <= off_base && off_side <= off_top) then side
  else if off_base < off_top then base_cap
  else top_cap

(* The outward normal of one surface at the point [s.px, s.py, s.pz]:
   the side's, or a cap's along the axis. *)
let[@inline] surface_normal (s : Scratch.t) g o surface =
  let bx = Array.unsafe_get g o and by = Array.unsafe_get g (o + 1) and bz = Array.unsafe_get g (o + 2) in
  let ax = Array.unsafe_get g (o + 3) -. bx and ay = Array.unsafe_get g (o + 4) -. by and az = Array.unsafe_get g (o + 5) -. bz in
  let dr = Array.unsafe_get g (o + 7) -. Array.unsafe_get g (o + 6) in
  let hh = (ax *. ax) +. (ay *. ay) +. (az *. az) in
  let h = sqrt hh in
  if surface = side then begin
    let wx = s.px -. bx and wy = s.py -. by and wz = s.pz -. bz in
    let kw = ((wx *. ax) +. (wy *. ay) +. (wz *. az)) /. hh in
    let px = wx -. (kw *. ax) and py = wy -. (kw *. ay) and pz = wz -. (kw *. az) in
    let radial = sqrt ((px *. px) +. (py *. py) +. (pz *. pz)) in
    if radial > 0. then begin
      (* The gradient of [|p| - rho]: the unit radial minus the slope
         along the unit axis. *)
      let k = dr /. hh in
      let nx = (px /. radial) -. (k *. ax) and ny = (py /. radial) -. (k *. ay) and nz = (pz /. radial) -. (k *. az) in
      let l = sqrt ((nx *. nx) +. (ny *. ny) +. (nz *. nz)) in
      s.nx <- nx /. l;
      s.ny <- ny /. l;
      s.nz <- nz /. l
    end
    else begin
      (* On the axis: the apex of a pointed cone, whose normal is taken
         along the axis, out of the point. *)
      let sign = if dr < 0. then 1. else -1. in
      s.nx <- sign *. ax /. h;
      s.ny <- sign *. ay /. h;
      s.nz <- sign *. az /. h
    end
  end
  else begin
    let sign = if surface = base_cap then -1. else 1. in
    s.nx <- sign *. ax /. h;
    s.ny <- sign *. ay /. h;
    s.nz <- sign *. az /. h
  end

(* The root the caller keeps is in [s.near] (the traversal's [s.t], a
   CSG solid's crossing): the surface [solve] found it on, for the same
   ray, gives the normal. *)
let[@inline never] normal (s : Scratch.t) g o =
  let t = s.near and far = s.far in
  let code = solve s g o in
  let surface =
    if code >= 0 && t = s.near then code mod 3
    else if code >= 0 && t = s.far then code mod 9 / 3
    else nearest_surface s g o
  in
  s.near <- t;
  s.far <- far;
  surface_normal s g o surface;
  (* A tangent line touches the outside: its normal, across the ray up
     to rounding, is reflected off the ray where it leans along it, so
     that the side seen is the outside whatever the rounding. *)
  if code >= 9 && surface = side then begin
    let e = (s.nx *. s.dx) +. (s.ny *. s.dy) +. (s.nz *. s.dz) in
    if e > 0. then begin
      let k = 2. *. e /. ((s.dx *. s.dx) +. (s.dy *. s.dy) +. (s.dz *. s.dz)) in
      s.nx <- s.nx -. (k *. s.dx);
      s.ny <- s.ny -. (k *. s.dy);
      s.nz <- s.nz -. (k *. s.dz)
    end
  end

(* The executable specification's crossings, from the definition, with
   none of the kernel's arithmetic: a point [P] is on the side when its
   height [y = (P - B).u] along the unit axis is in [0, len] and its
   squared distance from the axis, [|P - B|^2 - y^2], is the square of
   the radius there, [r0 + (r1 - r0) y / len]: a quadratic in [t] in the
   textbook's form; on a cap when it is in the cap's plane within its
   radius. A capped cone is convex: its entry and exit are the first and
   last of those points. *)
(* The sign of the side's discriminant, exactly: with the axis [a = T -
   B] unnormalised, [w = O - B], the side's equation times [|a|^4] is
   [hh^2 |w + t D|^2 - hh y^2 = (r0 hh + dr y)^2], [hh = a.a], [y = (w +
   t D).a], [dr = r1 - r0]: a quadratic [A t^2 + 2 B t + C] whose
   coefficients are polynomials in the scene's floats, and whose
   discriminant [B^2 - A C] has the sign of [literal]'s. *)
let exact_discriminant c ~(origin : Vec3.t) ~(direction : Vec3.t) =
  let open Exact_float in
  let ( + ) = add and ( - ) = sub and ( * ) = mul in
  let dot (x1, y1, z1) (x2, y2, z2) = (x1 * x2) + (y1 * y2) + (z1 * z2) in
  let a = (diff c.top.x c.base.x, diff c.top.y c.base.y, diff c.top.z c.base.z) in
  let w = (diff origin.x c.base.x, diff origin.y c.base.y, diff origin.z c.base.z) in
  let d = (of_float direction.x, of_float direction.y, of_float direction.z) in
  let hh = dot a a and wa = dot w a and da = dot d a in
  let r0 = of_float c.radius and dr = diff c.top_radius c.radius in
  let m = (r0 * hh) + (dr * wa) in
  let hh2 = hh * hh in
  let qa = (hh2 * dot d d) - (hh * da * da) - (dr * dr * da * da) in
  let qb = (hh2 * dot w d) - (hh * wa * da) - (m * dr * da) in
  let qc = (hh2 * dot w w) - (hh * wa * wa) - (m * m) in
  sign ((qb * qb) - (qa * qc))

let literal c ~origin ~direction =
  let open Vec3 in
  let axis = sub c.top c.base in
  let len = norm axis in
  let u = smul (1. /. len) axis in
  let k = (c.top_radius -. c.radius) /. len in
  let w = sub origin c.base in
  let wu = dot w u and du = dot direction u in
  let qa = dot direction direction -. (du *. du) -. (k *. k *. du *. du) in
  let qb = 2. *. (dot w direction -. (wu *. du) -. (k *. du *. (c.radius +. (k *. wu)))) in
  let qc = dot w w -. (wu *. wu) -. ((c.radius +. (k *. wu)) *. (c.radius +. (k *. wu))) in
  let height t = wu +. (t *. du) in
  let on_side t = 0. <= height t && height t <= len in
  let side_normal t =
    let p = add w (smul t direction) in
    let radial = sub p (smul (dot p u) u) in
    let r = norm radial in
    if r = 0. then if k < 0. then u else neg u else Vec3.unit (sub (smul (1. /. r) radial) (smul k u))
  in
  let candidates =
    if qa = 0. then if qb = 0. then [] else [ (-.qc /. qb, false) ]
    else
      let disc = (qb *. qb) -. (4. *. qa *. qc) in
      (* The discriminant's sign from the floats where it is far above
         their rounding (the terms' magnitudes, times a margin that no
         rounding reaches); near 0, exactly ([exact_discriminant]): a line
         tangent to the side touches it, whatever the noise. *)
      let scale =
        let qa_m = dot direction direction +. (du *. du *. (1. +. (k *. k))) in
        let qb_m = 2. *. ((norm w *. norm direction) +. Float.abs (wu *. du) +. Float.abs (k *. du *. (Float.abs c.radius +. Float.abs (k *. wu)))) in
        let qc_m = dot w w +. (wu *. wu) +. ((Float.abs c.radius +. Float.abs (k *. wu)) ** 2.) in
        (qb_m *. qb_m) +. (4. *. qa_m *. qc_m)
      in
      let sign = if Float.abs disc > 1e-6 *. scale then Float.compare disc 0. else exact_discriminant c ~origin ~direction in
      if sign < 0 then []
      else if sign = 0 || disc <= 0. then [ (-.qb /. (2. *. qa), true) ]
      else
        (* Numerical Recipes' form: [(-b -+ sqrt disc) / 2a] loses the
           root near the origin to cancellation when [a] is small (a
           line almost along the side). *)
        let h = -0.5 *. (qb +. Float.copy_sign (sqrt disc) qb) in
        if h = 0. then [ (0., false) ] else [ (qc /. h, false); (h /. qa, false) ]
  in
  (* A tangent line touches the side's outside: a normal leaning along
     the ray (by rounding) is reflected off it. *)
  let off_ray n =
    let e = dot n direction in
    if e > 0. then sub n (smul (2. *. e /. dot direction direction) direction) else n
  in
  let side =
    List.filter_map
      (fun (t, tangent) -> if on_side t then Some (t, if tangent then off_ray (side_normal t) else side_normal t) else None)
      candidates
  in
  let cap center radius n =
    let dn = dot direction n in
    if dn = 0. then []
    else
      let t = dot (sub center origin) n /. dn in
      let d = sub (add origin (smul t direction)) center in
      if dot d d <= radius *. radius then [ (t, n) ] else []
  in
  let by_t = List.sort (fun (x, _) (y, _) -> Float.compare x y) in
  if c.capped then
    Cylinder.solid_ends ~direction (by_t (side @ cap c.base c.radius (neg u) @ cap c.top c.top_radius u))
  else by_t side

(* Each cap's disk lies within its radius of its centre on every axis;
   rounded outward by a float's step. *)
let bounds c =
  let lo (f : Vec3.t -> float) = Float.pred (Float.min (f c.base -. c.radius) (f c.top -. c.top_radius))
  and hi (f : Vec3.t -> float) = Float.succ (Float.max (f c.base +. c.radius) (f c.top +. c.top_radius)) in
  let x (v : Vec3.t) = v.x and y (v : Vec3.t) = v.y and z (v : Vec3.t) = v.z in
  (Vec3.v (lo x) (lo y) (lo z), Vec3.v (hi x) (hi y) (hi z))

let pp ppf c =
  Format.fprintf ppf "(cone (base %a) (top %a) (radius %s) (top-radius %s) (capped %b) %a)" Vec3.pp_components c.base
    Vec3.pp_components c.top (Float_text.to_string c.radius) (Float_text.to_string c.top_radius) c.capped Material.pp
    c.material

let intersect c ~origin ~direction =
  let g = Array.make 9 0. and s = Scratch.create () in
  store c g 0;
  Scratch.set_ray s origin direction;
  if roots s g 0 then (s.near, s.far) else (infinity, infinity)

let desc =
  {
    Shape_desc.name = "cone";
    kind = Kind.Cone;
    witness = Shape_desc.witness ();
    fields = [ ("base", Point); ("top", Point); ("radius", Number); ("top-radius", Number); ("capped", Flag true) ];
    read =
      (fun r m ->
        v ~capped:(r.flag "capped") ~base:(r.point "base") ~top:(r.point "top") ~radius:(r.number "radius")
          ~top_radius:(r.number "top-radius") m);
    validate;
    material = (fun c -> c.material);
    closed = (fun c -> c.capped);
    bounds;
    store;
    pp;
    equal;
    literal;
  }
