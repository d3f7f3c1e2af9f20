open Scratch
open Tracer

(* The ray tree (scenes with transparency; Ray_tree describes its
   storage). A hit's colour is [local (1 - r - t) + reflected wr +
   refracted wt]: [wr = r + t R] and [wt = t (1 - R)], [R] the
   reflectance ([0] without Fresnel, [1] on total internal reflection, so
   that it folds into the reflected part). Opaque hits ([t = 0]) take the
   same floating-point operations as [trace_in], so a transparent object
   changes nothing where it is not seen. *)

(* May level [l] skip its child of weight [w] ([tree.tracing.(l)] set)?
   Checking costs a walk up the tree: worth it only when the child weighs
   less than a unit. *)
let[@inline] skip_child tr l w =
  let p = tr.p in
  p.early_stop
  && Array.unsafe_get tr.tree.weight l *. w *. p.max_channel < 1.
  && Byte_exact.settled_tree tr l
  && begin
       tr.counters.early_stops <- tr.counters.early_stops + 1;
       true
     end

(* The surface the ray of level [l] hits, or [-1]: surfaces that change
   nothing (transparency 1, the same index on both sides) are crossed on
   the same ray, with no bounce and no rounding. *)
let[@inline] search tr l =
  let p = tr.p and s = tr.s and tree = tr.tree in
  let base = Ray_tree.media_cap * l in
  let media = tree.media and index = p.refractive_index and io = tree.optics in
  let searching = ref true and hit = ref (-1) and first = ref (l = 0) in
  while !searching do
    if not !first then check_budget tr;
    let i =
      if !first then if p.all_spheres then Traversal.primary_hit_spheres tr else Traversal.primary_hit_objects tr
      else Traversal.closest tr
    in
    first := false;
    if i < 0 then searching := false
    else begin
      let m = Array.unsafe_get p.material i in
      let n = Array.unsafe_get tree.n_media l in
      if Array.unsafe_get p.transparency m = 1.
         && begin
              Ray_tree.indices index media base n m io;
              Array.unsafe_get io 0 = Array.unsafe_get io 1
            end
      then begin
        Array.unsafe_set tree.n_media l (Ray_tree.cross media base n m);
        s.t_min <- s.t
      end
      else begin
        hit := i;
        searching := false
      end
    end
  done;
  !hit

