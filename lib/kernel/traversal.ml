open Scratch
open Tracer

(* Two ways to intersect. The document's mode (the scene gives an epsilon)
   uses the textbook quadratic of section 6.1 in CGFS's order of operations,
   so that it reproduces the document's images byte for byte. The robust
   mode uses the cancellation-free roots of [Sphere.roots] (its formulas,
   with [1 / a] computed once a ray: the far root is [q * (1 / a)], where
   [Sphere.roots] and the CSG table divide, [q / a]) and needs no epsilon: a secondary ray cannot hit the sphere
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
     displacement from its offset, not an index computed per load (fewer
     instructions a test: docs/performance.md, "Round 3: the kernel's
     modules"). The order is the same for every triangle
     of a ray: its branch is predicted. *)
  match tr.order with
  | 0 -> Triangle.hit s g o0 o1 o2 1 2 0
  | 1 -> Triangle.hit s g o0 o1 o2 2 1 0
  | 2 -> Triangle.hit s g o0 o1 o2 0 2 1
  | 3 -> Triangle.hit s g o0 o1 o2 2 0 1
  | 4 -> Triangle.hit s g o0 o1 o2 0 1 2
  | _ -> Triangle.hit s g o0 o1 o2 1 0 2

(* The triangles in slots [first .. last] of a leaf, each tested
   against the ray in [s] (sheared: [tr.kz >= 0]) with the axes [kx, ky,
   kz] as constants, keeping the better hit: [triangle_hit]'s test with
   its order chosen once a leaf, not once a triangle, and the arrays read
   into locals once a leaf. *)
let[@inline] leaf_closest tr s first last kx ky kz =
  let p = tr.p in
  let g = p.vertex and at0 = p.at0 and at1 = p.at1 and at2 = p.at2 in
  for i = first to last do
    if Triangle.hit s g (Array.unsafe_get at0 i) (Array.unsafe_get at1 i) (Array.unsafe_get at2 i) kx ky kz then
      keep tr s i s.near
  done

(* [leaf_closest] in the ray's order of the axes ([triangle_hit]'s six). *)
let[@inline] triangles_closest tr s first last =
  match tr.order with
  | 0 -> leaf_closest tr s first last 1 2 0
  | 1 -> leaf_closest tr s first last 2 1 0
  | 2 -> leaf_closest tr s first last 0 2 1
  | 3 -> leaf_closest tr s first last 2 0 1
  | 4 -> leaf_closest tr s first last 0 1 2
  | _ -> leaf_closest tr s first last 1 0 2

(* The first of the triangles in slots [first .. last - 1] of a leaf
   that the ray in [s] (sheared) meets with [t_min < t < t_max], or
   [last]: [triangle_blocks]'s test, the axes [kx, ky, kz] constants as in
   [leaf_closest]. The light's last blocker, already tried and found not
   to block ([blocked_from]), is not skipped: the same test of the same
   ray gives the same answer again, and a compare per triangle costs more
   than the one test it would save. *)
let[@inline] leaf_blocker tr s first last kx ky kz =
  let p = tr.p in
  let g = p.vertex and at0 = p.at0 and at1 = p.at1 and at2 = p.at2 in
  let i = ref first in
  while
    !i < last
    && not
         (Triangle.hit s g (Array.unsafe_get at0 !i) (Array.unsafe_get at1 !i) (Array.unsafe_get at2 !i) kx ky kz
         &&
         let t = s.near in
         s.t_min < t && t < s.t_max)
  do
    incr i
  done;
  !i

let[@inline] triangles_blocker tr s first last =
  match tr.order with
  | 0 -> leaf_blocker tr s first last 1 2 0
  | 1 -> leaf_blocker tr s first last 2 1 0
  | 2 -> leaf_blocker tr s first last 0 2 1
  | 3 -> leaf_blocker tr s first last 2 0 1
  | 4 -> leaf_blocker tr s first last 0 1 2
  | _ -> leaf_blocker tr s first last 1 0 2

