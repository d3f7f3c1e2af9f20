type counters = {
  mutable primary : int;
  mutable shadow : int;
  mutable reflection : int;
  mutable tests : int;
  mutable box_tests : int;
  mutable early_stops : int;
}

(* The per-ray state (ray, roots, hit point, colour) is [Scratch.t], at
   the bottom of the kernel, so that the shapes' root routines read the ray
   without depending on the tracer. *)
open Scratch

type t = {
  p : Prepared.t;
  s : Scratch.t;
  stack : float array;  (** Per reflection level: local r, g, b and reflectivity. *)
  last_blocker : int array;  (** Per light: the sphere that last shadowed it. *)
  blockers : float array;
      (** The document's kernel: per light [l], from [4 n l] on ([n] =
          [n_objects]), a copy of [sphere4] in the order its shadow rays
          try the spheres: the last blocker found first. One array read per
          sphere, not an index then the sphere. *)
  blockers_first : int array;  (** Per light [l]: [4 n l], read rather than multiplied per shadow ray. *)
  counters : counters;
  nodes : int array;  (** Stack of hierarchy nodes still to visit: their offsets in [Bvh.t]'s [nodes]. *)
  csg : Csg.work;  (** Room for the intervals of the CSG solids. *)
  mutable hit : int;  (** Index of the sphere found by [closest]. *)
  mutable origin_sphere : int;
      (** The slot of the sphere the current secondary ray leaves, or
          [-1]: in the robust mode that sphere is handled exactly. (An
          identical sphere has no slot of its own: {!Prepared.prepare}.) *)
  mutable first_hit : int;
  triangles : bool;
      (** Every object in the hierarchy is a triangle (a mesh, maybe on
          planes, which are outside it): the traversals then read no
          object's kind, one array (and a cache miss a leaf) less. *)
  mutable kx : int;
      (** The axes of the ray in [s] for the triangle test
          ({!Triangle.shear}), [kz = -1] until a traversal's first triangle
          finds them (a traversal of a hierarchy of triangles alone finds
          them before its first box): once a ray, not once a triangle. *)
  mutable ky : int;
  mutable kz : int;
  mutable order : int;
      (** [kx], [ky], [kz] as one of the six orders of the axes, 0 to 5
          (see [triangle_hit]). *)
  averaging : bool;  (** Samples are averaged: see [settled]. *)
  mutable assumed : int;  (** Sphere the primary ray is assumed to hit, see [primary_hit]. *)
  mutable budget : int;  (** Most tests [check_budget] accepts before it calls [refill]. *)
  mutable refill : int -> int;
      (** Called with the work done once it passes [budget]: the next
          budget, or it raises [Limits.Work_exceeded]. *)
  tracer : int;  (** The loop of [trace]: [spheres_chain], [objects_chain] or [tree]. *)
  tree : Ray_tree.t;  (** The ray tree's levels: transparent scenes only. *)
  cand : int array;
      (** The document's kernel: per tile column, the spheres (slots, in
          scene order) that the camera rays of its current tile may meet,
          [n_objects] places each; then every slot, for rays of no tile. *)
  tile_row : int array;  (** Per tile column: the tile row [cand] holds, or [-1]. *)
  tile_count : int array;  (** Per tile column: how many spheres [cand] holds. *)
  corners : float array;  (** Scratch: the four corner directions of a tile. *)
  mutable cand_first : int;  (** The next camera ray tests [cand] from here on... *)
  mutable cand_count : int;  (** ...this many spheres. *)
}

(* The tracing loops, chosen once per tracer. *)
let spheres_chain = 0
let objects_chain = 1
let tree = 2

(* [assumed] when the primary ray searches every sphere. *)
let no_assumption = -2

(* Camera rays are culled by square tiles of this many pixels a side. *)
let tile = 8

(* The tile columns of the canvas, where culling applies. *)
let tiles_across (p : Prepared.t) = if p.cull && p.textbook_all then (p.width + tile - 1) / tile else 0

(* Whether [p] has a hierarchy and every object in it is a triangle:
   every object is one, or a plane (planes are not in the hierarchy). *)
let hierarchy_of_triangles (p : Prepared.t) =
  p.bvh <> None && Array.for_all (fun k -> Kind.is_triangle k || not (Kind.bounded k)) p.kind

let exhausted w = raise (Limits.Work_exceeded w)

let create ?(averaging = false) (p : Prepared.t) =
  {
    p;
    s = Scratch.create ();
    stack = Array.make (4 * (p.depth + 1)) 0.;
    last_blocker = Array.make (max 1 p.n_lights) (-1);
    blockers =
      (let n4 = Array.length p.sphere4 in
       Array.init (p.n_lights * n4) (fun k -> p.sphere4.(k mod n4)));
    blockers_first = Array.init p.n_lights (fun l -> l * Array.length p.sphere4);
    counters = { primary = 0; shadow = 0; reflection = 0; tests = 0; box_tests = 0; early_stops = 0 };
    nodes =
      Array.make (match p.bvh with Some b -> (2 * b.depth) + 2 | None -> 1) 0;
    csg = Csg.work p.csg;
    hit = -1;
    origin_sphere = -1;
    first_hit = -1;
    triangles = hierarchy_of_triangles p;
    kx = 0;
    ky = 0;
    kz = -1;
    order = 0;
    averaging;
    assumed = no_assumption;
    budget = Limits.work_budget Limits.default;
    refill = exhausted;
    tracer = (if p.transparent then tree else if p.all_spheres then spheres_chain else objects_chain);
    tree = (if p.transparent then Ray_tree.create ~depth:p.depth else Ray_tree.empty);
    (* Read by the document's kernel alone ([textbook_all]): other scenes,
       a million objects in a hierarchy, would make 8 MB per tracer (per
       worker) for nothing. *)
    cand = (let n = if p.textbook_all then p.n_objects else 0 and tiles = tiles_across p in
            Array.init ((tiles * n) + n) (fun k -> if k >= tiles * n then k - (tiles * n) else 0));
    tile_row = Array.make (tiles_across p) (-1);
    tile_count = Array.make (tiles_across p) 0;
    corners = Array.make 12 0.;
    cand_first = (if p.cull && p.textbook_all then tiles_across p * p.n_objects else 0);
    cand_count = p.n_objects;
  }

let prepared tr = tr.p
(* A CSG solid's leaf tests are counted in its work room, and taken into
   the counters whenever they are read: nothing per ray. *)
let counters tr =
  let c = tr.counters in
  c.tests <- c.tests + Csg.take_tests tr.csg;
  c.box_tests <- c.box_tests + Csg.take_boxes tr.csg;
  c

let work tr =
  let c = counters tr in
  c.tests + c.box_tests

let set_budget ?(refill = exhausted) tr n =
  tr.budget <- n;
  tr.refill <- refill

(* Out of line: the check itself is a sum and a comparison, made once a
   pixel; the CSG leaves' tests not yet taken into the counters count too. *)
let[@inline never] over_budget tr = tr.budget <- tr.refill (work tr)

let[@inline] check_budget tr =
  if tr.counters.tests + tr.counters.box_tests + Csg.pending tr.csg > tr.budget then over_budget tr

let red tr = tr.s.r
let green tr = tr.s.g
let blue tr = tr.s.b
let hit_object tr = if tr.first_hit < 0 then -1 else Array.unsafe_get tr.p.index tr.first_hit

(* [Color.to_byte], copied so that no float crosses a module boundary on the
   per-ray path: in dev builds (-opaque) such a call boxes its argument. A
   test checks the two agree. *)
let to_byte x =
  if not (x > 0.) then 0
  else if x >= 255. then 255
  else
    (* In [2^52, 2^53) the floats are the integers: adding 2^52 rounds
       [x] to an integer, half to even (the default rounding), exactly. *)
    truncate ((x +. 0x1p52) -. 0x1p52)
[@@inline]

let store tr (buffer : Image.buffer) k =
  let s = tr.s in
  Bigarray.Array1.unsafe_set buffer k (to_byte s.r);
  Bigarray.Array1.unsafe_set buffer (k + 1) (to_byte s.g);
  Bigarray.Array1.unsafe_set buffer (k + 2) (to_byte s.b)

(* Two ways to intersect. The document's mode (the scene gives an epsilon)
   uses the textbook quadratic of section 6.1 in CGFS's order of operations,
   so that it reproduces the document's images byte for byte. The robust
   mode uses the cancellation-free roots of [Sphere.roots] (same arithmetic,
   inlined here) and needs no epsilon: a secondary ray cannot hit the sphere
   it leaves except at that sphere's other root (see [leaving]). *)

(* Is root [t] of the sphere in slot [i] better than the best so far?
   Closer, or as close and earlier in the scene's list: the brute-force loop
   of CGFS keeps the first of equal roots, and the hierarchy, which visits
   spheres in another order, must give the same answer. *)
let[@inline] better tr s i t =
  t < s.t
  || (t = s.t && tr.hit >= 0
     && Array.unsafe_get tr.p.index i < Array.unsafe_get tr.p.index tr.hit)

(* Keeps root [t] of the sphere in slot [i] if it is in range and better. *)
let[@inline] keep tr s i t =
  if better tr s i t && s.t_min < t && t < s.t_max then begin
    s.t <- t;
    tr.hit <- i
  end

(* Textbook: k1 = <D,D>, k2 = 2 <CO,D>, k3 = <CO,CO> - r^2, disc
   k2^2 - 4 k1 k3, roots (-k2 +- sqrt disc) / 2 k1. The smaller root t2 is
   tried first: it wins whenever both are in range, as in CGFS. *)
let[@inline] consider_textbook tr s i k1x4 two_k1 k2 k3 =
  let disc = (k2 *. k2) -. (k1x4 *. k3) in
  if disc >= 0. then begin
    let sq = sqrt disc in
    let t2 = (-.k2 -. sq) /. two_k1 in
    if better tr s i t2 && s.t_min < t2 && t2 < s.t_max then begin
      s.t <- t2;
      tr.hit <- i
    end
    else keep tr s i ((-.k2 +. sq) /. two_k1)
  end

(* Robust: with f = O - C, b = <f, D>, l = f - (b / a) D is the vector from
   the center to the line; the ray hits iff |l| <= r. The roots are
   q / a and c / q with q = -(b + sign(b) sqrt (a (r - |l|)(r + |l|))):
   neither subtracts nearly equal numbers. Leaves the roots in
   [s.near <= s.far]; [false] if the ray misses. *)
let[@inline] robust_roots (p : Prepared.t) s i fx fy fz dx dy dz a inv_a =
  let b = (fx *. dx) +. (fy *. dy) +. (fz *. dz) in
  let k = b *. inv_a in
  let lx = fx -. (k *. dx) and ly = fy -. (k *. dy) and lz = fz -. (k *. dz) in
  let l2 = (lx *. lx) +. (ly *. ly) +. (lz *. lz) in
  let r2 = Array.unsafe_get p.r2 i in
  l2 <= r2
  &&
  let r = Array.unsafe_get p.radius i in
  let len = sqrt l2 in
  let sq = sqrt (a *. ((r -. len) *. (r +. len))) in
  let q = -.(b +. Float.copy_sign sq b) in
  if q = 0. then begin
    s.near <- 0.;
    s.far <- 0.
  end
  else begin
    let t0 = (((fx *. fx) +. (fy *. fy) +. (fz *. fz)) -. r2) /. q and t1 = q *. inv_a in
    if t0 <= t1 then begin
      s.near <- t0;
      s.far <- t1
    end
    else begin
      s.near <- t1;
      s.far <- t0
    end
  end;
  true

(* The other root of the sphere a secondary ray leaves: its origin P is on
   the sphere, so with f = P - C the roots are 0 and -2 <f, D> / <D, D>.
   The root 0 is the origin itself and never counts; the other is a hit only
   if the ray goes into the sphere (a shadow ray toward a light behind the
   surface), by more than the rounding of <f, D> (at most about 8 u |f| |D|)
   can explain. No distance threshold: the test is relative. *)
let leaving_margin = 16. *. epsilon_float *. epsilon_float (* (8u)^2, u = epsilon_float / 2 *)

(* Whether the ray re-enters the sphere it leaves; then its other root is
   [-2 b / a]. (A bool, not a float with [infinity] for "no": a float
   chosen by an [if] is boxed.) *)
let[@inline] reenters b fx fy fz a = b < 0. && b *. b > leaving_margin *. ((fx *. fx) +. (fy *. fy) +. (fz *. fz)) *. a

let[@inline] consider_robust tr s i dx dy dz a inv_a fx fy fz =
  if i = tr.origin_sphere then begin
    let b = (fx *. dx) +. (fy *. dy) +. (fz *. dz) in
    if reenters b fx fy fz a then keep tr s i (-2. *. b *. inv_a)
  end
  else if robust_roots tr.p s i fx fy fz dx dy dz a inv_a then begin
    let near = s.near in
    if better tr s i near && s.t_min < near && near < s.t_max then begin
      s.t <- near;
      tr.hit <- i
    end
    else keep tr s i s.far
  end

(* The roots of the sphere in slot [i] for the ray in [s], in [s.near <=
   s.far], by the mode's arithmetic; [false] if it misses. For
   [shape_roots]'s callers that meet a sphere ([roots]): the traversals
   test spheres with [test] and [blocks], which share the roots' work
   between them. *)
let[@inline never] sphere_roots tr s i =
  let p = tr.p in
  let fx = s.ox -. Array.unsafe_get p.cx i and fy = s.oy -. Array.unsafe_get p.cy i and fz = s.oz -. Array.unsafe_get p.cz i in
  let dx = s.dx and dy = s.dy and dz = s.dz in
  let a = (dx *. dx) +. (dy *. dy) +. (dz *. dz) in
  if p.robust then
    if i = tr.origin_sphere then begin
      (* The sphere the ray leaves: its other root alone ([leaving]). *)
      let b = (fx *. dx) +. (fy *. dy) +. (fz *. dz) in
      reenters b fx fy fz a
      &&
      let t = -2. *. b *. (1. /. a) in
      s.near <- t;
      s.far <- t;
      true
    end
    else robust_roots p s i fx fy fz dx dy dz a (1. /. a)
  else begin
    let k2 = 2. *. ((fx *. dx) +. (fy *. dy) +. (fz *. dz)) in
    let k3 = ((fx *. fx) +. (fy *. fy) +. (fz *. fz)) -. Array.unsafe_get p.r2 i in
    let disc = (k2 *. k2) -. (4. *. a *. k3) in
    disc >= 0.
    &&
    let sq = sqrt disc in
    s.near <- (-.k2 -. sq) /. (2. *. a);
    s.far <- (-.k2 +. sq) /. (2. *. a);
    true
  end

(* The ray's axes for the triangle test ({!Triangle.shear}), found at the
   first triangle a ray meets, not at each: a traversal over shapes sets
   [tr.kz] to [-1] (not found yet) before its first test. *)
let[@inline] shear_once tr s =
  if tr.kz < 0 then begin
    let axes = Triangle.shear s in
    let kx = Triangle.axis_x axes and ky = Triangle.axis_y axes and kz = Triangle.axis_z axes in
    tr.kx <- kx;
    tr.ky <- ky;
    tr.kz <- kz;
    tr.order <- (2 * kz) + if kx > ky then 1 else 0
  end

(* [Kind.is_triangle], here so that the dev profile's [-opaque] makes no
   call of it per test. *)
let[@inline] is_triangle (k : Kind.t) =
  match k with Triangle | Smooth_triangle -> true | Sphere | Plane | Box | Csg -> false

(* Whether the ray in [s] meets the triangle in slot [i], its root then in
   [s.near]: {!Triangle.hit} inlined, nothing written for a miss. (Not a
   float returned: without cross-module inlining, as in the dev profile,
   it would be boxed.) *)
let[@inline] triangle_hit tr s i ~sheared =
  let p = tr.p in
  if not sheared then shear_once tr s;
  let g = p.vertex in
  let o0 = Array.unsafe_get p.at0 i and o1 = Array.unsafe_get p.at1 i and o2 = Array.unsafe_get p.at2 i in
  (* One copy of the test per order of the axes, each with its axes as
     constants: a vertex's coordinate is then one load at a fixed
     displacement from its offset, not an index computed per load (20
     instructions less a test). The order is the same for every triangle
     of a ray: its branch is predicted. *)
  match tr.order with
  | 0 -> Triangle.hit s g o0 o1 o2 1 2 0
  | 1 -> Triangle.hit s g o0 o1 o2 2 1 0
  | 2 -> Triangle.hit s g o0 o1 o2 0 2 1
  | 3 -> Triangle.hit s g o0 o1 o2 2 0 1
  | 4 -> Triangle.hit s g o0 o1 o2 0 1 2
  | _ -> Triangle.hit s g o0 o1 o2 1 0 2

(* The roots of the shape (not a sphere) in slot [i], by its module's
   routine, in [s.near] and [s.far]; [false] if it misses. A CSG solid
   gives its first crossing beyond [s.t_min] as both. *)
let shape_roots tr s i =
  let p = tr.p in
  match Array.unsafe_get p.kind i with
  | Triangle | Smooth_triangle ->
      shear_once tr s;
      Triangle.roots_at s p.vertex (Array.unsafe_get p.at0 i) (Array.unsafe_get p.at1 i) (Array.unsafe_get p.at2 i) tr.kx
        tr.ky tr.kz
  | Plane -> Plane.roots s p.geom (Kind.stride * Array.unsafe_get p.at0 i)
  | Box -> Box.roots s p.geom (Kind.stride * Array.unsafe_get p.at0 i)
  | Csg -> Csg.roots p.csg tr.csg s (truncate (Array.unsafe_get p.geom (Kind.stride * Array.unsafe_get p.at0 i)))
  | Sphere -> sphere_roots tr s i

(* Tests the ray in [s] against the shape (not a sphere) in slot [i],
   keeping the better hit. Secondary rays of the robust mode start off
   the surface they leave (see [trace]), so no shape is special here. *)
let shape_test tr s i =
  if shape_roots tr s i then begin
    let near = s.near in
    if better tr s i near && s.t_min < near && near < s.t_max then begin
      s.t <- near;
      tr.hit <- i
    end
    else keep tr s i s.far
  end

(* Tests the ray in [s] against the object in slot [i], keeping the better
   hit. From the camera ([primary]), [CO] and the textbook's [k3] are
   per-frame constants. *)
let[@inline] test_sphere tr s i ~primary dx dy dz a inv_a two_k1 k1x4 =
  let p = tr.p in
  let fx = if primary then Array.unsafe_get p.primary_ocx i else s.ox -. Array.unsafe_get p.cx i in
  let fy = if primary then Array.unsafe_get p.primary_ocy i else s.oy -. Array.unsafe_get p.cy i in
  let fz = if primary then Array.unsafe_get p.primary_ocz i else s.oz -. Array.unsafe_get p.cz i in
  if p.robust then consider_robust tr s i dx dy dz a inv_a fx fy fz
  else
    let k2 = 2. *. ((fx *. dx) +. (fy *. dy) +. (fz *. dz)) in
    let k3 =
      if primary then Array.unsafe_get p.primary_k3 i
      else ((fx *. fx) +. (fy *. fy) +. (fz *. fz)) -. Array.unsafe_get p.r2 i
    in
    consider_textbook tr s i k1x4 two_k1 k2 k3

(* The kernel's dispatch on the kind of a slot in the traversals: the copy
   for spheres alone and the one for triangles alone read no kind. A
   triangle's one root is its near and far: [keep] once is [shape_test]'s
   two tries. *)
let[@inline] test tr s i ~primary ~spheres ~triangles dx dy dz a inv_a two_k1 k1x4 =
  if spheres then test_sphere tr s i ~primary dx dy dz a inv_a two_k1 k1x4
  else if triangles then (if triangle_hit tr s i ~sheared:true then keep tr s i s.near)
  else
    match Array.unsafe_get tr.p.kind i with
    | Triangle | Smooth_triangle -> if triangle_hit tr s i ~sheared:false then keep tr s i s.near
    | Sphere -> test_sphere tr s i ~primary dx dy dz a inv_a two_k1 k1x4
    | Plane | Box | Csg -> shape_test tr s i

(* The reciprocal of a direction coordinate for the slab test; a zero
   coordinate gets a huge finite value instead of an infinity, so that
   [0 * inv] is 0, never NaN (rays only look at t >= 0). *)
let[@inline] slab_inverse d = if d = 0. then 1e300 else 1. /. d

(* A node of the hierarchy at offset [o] of [nodes] (the layout of
   {!Bvh.t}): its box's lower corner at [o], its upper corner at [o + 3],
   its link at [o + 6], its tag at [o + 7]. Read here with the array's
   own primitives: a float returned by a function of another module is
   boxed where that module's code is not inlined (the dev profile). *)
let[@inline] node_link (nodes : float array) o = truncate (Array.unsafe_get nodes (o + 6))
let[@inline] node_tag (nodes : float array) o = truncate (Array.unsafe_get nodes (o + 7))

(* Does the ray in [s] (with slab inverses [ix, iy, iz]) meet the box of
   the node at offset [o] of [nodes] at some t in [t_min, limit]? *)
let[@inline] meets_box (nodes : float array) s o ix iy iz limit =
  let ox = s.ox and oy = s.oy and oz = s.oz in
  let x0 = (Array.unsafe_get nodes o -. ox) *. ix and x1 = (Array.unsafe_get nodes (o + 3) -. ox) *. ix in
  let y0 = (Array.unsafe_get nodes (o + 1) -. oy) *. iy and y1 = (Array.unsafe_get nodes (o + 4) -. oy) *. iy in
  let z0 = (Array.unsafe_get nodes (o + 2) -. oz) *. iz and z1 = (Array.unsafe_get nodes (o + 5) -. oz) *. iz in
  let enter_x = if x0 < x1 then x0 else x1 and exit_x = if x0 < x1 then x1 else x0 in
  let enter_y = if y0 < y1 then y0 else y1 and exit_y = if y0 < y1 then y1 else y0 in
  let enter_z = if z0 < z1 then z0 else z1 and exit_z = if z0 < z1 then z1 else z0 in
  let enter = if enter_x > enter_y then enter_x else enter_y in
  let enter = if enter > enter_z then enter else enter_z in
  let exit = if exit_x < exit_y then exit_x else exit_y in
  let exit = if exit < exit_z then exit else exit_z in
  enter <= exit && exit >= s.t_min && enter <= limit

(* Pushes the children of the inner node at offset [o] of [nodes] on
   [stack] above [sp], so that the nearer along the ray is popped first;
   the new stack pointer. The stack holds nodes' offsets: the left child
   follows its parent (8 floats on), the right one is at its link. *)
let[@inline] push_children nodes stack sp o dx dy dz =
  let right = node_link nodes o and left = o + 8 in
  let tag = node_tag nodes o in
  let d = if tag = -1 then dx else if tag = -2 then dy else dz in
  if d >= 0. then begin
    Array.unsafe_set stack sp right;
    Array.unsafe_set stack (sp + 1) left
  end
  else begin
    Array.unsafe_set stack sp left;
    Array.unsafe_set stack (sp + 1) right
  end;
  sp + 2

(* The intersection loops below read every loop invariant (arrays, ray,
   range) into a local once per ray: without flambda, OCaml reloads a
   record field at every use. *)

(* Every sphere, in scene order, with the textbook roots: the document's
   mode without a hierarchy (the reference scene). Scene order makes a plain
   [<] keep the first of equal roots, as CGFS does. Inlined into a copy for
   camera rays and one for the others, so that [primary] costs nothing. *)
let[@inline] closest_textbook_all tr ~primary =
  let p = tr.p and s = tr.s in
  let cx = p.cx and cy = p.cy and cz = p.cz and r2 = p.r2 in
  let pox = p.primary_ocx and poy = p.primary_ocy and poz = p.primary_ocz and pk3 = p.primary_k3 in
  let ox = s.ox and oy = s.oy and oz = s.oz and dx = s.dx and dy = s.dy and dz = s.dz in
  let t_min = s.t_min and t_max = s.t_max in
  let a = (dx *. dx) +. (dy *. dy) +. (dz *. dz) in
  let two_k1 = 2. *. a and k1x4 = 4. *. a in
  let best = ref infinity and hit = ref (-1) in
  let n = p.n_objects in
  tr.counters.tests <- tr.counters.tests + n;
  for i = 0 to n - 1 do
    let fx = if primary then Array.unsafe_get pox i else ox -. Array.unsafe_get cx i in
    let fy = if primary then Array.unsafe_get poy i else oy -. Array.unsafe_get cy i in
    let fz = if primary then Array.unsafe_get poz i else oz -. Array.unsafe_get cz i in
    let k2 = 2. *. ((fx *. dx) +. (fy *. dy) +. (fz *. dz)) in
    let k3 =
      if primary then Array.unsafe_get pk3 i
      else ((fx *. fx) +. (fy *. fy) +. (fz *. fz)) -. Array.unsafe_get r2 i
    in
    let disc = (k2 *. k2) -. (k1x4 *. k3) in
    if disc >= 0. then begin
      let sq = sqrt disc in
      let t2 = (-.k2 -. sq) /. two_k1 in
      if t2 < !best && t_min < t2 && t2 < t_max then begin
        best := t2;
        hit := i
      end
      else
        let t1 = (-.k2 +. sq) /. two_k1 in
        if t1 < !best && t_min < t1 && t1 < t_max then begin
          best := t1;
          hit := i
        end
    end
  done;
  s.t <- !best;
  tr.hit <- !hit;
  !hit

let closest_textbook_primary tr = closest_textbook_all tr ~primary:true
let closest_textbook_secondary tr = closest_textbook_all tr ~primary:false

(* The closest object hit by the ray in [s], with [t_min < t < t_max]; its
   [t] is left in [s.t] ([infinity] if none), its slot is returned. One
   traversal for every kind of object; spheres alone in the document's
   mode without a hierarchy (the reference scene) take the loop above. *)
let[@inline] closest_from tr ~primary ~spheres ~triangles =
  let p = tr.p and s = tr.s in
      if not spheres then tr.kz <- -1;
      let bvh = p.bvh in
      let dx = s.dx and dy = s.dy and dz = s.dz in
      let a = (dx *. dx) +. (dy *. dy) +. (dz *. dz) in
      let inv_a = 1. /. a and two_k1 = 2. *. a and k1x4 = 4. *. a in
      tr.hit <- -1;
      s.t <- infinity;
      (match bvh with
      | None ->
          let n = p.n_objects in
          tr.counters.tests <- tr.counters.tests + n;
          for i = 0 to n - 1 do
            test tr s i ~primary ~spheres ~triangles:false dx dy dz a inv_a two_k1 k1x4
          done
      | Some b ->
          (* Planes, unbounded, are outside the hierarchy. *)
          let planes = p.unbounded in
          let n = Array.length planes in
          if (not spheres) && n > 0 then begin
            tr.counters.tests <- tr.counters.tests + n;
            for j = 0 to n - 1 do
              shape_test tr s (Array.unsafe_get planes j)
            done
          end;
          let ix = slab_inverse dx and iy = slab_inverse dy and iz = slab_inverse dz in
          (* A hierarchy of triangles: the ray's shear once, here, rather
             than a check of [tr.kz] at every triangle. *)
          if triangles then shear_once tr s;
          let nodes = b.nodes and stack = tr.nodes and sp = ref 1 in
          (* Counted here, added to the counters once a ray. *)
          let boxes = ref 0 and tests = ref 0 in
          Array.unsafe_set stack 0 b.root;
          while !sp > 0 do
            decr sp;
            let o = Array.unsafe_get stack !sp in
            incr boxes;
            (* A box entered beyond the best hit so far cannot hold a better
               one (its spheres' hit points lie inside it, rounding
               included); one entered exactly there may hold an equal one. *)
            if meets_box nodes s o ix iy iz (if s.t < s.t_max then s.t else s.t_max) then begin
              let count = node_tag nodes o in
              if count > 0 then begin
                let first = node_link nodes o in
                tests := !tests + count;
                for i = first to first + count - 1 do
                  test tr s i ~primary ~spheres ~triangles dx dy dz a inv_a two_k1 k1x4
                done
              end
              else sp := push_children nodes stack !sp o dx dy dz
            end
          done;
          tr.counters.box_tests <- tr.counters.box_tests + !boxes;
          tr.counters.tests <- tr.counters.tests + !tests);
      tr.hit

(* One copy of the traversal per kind of ray and per kind of scene:
   spheres alone test no object's kind. *)
let closest_objects tr =
  if tr.triangles then closest_from tr ~primary:false ~spheres:false ~triangles:true
  else closest_from tr ~primary:false ~spheres:false ~triangles:false

let closest_primary_objects tr =
  if tr.triangles then closest_from tr ~primary:true ~spheres:false ~triangles:true
  else closest_from tr ~primary:true ~spheres:false ~triangles:false

(* The closest hit where the caller knows whether the scene has spheres
   alone (a scene with other shapes is never the textbook one). *)
let[@inline] closest_in tr ~spheres =
  if not spheres then closest_objects tr
  else if tr.p.textbook_all then closest_textbook_secondary tr
  else closest_from tr ~primary:false ~spheres:true ~triangles:false

let[@inline] closest_primary_in tr ~spheres =
  if not spheres then closest_primary_objects tr
  else if tr.p.textbook_all then closest_textbook_primary tr
  else closest_from tr ~primary:true ~spheres:true ~triangles:false

let[@inline] closest tr = if tr.p.all_spheres then closest_in tr ~spheres:true else closest_in tr ~spheres:false

(* Does the shape (not a sphere) in slot [i] meet the ray in [s] with
   [t_min < t < t_max]? *)
let shape_blocks tr i =
  let s = tr.s in
  shape_roots tr s i
  && ((s.t_min < s.near && s.near < s.t_max) || (s.t_min < s.far && s.far < s.t_max))

(* Does the object in slot [i] meet the ray in [s] with
   [t_min < t < t_max]? The same roots as [closest], so an object blocks
   exactly when [closest] would have found it. *)
let[@inline] sphere_blocks tr i a inv_a =
  let p = tr.p and s = tr.s in
  let dx = s.dx and dy = s.dy and dz = s.dz in
  let fx = s.ox -. Array.unsafe_get p.cx i
  and fy = s.oy -. Array.unsafe_get p.cy i
  and fz = s.oz -. Array.unsafe_get p.cz i in
  if p.robust then
    if i = tr.origin_sphere then
      let b = (fx *. dx) +. (fy *. dy) +. (fz *. dz) in
      reenters b fx fy fz a
      &&
      let t = -2. *. b *. inv_a in
      s.t_min < t && t < s.t_max
    else
      robust_roots p s i fx fy fz dx dy dz a inv_a
      && ((s.t_min < s.near && s.near < s.t_max) || (s.t_min < s.far && s.far < s.t_max))
  else
    let k2 = 2. *. ((fx *. dx) +. (fy *. dy) +. (fz *. dz)) in
    let k3 = ((fx *. fx) +. (fy *. fy) +. (fz *. fz)) -. Array.unsafe_get p.r2 i in
    let disc = (k2 *. k2) -. (4. *. a *. k3) in
    disc >= 0.
    &&
    let sq = sqrt disc in
    let t2 = (-.k2 -. sq) /. (2. *. a) in
    (s.t_min < t2 && t2 < s.t_max)
    ||
    let t1 = (-.k2 +. sq) /. (2. *. a) in
    s.t_min < t1 && t1 < s.t_max

(* [test]'s dispatch, for any hit in range. *)
let[@inline] triangle_blocks tr s i ~sheared =
  triangle_hit tr s i ~sheared
  &&
  let t = s.near in
  s.t_min < t && t < s.t_max

let[@inline] blocks tr i ~spheres ~triangles a inv_a =
  if spheres then sphere_blocks tr i a inv_a
  else if triangles then triangle_blocks tr tr.s i ~sheared:true
  else
    match Array.unsafe_get tr.p.kind i with
    | Triangle | Smooth_triangle -> triangle_blocks tr tr.s i ~sheared:false
    | Sphere -> sphere_blocks tr i a inv_a
    | Plane | Box | Csg -> shape_blocks tr i

(* Does sphere [i] meet the ray [o + t d] with [t_min < t < t_max]? The
   textbook roots, on loop invariants passed in (see below). *)
let[@inline] textbook_blocks cx cy cz r2 ox oy oz dx dy dz t_min t_max two_k1 k1x4 i =
  let fx = ox -. Array.unsafe_get cx i
  and fy = oy -. Array.unsafe_get cy i
  and fz = oz -. Array.unsafe_get cz i in
  let k2 = 2. *. ((fx *. dx) +. (fy *. dy) +. (fz *. dz)) in
  let k3 = ((fx *. fx) +. (fy *. fy) +. (fz *. fz)) -. Array.unsafe_get r2 i in
  let disc = (k2 *. k2) -. (k1x4 *. k3) in
  disc >= 0.
  &&
  let sq = sqrt disc in
  let t2 = (-.k2 -. sq) /. two_k1 in
  (t_min < t2 && t2 < t_max)
  ||
  let t1 = (-.k2 +. sq) /. two_k1 in
  t_min < t1 && t1 < t_max

(* A blocker of the ray in [s] with the textbook roots and no hierarchy:
   slot [last] first (the blocker of this light's previous shadow ray, if
   [last >= 0]), then the others in scene order; [-1] if none. Not
   inlined: inlined in [shadowed], it cost the loop of [first_blocker_from]
   its index's register (two more instructions per sphere tested: 9 M more
   on the robust scenes/mirrors.scene). *)
let[@inline never] blocker_textbook_all tr last =
  let p = tr.p and s = tr.s in
  let cx = p.cx and cy = p.cy and cz = p.cz and r2 = p.r2 in
  let ox = s.ox and oy = s.oy and oz = s.oz and dx = s.dx and dy = s.dy and dz = s.dz in
  let t_min = s.t_min and t_max = s.t_max in
  let a = (dx *. dx) +. (dy *. dy) +. (dz *. dz) in
  let two_k1 = 2. *. a and k1x4 = 4. *. a in
  if last >= 0 && textbook_blocks cx cy cz r2 ox oy oz dx dy dz t_min t_max two_k1 k1x4 last then begin
    tr.counters.tests <- tr.counters.tests + 1;
    last
  end
  else begin
    let n = p.n_objects in
    let i = ref 0 in
    while
      !i < n
      && (!i = last || not (textbook_blocks cx cy cz r2 ox oy oz dx dy dz t_min t_max two_k1 k1x4 !i))
    do
      incr i
    done;
    tr.counters.tests <- tr.counters.tests + !i + if last >= 0 then 1 else 0;
    if !i < n then !i else -1
  end

(* The first blocker of the ray in [s] other than slot [skip], or [-1]. *)
let[@inline] first_blocker_from tr ~spheres ~triangles skip a inv_a =
  let p = tr.p and s = tr.s in
  match p.bvh with
  | None ->
      let n = p.n_objects in
      let i = ref 0 in
      while !i < n && (!i = skip || not (blocks tr !i ~spheres ~triangles:false a inv_a)) do
        incr i
      done;
      tr.counters.tests <- tr.counters.tests + !i + 1;
      if !i < n then !i else -1
  | Some b ->
      let dx = s.dx and dy = s.dy and dz = s.dz in
      let ix = slab_inverse dx and iy = slab_inverse dy and iz = slab_inverse dz in
      if triangles then shear_once tr s;
      let nodes = b.nodes and stack = tr.nodes and sp = ref 1 and found = ref (-1) in
      let boxes = ref 0 and tests = ref 0 in
      (* Planes first: they are outside the hierarchy. *)
      let planes = p.unbounded in
      let n = Array.length planes in
      if (not spheres) && n > 0 then begin
        let j = ref 0 in
        while !j < n && (Array.unsafe_get planes !j = skip || not (shape_blocks tr (Array.unsafe_get planes !j))) do
          incr j
        done;
        tr.counters.tests <- tr.counters.tests + (if !j < n then !j + 1 else n);
        if !j < n then begin
          found := Array.unsafe_get planes !j;
          sp := 0
        end
      end;
      Array.unsafe_set stack 0 b.root;
      while !sp > 0 do
        decr sp;
        let o = Array.unsafe_get stack !sp in
        incr boxes;
        if meets_box nodes s o ix iy iz s.t_max then begin
          let count = node_tag nodes o in
          if count > 0 then begin
            let first = node_link nodes o in
            let i = ref first and last = first + count in
            while !i < last && (!i = skip || not (blocks tr !i ~spheres ~triangles a inv_a)) do
              incr i
            done;
            tests := !tests + count;
            if !i < last then begin
              found := !i;
              sp := 0
            end
          end
          else sp := push_children nodes stack !sp o dx dy dz
        end
      done;
      tr.counters.box_tests <- tr.counters.box_tests + !boxes;
      tr.counters.tests <- tr.counters.tests + !tests;
      !found

(* With skips and a hierarchy or the robust roots: light [l]'s last
   blocker first, then the first blocker of the others. One copy per kind
   of scene, so that spheres alone ask the kind once per shadow ray. *)
let[@inline] blocked_from tr l ~spheres ~triangles =
  let s = tr.s in
  if not spheres then tr.kz <- -1;
  let last = Array.unsafe_get tr.last_blocker l in
  let dx = s.dx and dy = s.dy and dz = s.dz in
  let a = (dx *. dx) +. (dy *. dy) +. (dz *. dz) in
  let inv_a = 1. /. a in
  (* The last blocker may be a plane: its kind is looked up. *)
  if last >= 0 && blocks tr last ~spheres ~triangles:false a inv_a then begin
    tr.counters.tests <- tr.counters.tests + 1;
    true
  end
  else
    let blocker = first_blocker_from tr ~spheres ~triangles last a inv_a in
    if blocker >= 0 then Array.unsafe_set tr.last_blocker l blocker;
    blocker >= 0

let[@inline] blocked_objects tr l =
  if tr.triangles then blocked_from tr l ~spheres:false ~triangles:true
  else blocked_from tr l ~spheres:false ~triangles:false

(* Is the shadow ray in [s] blocked (section 7.7)? With skips, it stops at
   the first blocker and tries light [l]'s last blocker first; without, it
   searches for the closest hit as the document does. Same answer. *)
let shadowed tr l =
  let p = tr.p in
  tr.counters.shadow <- tr.counters.shadow + 1;
  if not p.skips then closest tr >= 0
  else if p.textbook_all then begin
    let blocker = blocker_textbook_all tr (Array.unsafe_get tr.last_blocker l) in
    if blocker >= 0 then Array.unsafe_set tr.last_blocker l blocker;
    blocker >= 0
  end
  else if p.all_spheres then blocked_from tr l ~spheres:true ~triangles:false
  else blocked_objects tr l

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
    let i = closest tr in
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

(* The total intensity at the hit point [s.px..] with unit normal [s.nx..]
   and view vector [s.vx..] (sections 7.4 to 7.7), left in [s.intensity].
   The shadow rays reuse [s]'s ray fields. [through]: shadow rays pass
   through transparent objects ([transmit]); otherwise any object stops
   them. Both terms of a light are decided before its shadow ray: with
   [p.shadow_skip], a light that would add neither casts none (lit or
   not, it leaves the sum as it is), as in the document's kernel. *)
let[@inline] lighting_with tr ~through ~shiny ~specular_of m =
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
        else if not (shadowed tr l) then add_terms s ~specular_of m li n_dot_l cos length_n
      end
    end
  done

let lighting tr ~shiny ~specular_of m = lighting_with tr ~through:false ~shiny ~specular_of m
let lighting_through tr ~shiny ~specular_of m = lighting_with tr ~through:true ~shiny ~specular_of m

(* When samples are averaged, a pixel is the mean of the samples' clamped
   floats, not of their bytes: a reflection may stop only if it cannot
   change the clamped float itself. Clamping is monotonic, so that holds
   when both extremes clamp alike: both [>= 255], both [<= 0], or equal. *)
let[@inline] same_clamped (lo : float) (hi : float) = hi <= 0. || lo >= 255. || lo = hi

(* Byte-exact early stop of reflection: the pixel's colour is a
   non-decreasing function of the colour [rc] still to be traced (each blend
   is local (1 - r) + rc r with r >= 0, and rounding is monotonic), and
   0 <= rc <= max_channel. If the blend of the stack gives the same bytes
   for rc = 0 and rc = max_channel, it gives them for the true rc too. *)
let settled tr levels =
  let stack = tr.stack and hi = tr.p.max_channel in
  let lo_r = ref 0. and lo_g = ref 0. and lo_b = ref 0. in
  let hi_r = ref hi and hi_g = ref hi and hi_b = ref hi in
  for l = levels - 1 downto 0 do
    let refl = Array.unsafe_get stack ((4 * l) + 3) in
    let keep = 1. -. refl in
    let r = Array.unsafe_get stack (4 * l) *. keep
    and g = Array.unsafe_get stack ((4 * l) + 1) *. keep
    and b = Array.unsafe_get stack ((4 * l) + 2) *. keep in
    lo_r := r +. (!lo_r *. refl);
    lo_g := g +. (!lo_g *. refl);
    lo_b := b +. (!lo_b *. refl);
    hi_r := r +. (!hi_r *. refl);
    hi_g := g +. (!hi_g *. refl);
    hi_b := b +. (!hi_b *. refl)
  done;
  if tr.averaging then same_clamped !lo_r !hi_r && same_clamped !lo_g !hi_g && same_clamped !lo_b !hi_b
  else to_byte !lo_r = to_byte !hi_r && to_byte !lo_g = to_byte !hi_g && to_byte !lo_b = to_byte !hi_b

(* CGFS's subsampling: when [tr.assumed] names a sphere, the primary ray is
   tested against it alone (against none for [-1]); a ray that misses the
   assumed sphere falls back to the full search. Approximate: a sphere in
   front of the assumed one is not seen. *)
let[@inline] primary_hit_in tr ~spheres =
  let k = tr.assumed in
  if k = no_assumption then closest_primary_in tr ~spheres
  else if k < 0 then begin
    tr.hit <- -1;
    tr.s.t <- infinity;
    -1
  end
  else begin
    let s = tr.s in
    let dx = s.dx and dy = s.dy and dz = s.dz in
    let a = (dx *. dx) +. (dy *. dy) +. (dz *. dz) in
    tr.hit <- -1;
    s.t <- infinity;
    tr.counters.tests <- tr.counters.tests + 1;
    if not spheres then tr.kz <- -1;
    (* The same test as [closest_primary] makes of that sphere: the same t. *)
    test tr s (Array.unsafe_get tr.p.slot k) ~primary:true ~spheres ~triangles:false dx dy dz a (1. /. a) (2. *. a) (4. *. a);
    if tr.hit >= 0 then tr.hit else closest_primary_in tr ~spheres
  end

let[@inline never] primary_hit_spheres tr = primary_hit_in tr ~spheres:true
let[@inline never] primary_hit_objects tr = primary_hit_in tr ~spheres:false

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

let shape_hit tr i =
  let p = tr.p and s = tr.s in
  let dx = s.dx and dy = s.dy and dz = s.dz in
  let px = s.px and py = s.py and pz = s.pz in
  let k = Array.unsafe_get p.kind i in
  let triangle = is_triangle k in
  (* A triangle's corners in [p.vertex], or the shape's number in [p.geom]. *)
  let o0 = Array.unsafe_get p.at0 i in
  let o1 = if triangle then Array.unsafe_get p.at1 i else 0 and o2 = if triangle then Array.unsafe_get p.at2 i else 0 in
  let o = Kind.stride * o0 in
  (match k with
  | Triangle | Smooth_triangle -> Triangle.normal_at s p.vertex o0 o1 o2
  | Plane -> Plane.normal s p.geom o
  | Box ->
      (* The root kept, for the face whose slab decides it. *)
      s.near <- s.t;
      Box.hit_normal s p.geom o
  | Csg ->
      (* The surface hit, found again for the ray still in [s]: the same
         first crossing that [closest] kept. The normal is the solid's
         outward one, as a box's, before it is turned toward the ray. *)
      ignore (Csg.roots p.csg tr.csg s (truncate (Array.unsafe_get p.geom o)));
      Csg.normal p.csg tr.csg s
  | Sphere -> not_here "shape_hit");
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
  | Sphere | Plane | Triangle | Smooth_triangle | Box -> Array.unsafe_get p.material i

(* The material whose colour the hit of the ray in [s] at [s.t] shows:
   [m], or the material of its pattern's second colour. {!Pattern.odd}
   reads the hit point as [trace_in] computed it, before the robust mode
   moved it off a shape (the pattern moves it its own way): recomputed
   here with the same operations, put in [s] for the call, and the moved
   point put back. Not inlined: its code would make [trace_objects] too
   big for OCaml to inline into the render loop. *)
let[@inline never] local_material tr m =
  let p = tr.p in
  let alt = Array.unsafe_get p.alternate m in
  if alt < 0 then m
  else begin
    let s = tr.s in
    let t = s.t in
    let px = s.ox +. (s.dx *. t) and py = s.oy +. (s.dy *. t) and pz = s.oz +. (s.dz *. t) in
    let sx = s.px and sy = s.py and sz = s.pz in
    s.px <- px;
    s.py <- py;
    s.pz <- pz;
    let odd = Pattern.odd s p.pattern (Pattern.stride * m) in
    s.px <- sx;
    s.py <- sy;
    s.pz <- sz;
    if odd then alt else m
  end

(* The hit point [px, py, pz] (already in [s]) on the sphere in slot
   [i], for a ray of direction [dx, dy, dz]: its outward normal and the
   view vector, in [s]. *)
let[@inline] sphere_hit tr i px py pz dx dy dz =
  let p = tr.p and s = tr.s in
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

(* The direction of the camera ray through viewport point [(vx, vy, vz)],
   turned by the camera's matrix [m] unless it is the identity. *)
let[@inline] set_direction s identity (m : Camera.rotation) vx vy vz =
  if identity then begin
    s.dx <- vx;
    s.dy <- vy;
    s.dz <- vz
  end
  else begin
    s.dx <- (vx *. m.row0.x) +. (vy *. m.row0.y) +. (vz *. m.row0.z);
    s.dy <- (vx *. m.row1.x) +. (vy *. m.row1.y) +. (vz *. m.row1.z);
    s.dz <- (vx *. m.row2.x) +. (vy *. m.row2.y) +. (vz *. m.row2.z)
  end

(* The buffer of the kernel's one-ray copies, which store nothing. *)
let no_buffer : Image.buffer = Bigarray.Array1.create Bigarray.int8_unsigned Bigarray.c_layout 0

(* The document's kernel: spheres alone, the textbook roots, no hierarchy
   (the reference scene), with the skips on. The whole ray tree of a pixel
   is one loop over local variables: rays, hit points, normals and light
   vectors stay in registers or on the stack, never in memory the
   shadow test must read back, and nothing is called per ray but [pow]
   and, rarely, [settled]. Every value that reaches a pixel is computed
   with the operands and the order of [trace_in] (the reference path, which
   [~skips:false] runs), so the bytes are the same; the skips below only
   leave out work whose result cannot matter.

   Both roots behind ([behind]): when k2 > 0 and k3 > 0, disc =
   fl(fl(k2^2) - fl(4 k1 k3)) <= fl(k2^2), since fl(4 k1 k3) >= 0 and
   rounding is monotonic, and sqrt (fl (k2^2)) = k2 exactly (a theorem of
   binary floating point; an overflow gives infinity either way), so
   -k2 + sq <= 0 and both roots, divided by 2 k1 >= 0, are <= 0 or NaN:
   never in (t_min, t_max) with t_min >= 0 (1 for the camera, the scene's
   epsilon, validated >= 0, for the others). Such a sphere is rejected
   without the square root and the two divisions. *)
let[@inline] blocks_unless_behind sph ox oy oz dx dy dz t_min t_max two_k1 k1x4 zero ~behind k =
  let fx = ox -. Array.unsafe_get sph k
  and fy = oy -. Array.unsafe_get sph (k + 1)
  and fz = oz -. Array.unsafe_get sph (k + 2) in
  let h = (fx *. dx) +. (fy *. dy) +. (fz *. dz) in
  let k2 = h +. h in
  let k3 = ((fx *. fx) +. (fy *. fy) +. (fz *. fz)) -. Array.unsafe_get sph (k + 3) in
  (not (behind && k2 > zero && k3 > zero))
  &&
  let disc = (k2 *. k2) -. (k1x4 *. k3) in
  disc >= zero
  &&
  let sq = sqrt disc in
  let t2 = (-.k2 -. sq) /. two_k1 in
  (t_min < t2 && t2 < t_max)
  ||
  let t1 = (-.k2 +. sq) /. two_k1 in
  t_min < t1 && t1 < t_max

(* The camera rays of a tile: their directions are affine in the pixel's
   (gx, gy) (to within the rounding of the viewport mapping, about an ulp),
   so they lie in the convex hull of the four corner rays, hence in the cone
   around the corners' mean direction whose half-angle theta is the largest
   corner angle (cones of half-angle below pi / 2 are convex). A sphere of
   radius r at distance dist from the camera is seen within the angle
   alpha = asin (re / dist) of its centre's direction, with re = r (1 +
   1e-6) + 1e-6 dist; if that direction is more than theta + alpha + 1e-6
   from the axis, every ray of the tile passes the centre at a distance
   over re + 1e-6 dist cos alpha: the true discriminant
   4 k1 ((dist^2 - dist^2 sin^2) ...) is negative by at least
   4 k1 1e-12 dist^2, some thousand times the rounding of the textbook's
   k2^2 - 4 k1 k3 (a few ulps of 4 k1 dist^2) and of these angles (acos
   near 1 loses at most sqrt u, 1e-8 rad). So the textbook test of the
   culled spheres gives disc < 0 for every ray of the tile: a culled sphere
   is one the ray would have missed. Spheres near or around the camera
   (dist <= 2 re), wide tiles (theta > 1 rad) and anything NaN keep every
   sphere. The kept spheres stay in scene order, so equal roots keep the
   first sphere, as the full loop does. *)
let[@inline never] tile_candidates tr tx ty =
  let p = tr.p and c = tr.corners in
  let n = p.n_objects and vz = p.viewport.distance and m = p.camera.rotation in
  let col0 = tx * tile and row0 = ty * tile in
  let col1 = Int.min (p.width - 1) (col0 + tile - 1) and row1 = Int.min (p.height - 1) (row0 + tile - 1) in
  for k = 0 to 3 do
    let vx = Array.unsafe_get p.column_vx (if k land 1 = 0 then col0 else col1) in
    let vy = Array.unsafe_get p.row_vy (if k land 2 = 0 then row0 else row1) in
    let x = (vx *. m.row0.x) +. (vy *. m.row0.y) +. (vz *. m.row0.z) in
    let y = (vx *. m.row1.x) +. (vy *. m.row1.y) +. (vz *. m.row1.z) in
    let z = (vx *. m.row2.x) +. (vy *. m.row2.y) +. (vz *. m.row2.z) in
    let len = sqrt ((x *. x) +. (y *. y) +. (z *. z)) in
    c.(3 * k) <- x /. len;
    c.((3 * k) + 1) <- y /. len;
    c.((3 * k) + 2) <- z /. len
  done;
  let ax = c.(0) +. c.(3) +. c.(6) +. c.(9) in
  let ay = c.(1) +. c.(4) +. c.(7) +. c.(10) in
  let az = c.(2) +. c.(5) +. c.(8) +. c.(11) in
  let al = sqrt ((ax *. ax) +. (ay *. ay) +. (az *. az)) in
  let ax = ax /. al and ay = ay /. al and az = az /. al in
  let cos_min = ref 1. in
  for k = 0 to 3 do
    let cs = (ax *. c.(3 * k)) +. (ay *. c.((3 * k) + 1)) +. (az *. c.((3 * k) + 2)) in
    if not (cs >= !cos_min) then cos_min := cs
  done;
  let theta = Float.acos (Float.min 1. (Float.max (-1.) !cos_min)) in
  let margin = 1e-6 in
  let base = tx * n and count = ref 0 in
  for i = 0 to n - 1 do
    let qx = -.Array.unsafe_get p.primary_ocx i
    and qy = -.Array.unsafe_get p.primary_ocy i
    and qz = -.Array.unsafe_get p.primary_ocz i in
    let dist = sqrt ((qx *. qx) +. (qy *. qy) +. (qz *. qz)) in
    let re = (Array.unsafe_get p.radius i *. (1. +. margin)) +. (margin *. dist) in
    let keep =
      (not (dist > 2. *. re && theta <= 1.))
      ||
      let alpha = Float.asin (re /. dist) in
      let beta = Float.acos (Float.min 1. (Float.max (-1.) (((ax *. qx) +. (ay *. qy) +. (az *. qz)) /. dist))) in
      not (beta > theta +. alpha +. margin)
    in
    if keep then begin
      Array.unsafe_set tr.cand (base + !count) i;
      incr count
    end
  done;
  tr.tile_row.(tx) <- ty;
  tr.tile_count.(tx) <- !count

let[@inline] textbook_kernel tr ~behind ~row (buffer : Image.buffer) k0 col0 count r =
  let p = tr.p and s = tr.s in
  let sph = p.sphere4 in
  (* Floats computed, not read: a float field or [infinity] bound as is
     stays a pointer to a boxed float, read through once more at every use
     (eps >= 0, so adding 0. changes no comparison). *)
  let n = p.n_objects and eps = p.epsilon +. 0. and inf = 1. /. 0. in
  (* A zero the compiler does not know: compared in a register (or the
     stack), not made afresh with an instruction before every test. *)
  let zero = Float.of_int (Sys.opaque_identity 0) in
  let n4 = 4 * n in
  let n_lights = p.n_lights and light6 = p.light6 and kinds = p.light_kind in
  let blockers = tr.blockers and blockers_first = tr.blockers_first and shadow_skip = p.shadow_skip in
  (* With [row], the camera rays of columns [col0] to [col0 + count - 1] of
     canvas row [r], set up as [row] would, with what is constant along the
     row read once, and each pixel stored at [k0 + 3 (col - col0)];
     without, the one ray in [s] ([count] = 1). Its setup is then once per
     row, not once per pixel. *)
  let c = tr.counters and ty = r / tile and vx = p.column_vx and cull = row && p.cull in
  let vy = if row then Array.unsafe_get p.row_vy r else 0. in
  let vz = p.viewport.distance and m = p.camera.rotation and o = p.camera.position in
  let identity = p.identity_rotation in
  (* The counts of the whole row, added to the counters once. *)
  let tests = ref 0 and shadows = ref 0 and reflections = ref 0 in
  tr.origin_sphere <- -1;
  for col = col0 to col0 + count - 1 do
    if row then begin
      if cull && (col = col0 || col land (tile - 1) = 0) then begin
        let tx = col / tile in
        if Array.unsafe_get tr.tile_row tx <> ty then tile_candidates tr tx ty;
        tr.cand_first <- tx * n;
        tr.cand_count <- Array.unsafe_get tr.tile_count tx
      end;
      set_direction s identity m (Array.unsafe_get vx col) vy vz;
      s.ox <- o.x;
      s.oy <- o.y;
      s.oz <- o.z;
      (* No [t_max]: the kernel's camera and mirror rays reach infinity,
         which [t < best] already implies, and it reads none. *)
      s.t_min <- 1.
    end;
    let levels = ref 0 and tracing = ref true in
    (* The weight of the colour still to be traced: the product of the
       reflectivities on the stack. *)
    let weight = ref 1. in
    while !tracing do
      (* The ray of this level is in [s]: read once, into registers.
         Doublings are written [x +. x]: the same bits as [2. *. x] (both
         exact, or both infinite), one instruction, no constant to load. *)
      let ox' = s.ox and oy' = s.oy and oz' = s.oz and dx' = s.dx and dy' = s.dy and dz' = s.dz in
      let t_min' = s.t_min in
      let a = (dx' *. dx') +. (dy' *. dy') +. (dz' *. dz') in
      let two_k1 = a +. a and k1x4 = 4. *. a in
      (* The closest hit, as [closest_textbook_all] finds it: the t_max of
         camera and mirror rays is infinity, which [t < best] already
         implies. *)
      let best = ref inf and hit = ref (-1) in
      if !levels > 0 then begin
        tests := !tests + n;
        (* Fresh names for what the loop reads: values live across the calls
           (pow, settled) stay on the stack, reloaded at every use otherwise. *)
        let sph = Sys.opaque_identity sph and n4 = Sys.opaque_identity n4 in
        let k = ref 0 in
        while !k < n4 do
          let i = !k in
          let fx = ox' -. Array.unsafe_get sph i and fy = oy' -. Array.unsafe_get sph (i + 1) and fz = oz' -. Array.unsafe_get sph (i + 2) in
          let h = (fx *. dx') +. (fy *. dy') +. (fz *. dz') in
          let k2 = h +. h in
          let k3 = ((fx *. fx) +. (fy *. fy) +. (fz *. fz)) -. Array.unsafe_get sph (i + 3) in
          if not (behind && k2 > zero && k3 > zero) then begin
            let disc = (k2 *. k2) -. (k1x4 *. k3) in
            if disc >= zero then begin
              let sq = sqrt disc in
              let t2 = (-.k2 -. sq) /. two_k1 in
              if t2 < !best && t_min' < t2 then begin
                best := t2;
                hit := i
              end
              else
                let t1 = (-.k2 +. sq) /. two_k1 in
                if t1 < !best && t_min' < t1 then begin
                  best := t1;
                  hit := i
                end
            end
          end;
          k := i + 4
        done;
        (* Slots, not places in [sph]. *)
        if !hit >= 0 then hit := !hit / 4
      end
      else if (not row) && tr.assumed <> no_assumption then begin
        (* Not in a row: [row] leaves an assumed sphere to [pixel], so the
           row's copy calls nothing here, and the ray's values need not be
           saved on the stack around a call at every level. *)
        hit := primary_hit_spheres tr;
        best := s.t;
        tr.first_hit <- !hit
      end
      else begin
        (* From the camera, CO and k3 are per-frame constants; only the
           tile's spheres are tested. *)
        let pr = p.primary4 in
        let cand = tr.cand and first = tr.cand_first and count = tr.cand_count in
        tests := !tests + count;
        for j = first to first + count - 1 do
          let i = Array.unsafe_get cand j in
          let k = 4 * i in
          let fx = Array.unsafe_get pr k and fy = Array.unsafe_get pr (k + 1) and fz = Array.unsafe_get pr (k + 2) in
          let h = (fx *. dx') +. (fy *. dy') +. (fz *. dz') in
          let k2 = h +. h in
          let k3 = Array.unsafe_get pr (k + 3) in
          if not (behind && k2 > zero && k3 > zero) then begin
            let disc = (k2 *. k2) -. (k1x4 *. k3) in
            if disc >= zero then begin
              let sq = sqrt disc in
              let t2 = (-.k2 -. sq) /. two_k1 in
              if t2 < !best && t_min' < t2 then begin
                best := t2;
                hit := i
              end
              else
                let t1 = (-.k2 +. sq) /. two_k1 in
                if t1 < !best && t_min' < t1 then begin
                  best := t1;
                  hit := i
                end
            end
          end
        done;
        tr.first_hit <- !hit
      end;
      let i = !hit in
      if i < 0 then begin
        s.r <- p.background.r;
        s.g <- p.background.g;
        s.b <- p.background.b;
        tracing := false
      end
      else begin
        let t = !best in
        let px = ox' +. (dx' *. t) and py = oy' +. (dy' *. t) and pz = oz' +. (dz' *. t) in
        let nx = px -. Array.unsafe_get sph (4 * i) and ny = py -. Array.unsafe_get sph ((4 * i) + 1) and nz = pz -. Array.unsafe_get sph ((4 * i) + 2) in
        let inv = 1. /. sqrt ((nx *. nx) +. (ny *. ny) +. (nz *. nz)) in
        let nx = nx *. inv and ny = ny *. inv and nz = nz *. inv in
        let vx = -.dx' and vy = -.dy' and vz = -.dz' in
        let m = Array.unsafe_get p.material i in
        (* [lighting], with the shadow ray inlined. *)
        let specular = Array.unsafe_get p.specular m and cut = p.specular_cut and mo = m * n_lights in
        (* The ambient lights that come first add up to the same sum in any
           case: it starts from their total (Prepared.ambient_lead). *)
        let intensity = ref p.ambient_lead in
        let length_n = sqrt ((nx *. nx) +. (ny *. ny) +. (nz *. nz)) in
        (* |V| = |D|: negating changes no square, [a] sums them alike. *)
        let length_v = sqrt a in
        for l = p.first_light to n_lights - 1 do
          let o = 6 * l in
          let kind = Array.unsafe_get kinds l and li = Array.unsafe_get light6 (o + 1) in
          if kind = Prepared.ambient then intensity := !intensity +. li
          else begin
            let lx = ref (Array.unsafe_get light6 (o + 2))
            and ly = ref (Array.unsafe_get light6 (o + 3))
            and lz = ref (Array.unsafe_get light6 (o + 4)) in
            if kind = Prepared.point then begin
              lx := !lx -. px;
              ly := !ly -. py;
              lz := !lz -. pz
            end;
            let lx = !lx and ly = !ly and lz = !lz in
            let n_dot_l = (nx *. lx) +. (ny *. ly) +. (nz *. lz) in
            let add_diffuse = n_dot_l > zero in
            (* The specular term's cosine, as [lighting] computes it
               (its 2 <L, N> is 2 n_dot_l: the same products, summed in the
               same order); computed for matte spheres too, whose cut is
               infinite, rather than asking the material at every light. *)
            let k = n_dot_l +. n_dot_l in
            let rx = (nx *. k) -. lx and ry = (ny *. k) -. ly and rz = (nz *. k) -. lz in
            let r_dot_v = (rx *. vx) +. (ry *. vy) +. (rz *. vz) in
            let cos = if r_dot_v > zero then r_dot_v /. (sqrt ((rx *. rx) +. (ry *. ry) +. (rz *. rz)) *. length_v) else zero in
            (* At or below the cut, li cos^s is 0 or too small to change
               the sum (Prepared.specular_cut): the sum is what it would be
               with the term, and pow is not called. *)
            let add_specular = cos > Array.unsafe_get cut (mo + l) in
            (* The shadow ray only matters if a term would be added: a light
               that adds nothing leaves the sum as it is, lit or not. (A
               point light on the point itself, L = 0, adds nothing:
               n_dot_l = 0 and R = 0. Without the skip it is left out, as
               [lighting] does.) *)
            if
              (if shadow_skip then add_diffuse || add_specular
               else kind <> Prepared.point || lx <> 0. || ly <> 0. || lz <> 0.)
              &&
              (* [shadowed] with the skips: any blocker will do, so the
                 spheres are tried in this light's order of [blockers],
                 where the last one found was swapped to the front. *)
              let a = (lx *. lx) +. (ly *. ly) +. (lz *. lz) in
              let two_k1 = a +. a and k1x4 = 4. *. a in
              incr shadows;
              let first = Array.unsafe_get blockers_first l in
              let stop = first + n4 in
              let q = ref first in
              (* Its range: 1 for a point light, infinity for a directional one. *)
              let t_max = Array.unsafe_get light6 o in
              while !q < stop && not (blocks_unless_behind blockers px py pz lx ly lz eps t_max two_k1 k1x4 zero ~behind !q) do
                q := !q + 4
              done;
              let q = !q in
              if q < stop then begin
                tests := !tests + ((q - first) / 4) + 1;
                if q > first then
                  for c = 0 to 3 do
                    let x = Array.unsafe_get blockers (q + c) in
                    Array.unsafe_set blockers (q + c) (Array.unsafe_get blockers (first + c));
                    Array.unsafe_set blockers (first + c) x
                  done;
                false
              end
              else begin
                tests := !tests + n;
                true
              end
            then begin
              if add_diffuse then begin
                let len = if kind = Prepared.point then sqrt ((lx *. lx) +. (ly *. ly) +. (lz *. lz)) else Array.unsafe_get light6 (o + 5) in
                intensity := !intensity +. (li *. n_dot_l /. (length_n *. len))
              end;
              if add_specular then intensity := !intensity +. (li *. Float.pow cos specular)
            end
          end
        done;
        let light = !intensity in
        let lr = Array.unsafe_get p.red m *. light and lg = Array.unsafe_get p.green m *. light and lb = Array.unsafe_get p.blue m *. light in
        let refl = Array.unsafe_get p.reflective m in
        if refl <= 0. || !levels >= p.depth then begin
          s.r <- lr;
          s.g <- lg;
          s.b <- lb;
          tracing := false
        end
        else begin
          let k = 4 * !levels in
          Array.unsafe_set tr.stack k lr;
          Array.unsafe_set tr.stack (k + 1) lg;
          Array.unsafe_set tr.stack (k + 2) lb;
          Array.unsafe_set tr.stack (k + 3) refl;
          incr levels;
          weight := !weight *. refl;
          (* As in [trace_in]. *)
          if p.early_stop
             && (!weight *. p.max_channel < 1. || (lr >= 255. && lg >= 255. && lb >= 255.))
             && settled tr !levels
          then begin
            tr.counters.early_stops <- tr.counters.early_stops + 1;
            s.r <- 0.;
            s.g <- 0.;
            s.b <- 0.;
            tracing := false
          end
          else begin
            (* The mirror ray R = 2 <V, N> N - V from the hit point. *)
            let h = (vx *. nx) +. (vy *. ny) +. (vz *. nz) in
            let k = h +. h in
            s.ox <- px;
            s.oy <- py;
            s.oz <- pz;
            s.dx <- (nx *. k) -. vx;
            s.dy <- (ny *. k) -. vy;
            s.dz <- (nz *. k) -. vz;
            s.t_min <- eps;
            incr reflections
          end
        end
      end
    done;
    for l = !levels - 1 downto 0 do
      let refl = Array.unsafe_get tr.stack ((4 * l) + 3) in
      let keep = 1. -. refl in
      s.r <- (Array.unsafe_get tr.stack (4 * l) *. keep) +. (s.r *. refl);
      s.g <- (Array.unsafe_get tr.stack ((4 * l) + 1) *. keep) +. (s.g *. refl);
      s.b <- (Array.unsafe_get tr.stack ((4 * l) + 2) *. keep) +. (s.b *. refl)
    done;
    if row then store tr buffer (k0 + (3 * (col - col0)))
  done;
  if row then c.primary <- c.primary + count;
  c.tests <- c.tests + !tests;
  c.shadow <- c.shadow + !shadows;
  c.reflection <- c.reflection + !reflections

(* One copy with the rejection of spheres behind, one without (for the
   tests of its exactness); each for one ray and for a row of camera rays. *)
let[@inline never] trace_textbook_behind tr = textbook_kernel tr ~behind:true ~row:false no_buffer 0 0 1 0
let[@inline never] trace_textbook_all_roots tr = textbook_kernel tr ~behind:false ~row:false no_buffer 0 0 1 0
let[@inline never] row_textbook_behind tr buffer k col0 count r = textbook_kernel tr ~behind:true ~row:true buffer k col0 count r
let[@inline never] row_textbook_all_roots tr buffer k col0 count r = textbook_kernel tr ~behind:false ~row:true buffer k col0 count r

(* Section 7.8 as a loop: each level traces one ray; a reflective hit pushes
   its local colour and reflectivity and continues with the mirror ray; then
   the stack is folded back from the deepest colour, blend by blend, in the
   same order as the recursion. The ray to trace is in [s]. *)
let[@inline] trace_in tr ~spheres =
  let p = tr.p and s = tr.s in
  let levels = ref 0 and tracing = ref true in
  (* The weight of the colour still to be traced: the product of the
     reflectivities on the stack. *)
  let weight = ref 1. in
  tr.first_hit <- -1;
  tr.origin_sphere <- -1;
  while !tracing do
    let i = if !levels = 0 then (if spheres then primary_hit_spheres tr else primary_hit_objects tr) else closest_in tr ~spheres in
    if !levels = 0 then tr.first_hit <- i;
    if i < 0 then begin
      s.r <- p.background.r;
      s.g <- p.background.g;
      s.b <- p.background.b;
      tracing := false
    end
    else begin
      let t = s.t in
      let dx = s.dx and dy = s.dy and dz = s.dz in
      let px = s.ox +. (dx *. t) and py = s.oy +. (dy *. t) and pz = s.oz +. (dz *. t) in
      let m =
      if spheres || Array.unsafe_get p.kind i = Kind.Sphere then begin
        s.px <- px;
        s.py <- py;
        s.pz <- pz;
        sphere_hit tr i px py pz dx dy dz;
        Array.unsafe_get p.material i
      end
      else begin
        (* The point goes in [s], not as arguments: floats passed to a
           function that is not inlined are boxed. *)
        s.px <- px;
        s.py <- py;
        s.pz <- pz;
        shape_hit tr i
      end
      in
      (* A pattern's second colour is a material that differs from the
         object's in its colour alone. Looked up before the lighting, whose
         shadow rays reuse [s]'s ray. *)
      let m = if (not spheres) && p.patterned then local_material tr m else m
      in
      lighting tr ~shiny:(Array.unsafe_get p.specular m <> Sphere.matte) ~specular_of:p.specular m;
      let light = s.intensity in
      let lr = Array.unsafe_get p.red m *. light and lg = Array.unsafe_get p.green m *. light and lb = Array.unsafe_get p.blue m *. light in
      let refl = Array.unsafe_get p.reflective m in
      if refl <= 0. || !levels >= p.depth then begin
        s.r <- lr;
        s.g <- lg;
        s.b <- lb;
        tracing := false
      end
      else begin
        let k = 4 * !levels in
        Array.unsafe_set tr.stack k lr;
        Array.unsafe_set tr.stack (k + 1) lg;
        Array.unsafe_set tr.stack (k + 2) lb;
        Array.unsafe_set tr.stack (k + 3) refl;
        incr levels;
        weight := !weight *. refl;
        (* Checking costs two folds of the stack: worth it only when what is
           left weighs less than a unit, or this colour saturates. Skipping
           the check is always exact. *)
        if p.early_stop
           && (!weight *. p.max_channel < 1. || (lr >= 255. && lg >= 255. && lb >= 255.))
           && settled tr !levels
        then begin
          tr.counters.early_stops <- tr.counters.early_stops + 1;
          s.r <- 0.;
          s.g <- 0.;
          s.b <- 0.;
          tracing := false
        end
        else begin
          mirror_ray p s;
          tr.counters.reflection <- tr.counters.reflection + 1
        end
      end
    end
  done;
  for l = !levels - 1 downto 0 do
    let refl = Array.unsafe_get tr.stack ((4 * l) + 3) in
    let keep = 1. -. refl in
    s.r <- (Array.unsafe_get tr.stack (4 * l) *. keep) +. (s.r *. refl);
    s.g <- (Array.unsafe_get tr.stack ((4 * l) + 1) *. keep) +. (s.g *. refl);
    s.b <- (Array.unsafe_get tr.stack ((4 * l) + 2) *. keep) +. (s.b *. refl)
  done

(* One copy per kind of scene: spheres alone ask no object its kind, nor
   its pattern ({!Prepared.all_spheres}); the other scenes test per hit
   whether any material has a pattern. (A copy of the loop for patterns
   made [trace_objects] too big for OCaml to inline into the render loop
   it is called from, which cost more than the test: 13 instructions per
   pixel on scenes/boxes.scene.) *)
let trace_spheres tr = trace_in tr ~spheres:true
let trace_objects tr = trace_in tr ~spheres:false

(* The ray tree (scenes with transparency; Ray_tree describes its
   storage). A hit's colour is [local (1 - r - t) + reflected wr +
   refracted wt]: [wr = r + t R] and [wt = t (1 - R)], [R] the
   reflectance ([0] without Fresnel, [1] on total internal reflection, so
   that it folds into the reflected part). Opaque hits ([t = 0]) take the
   same floating-point operations as [trace_in], so a transparent object
   changes nothing where it is not seen. *)

(* Byte-exact early stop in the tree: before level [l] traces the child
   [tree.tracing.(l)] names, the pixel is a non-decreasing function of the
   colours still unknown (that child, and the refracted children still
   pending on the way up), each in [\[0, max_channel\]], evaluated with the
   operations of [shade]: if both extremes give the same bytes, so does the
   truth, whatever the children are (the argument of [settled]). *)
let settled_tree tr l =
  let tree = tr.tree and hi = tr.p.max_channel in
  let node = tree.node in
  let lo_r = ref 0. and lo_g = ref 0. and lo_b = ref 0. in
  let hi_r = ref hi and hi_g = ref hi and hi_b = ref hi in
  for k = l downto 0 do
    let o = Ray_tree.node_stride * k in
    let lr = Array.unsafe_get node o and lg = Array.unsafe_get node (o + 1) and lb = Array.unsafe_get node (o + 2) in
    let wr = Array.unsafe_get node (o + 3) and wt = Array.unsafe_get node (o + 4) in
    if Array.unsafe_get tree.tracing k = 0 then begin
      (* The reflected child is the unknown one; the refracted one, if
         any, is still to come: 0 at least, max_channel at most. *)
      lo_r := lr +. (!lo_r *. wr);
      lo_g := lg +. (!lo_g *. wr);
      lo_b := lb +. (!lo_b *. wr);
      hi_r := lr +. (!hi_r *. wr);
      hi_g := lg +. (!hi_g *. wr);
      hi_b := lb +. (!hi_b *. wr);
      if wt > 0. then begin
        lo_r := !lo_r +. (0. *. wt);
        lo_g := !lo_g +. (0. *. wt);
        lo_b := !lo_b +. (0. *. wt);
        hi_r := !hi_r +. (hi *. wt);
        hi_g := !hi_g +. (hi *. wt);
        hi_b := !hi_b +. (hi *. wt)
      end
    end
    else begin
      let br = ref lr and bg = ref lg and bb = ref lb in
      if wr > 0. then begin
        br := lr +. (Array.unsafe_get node (o + 5) *. wr);
        bg := lg +. (Array.unsafe_get node (o + 6) *. wr);
        bb := lb +. (Array.unsafe_get node (o + 7) *. wr)
      end;
      lo_r := !br +. (!lo_r *. wt);
      lo_g := !bg +. (!lo_g *. wt);
      lo_b := !bb +. (!lo_b *. wt);
      hi_r := !br +. (!hi_r *. wt);
      hi_g := !bg +. (!hi_g *. wt);
      hi_b := !bb +. (!hi_b *. wt)
    end
  done;
  if tr.averaging then same_clamped !lo_r !hi_r && same_clamped !lo_g !hi_g && same_clamped !lo_b !hi_b
  else to_byte !lo_r = to_byte !hi_r && to_byte !lo_g = to_byte !hi_g && to_byte !lo_b = to_byte !hi_b

(* May level [l] skip its child of weight [w] ([tree.tracing.(l)] set)?
   Checking costs a walk up the tree: worth it only when the child weighs
   less than a unit. *)
let[@inline] skip_child tr l w =
  let p = tr.p in
  p.early_stop
  && Array.unsafe_get tr.tree.weight l *. w *. p.max_channel < 1.
  && settled_tree tr l
  && begin
       tr.counters.early_stops <- tr.counters.early_stops + 1;
       true
     end

(* The ray of level [l] is in [s] (range, [tr.origin_sphere]), its medium
   stack in [tree.media] at level [l]; its colour is left in [s.r..]. *)
let rec shade tr l =
  (* Without the early stop, a tree of depth 64 may have 2^64 rays: the
     work bound is checked at every hit, not only after each column. *)
  check_budget tr;
  let p = tr.p and s = tr.s and tree = tr.tree in
  let base = Ray_tree.media_cap * l in
  let media = tree.media and index = p.refractive_index and io = tree.optics in
  (* Surfaces that change nothing (transparency 1, the same index on both
     sides) are crossed on the same ray: no bounce, no rounding. *)
  let searching = ref true and hit = ref (-1) and first = ref (l = 0) in
  while !searching do
    if not !first then check_budget tr;
    let i =
      if !first then if p.all_spheres then primary_hit_spheres tr else primary_hit_objects tr else closest tr
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
  let i = !hit in
  if l = 0 then tr.first_hit <- i;
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
    let m = if sphere then (sphere_hit tr i px py pz dx dy dz; Array.unsafe_get p.material i) else shape_hit tr i in
    let m = if p.patterned then local_material tr m else m in
    let medium = Array.unsafe_get p.material i in
    let refl = Array.unsafe_get p.reflective m and tt = Array.unsafe_get p.transparency m in
    let keep = 1. -. refl -. tt in
    let o = Ray_tree.pending_stride * l in
    let n = Array.unsafe_get tree.n_media l in
    (* The refracted ray, set aside while the reflected one is traced:
       Snell's law with the normal turned toward the ray. *)
    let reflectance =
      if tt > 0. then begin
        let nx = s.nx and ny = s.ny and nz = s.nz in
        let facing = (nx *. dx) +. (ny *. dy) +. (nz *. dz) <= 0. in
        let nx = if facing then nx else -.nx and ny = if facing then ny else -.ny and nz = if facing then nz else -.nz in
        Ray_tree.indices index media base n medium io;
        Array.unsafe_set io 2 dx;
        Array.unsafe_set io 3 dy;
        Array.unsafe_set io 4 dz;
        Array.unsafe_set io 5 nx;
        Array.unsafe_set io 6 ny;
        Array.unsafe_set io 7 nz;
        let fresnel = Array.unsafe_get p.fresnel m in
        Ray_tree.split io ~fresnel;
        (* A smooth triangle's interpolated normal may bend the ray back
           to the side it came from, which it would not cross: then the
           flat normal, turned toward the ray, decides. *)
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
      end
      else 0.
    in
    let wr = refl +. (tt *. reflectance) and wt = tt *. (1. -. reflectance) in
    if l >= p.depth || (wr <= 0. && wt <= 0.) then begin
      lighting_through tr ~shiny:(Array.unsafe_get p.specular m <> Sphere.matte) ~specular_of:p.specular m;
      let light = s.intensity in
      s.r <- Array.unsafe_get p.red m *. light;
      s.g <- Array.unsafe_get p.green m *. light;
      s.b <- Array.unsafe_get p.blue m *. light
    end
    else begin
      if wt > 0. then begin
        (* Its origin: the hit point, on the far side of the surface. A
           sphere is left exactly (its slot), another shape from the
           point [shape_hit] moved toward the ray, mirrored through the
           surface. *)
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
        Ray_tree.copy_media media base n tree.pending_media pbase;
        Array.unsafe_set tree.pending_n_media l (Ray_tree.cross tree.pending_media pbase n medium)
      end;
      let no = Ray_tree.node_stride * l in
      let node = tree.node in
      if keep > 0. then begin
        lighting_through tr ~shiny:(Array.unsafe_get p.specular m <> Sphere.matte) ~specular_of:p.specular m;
        let light = s.intensity in
        Array.unsafe_set node no (Array.unsafe_get p.red m *. light *. keep);
        Array.unsafe_set node (no + 1) (Array.unsafe_get p.green m *. light *. keep);
        Array.unsafe_set node (no + 2) (Array.unsafe_get p.blue m *. light *. keep)
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
      Array.unsafe_set node (no + 7) 0.;
      let weight = Array.unsafe_get tree.weight l in
      let child = l + 1 and cbase = Ray_tree.media_cap * (l + 1) in
      if wr > 0. then begin
        Array.unsafe_set tree.tracing l 0;
        if not (skip_child tr l wr) then begin
          (* In the same medium. *)
          mirror_ray p s;
          tr.origin_sphere <- (if sphere then i else -1);
          Ray_tree.copy_media media base n media cbase;
          Array.unsafe_set tree.n_media child n;
          Array.unsafe_set tree.weight child (weight *. wr);
          tr.counters.reflection <- tr.counters.reflection + 1;
          shade tr child;
          Array.unsafe_set node (no + 5) s.r;
          Array.unsafe_set node (no + 6) s.g;
          Array.unsafe_set node (no + 7) s.b
        end
      end;
      let tr_r = ref 0. and tr_g = ref 0. and tr_b = ref 0. in
      if wt > 0. then begin
        Array.unsafe_set tree.tracing l 1;
        if not (skip_child tr l wt) then begin
          let pending = tree.pending in
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
          Ray_tree.copy_media tree.pending_media base pn media cbase;
          Array.unsafe_set tree.n_media child pn;
          Array.unsafe_set tree.weight child (weight *. wt);
          tr.counters.reflection <- tr.counters.reflection + 1;
          shade tr child;
          tr_r := s.r;
          tr_g := s.g;
          tr_b := s.b
        end
      end;
      (* The blend, in the order [settled_tree] bounds it. *)
      let r = ref (Array.unsafe_get node no) and g = ref (Array.unsafe_get node (no + 1)) and b = ref (Array.unsafe_get node (no + 2)) in
      if wr > 0. then begin
        r := !r +. (Array.unsafe_get node (no + 5) *. wr);
        g := !g +. (Array.unsafe_get node (no + 6) *. wr);
        b := !b +. (Array.unsafe_get node (no + 7) *. wr)
      end;
      if wt > 0. then begin
        r := !r +. (!tr_r *. wt);
        g := !g +. (!tr_g *. wt);
        b := !b +. (!tr_b *. wt)
      end;
      s.r <- !r;
      s.g <- !g;
      s.b <- !b
    end
  end

let trace_tree tr =
  let tree = tr.tree in
  tr.first_hit <- -1;
  tr.origin_sphere <- -1;
  Array.unsafe_set tree.n_media 0 0;
  Array.unsafe_set tree.weight 0 1.;
  shade tr 0

let[@inline] trace tr =
  let p = tr.p in
  if p.textbook_all && p.skips then (if p.behind then trace_textbook_behind tr else trace_textbook_all_roots tr)
  else
    let k = tr.tracer in
    if k = spheres_chain then trace_spheres tr else if k = objects_chain then trace_objects tr else trace_tree tr

(* The camera ray through viewport point [(vx, vy, d)]. *)
let[@inline] primary_through tr vx vy =
  let p = tr.p and s = tr.s in
  let vz = p.viewport.distance in
  let cam = p.camera in
  set_direction s p.identity_rotation cam.rotation vx vy vz;
  s.ox <- cam.position.x;
  s.oy <- cam.position.y;
  s.oz <- cam.position.z;
  s.t_min <- 1.;
  s.t_max <- infinity;
  tr.counters.primary <- tr.counters.primary + 1;
  trace tr

(* The camera ray of no tile tests every sphere. *)
let[@inline] untiled tr =
  tr.cand_first <- Array.length tr.cand - tr.p.n_objects;
  tr.cand_count <- tr.p.n_objects

(* The primary ray through canvas point [s.gx, s.gy]. *)
let primary tr =
  let p = tr.p and s = tr.s in
  let gx = s.gx and gy = s.gy in
  let vp = p.viewport in
  untiled tr;
  (* Viewport point (section 3), multiplied before dividing as written. *)
  let vx = gx *. vp.width /. Float.of_int p.width in
  let vy = gy *. vp.height /. Float.of_int p.height in
  primary_through tr vx vy

(* A pixel's centre: its viewport point is the frame's (the same
   operations as [primary]'s), and its tile's spheres are the candidates. *)
let[@inline] pixel tr gx gy =
  let p = tr.p in
  check_budget tr;
  let col = gx + (p.width / 2) and row = gy + (p.height / 2) in
  if col >= 0 && col < p.width && row >= 0 && row < p.height then begin
    if p.cull && p.textbook_all then begin
      let tx = col / tile and ty = row / tile in
      if Array.unsafe_get tr.tile_row tx <> ty then tile_candidates tr tx ty;
      tr.cand_first <- tx * p.n_objects;
      tr.cand_count <- Array.unsafe_get tr.tile_count tx
    end;
    primary_through tr (Array.unsafe_get p.column_vx col) (Array.unsafe_get p.row_vy row)
  end
  else begin
    tr.s.gx <- Float.of_int gx;
    tr.s.gy <- Float.of_int gy;
    primary tr
  end

(* The pixels of a row the document's kernel traces between two checks of
   the budget: a multiple of [tile], so that blocks start on tiles. *)
let block = 32 * tile

let row tr buffer k gx gy count =
  let p = tr.p in
  let col0 = gx + (p.width / 2) and r = gy + (p.height / 2) in
  if r >= 0 && r < p.height && col0 >= 0 && count >= 0 && col0 + count <= p.width then begin
    (* [pixel], with what is constant along the row read once; the
       document's kernel takes the whole row. *)
    (* The kernel's row copy takes no assumed sphere (see [textbook_kernel]). *)
    if p.textbook_all && p.skips && tr.assumed = no_assumption then begin
      (* In blocks of pixels, with the budget checked before each: a
         single wide row cannot run far past it. *)
      let c = ref 0 in
      while !c < count do
        let n = if count - !c < block then count - !c else block in
        check_budget tr;
        if p.behind then row_textbook_behind tr buffer (k + (3 * !c)) (col0 + !c) n r
        else row_textbook_all_roots tr buffer (k + (3 * !c)) (col0 + !c) n r;
        c := !c + n
      done
    end
    else
      let s = tr.s and c = tr.counters in
      let vy = Array.unsafe_get p.row_vy r and vx = p.column_vx in
      let vz = p.viewport.distance and m = p.camera.rotation and o = p.camera.position in
      let identity = p.identity_rotation in
      for col = col0 to col0 + count - 1 do
        check_budget tr;
        set_direction s identity m (Array.unsafe_get vx col) vy vz;
        s.ox <- o.x;
        s.oy <- o.y;
        s.oz <- o.z;
        s.t_min <- 1.;
        s.t_max <- infinity;
        c.primary <- c.primary + 1;
        trace tr;
        store tr buffer (k + (3 * (col - col0)))
      done
  end
  else
    for c = 0 to count - 1 do
      pixel tr (gx + c) gy;
      store tr buffer (k + (3 * c))
    done

let sample tr gx gy ~i ~j ~n =
  let n = Float.of_int n in
  (* For n = 1 the offsets are 0.5 /. 1. -. 0.5 = 0 exactly: [pixel]. *)
  tr.s.gx <- Float.of_int gx +. (((Float.of_int i +. 0.5) /. n) -. 0.5);
  tr.s.gy <- Float.of_int gy +. (((Float.of_int j +. 0.5) /. n) -. 0.5);
  primary tr

let cast tr ~from (o : Vec3.t) (d : Vec3.t) =
  let s = tr.s in
  s.ox <- o.x;
  s.oy <- o.y;
  s.oz <- o.z;
  s.dx <- d.x;
  s.dy <- d.y;
  s.dz <- d.z;
  s.t_min <- tr.p.epsilon;
  s.t_max <- infinity;
  tr.origin_sphere <-
    (if from < 0 || tr.p.kind.(tr.p.slot.(from)) <> Kind.Sphere then -1 else tr.p.slot.(from));
  let hit = closest tr in
  if hit < 0 then -1 else tr.p.index.(hit)

(* The roots of object [k]'s test, by the same code as [closest] runs for a
   secondary ray (not the camera's per-frame constants). *)
let roots tr k (o : Vec3.t) (d : Vec3.t) =
  let p = tr.p and s = tr.s in
  if k < 0 || k >= p.n_scene_objects then invalid_arg "Trace.roots: no such object";
  let i = p.slot.(k) in
  Scratch.set_ray s o d;
  if p.kind.(i) <> Kind.Sphere then begin
    (* A CSG solid's root is its first crossing beyond [t_min]: all of them. *)
    s.t_min <- neg_infinity;
    tr.kz <- -1;
    if shape_roots tr s i then (s.near, s.far) else (infinity, infinity)
  end
  else
    let fx = s.ox -. p.cx.(i) and fy = s.oy -. p.cy.(i) and fz = s.oz -. p.cz.(i) in
    let dx = s.dx and dy = s.dy and dz = s.dz in
    let a = (dx *. dx) +. (dy *. dy) +. (dz *. dz) in
    if p.robust then
      if robust_roots p s i fx fy fz dx dy dz a (1. /. a) then (s.near, s.far) else (infinity, infinity)
    else begin
      (* [consider_textbook]'s roots, kept when in range: the range is opened
         wide, and the better of the two, then the other, read back. *)
      s.t_min <- neg_infinity;
      s.t_max <- infinity;
      let k2 = 2. *. ((fx *. dx) +. (fy *. dy) +. (fz *. dz)) in
      let k3 = ((fx *. fx) +. (fy *. fy) +. (fz *. fz)) -. p.r2.(i) in
      tr.hit <- -1;
      s.t <- infinity;
      consider_textbook tr s i (4. *. a) (2. *. a) k2 k3;
      if tr.hit < 0 then (infinity, infinity)
      else
        let near = s.t in
        let disc = (k2 *. k2) -. (4. *. a *. k3) in
        let far = (-.k2 +. sqrt disc) /. (2. *. a) in
        (near, if far < near then near else far)
    end

(* Several rays per pixel. The colours are summed here, in the scratch
   record, so that no float crosses a module boundary per sample. *)

type samples = (float, Bigarray.float64_elt, Bigarray.c_layout) Bigarray.Array1.t

let averaging tr = tr.averaging

let pixel_assuming tr gx gy k =
  if k < -1 || k >= tr.p.n_scene_objects then invalid_arg "Trace.pixel_assuming: no such object";
  tr.assumed <- k;
  pixel tr gx gy;
  tr.assumed <- no_assumption

(* [Color.clamp] without the NaN case (no NaN reaches a colour here). *)
let[@inline] clamp x = if x >= 255. then 255. else if x > 0. then x else 0.

let check_averaging tr fn =
  if not tr.averaging then
    invalid_arg (Printf.sprintf "Trace.%s: the tracer was not created with ~averaging:true" fn)

let clear tr =
  let s = tr.s in
  s.acc_r <- 0.;
  s.acc_g <- 0.;
  s.acc_b <- 0.

let[@inline] add_clamped s =
  s.acc_r <- s.acc_r +. clamp s.r;
  s.acc_g <- s.acc_g +. clamp s.g;
  s.acc_b <- s.acc_b +. clamp s.b

let accumulate tr =
  check_averaging tr "accumulate";
  add_clamped tr.s

(* The samples of the grid in one fixed order, rows [j] then columns [i]:
   [average] and [average_reusing] add the same floats in the same order,
   so they give the same sums. *)
let grid tr gx gy n ~reuse (saved : samples) k =
  let c = n / 2 in
  let s = tr.s in
  clear tr;
  for j = 0 to n - 1 do
    for i = 0 to n - 1 do
      if reuse && i = c && j = c then begin
        s.acc_r <- s.acc_r +. Bigarray.Array1.get saved k;
        s.acc_g <- s.acc_g +. Bigarray.Array1.get saved (k + 1);
        s.acc_b <- s.acc_b +. Bigarray.Array1.get saved (k + 2)
      end
      else begin
        sample tr gx gy ~i ~j ~n;
        add_clamped s
      end
    done
  done

(* A 0-element array for [grid ~reuse:false], which never reads it. *)
let no_samples : samples = Bigarray.Array1.create Bigarray.float64 Bigarray.c_layout 0

let average tr gx gy ~n =
  check_averaging tr "average";
  if n < 1 then invalid_arg "Trace.average: n < 1";
  check_budget tr;
  grid tr gx gy n ~reuse:false no_samples 0

(* For an odd [n], the centre sample [(n / 2, n / 2)] has offsets
   [(n / 2 + 0.5) / n - 0.5 = 0.5 - 0.5 = 0] exactly ([n / 2 + 0.5] is
   [n / 2] exactly in floats), so it is the ray of [pixel]. *)
let save tr (saved : samples) k =
  let s = tr.s in
  Bigarray.Array1.set saved k (clamp s.r);
  Bigarray.Array1.set saved (k + 1) (clamp s.g);
  Bigarray.Array1.set saved (k + 2) (clamp s.b)

let average_reusing tr saved k gx gy ~n =
  check_averaging tr "average_reusing";
  if n < 1 || n land 1 = 0 then invalid_arg "Trace.average_reusing: n is not odd and positive";
  check_budget tr;
  grid tr gx gy n ~reuse:true saved k

let store_average tr (buffer : Image.buffer) k ~count =
  let s = tr.s and c = Float.of_int count in
  Bigarray.Array1.unsafe_set buffer k (to_byte (s.acc_r /. c));
  Bigarray.Array1.unsafe_set buffer (k + 1) (to_byte (s.acc_g /. c));
  Bigarray.Array1.unsafe_set buffer (k + 2) (to_byte (s.acc_b /. c))
