open Scratch
open Tracer

(* [64 u]: the hit point [O + t D] of a plane, triangle or box lies within
   [32 u (|O| + |P| + extent)] of the surface (the shapes' stated bounds,
   plus the rounding of [P]); twice that leaves the secondary ray's own
   root on the surface (error [16 u (|P| + extent)] at most) negative. *)
let offset_bound = 32. *. epsilon_float

(* The hit point [s.px, s.py, s.pz] on the shape (not a sphere) in slot
   [i], for the ray in [s]: its normal, turned toward the ray (planes and
   triangles are seen from both sides, and a box from inside shows its
   walls' inner sides), and the view vector, in [s]. In the robust mode,
   the point is then moved off the surface, along the normal toward the
   ray's side, by a bound on its rounding error (Ray Tracing Gems,
   chapter 6): shadow and mirror rays leave from there, and their roots on
   this surface, or on any surface through the same point, are negative
   whatever the angle, with no constant tied to the scene's scale. The
   material's number of the point is returned: a CSG solid's is its
   leaf's. *)
let[@inline] fmax_abs (e : float) x =
  let x = Float.abs x in
  if x > e then x else e

(* The offset in [p.vnormal] of the normal of the corner at offset [o] in
   [p.vertex], where normals follow their vertices. *)
let[@inline] normal_of (p : Prepared.t) o = if Array.length p.vsource = 0 then o else p.vsource.(o / 3)

(* Spheres are hit by [sphere_hit]: the sphere a ray leaves is handled
   exactly, not offset. *)
let not_here fn = invalid_arg ("Trace." ^ fn ^ ": a sphere")

(* The hit point [px, py, pz] (already in [s]) on the sphere in slot
   [i], for a ray of direction [dx, dy, dz]: its outward normal and the
   view vector, in [s]. *)
let[@inline] sphere_hit tr i =
  let p = tr.p and s = tr.s in
  let px = s.px and py = s.py and pz = s.pz and dx = s.dx and dy = s.dy and dz = s.dz in
  let nx = px -. Array.unsafe_get p.cx i and ny = py -. Array.unsafe_get p.cy i and nz = pz -. Array.unsafe_get p.cz i in
  let inv = 1. /. sqrt ((nx *. nx) +. (ny *. ny) +. (nz *. nz)) in
  s.nx <- nx *. inv;
  s.ny <- ny *. inv;
  s.nz <- nz *. inv;
  s.vx <- -.dx;
  s.vy <- -.dy;
  s.vz <- -.dz;
  (* Shadow and mirror rays leave sphere i. *)
  tr.origin_sphere <- i

(* The material whose colour the hit of the ray in [s] at [s.t] shows:
   [m], or the material [alt >= 0] of its pattern's second colour, stored
   at [m] in [table]. {!Pattern.odd} reads the hit point as [trace_in]
   computed it, before the robust mode moved it off a shape (the pattern
   moves it its own way): recomputed here with the same operations, put
   in [s] for the call, and the moved point put back. *)
let[@inline] second_colour s table m alt =
  let t = s.t in
  let px = s.ox +. (s.dx *. t) and py = s.oy +. (s.dy *. t) and pz = s.oz +. (s.dz *. t) in
  let sx = s.px and sy = s.py and sz = s.pz in
  s.px <- px;
  s.py <- py;
  s.pz <- pz;
  let odd = Pattern.odd s table (Pattern.stride * m) in
  s.px <- sx;
  s.py <- sy;
  s.pz <- sz;
  if odd then alt else m

let[@warning "-11"] rec shape_hit tr i =
  let p = tr.p and s = tr.s in
  let dx = s.dx and dy = s.dy and dz = s.dz in
  let px = s.px and py = s.py and pz = s.pz in
  let k = Array.unsafe_get p.kind i in
  let triangle = Kind.is_triangle k in
  (* A triangle's corners in [p.vertex], or the shape's number in [p.geom]. *)
  let o0 = Array.unsafe_get p.at0 i in
  let o1 = if triangle then Array.unsafe_get p.at1 i else 0 and o2 = if triangle then Array.unsafe_get p.at2 i else 0 in
  let o = Kind.stride * o0 in
  (match k with
  | Triangle | Smooth_triangle -> Triangle.normal_at s p.vertex o0 o1 o2
  | Csg ->
      (* The surface hit, found again for the ray still in [s]: the same
         first crossing that [closest] kept. The normal is the solid's
         outward one, as a box's, before it is turned toward the ray. *)
      ignore (Csg.roots p.csg tr.csg s (truncate (Array.unsafe_get p.geom o)));
      Csg.normal p.csg tr.csg s
  | Sphere -> not_here "shape_hit"
  | Instance -> instance_normal tr i
  (* The first kinds' arms inline, as in [Traversal.shape_roots]. *)
  | Plane -> Plane.normal s p.geom o
  | Box ->
      (* The root kept, for the face whose slab decides it. *)
      s.near <- s.t;
      Box.hit_normal s p.geom o
  | k ->
      s.near <- s.t;
      Kind_dispatch.normal k s p.geom o);
  let flip = (s.nx *. dx) +. (s.ny *. dy) +. (s.nz *. dz) > 0. in
  if flip then begin
    s.nx <- -.s.nx;
    s.ny <- -.s.ny;
    s.nz <- -.s.nz
  end;
  (* The geometric normal, turned toward the ray: the side to start
     secondary rays on. *)
  let gx = s.nx and gy = s.ny and gz = s.nz in
  (* A smooth triangle shades with its interpolated normal, on the side
     the ray sees. *)
  if k = Smooth_triangle
     && (let follow = Array.length p.vcorner = 0 and j = 3 * i in
         Triangle.smooth_normal_at s p.vertex o0 o1 o2 p.vnormal
           (if follow then normal_of p o0 else Array.unsafe_get p.vcorner j)
           (if follow then normal_of p o1 else Array.unsafe_get p.vcorner (j + 1))
           (if follow then normal_of p o2 else Array.unsafe_get p.vcorner (j + 2)))
     && flip then begin
    s.nx <- -.s.nx;
    s.ny <- -.s.ny;
    s.nz <- -.s.nz
  end;
  s.vx <- -.dx;
  s.vy <- -.dy;
  s.vz <- -.dz;
  tr.origin_sphere <- -1;
  if p.robust then begin
    (* A triangle's extent from its corners, [fmax] of their magnitudes as
       [Prepared] finds a shape's: no array of them per triangle. *)
    let extent =
      if triangle then
        let v = p.vertex in
        let e = fmax_abs 0. (Array.unsafe_get v o0) in
        let e = fmax_abs e (Array.unsafe_get v (o0 + 1)) in
        let e = fmax_abs e (Array.unsafe_get v (o0 + 2)) in
        let e = fmax_abs e (Array.unsafe_get v o1) in
        let e = fmax_abs e (Array.unsafe_get v (o1 + 1)) in
        let e = fmax_abs e (Array.unsafe_get v (o1 + 2)) in
        let e = fmax_abs e (Array.unsafe_get v o2) in
        let e = fmax_abs e (Array.unsafe_get v (o2 + 1)) in
        fmax_abs e (Array.unsafe_get v (o2 + 2))
      else Array.unsafe_get p.extent o0
    in
    let size =
      Float.abs s.ox +. Float.abs s.oy +. Float.abs s.oz +. Float.abs px +. Float.abs py +. Float.abs pz
      +. extent
    in
    let e = offset_bound *. size in
    s.px <- px +. (e *. gx);
    s.py <- py +. (e *. gy);
    s.pz <- pz +. (e *. gz)
  end;
  match k with
  | Csg -> Csg.material p.csg tr.csg
  | Instance -> instance_material tr i
  | _ -> Array.unsafe_get p.material i

(* The normal of the instance in slot [i] at the hit that [closest] kept:
   the hit found again in the bottom level (the same search on the same
   carried ray), its surface's normal there, as that level's own
   [shape_hit] or [sphere_hit] makes it, brought to the world by the
   inverse transpose of the linear part (the transpose of the
   world-to-object matrix's) and divided by its length. Its material, in
   the bottom level's numbering, is left in [tr.inner_material]. *)
and instance_normal tr i =
  let sub = Traversal.instance_hit tr i in
  let s = tr.s and ss = sub.s in
  let j = sub.hit in
  if j < 0 then begin
    (* Not found again (no ray gets here: the search is the same); the
       normal faces the ray. *)
    ss.nx <- -.ss.dx;
    ss.ny <- -.ss.dy;
    ss.nz <- -.ss.dz;
    tr.inner_material <- 0
  end
  else begin
    let t = ss.t in
    ss.px <- ss.ox +. (ss.dx *. t);
    ss.py <- ss.oy +. (ss.dy *. t);
    ss.pz <- ss.oz +. (ss.dz *. t);
    tr.inner_material <-
      (if Array.unsafe_get sub.p.kind j = Kind.Sphere then begin
         sphere_hit sub j;
         Array.unsafe_get sub.p.material j
       end
       else shape_hit sub j)
  end;
  let m = tr.p.instances.to_object and o = 12 * Traversal.instance_number tr i in
  s.nx <- ss.nx;
  s.ny <- ss.ny;
  s.nz <- ss.nz;
  Scratch.normal_to_world s m o

(* The material of the instance in slot [i] at the hit that
   [instance_normal] found again: its bottom level's material
   ([tr.inner_material]) in this scene's numbering, or, where that has a
   pattern, its second colour's if the pattern says so. The pattern lies
   in the object's frame: looked up on the ray still carried there, in
   the bottom level's record, with the normal in that frame. A texture
   likewise, the object's own or the instance's own material's: the
   world's material [m]'s texture, mapped on the surface the bottom
   level's tracer found, on the carried ray, at the hit it found. *)
and[@inline never] instance_material tr i =
  let inst = tr.p.instances in
  let n = Traversal.instance_number tr i in
  let inner = tr.inner_material in
  let m = Array.unsafe_get (Array.unsafe_get inst.material_map n) inner in
  let placed = inst.placed_alternate and world = tr.p.alternate in
  if Array.length world > 0 && Array.unsafe_get world m = Prepared.textured_material then begin
    let sub = Array.unsafe_get tr.inner (Array.unsafe_get inst.bottom n) in
    Texturing.colour_at tr m sub sub.hit;
    m
  end
  else if Array.length placed = 0 then m
  else
    let alt = Array.unsafe_get placed m in
    if alt < 0 then m
    else second_colour (Array.unsafe_get tr.inner (Array.unsafe_get inst.bottom n)).s tr.p.pattern m alt

(* The material whose colour the hit of the ray in [tr.s] on slot [i]
   shows, by the world's patterns ([second_colour]); a textured material's
   colour there is written to the tracer's colour arrays ({!Texturing}).
   Not inlined: its code would make [trace_objects] too big for OCaml to
   inline into the render loop. *)
let[@inline never] local_material tr i m =
  let alt = Array.unsafe_get tr.p.alternate m in
  if alt >= 0 then second_colour tr.s tr.p.pattern m alt
  else if alt = Prepared.textured_material then begin
    (* An instance's hit has its colour already ([instance_material]). *)
    if Array.unsafe_get tr.p.kind i <> Kind.Instance then Texturing.colour tr i m;
    m
  end
  else m

(* The mirror ray R = 2 <V, N> N - V from the hit point, in [s]. *)
let[@inline] mirror_ray (p : Prepared.t) s =
  let nx = s.nx and ny = s.ny and nz = s.nz and vx = s.vx and vy = s.vy and vz = s.vz in
  let k = 2. *. ((vx *. nx) +. (vy *. ny) +. (vz *. nz)) in
  s.ox <- s.px;
  s.oy <- s.py;
  s.oz <- s.pz;
  s.dx <- (nx *. k) -. vx;
  s.dy <- (ny *. k) -. vy;
  s.dz <- (nz *. k) -. vz;
  s.t_min <- p.epsilon;
  s.t_max <- infinity

