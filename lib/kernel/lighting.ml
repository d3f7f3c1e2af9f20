open Scratch
open Tracer

(* Light through transparent objects: the shadow ray in [s] (its range
   set by [lighting]) is followed from surface to surface, nearest first
   (the same order for every traversal, so the product rounds alike),
   and the light it carries is scaled by the transparency of each surface
   it crosses: twice through a ball, once out of the one it starts in; an
   opaque one stops it. The factor is left in [tr.tree.attenuation.(0)]
   (a float returned by a call is boxed). *)
let[@inline never] transmit tr =
  let p = tr.p and s = tr.s in
  tr.counters.shadow <- tr.counters.shadow + 1;
  let f = ref 1. and go = ref true in
  while !go do
    let i = Traversal.closest tr in
    if i < 0 then go := false
    else begin
      f := !f *. Array.unsafe_get p.transparency (Array.unsafe_get p.material i);
      if !f > 0. then begin
        s.t_min <- s.t;
        (* A shadow ray may cross every transparent surface: each further
           crossing is a search, checked against the budget like a hit of
           the tree (the first one is the hit's, checked there). *)
        check_budget tr
      end
      else go := false
    end
  done;
  Array.unsafe_set tr.tree.attenuation 0 !f

(* Adds light [l]'s terms, of intensity [li] and unnormalised direction
   [s.dx..], to [s.intensity]: the diffuse one if [n_dot_l > 0], the
   specular one of cosine [cos] if [cos > 0] (see [lighting_with]). *)
let[@inline] add_terms s ~specular_of m li n_dot_l cos length_n =
  if n_dot_l > 0. then begin
    let lx = s.dx and ly = s.dy and lz = s.dz in
    s.intensity <- s.intensity +. (li *. n_dot_l /. (length_n *. sqrt ((lx *. lx) +. (ly *. ly) +. (lz *. lz))))
  end;
  if cos > 0. then s.intensity <- s.intensity +. (li *. Float.pow cos (Array.unsafe_get specular_of m))

(* {1 Area, sphere and spot lights}

   Each sample of these lights is a point light at a point [Q] of its own
   (Light, "Sample points"). Their code is apart from the loop of the
   document's lights, which keeps its instructions: a scene without them
   pays one comparison of the light's kind. *)

(* [Sample_key.stratum h ~n i], here so that its float is not boxed (a
   float returned by another module's function is, without flambda): the
   same operations, pinned against [Literal], which calls [Sample_key]. *)
let[@inline] stratum h n i =
  let x = (Float.of_int i +. (Float.of_int (Sample_key.mix (Sample_key.key h i)) *. 0x1p-31)) /. Float.of_int n in
  if x < 1. then x else 0x1.fffffffffffffp-1

(* [Sample_key.unit h], likewise unboxed. *)
let[@inline] unit h = Float.of_int (Sample_key.mix h) *. 0x1p-31

(* The terms of one sample, of intensity [li]: the point light at
   [s.px.. + s.dx..], with its shadow ray (range [(epsilon, 1)]). As the
   document's point light in [lighting_with]: both terms decided first, a
   sample that would add neither casts no shadow ray with the skips. The
   specular cut of light [l] was found for its whole intensity: a sample's
   term, no larger, is no more able to change the sum. [lit]: the sample
   is taken as seen without a shadow ray (an adaptive area light whose
   corners are all seen). *)
let[@inline] sample_terms tr ~through ~shiny ~specular_of m l li length_n length_v ~lit =
  let p = tr.p and s = tr.s in
  s.ox <- s.px;
  s.oy <- s.py;
  s.oz <- s.pz;
  s.t_min <- p.epsilon;
  s.t_max <- 1.;
  let nx = s.nx and ny = s.ny and nz = s.nz in
  let lx = s.dx and ly = s.dy and lz = s.dz in
  let n_dot_l = (nx *. lx) +. (ny *. ly) +. (nz *. lz) in
  let cos =
    if shiny then begin
      let k = 2. *. n_dot_l in
      let rx = (nx *. k) -. lx and ry = (ny *. k) -. ly and rz = (nz *. k) -. lz in
      let r_dot_v = (rx *. s.vx) +. (ry *. s.vy) +. (rz *. s.vz) in
      let cos = if r_dot_v > 0. then r_dot_v /. (sqrt ((rx *. rx) +. (ry *. ry) +. (rz *. rz)) *. length_v) else 0. in
      if cos > Array.unsafe_get p.specular_cut ((m * p.n_lights) + l) then cos else 0.
    end
    else 0.
  in
  if if p.shadow_skip then n_dot_l > 0. || cos > 0. else lx <> 0. || ly <> 0. || lz <> 0. then begin
    if lit then add_terms s ~specular_of m li n_dot_l cos length_n
    else if through then begin
      transmit tr;
      let f = Array.unsafe_get tr.tree.attenuation 0 in
      if f > 0. then add_terms s ~specular_of m (li *. f) n_dot_l cos length_n
    end
    else if not (Traversal.shadowed tr l) then add_terms s ~specular_of m li n_dot_l cos length_n
  end

(* How an adaptive area light's four corners are seen from [s.px..]:
   [0] all hidden, [1] all seen (through glass: a factor of exactly 1),
   [2] in doubt (Light, "Penumbra-only sampling"). *)
let hidden = 0
let seen = 1
let doubt = 2

(* The shadow ray from [s.px..] to the point [(su, sv)] of the area light
   at corner [c..] with edges [a..], [b..], in [s]; range [(epsilon, 1)]. *)
let[@inline] aim tr cx cy cz ax ay az bx by bz su sv =
  let s = tr.s in
  s.dx <- cx +. (su *. ax) +. (sv *. bx) -. s.px;
  s.dy <- cy +. (su *. ay) +. (sv *. by) -. s.py;
  s.dz <- cz +. (su *. az) +. (sv *. bz) -. s.pz;
  s.ox <- s.px;
  s.oy <- s.py;
  s.oz <- s.pz;
  s.t_min <- tr.p.epsilon;
  s.t_max <- 1.

(* The corners in the order (0, 0), (1, 1), (1, 0), (0, 1), the diagonal
   first, and only while they agree: once one is seen and another hidden
   (or one seen through glass) the point is in doubt whatever the others
   are, and their rays would be spent for nothing (the same verdict, fewer
   rays in the penumbra). *)
let[@inline] corners tr ~through l cx cy cz ax ay az bx by bz =
  let n_seen = ref 0 and n_hidden = ref 0 and c = ref 0 in
  while !c < 4 && (!n_seen = !c || !n_hidden = !c) do
    let k = !c in
    aim tr cx cy cz ax ay az bx by bz (if k = 1 || k = 2 then 1. else 0.) (if k = 1 || k = 3 then 1. else 0.);
    if through then begin
      transmit tr;
      let f = Array.unsafe_get tr.tree.attenuation 0 in
      if f = 1. then incr n_seen else if f = 0. then incr n_hidden
    end
    else if Traversal.shadowed tr l then incr n_hidden
    else incr n_seen;
    c := k + 1
  done;
  if !n_seen = 4 then seen else if !n_hidden = 4 then hidden else doubt

(* The sample of cell [(a, b)] of an area light of [u x v] cells, the
   mixed key of its cell [m = mix (key hl (a v + b))]: its place [(s, t)]
   on the rectangle, in the sub-stratum [cells.(b)] of the cell's [v]
   columns and [cells.(v + a)] of its [u] rows (Light, "Sample points":
   correlated multi-jittered, the [u v] abscissae one in each of [u v]
   columns, the ordinates one in each of [u v] rows). *)
let[@inline] below_1 x = if x < 1. then x else 0x1.fffffffffffffp-1

let[@inline] cell_s cells u v a b m =
  below_1 ((Float.of_int ((a * v) + Array.unsafe_get cells b) +. (Float.of_int m *. 0x1p-31)) /. Float.of_int (u * v))

let[@inline] cell_t cells u v a b m =
  below_1
    ((Float.of_int ((b * u) + Array.unsafe_get cells (v + a)) +. (Float.of_int (Sample_key.mix m) *. 0x1p-31))
    /. Float.of_int (u * v))

let[@inline] cell_key hl v a b = Sample_key.mix (Sample_key.key hl ((a * v) + b))

(* The point's two permutations of the cells' sub-strata, of the [v]
   columns and of the [u] rows, into [tr.light_cells]: one walk a cell
   side, none for a side of one cell. *)
let cells tr hl u v =
  let t = tr.light_cells in
  if v = 1 then t.(0) <- 0 else Sample_key.fill t ~at:0 ~shift:0 ~p:(Sample_key.mix (Sample_key.key hl (-1))) ~n:v;
  if u = 1 then t.(v) <- 0 else Sample_key.fill t ~at:v ~shift:0 ~p:(Sample_key.mix (Sample_key.key hl (-2))) ~n:u

(* Is the shadow ray from [s.px..] to the point [(su, sv)] of the area
   light stopped? *)
let[@inline] blocked_at tr l cx cy cz ax ay az bx by bz su sv =
  aim tr cx cy cz ax ay az bx by bz su sv;
  Traversal.shadowed tr l

(* {1 The whole light in view}

   A lit point [P] sees the whole of a light's rectangle (an area light's,
   or the square around a sphere light's disc) when no object meets the
   hull [H] of [P] and the rectangle's corners [C0 .. C3]: every shadow ray
   to a point [Q] of the rectangle is the segment from [P] to [Q], inside
   [H]. Then every sample is seen, and its terms are summed without a
   shadow ray: exactly what the rays would have found, in the same order
   (the same bytes). The blockers are the planes ([p.unbounded]) and the
   boxes of [p.casters], which hold every bounded object.

   A box is apart from [H] if some axis [n] separates their projections:
   [H]'s is spanned by [P]'s and the corners', a box's is its centre's
   plus or minus [|n_x| h_x + |n_y| h_y + |n_z| h_z]. The axes tried are
   x, y, z, the rectangle's normal and the normals of [H]'s four sides
   through [P] (not the edges' cross products: a box that only those
   would separate is taken as a blocker, which costs rays, never bytes).
   Any axis at all, rounded or not, separates if the projections are
   apart, so the rounding of the axes does not matter; that of the
   projections is covered by a margin of [2^-30 |n|_1 S] ([S] the largest
   magnitude of a coordinate involved, plus one), and a hit the kernel
   reports lies inside its object's padded box ([Prepared.t]'s
   [casters]). Up to those margins, this test is exact.

   A plane is tested as the kernel tests it ([Plane.roots]): from [P], the
   ray toward [Q] meets it at [t = num / den], [num] computed from [P] by
   the kernel's own operations (the same float) and [den] the plane's
   normal against [Q - P], linear in [Q]: its extremes over the rectangle
   are at its corners. A plane does not stop the ray if [t] is outside
   [(epsilon, 1)] for every [Q]: for [num <= 0], every [den > num] ([den >
   0] gives [t <= 0]; [num < den < 0] gives [t > 1], and the rounded
   quotient of numbers of magnitudes so ordered is at least 1); for [num
   >= 0], every [den < num], likewise; [den]'s rounding, in the kernel and
   here, covered by the margin. *)

let[@inline] fmin (a : float) b = if a < b then a else b
let[@inline] fmax (a : float) b = if a > b then a else b
let[@inline] large x y z = fmax (Float.abs x) (fmax (Float.abs y) (Float.abs z))
let[@inline] dot nx ny nz x y z = (nx *. x) +. (ny *. y) +. (nz *. z)

(* Are the box of centre [m..] (relative to [P]) and half sides [h..]
   apart from [H] along axis [n..], [H]'s projection [(lo, hi)]? *)
let[@inline] apart nx ny nz lo hi mx my mz hx hy hz scale =
  let c = (nx *. mx) +. (ny *. my) +. (nz *. mz) in
  let r = (Float.abs nx *. hx) +. (Float.abs ny *. hy) +. (Float.abs nz *. hz) in
  let tol = (Float.abs nx +. Float.abs ny +. Float.abs nz) *. scale in
  c -. r > hi +. tol || c +. r < lo -. tol

(* The fewest samples (shadow rays) a light must have for the test: it
   costs about as much as three or four shadow rays through a few objects
   (made for every light of the [ball] and [area-room] scenes of
   bench/quality.ml at 1 x 1, it cost 11.9 M and 10.3 M instructions more
   than the rays it saved). *)
let min_whole = 4

(* Is box [o] of [casters] beside the extent [(l.., h..)] (relative to
   [p..]) along x, y or z? *)
let[@inline] beside c o px py pz lx hx ly hy lz hz scale =
  let mx = Array.unsafe_get c o -. px and my = Array.unsafe_get c (o + 1) -. py and mz = Array.unsafe_get c (o + 2) -. pz in
  let wx = Array.unsafe_get c (o + 3) and wy = Array.unsafe_get c (o + 4) and wz = Array.unsafe_get c (o + 5) in
  mx -. wx > hx +. scale || mx +. wx < lx -. scale || my -. wy > hy +. scale || my +. wy < ly -. scale
  || mz -. wz > hz +. scale || mz +. wz < lz -. scale

(* Does no plane and no box of [p.casters] meet the hull of [s.px..] and
   the rectangle of corner [c..] and edges [a..], [b..]? *)
let[@inline] whole_in_view tr cx cy cz ax ay az bx by bz =
  let p = tr.p and s = tr.s in
  let px = s.px and py = s.py and pz = s.pz in
  (* The corners relative to [P]: C, C + a, C + a + b, C + b. *)
  let x0 = cx -. px and y0 = cy -. py and z0 = cz -. pz in
  let x1 = x0 +. ax and y1 = y0 +. ay and z1 = z0 +. az in
  let x2 = x1 +. bx and y2 = y1 +. by and z2 = z1 +. bz in
  let x3 = x0 +. bx and y3 = y0 +. by and z3 = z0 +. bz in
  let big =
    1. +. large px py pz +. large cx cy cz +. large ax ay az +. large bx by bz
    +. if Array.length p.casters > 0 then Array.unsafe_get p.casters 0 else 0.
  in
  let scale = big *. 0x1p-30 in
  let clear = ref true in
  (* The planes, as the kernel tests them. *)
  let planes = p.unbounded and geom = p.geom in
  let i = ref 0 in
  while !clear && !i < Array.length planes do
    let o = Kind.stride * Array.unsafe_get p.at0 (Array.unsafe_get planes !i) in
    let nx = Array.unsafe_get geom (o + 6) and ny = Array.unsafe_get geom (o + 7) and nz = Array.unsafe_get geom (o + 8) in
    let num =
      ((Array.unsafe_get geom o -. px) *. nx) +. ((Array.unsafe_get geom (o + 1) -. py) *. ny)
      +. ((Array.unsafe_get geom (o + 2) -. pz) *. nz)
    in
    let d0 = (x0 *. nx) +. (y0 *. ny) +. (z0 *. nz) and d1 = (x1 *. nx) +. (y1 *. ny) +. (z1 *. nz) in
    let d2 = (x2 *. nx) +. (y2 *. ny) +. (z2 *. nz) and d3 = (x3 *. nx) +. (y3 *. ny) +. (z3 *. nz) in
    let tol = 2. *. scale in
    clear :=
      (num <= 0. && fmin (fmin d0 d1) (fmin d2 d3) > num +. tol)
      || (num >= 0. && fmax (fmax d0 d1) (fmax d2 d3) < num -. tol);
    incr i
  done;
  let c = p.casters in
  let n_boxes = if Array.length c = 0 then 0 else (Array.length c - 1) / 6 in
  (* The hull's extent along x, y, z, relative to [P]. *)
  let lx = fmin 0. (fmin (fmin x0 x1) (fmin x2 x3)) and hx = fmax 0. (fmax (fmax x0 x1) (fmax x2 x3)) in
  let ly = fmin 0. (fmin (fmin y0 y1) (fmin y2 y3)) and hy = fmax 0. (fmax (fmax y0 y1) (fmax y2 y3)) in
  let lz = fmin 0. (fmin (fmin z0 z1) (fmin z2 z3)) and hz = fmax 0. (fmax (fmax z0 z1) (fmax z2 z3)) in
  (* First the boxes' extents alone: where they all lie beside the hull's,
     no other axis is needed. *)
  let planes_clear = !clear in
  let k = ref 0 in
  while !clear && !k < n_boxes do
    let o = 1 + (6 * !k) in
    clear := beside c o px py pz lx hx ly hy lz hz scale;
    incr k
  done;
  if planes_clear && not !clear then begin
    clear := true;
    (* The rectangle's normal a x b: [P] at 0, the corners at [w]. *)
    let rx = (ay *. bz) -. (az *. by) and ry = (az *. bx) -. (ax *. bz) and rz = (ax *. by) -. (ay *. bx) in
    let w = dot rx ry rz x0 y0 z0 in
    let rlo = fmin 0. w and rhi = fmax 0. w in
    (* The side through [P], C_j and C_(j+1): its normal [e_j x e_(j+1)];
       [H]'s extent along it spans 0 ([P], C_j and C_(j+1), up to a
       rounding the margin covers) and the other two corners' values. *)
    let sx0 = (y0 *. z1) -. (z0 *. y1) and sy0 = (z0 *. x1) -. (x0 *. z1) and sz0 = (x0 *. y1) -. (y0 *. x1) in
    let sx1 = (y1 *. z2) -. (z1 *. y2) and sy1 = (z1 *. x2) -. (x1 *. z2) and sz1 = (x1 *. y2) -. (y1 *. x2) in
    let sx2 = (y2 *. z3) -. (z2 *. y3) and sy2 = (z2 *. x3) -. (x2 *. z3) and sz2 = (x2 *. y3) -. (y2 *. x3) in
    let sx3 = (y3 *. z0) -. (z3 *. y0) and sy3 = (z3 *. x0) -. (x3 *. z0) and sz3 = (x3 *. y0) -. (y3 *. x0) in
    let e0c = dot sx0 sy0 sz0 x2 y2 z2 and e0d = dot sx0 sy0 sz0 x3 y3 z3 in
    let lo0 = fmin 0. (fmin e0c e0d) and hi0 = fmax 0. (fmax e0c e0d) in
    let e1c = dot sx1 sy1 sz1 x3 y3 z3 and e1d = dot sx1 sy1 sz1 x0 y0 z0 in
    let lo1 = fmin 0. (fmin e1c e1d) and hi1 = fmax 0. (fmax e1c e1d) in
    let e2c = dot sx2 sy2 sz2 x0 y0 z0 and e2d = dot sx2 sy2 sz2 x1 y1 z1 in
    let lo2 = fmin 0. (fmin e2c e2d) and hi2 = fmax 0. (fmax e2c e2d) in
    let e3c = dot sx3 sy3 sz3 x1 y1 z1 and e3d = dot sx3 sy3 sz3 x2 y2 z2 in
    let lo3 = fmin 0. (fmin e3c e3d) and hi3 = fmax 0. (fmax e3c e3d) in
    let k = ref 0 in
    while !clear && !k < n_boxes do
      let o = 1 + (6 * !k) in
      let mx = Array.unsafe_get c o -. px and my = Array.unsafe_get c (o + 1) -. py and mz = Array.unsafe_get c (o + 2) -. pz in
      let wx = Array.unsafe_get c (o + 3) and wy = Array.unsafe_get c (o + 4) and wz = Array.unsafe_get c (o + 5) in
      clear :=
        beside c o px py pz lx hx ly hy lz hz scale
        || apart rx ry rz rlo rhi mx my mz wx wy wz scale
        || apart sx0 sy0 sz0 lo0 hi0 mx my mz wx wy wz scale
        || apart sx1 sy1 sz1 lo1 hi1 mx my mz wx wy wz scale
        || apart sx2 sy2 sz2 lo2 hi2 mx my mz wx wy wz scale
        || apart sx3 sy3 sz3 lo3 hi3 mx my mz wx wy wz scale;
      incr k
    done
  end;
  !clear

(* Kinds of object that are convex sets (a plane's blocked side is a
   half-space): the points of the light whose shadow rays one of them
   stops form a convex set (see [area]). *)
let[@inline] convex (k : Kind.t) =
  match k with
  | Sphere | Triangle | Smooth_triangle | Plane | Box | Disk -> true
  | Csg | Cylinder | Cone | Torus | Instance -> false

(* [(x, y)] lies strictly left of the line from [(x0, y0)] to [(x1, y1)],
   by a margin that covers the rounding of the sample points. *)
let[@inline] left x0 y0 x1 y1 x y = ((x1 -. x0) *. (y -. y0)) -. ((y1 -. y0) *. (x -. x0)) > 1e-9

(* An area light: its [u x v] cells in order, [a] along edge1 outside;
   adaptive, only where its corners leave the point in doubt.

   The exact umbra skip (with the skips, opaque shadow rays, [u, v >= 2]):
   the samples of the four corner cells are traced first (their answers
   kept and used in their turn, so the terms are summed in the same
   order). If one convex object [K] stops all four, it stops the ray to
   every point of their convex hull: for rays stopped at [t1] and [t2] in
   [(epsilon, 1)] toward [Q1] and [Q2], the segment between the two hit
   points lies in [K] and crosses the ray toward any point between [Q1]
   and [Q2] at the weighted harmonic mean of [t1] and [t2], also in
   [(epsilon, 1)] (the light outside [K], as lights are). The samples
   strictly inside that hull (in the rectangle's coordinates [(s, t)],
   which the sample points follow affinely) add nothing, and cast no ray.
   Exact up to the rounding of the sample points and of the kernel's own
   hit tests near [K]'s outline (the margin of [left] covers the first). *)
let[@inline] area tr ~through ~shiny ~specular_of m l length_n length_v =
  let p = tr.p and s = tr.s in
  let g = Prepared.light_stride * l and geom = p.light_geom in
  let u = Array.unsafe_get p.light_su l and v = Array.unsafe_get p.light_sv l in
  let li = Array.unsafe_get p.light_intensity l /. Float.of_int (u * v) in
  let hl = Sample_key.key tr.key (Array.unsafe_get p.light_number l) in
  let cx = Array.unsafe_get geom g and cy = Array.unsafe_get geom (g + 1) and cz = Array.unsafe_get geom (g + 2) in
  let ax = Array.unsafe_get geom (g + 3) and ay = Array.unsafe_get geom (g + 4) and az = Array.unsafe_get geom (g + 5) in
  let bx = Array.unsafe_get geom (g + 6) and by = Array.unsafe_get geom (g + 7) and bz = Array.unsafe_get geom (g + 8) in
  let px = s.px and py = s.py and pz = s.pz in
  let uniform = Array.unsafe_get p.light_uniform l in
  (* Not for [(sampling uniform)]: plain Monte Carlo, every sample traced,
     the baseline that bench/quality.ml measures the other two against
     (as it takes no umbra skip either); the test would change none of
     its bytes (docs/run-time-against-error.md, "The whole light in
     view", measures it both ways). *)
  let whole =
    (not uniform) && u * v >= min_whole && Array.length p.casters > 0 && whole_in_view tr cx cy cz ax ay az bx by bz
  in
  if whole then tr.counters.whole <- tr.counters.whole + 1;
  let verdict =
    if whole then seen
    else if Array.unsafe_get p.light_adaptive l then begin
      let v = corners tr ~through l cx cy cz ax ay az bx by bz in
      if v = doubt then tr.counters.penumbra <- tr.counters.penumbra + 1
      else tr.counters.decided <- tr.counters.decided + 1;
      v
    end
    else doubt
  in
  if verdict <> hidden then begin
    (* Facing the rectangle's centre: elsewhere the samples mostly add no
       term and cast no ray, and the corners' rays would be extra. Uniform
       samples have no corner cells whose hull holds the others. *)
    let early =
      verdict = doubt && (not uniform) && (not through) && p.umbra_skip && u >= 2 && v >= 2
      && (s.nx *. (cx +. (0.5 *. (ax +. bx)) -. px)) +. (s.ny *. (cy +. (0.5 *. (ay +. by)) -. py))
         +. (s.nz *. (cz +. (0.5 *. (az +. bz)) -. pz))
         > 0.
    in
    let u1 = u - 1 and v1 = v - 1 and c = tr.light_cells in
    if not uniform then cells tr hl u v;
    (* The corner cells' points, only where they are traced first. *)
    let s00 = if early then cell_s c u v 0 0 (cell_key hl v 0 0) else 0. in
    let t00 = if early then cell_t c u v 0 0 (cell_key hl v 0 0) else 0. in
    let s10 = if early then cell_s c u v u1 0 (cell_key hl v u1 0) else 0. in
    let t10 = if early then cell_t c u v u1 0 (cell_key hl v u1 0) else 0. in
    let s11 = if early then cell_s c u v u1 v1 (cell_key hl v u1 v1) else 0. in
    let t11 = if early then cell_t c u v u1 v1 (cell_key hl v u1 v1) else 0. in
    let s01 = if early then cell_s c u v 0 v1 (cell_key hl v 0 v1) else 0. in
    let t01 = if early then cell_t c u v 0 v1 (cell_key hl v 0 v1) else 0. in
    (* Per corner cell: stopped, and by which object ([-1]: seen). *)
    let k00 = ref (-1) and k10 = ref (-1) and k11 = ref (-1) and k01 = ref (-1) in
    if early then begin
      if blocked_at tr l cx cy cz ax ay az bx by bz s00 t00 then k00 := Array.unsafe_get tr.last_blocker l;
      if blocked_at tr l cx cy cz ax ay az bx by bz s10 t10 then k10 := Array.unsafe_get tr.last_blocker l;
      if blocked_at tr l cx cy cz ax ay az bx by bz s11 t11 then k11 := Array.unsafe_get tr.last_blocker l;
      if blocked_at tr l cx cy cz ax ay az bx by bz s01 t01 then k01 := Array.unsafe_get tr.last_blocker l
    end;
    let umbra = early && !k00 >= 0 && !k10 = !k00 && !k11 = !k00 && !k01 = !k00 && convex (Array.unsafe_get p.kind !k00) in
    for a = 0 to u - 1 do
      for b = 0 to v - 1 do
        let mk = cell_key hl v a b in
        let su = if uniform then Float.of_int mk *. 0x1p-31 else cell_s c u v a b mk in
        let sv = if uniform then Float.of_int (Sample_key.mix mk) *. 0x1p-31 else cell_t c u v a b mk in
        s.dx <- cx +. (su *. ax) +. (sv *. bx) -. px;
        s.dy <- cy +. (su *. ay) +. (sv *. by) -. py;
        s.dz <- cz +. (su *. az) +. (sv *. bz) -. pz;
        if early && (a = 0 || a = u1) && (b = 0 || b = v1) then begin
          (* A corner cell, traced above: its answer in its turn. *)
          let k = if a = 0 then if b = 0 then !k00 else !k01 else if b = 0 then !k10 else !k11 in
          if k < 0 then sample_terms tr ~through ~shiny ~specular_of m l li length_n length_v ~lit:true
        end
        else if
          umbra && left s00 t00 s10 t10 su sv && left s10 t10 s11 t11 su sv && left s11 t11 s01 t01 su sv
          && left s01 t01 s00 t00 su sv
        then tr.counters.umbra <- tr.counters.umbra + 1
        else sample_terms tr ~through ~shiny ~specular_of m l li length_n length_v ~lit:(verdict = seen)
      done
    done
  end

(* A sphere light: [n] rings of equal area of the disc facing the point. *)
let[@inline] sphere tr ~through ~shiny ~specular_of m l length_n length_v =
  let p = tr.p and s = tr.s in
  let g = Prepared.light_stride * l and geom = p.light_geom in
  let n = Array.unsafe_get p.light_su l in
  let li = Array.unsafe_get p.light_intensity l /. Float.of_int n in
  let hl = Sample_key.key tr.key (Array.unsafe_get p.light_number l) in
  let cx = Array.unsafe_get geom g and cy = Array.unsafe_get geom (g + 1) and cz = Array.unsafe_get geom (g + 2) in
  let radius = Array.unsafe_get geom (g + 3) in
  let px = s.px and py = s.py and pz = s.pz in
  let wx = cx -. px and wy = cy -. py and wz = cz -. pz in
  let len = sqrt ((wx *. wx) +. (wy *. wy) +. (wz *. wz)) in
  (* At the centre the disc has no facing: no light, as Literal. *)
  if len > 0. then begin
    (* Scaled by the reciprocal, as [Vec3.unit] (Literal's) does. *)
    let inv = 1. /. len in
    let wx = inv *. wx and wy = inv *. wy and wz = inv *. wz in
    (* e1 = a x w, a the axis least along w. *)
    let along_x = Float.abs wx > 0.9 in
    let e1x = if along_x then wz else 0. and e1y = if along_x then 0. else -.wz and e1z = if along_x then -.wx else wy in
    let l1 = sqrt ((e1x *. e1x) +. (e1y *. e1y) +. (e1z *. e1z)) in
    let inv = 1. /. l1 in
    let e1x = inv *. e1x and e1y = inv *. e1y and e1z = inv *. e1z in
    let e2x = (wy *. e1z) -. (wz *. e1y) and e2y = (wz *. e1x) -. (wx *. e1z) and e2z = (wx *. e1y) -. (wy *. e1x) in
    (* The angles, stratified with the rings (Light, "Sample points"):
       [c] sectors, turned by [r]; ring [j]'s [a = j mod c], its block's
       [b] (a permutation of the [q] blocks, one walk a block). *)
    (* The disc lies in the square of corner [c - r e1 - r e2] and edges
       [2 r e1], [2 r e2]. *)
    let whole =
      n >= min_whole && Array.length p.casters > 0
      &&
      let d = 2. *. radius in
      whole_in_view tr
        (cx -. (radius *. (e1x +. e2x)))
        (cy -. (radius *. (e1y +. e2y)))
        (cz -. (radius *. (e1z +. e2z)))
        (d *. e1x) (d *. e1y) (d *. e1z) (d *. e2x) (d *. e2y) (d *. e2z)
    in
    if whole then tr.counters.whole <- tr.counters.whole + 1;
    let c = Light.sectors n in
    let q = (n + c - 1) / c in
    let r = unit (Sample_key.key hl (-1)) in
    let pb = Sample_key.mix (Sample_key.key hl (-2)) and wb = Sample_key.mask q in
    let fc = Float.of_int c and fq = Float.of_int q in
    let a = ref 0 and block = ref 0 and b = ref (Sample_key.walk ~p:pb ~w:wb ~n:q 0) in
    for j = 0 to n - 1 do
      let h = Sample_key.key hl j in
      let rho = radius *. sqrt (stratum (Sample_key.key h 0) n j) in
      let phi =
        2. *. Float.pi
        *. (r +. ((Float.of_int !a +. ((Float.of_int !b +. (Float.of_int (Sample_key.mix (Sample_key.key h 1)) *. 0x1p-31)) /. fq)) /. fc))
      in
      if !a = c - 1 then begin
        a := 0;
        incr block;
        if !block < q then b := Sample_key.walk ~p:pb ~w:wb ~n:q !block
      end
      else incr a;
      let c1 = rho *. cos phi and c2 = rho *. sin phi in
      s.dx <- cx +. (c1 *. e1x) +. (c2 *. e2x) -. px;
      s.dy <- cy +. (c1 *. e1y) +. (c2 *. e2y) -. py;
      s.dz <- cz +. (c1 *. e1z) +. (c2 *. e2z) -. pz;
      sample_terms tr ~through ~shiny ~specular_of m l li length_n length_v ~lit:whole
    done
  end

(* A spotlight: a point light scaled by [cos^falloff] of the angle off its
   axis, dark outside its cone (where it casts no shadow ray). *)
let[@inline] spot tr ~through ~shiny ~specular_of m l length_n length_v =
  let p = tr.p and s = tr.s in
  let g = Prepared.light_stride * l and geom = p.light_geom in
  let lx = Array.unsafe_get geom g -. s.px and ly = Array.unsafe_get geom (g + 1) -. s.py
  and lz = Array.unsafe_get geom (g + 2) -. s.pz in
  let dist = sqrt ((lx *. lx) +. (ly *. ly) +. (lz *. lz)) in
  let cos_off =
    -.((lx *. Array.unsafe_get geom (g + 3)) +. (ly *. Array.unsafe_get geom (g + 4)) +. (lz *. Array.unsafe_get geom (g + 5)))
    /. dist
  in
  if dist > 0. && cos_off >= Array.unsafe_get geom (g + 6) then begin
    s.dx <- lx;
    s.dy <- ly;
    s.dz <- lz;
    let li = Array.unsafe_get p.light_intensity l *. Float.pow cos_off (Array.unsafe_get geom (g + 7)) in
    sample_terms tr ~through ~shiny ~specular_of m l li length_n length_v ~lit:false
  end

let[@inline never] soft_light tr ~through ~shiny ~specular_of m l =
  let s = tr.s in
  let length_n = sqrt ((s.nx *. s.nx) +. (s.ny *. s.ny) +. (s.nz *. s.nz)) in
  let length_v = sqrt ((s.vx *. s.vx) +. (s.vy *. s.vy) +. (s.vz *. s.vz)) in
  let kind = Array.unsafe_get tr.p.light_kind l in
  if kind = Prepared.area then area tr ~through ~shiny ~specular_of m l length_n length_v
  else if kind = Prepared.sphere then sphere tr ~through ~shiny ~specular_of m l length_n length_v
  else spot tr ~through ~shiny ~specular_of m l length_n length_v

(* The total intensity at the hit point [s.px..] with unit normal [s.nx..]
   and view vector [s.vx..] (sections 7.4 to 7.7), left in [s.intensity].
   The shadow rays reuse [s]'s ray fields. [through]: shadow rays pass
   through transparent objects ([transmit]); otherwise any object stops
   them. Both terms of a light are decided before its shadow ray: with
   [p.shadow_skip], a light that would add neither casts none (lit or
   not, it leaves the sum as it is), as in the document's kernel. *)
let[@inline] lighting_with tr ~through ~soft ~shiny ~specular_of m =
  let p = tr.p and s = tr.s in
  let px = s.px and py = s.py and pz = s.pz in
  let nx = s.nx and ny = s.ny and nz = s.nz in
  let vx = s.vx and vy = s.vy and vz = s.vz in
  let shadow_skip = p.shadow_skip and cut = p.specular_cut and mo = m * p.n_lights in
  s.intensity <- 0.;
  let length_n = sqrt ((nx *. nx) +. (ny *. ny) +. (nz *. nz)) in
  let length_v = sqrt ((vx *. vx) +. (vy *. vy) +. (vz *. vz)) in
  for l = 0 to p.n_lights - 1 do
    let li = Array.unsafe_get p.light_intensity l in
    if Array.unsafe_get p.light_kind l = Prepared.ambient then s.intensity <- s.intensity +. li
    else if soft && Array.unsafe_get p.light_kind l > Prepared.directional then soft_light tr ~through ~shiny ~specular_of m l
    else begin
      let point = Array.unsafe_get p.light_kind l = Prepared.point in
      if point then begin
        s.dx <- Array.unsafe_get p.lx l -. px;
        s.dy <- Array.unsafe_get p.ly l -. py;
        s.dz <- Array.unsafe_get p.lz l -. pz;
        s.t_max <- 1.
      end
      else begin
        s.dx <- Array.unsafe_get p.lx l;
        s.dy <- Array.unsafe_get p.ly l;
        s.dz <- Array.unsafe_get p.lz l;
        s.t_max <- infinity
      end;
      s.ox <- px;
      s.oy <- py;
      s.oz <- pz;
      s.t_min <- p.epsilon;
      let lx = s.dx and ly = s.dy and lz = s.dz in
      let n_dot_l = (nx *. lx) +. (ny *. ly) +. (nz *. lz) in
      (* The specular cosine, or [0.] where no term is added: matte,
         <R, V> <= 0, or a cosine at or below the cut, where cos^s is 0 or
         too small to change the sum (Prepared.specular_cut, never below
         0): the sum is what it would be with the term. *)
      let cos =
        if shiny then begin
          (* R = 2 <L, N> N - L (section 7.6). *)
          let k = 2. *. n_dot_l in
          let rx = (nx *. k) -. lx and ry = (ny *. k) -. ly and rz = (nz *. k) -. lz in
          let r_dot_v = (rx *. vx) +. (ry *. vy) +. (rz *. vz) in
          let cos = if r_dot_v > 0. then r_dot_v /. (sqrt ((rx *. rx) +. (ry *. ry) +. (rz *. rz)) *. length_v) else 0. in
          if cos > Array.unsafe_get cut (mo + l) then cos else 0.
        end
        else 0.
      in
      (* A point light on the lit point itself gives no direction, L = 0:
         it is skipped (as Literal does), not divided by zero; with the
         skip, it adds no term (n_dot_l = 0 and R = 0). *)
      if
        if shadow_skip then n_dot_l > 0. || cos > 0.
        else (not point) || lx <> 0. || ly <> 0. || lz <> 0.
      then begin
        if through then begin
          (* [transmit] moves [s.t_min]; the direction stays. *)
          transmit tr;
          let f = Array.unsafe_get tr.tree.attenuation 0 in
          if f > 0. then add_terms s ~specular_of m (li *. f) n_dot_l cos length_n
        end
        else if not (Traversal.shadowed tr l) then add_terms s ~specular_of m li n_dot_l cos length_n
      end
    end
  done

(* Two copies of the loop: with [soft] false (a constant here) the
   document's lights' loop has no test of the new kinds, whose scenes
   take the other copy: one test per hit, not per light. *)
let lighting tr ~shiny ~specular_of m =
  if tr.p.soft_lights then lighting_with tr ~through:false ~soft:true ~shiny ~specular_of m
  else lighting_with tr ~through:false ~soft:false ~shiny ~specular_of m

let lighting_through tr ~shiny ~specular_of m =
  if tr.p.soft_lights then lighting_with tr ~through:true ~soft:true ~shiny ~specular_of m
  else lighting_with tr ~through:true ~soft:false ~shiny ~specular_of m

