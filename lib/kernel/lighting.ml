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
  let verdict =
    if Array.unsafe_get p.light_adaptive l then begin
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
      sample_terms tr ~through ~shiny ~specular_of m l li length_n length_v ~lit:false
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