(* The reflectance of the surface of material [m] in slot [i] bounding
   [medium], hit by the ray of level [l] (its normal in [s]); the refracted
   ray's direction, set aside in [tree.pending] while the reflected one is
   traced: Snell's law with the normal turned toward the ray. *)
let[@inline] refract tr l i m medium ~sphere =
  let p = tr.p and s = tr.s and tree = tr.tree in
  let io = tree.optics and o = Ray_tree.pending_stride * l in
  let dx = s.dx and dy = s.dy and dz = s.dz in
  let nx = s.nx and ny = s.ny and nz = s.nz in
  let facing = (nx *. dx) +. (ny *. dy) +. (nz *. dz) <= 0. in
  let nx = if facing then nx else -.nx and ny = if facing then ny else -.ny and nz = if facing then nz else -.nz in
  Ray_tree.indices p.refractive_index tree.media (Ray_tree.media_cap * l) (Array.unsafe_get tree.n_media l) medium io;
  Array.unsafe_set io 2 dx;
  Array.unsafe_set io 3 dy;
  Array.unsafe_set io 4 dz;
  Array.unsafe_set io 5 nx;
  Array.unsafe_set io 6 ny;
  Array.unsafe_set io 7 nz;
  let fresnel = Array.unsafe_get p.fresnel m in
  Ray_tree.split io ~fresnel;
  (* A smooth triangle's interpolated normal may bend the ray back to the
     side it came from, which it would not cross: then the flat normal,
     turned toward the ray, decides. *)
  if (not sphere) && Array.unsafe_get p.kind i = Kind.Smooth_triangle && Array.unsafe_get io 11 < 1. then begin
    let snx = s.nx and sny = s.ny and snz = s.nz in
    Triangle.normal_at s p.vertex (Array.unsafe_get p.at0 i) (Array.unsafe_get p.at1 i) (Array.unsafe_get p.at2 i);
    let gx = s.nx and gy = s.ny and gz = s.nz in
    s.nx <- snx;
    s.ny <- sny;
    s.nz <- snz;
    let g_dot_d = (gx *. dx) +. (gy *. dy) +. (gz *. dz) in
    let g_dot_t = (gx *. Array.unsafe_get io 8) +. (gy *. Array.unsafe_get io 9) +. (gz *. Array.unsafe_get io 10) in
    (* Crossing: the two directions on the same side of the flat surface. *)
    if not ((g_dot_d > 0. && g_dot_t > 0.) || (g_dot_d < 0. && g_dot_t < 0.)) then begin
      let flip = g_dot_d > 0. in
      Array.unsafe_set io 5 (if flip then -.gx else gx);
      Array.unsafe_set io 6 (if flip then -.gy else gy);
      Array.unsafe_set io 7 (if flip then -.gz else gz);
      Ray_tree.split io ~fresnel
    end
  end;
  Array.unsafe_set tree.pending (o + 3) (Array.unsafe_get io 8);
  Array.unsafe_set tree.pending (o + 4) (Array.unsafe_get io 9);
  Array.unsafe_set tree.pending (o + 5) (Array.unsafe_get io 10);
  Array.unsafe_get io 11

(* The refracted ray's origin, set aside with the media it enters: the
   hit point [(px, py, pz)], on the far side of the surface. A sphere is
   left exactly (its slot), another shape from the point [shape_hit]
   moved toward the ray ([s.px..]), mirrored through the surface. *)
let[@inline] set_aside tr l i medium ~sphere px py pz =
  let s = tr.s and tree = tr.tree in
  let o = Ray_tree.pending_stride * l and n = Array.unsafe_get tree.n_media l in
  if sphere then begin
    Array.unsafe_set tree.pending o s.px;
    Array.unsafe_set tree.pending (o + 1) s.py;
    Array.unsafe_set tree.pending (o + 2) s.pz;
    Array.unsafe_set tree.pending_leaving l i
  end
  else begin
    Array.unsafe_set tree.pending o (px -. (s.px -. px));
    Array.unsafe_set tree.pending (o + 1) (py -. (s.py -. py));
    Array.unsafe_set tree.pending (o + 2) (pz -. (s.pz -. pz));
    Array.unsafe_set tree.pending_leaving l (-1)
  end;
  let pbase = Ray_tree.media_cap * l in
  Ray_tree.copy_media tree.media pbase n tree.pending_media pbase;
  Array.unsafe_set tree.pending_n_media l (Ray_tree.cross tree.pending_media pbase n medium)

(* The local colour of material [m] at the hit, [keep] of it, as node
   [l]'s first three floats; the weights [wr] and [wt] after it, and no
   child colour yet. *)
let[@inline] set_node tr l m keep wr wt =
  let p = tr.p and s = tr.s and node = tr.tree.node in
  let no = Ray_tree.node_stride * l in
  if keep > 0. then begin
    Lighting.lighting_through tr ~shiny:(Array.unsafe_get p.specular m <> Sphere.matte) ~specular_of:p.specular m;
    let light = s.intensity in
    Array.unsafe_set node no (Array.unsafe_get tr.red m *. light *. keep);
    Array.unsafe_set node (no + 1) (Array.unsafe_get tr.green m *. light *. keep);
    Array.unsafe_set node (no + 2) (Array.unsafe_get tr.blue m *. light *. keep)
  end
  else begin
    Array.unsafe_set node no 0.;
    Array.unsafe_set node (no + 1) 0.;
    Array.unsafe_set node (no + 2) 0.
  end;
  Array.unsafe_set node (no + 3) wr;
  Array.unsafe_set node (no + 4) wt;
  Array.unsafe_set node (no + 5) 0.;
  Array.unsafe_set node (no + 6) 0.;
  Array.unsafe_set node (no + 7) 0.

(* Node [l]'s colour, in [s]: its local colour, its reflected child's and
   its refracted child's (in [s] if [refracted] traced it, else 0)
   weighted, in the order [settled_tree] bounds it. *)
let[@inline] blend tr l ~refracted =
  let s = tr.s and node = tr.tree.node in
  let no = Ray_tree.node_stride * l in
  let wr = Array.unsafe_get node (no + 3) and wt = Array.unsafe_get node (no + 4) in
  let tr_r = if refracted then s.r else 0. and tr_g = if refracted then s.g else 0. and tr_b = if refracted then s.b else 0. in
  let r = ref (Array.unsafe_get node no) and g = ref (Array.unsafe_get node (no + 1)) and b = ref (Array.unsafe_get node (no + 2)) in
  if wr > 0. then begin
    r := !r +. (Array.unsafe_get node (no + 5) *. wr);
    g := !g +. (Array.unsafe_get node (no + 6) *. wr);
    b := !b +. (Array.unsafe_get node (no + 7) *. wr)
  end;
  if wt > 0. then begin
    r := !r +. (tr_r *. wt);
    g := !g +. (tr_g *. wt);
    b := !b +. (tr_b *. wt)
  end;
  s.r <- !r;
  s.g <- !g;
  s.b <- !b

(* The ray of level [l] is in [s] (range, [tr.origin_sphere]), its medium
   stack in [tree.media] at level [l]; its colour is left in [s.r..]. The
   children are traced by [reflected] and [refracted], which take ints
   alone: a recursive function's floats would be boxed. *)
let rec shade tr l =
  (* Without the early stop, a tree of depth 64 may have 2^64 rays: the
     work bound is checked at every hit, not only after each column. *)
  check_budget tr;
  let p = tr.p and s = tr.s in
  let i = search tr l in
  if l = 0 then begin
    tr.first_hit <- i;
    (* For adaptive sampling's circle of confusion (Trace.save_blur). *)
    s.first_t <- s.t
  end;
  if i < 0 then begin
    s.r <- p.background.r;
    s.g <- p.background.g;
    s.b <- p.background.b
  end
  else begin
    let t = s.t in
    let dx = s.dx and dy = s.dy and dz = s.dz in
    let px = s.ox +. (dx *. t) and py = s.oy +. (dy *. t) and pz = s.oz +. (dz *. t) in
    s.px <- px;
    s.py <- py;
    s.pz <- pz;
    let sphere = p.all_spheres || Array.unsafe_get p.kind i = Kind.Sphere in
    (* The surface's material (a CSG solid's: the leaf hit), which a
       pattern may change to its second colour's; and the medium the
       surface bounds, the object's (a CSG solid is one medium, its first
       operand's: Literal.medium_material). *)
    let m = if sphere then (Surface.sphere_hit tr i; Array.unsafe_get p.material i) else Surface.shape_hit tr i in
    let m = if p.patterned then Surface.local_material tr i m else m in
    let medium = Array.unsafe_get p.material i in
    let refl = Array.unsafe_get p.reflective m and tt = Array.unsafe_get p.transparency m in
    let keep = 1. -. refl -. tt in
    let reflectance = if tt > 0. then refract tr l i m medium ~sphere else 0. in
    let wr = refl +. (tt *. reflectance) and wt = tt *. (1. -. reflectance) in
    if l >= p.depth || (wr <= 0. && wt <= 0.) then begin
      Lighting.lighting_through tr ~shiny:(Array.unsafe_get p.specular m <> Sphere.matte) ~specular_of:p.specular m;
      let light = s.intensity in
      s.r <- Array.unsafe_get tr.red m *. light;
      s.g <- Array.unsafe_get tr.green m *. light;
      s.b <- Array.unsafe_get tr.blue m *. light
    end
    else begin
      if wt > 0. then set_aside tr l i medium ~sphere px py pz;
      set_node tr l m keep wr wt;
      if wr > 0. then reflected tr l (if sphere then i else -1);
      let refracted = wt > 0. && refracted tr l in
      blend tr l ~refracted
    end
  end

(* The reflected child of node [l], in the same medium, leaving the
   sphere in slot [leaving] ([-1]: another shape), unless it cannot change
   a byte; its colour in the node. *)
and reflected tr l leaving =
  let p = tr.p and s = tr.s and tree = tr.tree in
  let no = Ray_tree.node_stride * l and node = tree.node in
  let wr = Array.unsafe_get node (no + 3) in
  Array.unsafe_set tree.tracing l 0;
  if not (skip_child tr l wr) then begin
    let child = l + 1 and base = Ray_tree.media_cap * l and n = Array.unsafe_get tree.n_media l in
    Surface.mirror_ray p s;
    tr.origin_sphere <- leaving;
    Ray_tree.copy_media tree.media base n tree.media (Ray_tree.media_cap * child);
    Array.unsafe_set tree.n_media child n;
    Array.unsafe_set tree.weight child (Array.unsafe_get tree.weight l *. wr);
    tr.counters.reflection <- tr.counters.reflection + 1;
    shade tr child;
    Array.unsafe_set node (no + 5) s.r;
    Array.unsafe_set node (no + 6) s.g;
    Array.unsafe_set node (no + 7) s.b
  end

(* The refracted child of node [l], set aside by [refract] and
   [set_aside], unless it cannot change a byte: [true] if traced, its
   colour then in [s]. *)
and refracted tr l =
  let p = tr.p and s = tr.s and tree = tr.tree in
  let wt = Array.unsafe_get tree.node ((Ray_tree.node_stride * l) + 4) in
  Array.unsafe_set tree.tracing l 1;
  (not (skip_child tr l wt))
  && begin
       let pending = tree.pending and o = Ray_tree.pending_stride * l and child = l + 1 in
       s.ox <- Array.unsafe_get pending o;
       s.oy <- Array.unsafe_get pending (o + 1);
       s.oz <- Array.unsafe_get pending (o + 2);
       s.dx <- Array.unsafe_get pending (o + 3);
       s.dy <- Array.unsafe_get pending (o + 4);
       s.dz <- Array.unsafe_get pending (o + 5);
       s.t_min <- p.epsilon;
       s.t_max <- infinity;
       tr.origin_sphere <- Array.unsafe_get tree.pending_leaving l;
       let pn = Array.unsafe_get tree.pending_n_media l in
       Ray_tree.copy_media tree.pending_media (Ray_tree.media_cap * l) pn tree.media (Ray_tree.media_cap * child);
       Array.unsafe_set tree.n_media child pn;
       Array.unsafe_set tree.weight child (Array.unsafe_get tree.weight l *. wt);
       tr.counters.reflection <- tr.counters.reflection + 1;
       shade tr child;
       true
     end

let trace_tree tr =
  let tree = tr.tree in
  tr.first_hit <- -1;
  tr.origin_sphere <- -1;
  Array.unsafe_set tree.n_media 0 0;
  Array.unsafe_set tree.weight 0 1.;
  shade tr 0

