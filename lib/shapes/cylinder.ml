type t = { base : Vec3.t; top : Vec3.t; radius : float; capped : bool; material : Material.t } [@@deriving eq]

let v ?(capped = true) ~base ~top ~radius material = { base; top; radius; capped; material }

let validate c =
  let ( let* ) = Result.bind in
  let* _ = Limits.check_point "cylinder base" c.base in
  let* _ = Limits.check_point "cylinder top" c.top in
  let* _ = Limits.check_size "cylinder radius" c.radius in
  let* () =
    (* The axis's squared length is the kernel's divisor: it must be a
       normal float, as a radius's square is. *)
    let axis = Vec3.sub c.top c.base in
    let l = Vec3.norm axis in
    if l >= Limits.min_size && Float.is_finite l then Ok ()
    else
      Error
        (`Msg
          (Format.asprintf "cylinder base and top must be at least %s apart, got %a and %a"
             (Float_text.to_string Limits.min_size) Vec3.pp c.base Vec3.pp c.top))
  in
  let* _ = Material.validate ~form:"cylinder" c.material in
  Ok c

(* The radius's sign says whether the caps are there: no eighth float, and
   no constant in the stored floats, whose largest magnitude bounds the
   hit point's rounding ([Prepared]'s extent). *)
let store c g o =
  g.(o) <- c.base.x;
  g.(o + 1) <- c.base.y;
  g.(o + 2) <- c.base.z;
  g.(o + 3) <- c.top.x;
  g.(o + 4) <- c.top.y;
  g.(o + 5) <- c.top.z;
  g.(o + 6) <- (if c.capped then c.radius else -.c.radius)

(* The surfaces a root is on, as [solve] tells them. *)
let side = 0
let base_cap = 1
let top_cap = 2

(* The kernel's intersection: the ray's entry and exit in [s.near] and
   [s.far], and which surface each is on ([near_surface + 3 far_surface]),
   or [-1] if it misses. Two independent problems, as a box's slabs: the
   slab [0 <= <P - B, A> <= |A|^2] of the caps' planes, and the side's
   circle in the plane across the axis, where the ray's origin and
   direction are projected ([p], [q]) and the quadratic solved as
   [Sphere.roots] solves it (the closest approach [l] of the projected
   line to the axis, [r^2 - |l|^2] as [(r - |l|)(r + |l|)], the second
   root as [c / q]), so that a far, thin cylinder's silhouette is exact.
   Capped, the solid is the two intervals' intersection; open, the side's
   roots within the slab. Inlined in [roots] and [normal] alone. *)
let[@inline] solve (s : Scratch.t) g o =
  let bx = Array.unsafe_get g o and by = Array.unsafe_get g (o + 1) and bz = Array.unsafe_get g (o + 2) in
  let ax = Array.unsafe_get g (o + 3) -. bx
  and ay = Array.unsafe_get g (o + 4) -. by
  and az = Array.unsafe_get g (o + 5) -. bz in
  let signed = Array.unsafe_get g (o + 6) in
  let r = Float.abs signed in
  let h = (ax *. ax) +. (ay *. ay) +. (az *. az) in
  let wx = s.ox -. bx and wy = s.oy -. by and wz = s.oz -. bz in
  let dx = s.dx and dy = s.dy and dz = s.dz in
  let wa = (wx *. ax) +. (wy *. ay) +. (wz *. az) and da = (dx *. ax) +. (dy *. ay) +. (dz *. az) in
  let kw = wa /. h and kd = da /. h in
  let px = wx -. (kw *. ax) and py = wy -. (kw *. ay) and pz = wz -. (kw *. az) in
  let qx = dx -. (kd *. ax) and qy = dy -. (kd *. ay) and qz = dz -. (kd *. az) in
  let qq = (qx *. qx) +. (qy *. qy) +. (qz *. qz) in
  let pq = (px *. qx) +. (py *. qy) +. (pz *. qz) in
  let r2 = r *. r in
  (* The side: [lo, hi] on the line, or all of it (a ray along the axis
     within the radius), or nothing. *)
  let k = if qq = 0. then 0. else pq /. qq in
  let lx = px -. (k *. qx) and ly = py -. (k *. qy) and lz = pz -. (k *. qz) in
  let l2 = (lx *. lx) +. (ly *. ly) +. (lz *. lz) in
  let side_hit = l2 <= r2 in
  let len = sqrt l2 in
  let root = sqrt (qq *. ((r -. len) *. (r +. len))) in
  let m = -.(pq +. Float.copy_sign root pq) in
  let c = (px *. px) +. (py *. py) +. (pz *. pz) -. r2 in
  let t0 = if m = 0. then 0. else c /. m and t1 = if m = 0. then 0. else m /. qq in
  let lo = if qq = 0. then neg_infinity else if t0 < t1 then t0 else t1 in
  let hi = if qq = 0. then infinity else if t0 < t1 then t1 else t0 in
  (* The slab: the base's plane at [-wa / da], the top's at [(h - wa) / da]. *)
  let tb = -.wa /. da and tt = (h -. wa) /. da in
  let enter = if da > 0. then tb else tt and leave = if da > 0. then tt else tb in
  let enter_cap = if da > 0. then base_cap else top_cap and leave_cap = if da > 0. then top_cap else base_cap in
  if signed > 0. then begin
    (* The solid: the side's interval within the slab. *)
    let in_slab = da <> 0. || (0. <= wa && wa <= h) in
    let near_cap = da <> 0. && enter > lo and far_cap = da <> 0. && leave < hi in
    let near = if near_cap then enter else lo and far = if far_cap then leave else hi in
    if side_hit && in_slab && near <= far then begin
      s.near <- near;
      s.far <- far;
      (if near_cap then enter_cap else side) + (3 * if far_cap then leave_cap else side)
    end
    else -1
  end
  else begin
    (* The tube: each root of the side whose point lies within the slab. *)
    let y0 = wa +. (lo *. da) and y1 = wa +. (hi *. da) in
    let keep0 = side_hit && qq <> 0. && 0. <= y0 && y0 <= h and keep1 = side_hit && qq <> 0. && 0. <= y1 && y1 <= h in
    if keep0 || keep1 then begin
      s.near <- (if keep0 then lo else hi);
      s.far <- (if keep1 then hi else lo);
      0
    end
    else -1
  end

let[@inline never] roots (s : Scratch.t) g o =
  if solve s g o >= 0 then true
  else begin
    s.near <- infinity;
    s.far <- infinity;
    false
  end

(* The outward normal of one surface at the hit point: the side's, away
   from the axis, or a cap's, along the axis. *)
let[@inline] surface_normal (s : Scratch.t) g o surface =
  let bx = Array.unsafe_get g o and by = Array.unsafe_get g (o + 1) and bz = Array.unsafe_get g (o + 2) in
  let ax = Array.unsafe_get g (o + 3) -. bx
  and ay = Array.unsafe_get g (o + 4) -. by
  and az = Array.unsafe_get g (o + 5) -. bz in
  let h = (ax *. ax) +. (ay *. ay) +. (az *. az) in
  if surface = side then begin
    let wx = s.px -. bx and wy = s.py -. by and wz = s.pz -. bz in
    let k = ((wx *. ax) +. (wy *. ay) +. (wz *. az)) /. h in
    let nx = wx -. (k *. ax) and ny = wy -. (k *. ay) and nz = wz -. (k *. az) in
    let inv = 1. /. sqrt ((nx *. nx) +. (ny *. ny) +. (nz *. nz)) in
    s.nx <- nx *. inv;
    s.ny <- ny *. inv;
    s.nz <- nz *. inv
  end
  else begin
    let inv = (if surface = top_cap then 1. else -1.) /. sqrt h in
    s.nx <- ax *. inv;
    s.ny <- ay *. inv;
    s.nz <- az *. inv
  end

(* The surface nearest the point alone (no ray, or a root [solve] did
   not find): the side, a cap, or the first of equally near ones. *)
let[@inline] nearest_surface (s : Scratch.t) g o =
  let bx = Array.unsafe_get g o and by = Array.unsafe_get g (o + 1) and bz = Array.unsafe_get g (o + 2) in
  let ax = Array.unsafe_get g (o + 3) -. bx
  and ay = Array.unsafe_get g (o + 4) -. by
  and az = Array.unsafe_get g (o + 5) -. bz in
  let signed = Array.unsafe_get g (o + 6) in
  let len = sqrt ((ax *. ax) +. (ay *. ay) +. (az *. az)) in
  let wx = s.px -. bx and wy = s.py -. by and wz = s.pz -. bz in
  let y = ((wx *. ax) +. (wy *. ay) +. (wz *. az)) /. len in
  let w2 = (wx *. wx) +. (wy *. wy) +. (wz *. wz) in
  let radial = sqrt (Float.max 0. (w2 -. (y *. y))) in
  let off_side = Float.abs (radial -. Float.abs signed) and off_base = Float.abs y and off_top = Float.abs (y -. len) in
  if signed < 0. || (off_side <= off_base && off_side <= off_top) then side
  else if off_base <= off_top then base_cap
  else top_cap

(* The root the caller keeps is in [s.near] (the traversal's [s.t], a
   CSG solid's crossing): the surface [solve] found it on, for the same
   ray, gives the normal, so that a ray through the rim gets the normal
   of the surface whose root it is. *)
let[@inline never] normal (s : Scratch.t) g o =
  let t = s.near and far = s.far in
  let code = solve s g o in
  let surface =
    if code >= 0 && t = s.near then code mod 3
    else if code >= 0 && t = s.far then code / 3
    else nearest_surface s g o
  in
  s.near <- t;
  s.far <- far;
  surface_normal s g o surface

(* The entry and the exit of a convex solid among its crossings sorted
   by [t]: at a tie of crossings (a ray through a rim), the first of
   those where the ray goes in (against the outward normal) and of those
   where it goes out; the side first, as the list has it. A ray touching
   a rim alone enters by one surface and leaves by the other. *)
let solid_ends ~direction = function
  | [] -> []
  | first :: _ as l ->
      let last = List.nth l (List.length l - 1) in
      let pick (t, n) sign =
        match List.find_opt (fun (t', n') -> t' = t && Float.compare (Vec3.dot n' direction) 0. = sign) l with
        | Some x -> x
        | None -> (t, n)
      in
      [ pick first (-1); pick last 1 ]

(* The executable specification's crossings, from the definition: the
   points of the line at distance [radius] from the axis line (a
   quadratic in the cross products [(O - B) x u] and [D x u], [u] the unit
   axis) whose projection on the axis lies on the segment, and, capped,
   the points of the caps' planes within [radius] of the cap's centre;
   each with its outward normal. Capped, the solid's first and last;
   open, every crossing. *)
let literal c ~origin ~direction =
  let open Vec3 in
  let axis = sub c.top c.base in
  let len = norm axis in
  let u = smul (1. /. len) axis in
  let w = sub origin c.base in
  let wu = cross w u and du = cross direction u in
  let a = dot du du and b = dot wu du and cc = dot wu wu -. (c.radius *. c.radius) in
  let on_segment t =
    let y = dot (add w (smul t direction)) u in
    0. <= y && y <= len
  in
  let side_normal t =
    let p = add w (smul t direction) in
    unit (sub p (smul (dot p u) u))
  in
  let side =
    let disc = (b *. b) -. (a *. cc) in
    if a = 0. || disc < 0. then []
    else
      (* The root of like signs first, the other as [cc / q]: the product
         of the roots is [cc / a]. *)
      let q = -.(b +. Float.copy_sign (sqrt disc) b) in
      let ts = if q = 0. then [ 0. ] else [ q /. a; cc /. q ] in
      List.filter_map (fun t -> if on_segment t then Some (t, side_normal t) else None) ts
  in
  let cap center n =
    let dn = dot direction n in
    if dn = 0. then []
    else
      let t = dot (sub center origin) n /. dn in
      let d = sub (add origin (smul t direction)) center in
      if dot d d <= c.radius *. c.radius then [ (t, n) ] else []
  in
  let sorted l = List.sort (fun (x, _) (y, _) -> Float.compare x y) l in
  if c.capped then
    solid_ends ~direction (sorted (side @ cap c.base (neg u) @ cap c.top u))
  else sorted side

(* The box of the two caps' circles (the cylinder is their convex hull),
   outward by an ulp after the one rounding of each sum: a cylinder along
   an axis ends at its caps along it. *)
let bounds c =
  let e = Disk.rim_extent c.radius (Vec3.sub c.top c.base) in
  let lo f g = Float.pred (Float.min (f c.base) (f c.top) -. g e)
  and hi f g = Float.succ (Float.max (f c.base) (f c.top) +. g e) in
  let x (v : Vec3.t) = v.x and y (v : Vec3.t) = v.y and z (v : Vec3.t) = v.z in
  (Vec3.v (lo x x) (lo y y) (lo z z), Vec3.v (hi x x) (hi y y) (hi z z))

let pp ppf c =
  Format.fprintf ppf "(cylinder (base %a) (top %a) (radius %s)%s %a)" Vec3.pp_components c.base Vec3.pp_components
    c.top (Float_text.to_string c.radius)
    (if c.capped then "" else " (capped false)")
    Material.pp c.material

let show c = Format.asprintf "%a" pp c

let desc =
  {
    Shape_desc.name = "cylinder";
    kind = Kind.Cylinder;
    witness = Shape_desc.witness ();
    fields = [ ("base", Point); ("top", Point); ("radius", Number); ("capped", Flag true) ];
    read =
      (fun r m -> v ~capped:(r.flag "capped") ~base:(r.point "base") ~top:(r.point "top") ~radius:(r.number "radius") m);
    validate;
    material = (fun c -> c.material);
    closed = (fun c -> c.capped);
    bounds;
    store;
    pp;
    equal;
    literal;
  }