(* {2 Instances}

   An instance's roots are the closest hit of its bottom level (its own
   prepared scene, traced by its own tracer [tr.inner]) for the ray
   carried into the object's frame: the origin by the world-to-object
   matrix, the direction by its linear part, not renormalised, so that
   the root [t] is the same number in both frames and the range
   [t_min, t_max] carries over unchanged. The closest search is defined
   below ([closest]); this reference to it is set once, when the module
   is initialised: a call through it allocates nothing. *)
let closest_ref : (Tracer.t -> int) ref = ref (fun _ -> -1)

(* Likewise the any-blocker search of a bottom level for shadow rays
   ([instance_roots]), defined below ([any_blocker]). *)
let blocker_ref : (Tracer.t -> bool) ref = ref (fun _ -> false)

(* Carries the ray in [s] into the frame of instance [n], in the per-ray
   record of its bottom level's tracer, which it returns. *)
let[@inline] carry tr s n =
  let inst = tr.p.instances in
  let sub = Array.unsafe_get tr.inner (Array.unsafe_get inst.bottom n) in
  let m = inst.to_object and o = 12 * n in
  let ss = sub.s in
  let x = s.ox and y = s.oy and z = s.oz and dx = s.dx and dy = s.dy and dz = s.dz in
  let a00 = Array.unsafe_get m o and a01 = Array.unsafe_get m (o + 1) and a02 = Array.unsafe_get m (o + 2) in
  let a10 = Array.unsafe_get m (o + 4) and a11 = Array.unsafe_get m (o + 5) and a12 = Array.unsafe_get m (o + 6) in
  let a20 = Array.unsafe_get m (o + 8) and a21 = Array.unsafe_get m (o + 9) and a22 = Array.unsafe_get m (o + 10) in
  ss.ox <- (a00 *. x) +. (a01 *. y) +. (a02 *. z) +. Array.unsafe_get m (o + 3);
  ss.oy <- (a10 *. x) +. (a11 *. y) +. (a12 *. z) +. Array.unsafe_get m (o + 7);
  ss.oz <- (a20 *. x) +. (a21 *. y) +. (a22 *. z) +. Array.unsafe_get m (o + 11);
  ss.dx <- (a00 *. dx) +. (a01 *. dy) +. (a02 *. dz);
  ss.dy <- (a10 *. dx) +. (a11 *. dy) +. (a12 *. dz);
  ss.dz <- (a20 *. dx) +. (a21 *. dy) +. (a22 *. dz);
  ss.t_min <- s.t_min;
  (* No hit beyond the best so far can be kept: the bottom level's search
     stops there (its boxes entered beyond it are skipped). A hit exactly
     there may still win a tie: the bound is above it, [t (1 + 2^-52)]
     rounded, at least the next float up for a normal [t > 0] (not
     [Float.succ]: a call to C's [nextafter] per instance test).
     Every closest search over shapes sets [s.t] to [infinity] before its
     first test, a shadow ray's to NaN ([shadow_search]): the bound is
     then [t_max]. *)
  ss.t_max <- (let t = s.t in let best = t +. (t *. epsilon_float) in if best < s.t_max then best else s.t_max);
  (* The bottom level's surfaces are left by no secondary ray of its own:
     the top level offsets an instance's hit point. *)
  sub.origin_sphere <- -1;
  sub

(* The instance in slot [i]: its closest hit in range in [s.near] and
   [s.far]; [false] if it has none. *)
let[@inline] instance_number tr i = truncate (Array.unsafe_get tr.p.geom (Kind.stride * Array.unsafe_get tr.p.at0 i))

(* Is the search in progress a shadow ray's ([blocked_from]), which
   asks for any blocker, not the closest hit? Its best hit so far is then
   NaN, not a number: there is none, and [carry]'s bound from it, [NaN <
   t_max], is false, so none. *)
let[@inline] shadow_search s = Float.is_nan s.t

let[@inline never] instance_roots tr s i =
  let sub = carry tr s (instance_number tr i) in
  if shadow_search s then
    (* A shadow ray's: any root in range will do, not the closest. *)
    !blocker_ref sub
    &&
    let t = sub.s.t in
    s.near <- t;
    s.far <- t;
    true
  else
    let j = !closest_ref sub in
    j >= 0
    &&
    let t = sub.s.t in
    s.near <- t;
    s.far <- t;
    (* Remembered for the normal ([instance_hit]). *)
    tr.inner_slot <- i;
    tr.inner_hit <- j;
    true

(* The roots of the shape (not a sphere) in slot [i], by its module's
   routine, in [s.near] and [s.far]; [false] if it misses. A CSG solid
   gives its first crossing beyond [s.t_min] as both. *)
let[@warning "-11"] shape_roots tr s i =
  let p = tr.p in
  match Array.unsafe_get p.kind i with
  | Triangle | Smooth_triangle ->
      shear_once tr s;
      Triangle.roots_at s p.vertex (Array.unsafe_get p.at0 i) (Array.unsafe_get p.at1 i) (Array.unsafe_get p.at2 i) tr.kx
        tr.ky tr.kz
  | Csg -> Csg.roots p.csg tr.csg s (truncate (Array.unsafe_get p.geom (Kind.stride * Array.unsafe_get p.at0 i)))
  | Sphere -> sphere_roots tr s i
  (* The first kinds' arms in this match's jump table, as [Kind_dispatch]
     has them: a second match per ray cost more than the gate allows.
     The catch-all sends a described kind to [Kind_dispatch]; it is
     unused until one is (warning 11 off). *)
  | Plane -> Plane.roots s p.geom (Kind.stride * Array.unsafe_get p.at0 i)
  | Box -> Box.roots s p.geom (Kind.stride * Array.unsafe_get p.at0 i)
  | Instance -> instance_roots tr s i
  | k -> Kind_dispatch.roots k s p.geom (Kind.stride * Array.unsafe_get p.at0 i)

(* Tests the ray in [s] against the shape (not a sphere) in slot [i],
   keeping the better hit. Secondary rays of the robust mode start off
   the surface they leave (see [trace]), so no shape is special here.
   Inlined by request: once a described kind exists, the catch-all of
   [shape_roots] is live, and this test grows past what OCaml inlines by
   itself into the loops; a call per shape test then cost the scenes of
   boxes and planes more than the gate allows (docs/performance.md,
   "Round 3: the first described kind"). *)
let[@inline] shape_test tr s i =
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
    | _ -> shape_test tr s i

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

(* The offsets in a node of the box's planes that a ray with slab
   inverses [ix, iy, iz] meets first: per axis, the lower corner's where
   the inverse is positive, the upper corner's where it is negative; the
   planes it meets last are the others ([far_x n = 3 - n], [far_y n =
   5 - n], [far_z n = 7 - n]). Chosen once a ray: [(b - o) * inv] is
   monotone in [b], rounding included, so the near plane's is the smaller
   of the two products, as a compare per axis and box would find (equal
   products are the same number). An inverse is never 0 nor NaN
   ([slab_inverse]). *)
let[@inline] near_x ix = if ix >= 0. then 0 else 3
let[@inline] near_y iy = if iy >= 0. then 1 else 4
let[@inline] near_z iz = if iz >= 0. then 2 else 5

(* The ray's entry into the box of the node at offset [o] of [nodes]: the
   largest of its three slabs' near distances ([nx], [ny], [nz] from
   [near_x] ...), with origin [ox, oy, oz] and slab inverses [ix, iy,
   iz]. *)
let[@inline] box_enter (nodes : float array) o nx ny nz ox oy oz ix iy iz =
  let enter_x = (Array.unsafe_get nodes (o + nx) -. ox) *. ix in
  let enter_y = (Array.unsafe_get nodes (o + ny) -. oy) *. iy in
  let enter_z = (Array.unsafe_get nodes (o + nz) -. oz) *. iz in
  let enter = if enter_x > enter_y then enter_x else enter_y in
  if enter > enter_z then enter else enter_z

(* Its exit: the smallest of the far distances. *)
let[@inline] box_exit (nodes : float array) o nx ny nz ox oy oz ix iy iz =
  let exit_x = (Array.unsafe_get nodes (o + 3 - nx) -. ox) *. ix in
  let exit_y = (Array.unsafe_get nodes (o + 5 - ny) -. oy) *. iy in
  let exit_z = (Array.unsafe_get nodes (o + 7 - nz) -. oz) *. iz in
  let exit = if exit_x < exit_y then exit_x else exit_y in
  if exit < exit_z then exit else exit_z

(* The children of the inner node at offset [o] of [nodes] whose boxes
   the ray meets in [t_min, limit], pushed on [stack] (their entries
   beside, in [entries]) above [sp]; the new stack pointer. With
   [by_entry], the nearer by its entry on top (the left one on a tie);
   otherwise the farther along the split axis ([tag], the node's
   [node_tag], which the caller has read: -1, -2, -3 for x, y, z) on top,
   by the sign of the direction's coordinate on it ([dx, dy, dz]), as
   shadow rays search:
   from the light's end back toward the ray's origin, which lies on a
   surface among leaves that seldom block it (docs/performance.md, "Issue
   28, round 3: the walk", shadow rays).
   The left child follows its parent (8 floats on), the right one is at
   its link. The near planes [nx, ny, nz] are constants in each of
   [visit_children]'s copies: a plane is then one load at a fixed
   displacement from the node's offset. *)
let[@inline] push_met (nodes : float array) stack entries sp o ~tag ~by_entry dx dy dz ox oy oz ix iy iz t_min limit nx ny nz =
  let left = o + 8 and right = node_link nodes o in
  let l_enter = box_enter nodes left nx ny nz ox oy oz ix iy iz in
  let l_exit = box_exit nodes left nx ny nz ox oy oz ix iy iz in
  let r_enter = box_enter nodes right nx ny nz ox oy oz ix iy iz in
  let r_exit = box_exit nodes right nx ny nz ox oy oz ix iy iz in
  if l_enter <= l_exit && l_exit >= t_min && l_enter <= limit then begin
    if r_enter <= r_exit && r_exit >= t_min && r_enter <= limit then begin
      let right_first =
        if by_entry then r_enter < l_enter
        else
          let d = if tag = -1 then dx else if tag = -2 then dy else dz in
          (* The farther on top. *)
          d >= 0.
      in
      if right_first then begin
        Array.unsafe_set stack sp left;
        Array.unsafe_set stack (sp + 1) right;
        if by_entry then begin
          Array.unsafe_set entries sp l_enter;
          Array.unsafe_set entries (sp + 1) r_enter
        end
      end
      else begin
        Array.unsafe_set stack sp right;
        Array.unsafe_set stack (sp + 1) left;
        if by_entry then begin
          Array.unsafe_set entries sp r_enter;
          Array.unsafe_set entries (sp + 1) l_enter
        end
      end;
      sp + 2
    end
    else begin
      Array.unsafe_set stack sp left;
      if by_entry then Array.unsafe_set entries sp l_enter;
      sp + 1
    end
  end
  else if r_enter <= r_exit && r_exit >= t_min && r_enter <= limit then begin
    Array.unsafe_set stack sp right;
    if by_entry then Array.unsafe_set entries sp r_enter;
    sp + 1
  end
  else sp

(* [push_met] in the ray's octant, [octant ix iy iz]: one copy per
   octant, its near planes constants. The octant is the same at every
   node of a ray: its branch is predicted. *)
let[@inline] octant ix iy iz = (if ix >= 0. then 0 else 1) + (if iy >= 0. then 0 else 2) + if iz >= 0. then 0 else 4

let[@inline] visit_children nodes stack entries sp o ~tag ~by_entry dx dy dz ox oy oz ix iy iz t_min limit oct =
  match oct with
  | 0 -> push_met nodes stack entries sp o ~tag ~by_entry dx dy dz ox oy oz ix iy iz t_min limit 0 1 2
  | 1 -> push_met nodes stack entries sp o ~tag ~by_entry dx dy dz ox oy oz ix iy iz t_min limit 3 1 2
  | 2 -> push_met nodes stack entries sp o ~tag ~by_entry dx dy dz ox oy oz ix iy iz t_min limit 0 4 2
  | 3 -> push_met nodes stack entries sp o ~tag ~by_entry dx dy dz ox oy oz ix iy iz t_min limit 3 4 2
  | 4 -> push_met nodes stack entries sp o ~tag ~by_entry dx dy dz ox oy oz ix iy iz t_min limit 0 1 5
  | 5 -> push_met nodes stack entries sp o ~tag ~by_entry dx dy dz ox oy oz ix iy iz t_min limit 3 1 5
  | 6 -> push_met nodes stack entries sp o ~tag ~by_entry dx dy dz ox oy oz ix iy iz t_min limit 0 4 5
  | _ -> push_met nodes stack entries sp o ~tag ~by_entry dx dy dz ox oy oz ix iy iz t_min limit 3 4 5

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
          let nx = near_x ix and ny = near_y iy and nz = near_z iz and oct = octant ix iy iz in
          (* A hierarchy of triangles: the ray's shear once, here, rather
             than a check of [tr.kz] at every triangle. *)
          if triangles then shear_once tr s;
          let nodes = b.nodes and stack = tr.nodes and entries = tr.entries and sp = ref 0 in
          let ox = s.ox and oy = s.oy and oz = s.oz and t_min = s.t_min in
          (* Counted here, added to the counters once a ray. *)
          let boxes = ref 1 and tests = ref 0 in
          (* A node is pushed only if the ray meets its box, with its entry
             distance, tested by its parent (the root here): both children's
             boxes are read together, and the nearer child is visited
             first. A box entered beyond the best hit so far cannot hold a
             better one (its objects' hit points lie inside it, rounding
             included); one entered exactly there may hold an equal one:
             the entry is checked again when the node is popped, against
             the best hit then. The same boxes are entered as by a test at
             the pop (the range only shrinks). *)
          let root = b.root in
          let enter = box_enter nodes root nx ny nz ox oy oz ix iy iz in
          let exit = box_exit nodes root nx ny nz ox oy oz ix iy iz in
          if enter <= exit && exit >= t_min && enter <= s.t_max then begin
            Array.unsafe_set stack 0 root;
            Array.unsafe_set entries 0 enter;
            sp := 1
          end;
          (* The best hit's bound, [min t t_max], read again after a leaf
             only: nothing else lowers [s.t]. *)
          let limit = ref (if s.t < s.t_max then s.t else s.t_max) in
          while !sp > 0 do
            decr sp;
            let o = Array.unsafe_get stack !sp in
            if Array.unsafe_get entries !sp <= !limit then begin
              let count = node_tag nodes o in
              if count > 0 then begin
                let first = node_link nodes o in
                tests := !tests + count;
                (if triangles then triangles_closest tr s first (first + count - 1)
                 else
                   for i = first to first + count - 1 do
                     test tr s i ~primary ~spheres ~triangles dx dy dz a inv_a two_k1 k1x4
                   done);
                limit := if s.t < s.t_max then s.t else s.t_max
              end
              else begin
                boxes := !boxes + 2;
                sp := visit_children nodes stack entries !sp o ~tag:0 ~by_entry:true dx dy dz ox oy oz ix iy iz t_min !limit oct
              end
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
let () = closest_ref := fun tr -> closest tr

(* The bottom level's hit is the one [instance_roots] remembered when
   slot [i] is the last instance that found one: the closest search that
   kept slot [i] tested it and found its hit ([tr.inner_slot <- i]);
   where a later instance's hit overwrote the record without being kept
   (a tie lost by scene order), the record names another slot, and the
   bottom level is walked again, bounded by the hit kept. Nothing runs
   an instance's closest search between a top-level search and its
   normal. The remembered hit is the walk's: the same ray carried the
   same way, and its [t] is the [s.t] the top level kept. *)
let instance_hit tr i =
  let sub = carry tr tr.s (instance_number tr i) in
  if tr.inner_slot = i then begin
    sub.hit <- tr.inner_hit;
    sub.s.t <- tr.s.t
  end
  else ignore (closest sub);
  sub

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
    | _ -> shape_blocks tr i

(* The first blocker of the ray in [s] other than slot [skip], or [-1].
   (The leaves of triangles test [skip] too: it is the light's last
   blocker, which [blocked_from] has found not to block this ray.) *)
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
      let nx = near_x ix and ny = near_y iy and nz = near_z iz and oct = octant ix iy iz in
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
      (* As in [closest_from], a node is pushed only if the ray meets its
         box, tested by its parent (the root here). Any blocker answers:
         the farther child along the split axis is visited first, the
         ray's origin is on a surface whose nearby leaves the ray meets but
         seldom blocks (the 1M knot's blocked shadow rays test 151
         triangles, not 265 nearer first). *)
      let ox = s.ox and oy = s.oy and oz = s.oz and t_min = s.t_min and t_max = s.t_max in
      if !sp > 0 then begin
        let root = b.root in
        incr boxes;
        let enter = box_enter nodes root nx ny nz ox oy oz ix iy iz in
        let exit = box_exit nodes root nx ny nz ox oy oz ix iy iz in
        if enter <= exit && exit >= t_min && enter <= t_max then Array.unsafe_set stack 0 root else sp := 0
      end;
      while !sp > 0 do
        decr sp;
        let o = Array.unsafe_get stack !sp in
        let count = node_tag nodes o in
        if count > 0 then begin
          let first = node_link nodes o in
          let last = first + count in
          let i =
            if triangles then triangles_blocker tr s first last
            else begin
              let i = ref first in
              while !i < last && (!i = skip || not (blocks tr !i ~spheres ~triangles a inv_a)) do
                incr i
              done;
              !i
            end
          in
          tests := !tests + count;
          if i < last then begin
            found := i;
            sp := 0
          end
        end
        else begin
          boxes := !boxes + 2;
          sp := visit_children nodes stack tr.entries !sp o ~tag:count ~by_entry:false dx dy dz ox oy oz ix iy iz t_min t_max oct
        end
      done;
      tr.counters.box_tests <- tr.counters.box_tests + !boxes;
      tr.counters.tests <- tr.counters.tests + !tests;
      !found

(* Whether any object of [tr]'s scene blocks the ray in [tr.s] (an
   instance's bottom level, the ray carried there by [instance_roots] for
   a shadow ray), its root in range then left in [s.t]:
   [first_blocker_from] with no last blocker to try first (a bottom level
   has no lights of its own: the light's last blocker is the top level's
   instance), then the blocker's roots again, for the one in range. The
   same roots as [closest], so the same answer as a closest search of the
   bottom level gives. *)
let any_blocker tr =
  let s = tr.s in
  let dx = s.dx and dy = s.dy and dz = s.dz in
  let a = (dx *. dx) +. (dy *. dy) +. (dz *. dz) in
  let inv_a = 1. /. a in
  let j =
    if tr.p.all_spheres then first_blocker_from tr ~spheres:true ~triangles:false (-1) a inv_a
    else begin
      tr.kz <- -1;
      (* A shadow ray's search ([shadow_search]): a nested instance
         answers as this one. *)
      s.t <- nan;
      if tr.triangles then first_blocker_from tr ~spheres:false ~triangles:true (-1) a inv_a
      else first_blocker_from tr ~spheres:false ~triangles:false (-1) a inv_a
    end
  in
  j >= 0
  && begin
       if Array.unsafe_get tr.p.kind j = Kind.Sphere then ignore (sphere_roots tr s j) else ignore (shape_roots tr s j);
       s.t <- (if s.t_min < s.near && s.near < s.t_max then s.near else s.far);
       true
     end

let () = blocker_ref := any_blocker

(* With skips and a hierarchy or the robust roots: light [l]'s last
   blocker first, then the first blocker of the others. One copy per kind
   of scene, so that spheres alone ask the kind once per shadow ray. *)
let[@inline] blocked_from tr l ~spheres ~triangles =
  let s = tr.s in
  if not spheres then begin
    tr.kz <- -1;
    (* No best hit, and a shadow ray's search ([shadow_search]): an
       instance's stops at its first blocker, bounded by none
       ([carry]). *)
    s.t <- nan
  end;
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
  else if p.all_spheres then blocked_from tr l ~spheres:true ~triangles:false
  else blocked_objects tr l

(* CGFS's subsampling: when [tr.assumed] names a sphere, the primary ray is
   tested against it alone (against none for [-1]); a ray that misses the
   assumed sphere falls back to the full search. Approximate: a sphere in
   front of the assumed one is not seen. *)
let[@inline] primary_hit_in tr ~spheres =
  let k = tr.assumed in
  if k = no_assumption then closest_primary_in tr ~spheres
  else if k = lens_rays then closest_in tr ~spheres
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
    s.t <- infinity;
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

