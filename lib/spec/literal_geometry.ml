(* The oracle's geometry, from the definitions. Nothing here calls a
   kernel routine: only the scene types' data, Vec3 and Exact_float. *)

let u = epsilon_float /. 2.

(* {1 Exact signs and crossing parameters} *)

(* Below this a float filter's bound may have underflowed: decide exactly. *)
let tiny = 1e-280

(* Decisions the float filter left to exact arithmetic: ties (exactly on
   a boundary) and near ones (within rounding of a boundary, off it). *)
let near_count = ref 0
let tie_count = ref 0
let undecided () = (!near_count, !tie_count)

(* [tie]: whether a zero is a tie that depends on the line's origin (a
   line through a triangle's edge), not a parallel, which the direction
   alone decides. *)
let exactly ?(tie = false) sign =
  if sign <> 0 then incr near_count else if tie then incr tie_count;
  sign

(* [if |approx| > bound then its sign else the exact one]: the filter of
   Shewchuk's adaptive predicates. *)
let filtered approx bound exact =
  if approx > bound && bound > tiny then 1 else if approx < -.bound && bound > tiny then -1 else exactly (Exact_float.sign (exact ()))

let ediff (p : Vec3.t) (o : Vec3.t) = Exact_float.(diff p.x o.x, diff p.y o.y, diff p.z o.z)

let ecross (ax, ay, az) (bx, by, bz) =
  Exact_float.(sub (mul ay bz) (mul az by), sub (mul az bx) (mul ax bz), sub (mul ax by) (mul ay bx))

let edot (ax, ay, az) (bx, by, bz) = Exact_float.(add (mul ax bx) (add (mul ay by) (mul az bz)))
let evec (d : Vec3.t) = Exact_float.(of_float d.x, of_float d.y, of_float d.z)
let abs_cross (a : Vec3.t) (b : Vec3.t) =
  Vec3.v
    (Float.abs (a.y *. b.z) +. Float.abs (a.z *. b.y))
    (Float.abs (a.z *. b.x) +. Float.abs (a.x *. b.z))
    (Float.abs (a.x *. b.y) +. Float.abs (a.y *. b.x))
let abs_dot (a : Vec3.t) (b : Vec3.t) = (Float.abs a.x *. b.x) +. (Float.abs a.y *. b.y) +. (Float.abs a.z *. b.z)

(* The sign of det[p - o, q - o, d] = <d, (p - o) x (q - o)>: which side
   of the plane through o, p and o + d the point q lies. The float value's
   error is below 7u of the sum of its terms' magnitudes (Shewchuk's
   orient3d bound; here one column is exact): 64u is a wide margin. *)
let orient ~(o : Vec3.t) ~(d : Vec3.t) (p : Vec3.t) (q : Vec3.t) =
  (* Written out on floats: a mesh's every triangle asks it four times per
     ray, and the filter nearly always decides. *)
  let ax = p.x -. o.x and ay = p.y -. o.y and az = p.z -. o.z in
  let bx = q.x -. o.x and by = q.y -. o.y and bz = q.z -. o.z in
  let cx = (ay *. bz) -. (az *. by) and cy = (az *. bx) -. (ax *. bz) and cz = (ax *. by) -. (ay *. bx) in
  let v = (d.x *. cx) +. (d.y *. cy) +. (d.z *. cz) in
  let m =
    (Float.abs d.x *. (Float.abs (ay *. bz) +. Float.abs (az *. by)))
    +. (Float.abs d.y *. (Float.abs (az *. bx) +. Float.abs (ax *. bz)))
    +. (Float.abs d.z *. (Float.abs (ax *. by) +. Float.abs (ay *. bx)))
  in
  let bound = 64. *. u *. m in
  if v > bound && bound > tiny then 1
  else if v < -.bound && bound > tiny then -1
  else exactly (Exact_float.sign (edot (evec d) (ecross (ediff p o) (ediff q o))))

(* The sign of component [k] of (q - p) x d. *)
let cross_component k ~(d : Vec3.t) (p : Vec3.t) (q : Vec3.t) =
  let w = Vec3.sub q p in
  let c = Vec3.cross w d and m = abs_cross w (Vec3.v (Float.abs d.x) (Float.abs d.y) (Float.abs d.z)) in
  let pick (v : Vec3.t) = if k = 0 then v.x else if k = 1 then v.y else v.z in
  filtered (pick c) (16. *. u *. pick m) (fun () ->
      let x, y, z = ecross (ediff q p) (evec d) in
      if k = 0 then x else if k = 1 then y else z)

type key = { t : float; lo : float; hi : float; num : Exact_float.t Lazy.t; den : Exact_float.t Lazy.t }

let key_of_float x = { t = x; lo = x; hi = x; num = lazy (Exact_float.of_float x); den = lazy (Exact_float.of_float 1.) }

(* Keys compare by their enclosures, and exactly where those overlap. *)
let compare_keys a b =
  if a.hi < b.lo then -1
  else if b.hi < a.lo then 1
  else if a == b then 0
  else if a.lo = a.hi && b.lo = b.hi then (* Two floats ([key_of_float]'s): exact. *) Float.compare a.t b.t
  else
    (* An exact tie of two parameters is not counted: CSG operands that
       share a face, coinciding surfaces and a line through a box's edge
       tie wherever the line's origin is, as the kernel must see them. *)
    exactly (Exact_float.compare_fractions (Lazy.force a.num) (Lazy.force a.den) (Lazy.force b.num) (Lazy.force b.den))

(* The document's range is strict, [t_min < t < t_max]. Its lower end
   is decided on the exact parameter: a plane met at exactly [t = 1] is
   not seen by the camera, though its rounded parameter may be
   [1 + ulp]. A ray continued from a hit ([continued], its [t_min] that
   hit's rounded parameter) must also pass it when rounded, or it would
   meet that surface there again: its exact parameter may lie above its
   rounding. The upper end, a light's [t = 1] for a shadow ray, is on the
   rounded parameter: the ray's direction [L - P] is rounded, so a
   surface through the light is met an ulp before or after [t = 1] by
   that rounding, not by the scene, and the document compares the
   computed [t]. *)
let above ~continued t_min k = compare_keys (key_of_float t_min) k < 0 && ((not continued) || t_min < k.t)
let below t_max k =
  (* Within its enclosure of [t_max], each formula's rounding decides (a
     plane through a point light, met at its [t = 1]). *)
  if k.lo < k.hi && k.lo <= t_max && t_max <= k.hi then incr near_count;
  k.t < t_max
let in_range ~continued ~t_min ~t_max k = above ~continued t_min k && below t_max k

(* (p - o) / d for floats, d <> 0: rounded twice, within 2u of |t|. *)
let ratio_key p o d =
  let t = (p -. o) /. d in
  let e = (4. *. u *. Float.abs t) +. (4. *. Float.min_float) in
  { t; lo = Float.pred (t -. e); hi = Float.succ (t +. e); num = lazy (Exact_float.diff p o); den = lazy (Exact_float.of_float d) }

(* {1 Spheres} *)

let sphere_textbook_roots (s : Sphere.t) ~origin ~direction =
  let co = Vec3.sub origin s.center in
  let a = Vec3.dot direction direction in
  let b = 2. *. Vec3.dot co direction in
  let c = Vec3.dot co co -. (s.radius *. s.radius) in
  let discriminant = (b *. b) -. (4. *. a *. c) in
  if discriminant < 0. then (infinity, infinity)
  else
    let sq = sqrt discriminant in
    ((-.b +. sq) /. (2. *. a), (-.b -. sq) /. (2. *. a))

let sphere_roots (s : Sphere.t) ~origin ~direction:d =
  let f = Vec3.sub origin s.center in
  let a = Vec3.dot d d and h = Vec3.dot f d in
  (* The discriminant h^2 - a c is a (r^2 - |l|^2), l the vector from the
     center to the line: no difference of large squares. *)
  let l = Vec3.sub f (Vec3.smul (h /. a) d) in
  let ll = Vec3.norm l and r = s.radius in
  if ll > r then None
  else
    let q = -.(h +. Float.copy_sign (sqrt (a *. ((r -. ll) *. (r +. ll)))) h) in
    if q = 0. then Some (0., 0.)
    else
      (* The root of like signs is q / a; the other c / q, not a
         difference of nearly equal numbers. *)
      let t0 = (Vec3.dot f f -. (r *. r)) /. q and t1 = q /. a in
      Some (Float.min t0 t1, Float.max t0 t1)

let sphere_normal (s : Sphere.t) p =
  let n = Vec3.sub p s.center in
  Vec3.smul (1. /. Vec3.norm n) n

(* {1 Planes} *)

(* [num / den] with [num] and [den] rounded within [en] and [ed]: an
   enclosure of the exact quotient, or none where [den] may be 0. *)
let enclosure t ~den ~en ~ed =
  if Float.abs den > 2. *. ed && Float.is_finite t then
    let e = 2. *. (((en +. (Float.abs t *. (1. +. u) *. ed)) /. (Float.abs den -. ed)) +. (u *. Float.abs t)) in
    (Float.pred (t -. e), Float.succ (t +. e))
  else (neg_infinity, infinity)

(* t = <P0 - O, n> / <D, n>, exactly for the given normal; in floats with
   the unit normal. *)
let plane_key (p : Plane.t) ~origin ~direction =
  let n_exact = evec p.normal in
  let den_exact = edot (evec direction) n_exact in
  if Exact_float.sign den_exact = 0 then None
  else
    let n = Vec3.unit p.normal and f = Vec3.sub p.point origin in
    let num = Vec3.dot f n and den = Vec3.dot direction n in
    let abs_n = Vec3.v (Float.abs n.x) (Float.abs n.y) (Float.abs n.z) in
    let ed = 16. *. u *. abs_dot direction abs_n in
    let num_exact = lazy (edot (ediff p.point origin) n_exact) in
    if Float.abs den > 2. *. ed then
      let t = num /. den in
      if not (Float.is_finite t) then None
      else
        let lo, hi = enclosure t ~den ~en:(16. *. u *. abs_dot f abs_n) ~ed in
        Some { t; lo; hi; num = num_exact; den = lazy den_exact }
    else
      (* The ray is within rounding of parallel, not parallel: the plane is
         met far away, where rounding decides whether a float computation
         finds it at all (its denominator may round to 0) and where. The
         parameter from the exact values, within 5u; a near decision. *)
      let t = Exact_float.approx (Lazy.force num_exact) /. Exact_float.approx den_exact in
      if not (Float.is_finite t) then None
      else begin
        incr near_count;
        let e = 5. *. u *. Float.abs t in
        Some { t; lo = Float.pred (t -. e); hi = Float.succ (t +. e); num = num_exact; den = lazy den_exact }
      end

let plane_normal (p : Plane.t) = Vec3.unit p.normal

(* {1 Triangles} *)

(* How far the kernel's origin of the ray being traced may lie from the
   oracle's, per coordinate: 0 for a camera ray (the camera's own value);
   for a ray from a hit point, which each side computes from its own
   rounded parameter, set by [Literal] while it traces such a ray. *)
let origin_slack = ref 0.

let from_origin ~computed (origin : Vec3.t) f =
  let before = !origin_slack in
  origin_slack :=
    if computed then 64. *. u *. Float.max (Float.abs origin.x) (Float.max (Float.abs origin.y) (Float.abs origin.z)) else 0.;
  Fun.protect ~finally:(fun () -> origin_slack := before) f

(* An edge function of the line's origin within [origin_slack] of 0 is
   rounding's: the kernel's origin may lie on the edge's other side. The
   origin moved by [w] changes det[p - o, q - o, d] by <d, w x (p - q)>. *)
let near_for_origin ~(o : Vec3.t) ~(d : Vec3.t) (p : Vec3.t) (q : Vec3.t) =
  if !origin_slack > 0. then begin
    let ax = p.x -. o.x and ay = p.y -. o.y and az = p.z -. o.z in
    let bx = q.x -. o.x and by = q.y -. o.y and bz = q.z -. o.z in
    let v = (d.x *. ((ay *. bz) -. (az *. by))) +. (d.y *. ((az *. bx) -. (ax *. bz))) +. (d.z *. ((ax *. by) -. (ay *. bx))) in
    let dn = Float.abs d.x +. Float.abs d.y +. Float.abs d.z
    and pq = Float.abs (p.x -. q.x) +. Float.abs (p.y -. q.y) +. Float.abs (p.z -. q.z) in
    if Float.abs v <= 2. *. !origin_slack *. dn *. pq then incr near_count
  end

let edge_signs ~origin ~direction a b c =
  let s = orient ~o:a ~d:direction b c in
  let e0 = orient ~o:origin ~d:direction b c and e1 = orient ~o:origin ~d:direction c a and e2 = orient ~o:origin ~d:direction a b in
  if s <> 0 then begin
    near_for_origin ~o:origin ~d:direction b c;
    near_for_origin ~o:origin ~d:direction c a;
    near_for_origin ~o:origin ~d:direction a b
  end;
  (* A zero edge function is a tie with the line's origin, unless the edge
     is parallel to the line, which makes it zero wherever the origin is. *)
  let through p q e =
    e = 0
    &&
    let x, y, z = ecross (ediff q p) (evec direction) in
    Exact_float.(sign x <> 0 || sign y <> 0 || sign z <> 0)
  in
  (* Nor where the origin lies in the triangle's plane: the line leaves
     the triangle there, at [t = 0], out of every ray's range. *)
  if
    s <> 0
    && (through b c e0 || through c a e1 || through a b e2)
    && Exact_float.sign (edot (ecross (ediff b a) (ediff c a)) (ediff origin a)) <> 0
  then ignore (exactly ~tie:true 0);
  (s, e0, e1, e2)

(* The plane's parameter of the line, in floats, with an enclosure of the
   exact one and the exact numerator and denominator:
   t = <A - O, n> / <D, n>, n = (B - A) x (C - A). *)
let triangle_key ~origin ~direction a b c =
  let e1 = Vec3.sub b a and e2 = Vec3.sub c a and f = Vec3.sub a origin in
  let n = Vec3.cross e1 e2 and big = abs_cross e1 e2 in
  let num = Vec3.dot f n and den = Vec3.dot direction n in
  let en = 16. *. u *. abs_dot f big and ed = 16. *. u *. abs_dot direction big in
  let t = num /. den in
  let lo, hi = enclosure t ~den ~en ~ed in
  let n_exact = lazy (ecross (ediff b a) (ediff c a)) in
  {
    t;
    lo;
    hi;
    num = lazy (edot (ediff a origin) (Lazy.force n_exact));
    den = lazy (edot (evec direction) (Lazy.force n_exact));
  }

(* The closed triangle: a line through an edge or a vertex meets it. *)
let triangle_hit ~origin ~direction a b c =
  let s, e0, e1, e2 = edge_signs ~origin ~direction a b c in
  let on_side e = e = 0 || e = s in
  if s <> 0 && on_side e0 && on_side e1 && on_side e2 then
    let k = triangle_key ~origin ~direction a b c in
    if Float.is_finite k.t then Some k else None
  else None

let triangle_root ~origin ~direction a b c =
  match triangle_hit ~origin ~direction a b c with Some k -> k.t | None -> infinity

let largest_axis (d : Vec3.t) =
  let ax = Float.abs d.x and ay = Float.abs d.y and az = Float.abs d.z in
  if ax >= ay && ax >= az then 0 else if ay >= az then 1 else 2

(* The sign of the edge function of p -> q for the line moved by
   e d1 + e^2 d2 (e infinitesimal, d1 and d2 the axes after the largest of
   D): det[p - o', q - o', D] = E - e (w x D)_k1 - e^2 (w x D)_k2, w = q - p. *)
let perturbed_sign ~origin ~direction ~k1 ~k2 p q =
  match orient ~o:origin ~d:direction p q with
  | 0 -> (
      ignore (exactly ~tie:true 0);
      match cross_component k1 ~d:direction p q with
      | 0 -> -cross_component k2 ~d:direction p q
      | c -> -c)
  | e -> e

let triangle_crossing ~origin ~direction a b c =
  let s = orient ~o:a ~d:direction b c in
  s <> 0
  &&
  let kz = largest_axis direction in
  let k1 = (kz + 1) mod 3 and k2 = (kz + 2) mod 3 in
  let side p q = perturbed_sign ~origin ~direction ~k1 ~k2 p q = s in
  near_for_origin ~o:origin ~d:direction b c;
  near_for_origin ~o:origin ~d:direction c a;
  near_for_origin ~o:origin ~d:direction a b;
  side b c && side c a && side a b

let triangle_normal a b c = Vec3.unit (Vec3.cross (Vec3.sub b a) (Vec3.sub c a))

(* Barycentric coordinates as ratios of signed areas, <n, (B - P) x (C - P)> / <n, n>
   for A's, and so on around. *)
let smooth_normal a b c (na, nb, nc) p =
  let n = Vec3.cross (Vec3.sub b a) (Vec3.sub c a) in
  let nn = Vec3.dot n n in
  let area x y = Vec3.dot n (Vec3.cross (Vec3.sub x p) (Vec3.sub y p)) /. nn in
  let wa = area b c and wb = area c a and wc = area a b in
  let s = Vec3.add (Vec3.smul wa na) (Vec3.add (Vec3.smul wb nb) (Vec3.smul wc nc)) in
  let l = Vec3.norm s in
  if l > 0. && l < infinity then Some (Vec3.smul (1. /. l) s) else None

(* {1 Boxes} *)

type box_hit = { enter : key; enter_normal : Vec3.t; exit : key; exit_normal : Vec3.t }

let axis_vector k x = if k = 0 then Vec3.v x 0. 0. else if k = 1 then Vec3.v 0. x 0. else Vec3.v 0. 0. x

(* The closed box is where each coordinate is within its slab: the line
   meets it iff the largest entry parameter is at most the smallest exit
   one, compared exactly. The face entered (left) is that of the axis whose
   entry (exit) decides, the first axis on a tie. *)
let box_hit (b : Box.t) ~(origin : Vec3.t) ~(direction : Vec3.t) =
  let coord (v : Vec3.t) k = if k = 0 then v.x else if k = 1 then v.y else v.z in
  let rec go k enter exit =
    if k = 3 then
      match (enter, exit) with
      | Some (enter, kn), Some (exit, kx) when compare_keys enter exit <= 0 ->
          let sd k = Float.copy_sign 1. (coord direction k) in
          Some { enter; enter_normal = axis_vector kn (-.sd kn); exit; exit_normal = axis_vector kx (sd kx) }
      | _ -> None
    else
      let lo = coord b.min k and hi = coord b.max k and o = coord origin k and d = coord direction k in
      if d = 0. then if lo <= o && o <= hi then go (k + 1) enter exit else None
      else
        let near = ratio_key (if d > 0. then lo else hi) o d and far = ratio_key (if d > 0. then hi else lo) o d in
        let enter = match enter with Some (e, _) when compare_keys e near >= 0 -> enter | _ -> Some (near, k) in
        let exit = match exit with Some (e, _) when compare_keys e far <= 0 -> exit | _ -> Some (far, k) in
        go (k + 1) enter exit
  in
  go 0 None None

(* {1 Constructive solid geometry} *)

type surface = Round of Sphere.t | Flat of Vec3.t | Facet of Vec3.t * Vec3.t * Vec3.t

type crossing = { key : key; leaf : int; surface : surface }

(* A leaf along the whole line: an interval of positive length, or a
   closed mesh's crossings in order. *)
type leaf_line = Interval of key * key | Crossings of key list

(* Each leaf as it shows: wrapped in an identity placement with the
   material that covers it, if that is not its own. *)
let shown (l, m, _) = if m == Csg.leaf_material l then l else Csg.placed ~material:m Transform.identity l

let leaves (c : Csg.t) = List.map shown (Csg.leaves c)

let mesh_crossings ~tested (m : Mesh.t) ~origin ~direction i =
  List.filter_map
    (fun k ->
      tested 1;
      let a = Mesh.vertex m k 0 and b = Mesh.vertex m k 1 and c = Mesh.vertex m k 2 in
      if triangle_crossing ~origin ~direction a b c then
        let key = triangle_key ~origin ~direction a b c in
        Some { key; leaf = i; surface = Facet (a, b, c) }
      else None)
    (List.init (Mesh.triangle_count m) Fun.id)

let leaf_crossings ~tested ~origin ~direction i = function
  | Csg.Sphere s -> (
      tested 1;
      match sphere_roots s ~origin ~direction with
      | Some (t0, t1) when t0 < t1 ->
          let a = key_of_float t0 and b = key_of_float t1 in
          (Interval (a, b), [ { key = a; leaf = i; surface = Round s }; { key = b; leaf = i; surface = Round s } ])
      | _ -> (Crossings [], []))
  | Csg.Box b -> (
      tested 1;
      match box_hit b ~origin ~direction with
      | Some h when compare_keys h.enter h.exit < 0 ->
          ( Interval (h.enter, h.exit),
            [ { key = h.enter; leaf = i; surface = Flat h.enter_normal }; { key = h.exit; leaf = i; surface = Flat h.exit_normal } ] )
      | _ -> (Crossings [], []))
  | Csg.Primitive p -> (
      tested 1;
      match Shape_desc.literal p ~origin ~direction with
      | [ (t0, n0); (t1, n1) ] when t0 < t1 ->
          let a = key_of_float t0 and b = key_of_float t1 in
          (Interval (a, b), [ { key = a; leaf = i; surface = Flat n0 }; { key = b; leaf = i; surface = Flat n1 } ])
      | xs when List.length xs > 2 ->
          (* A kind met in several intervals (a torus): inside after an
             odd number of crossings, as a mesh. *)
          let xs = List.map (fun (t, n) -> { key = key_of_float t; leaf = i; surface = Flat n }) xs in
          (Crossings (List.map (fun (x : crossing) -> x.key) xs), xs)
      | _ -> (Crossings [], []))
  | Csg.Mesh m ->
      let xs = List.stable_sort (fun x y -> compare_keys x.key y.key) (mesh_crossings ~tested m ~origin ~direction i) in
      (Crossings (List.map (fun x -> x.key) xs), xs)
  | Csg.Csg _ | Csg.Transformed _ -> invalid_arg "Literal_geometry: a CSG node is not a leaf"

(* Is the point of parameter [t] inside the leaf, just before [t] or just
   after it? An interval holds its ends' sides; a mesh, after an odd
   number of crossings. *)
let inside_leaf ~after t = function
  | Interval (a, b) ->
      if after then compare_keys a t <= 0 && compare_keys t b < 0 else compare_keys a t < 0 && compare_keys t b <= 0
  | Crossings xs ->
      let passed x = if after then compare_keys x t <= 0 else compare_keys x t < 0 in
      List.length (List.filter passed xs) mod 2 = 1

let rec inside lines ~after t next (s : Csg.solid) =
  match s with
  | Csg.Csg c -> (
      let a, next = inside lines ~after t next c.a in
      let b, next = inside lines ~after t next c.b in
      match c.op with
      | Union -> (a || b, next)
      | Intersection -> (a && b, next)
      | Difference -> (a && not b, next))
  | Csg.Transformed p -> inside lines ~after t next p.solid
  | _ -> (inside_leaf ~after t lines.(next), next + 1)

type csg_hit = { key : key; leaf : Csg.solid; normal : Vec3.t; entering : bool }

let csg_hit ?(continued = false) ~tested ~into ~out (c : Csg.t) ~origin ~direction ~t_min ~t_max =
  let placed = Array.of_list (Csg.leaves c) in
  let leaves = Array.map (fun (l, _, _) -> l) placed in
  (* Each leaf's line in its frame: the world's carried through the
     transforms around it, outermost first; [t] is the same number in
     every frame. *)
  let lines_in =
    Array.map (fun (_, _, frames) -> List.fold_left (fun (o, d) tr -> into tr o d) (origin, direction) (List.rev frames)) placed
  in
  let per_leaf =
    Array.mapi
      (fun i l ->
        let origin, direction = lines_in.(i) in
        leaf_crossings ~tested ~origin ~direction i l)
      leaves
  in
  let lines = Array.map fst per_leaf in
  let all =
    List.stable_sort (fun (x : crossing) (y : crossing) -> compare_keys x.key y.key) (List.concat_map snd (Array.to_list per_leaf))
  in
  let state ~after t = fst (inside lines ~after t 0 (Csg.Csg c)) in
  let boundary =
    List.find_opt
      (fun (x : crossing) ->
        above ~continued t_min x.key && state ~after:false x.key <> state ~after:true x.key)
      all
  in
  match boundary with
  | Some (x : crossing) when below t_max x.key ->
      let entering = state ~after:true x.key in
      let o, d = lines_in.(x.leaf) in
      let point = Vec3.add o (Vec3.smul x.key.t d) in
      let n =
        match x.surface with Round s -> sphere_normal s point | Flat n -> n | Facet (a, b, c) -> triangle_normal a b c
      in
      let _, _, frames = placed.(x.leaf) in
      let n = List.fold_left (fun n tr -> out tr n) n frames in
      (* Outward from the solid: against the ray where it enters. *)
      let n = if Vec3.dot n direction > 0. = entering then Vec3.neg n else n in
      Some { key = x.key; leaf = shown placed.(x.leaf); normal = n; entering }
  | _ -> None

(* {1 Patterns} *)

let odd (Pattern.Checker { size; _ }) ~frame:((o : Vec3.t), scale, extent) ~(origin : Vec3.t) ~direction ~(point : Vec3.t) ~normal =
  let l1 (v : Vec3.t) = Float.abs v.x +. Float.abs v.y +. Float.abs v.z in
  let e = 64. *. u *. (l1 origin +. l1 point +. extent) in
  let e = if Vec3.dot normal direction > 0. then -.e else e in
  let q = Vec3.add point (Vec3.smul e normal) in
  (* A cell boundary within rounding of the point (a quarter of the
     offset [e], a bound on the point's rounding): which side it lies on
     is the floats' choice, the kernel's and the oracle's each its own. *)
  let cell x o =
    let v = (x -. o) /. scale /. size in
    if Float.abs (v -. Float.round v) <= Float.abs e /. 4. /. scale /. size then
      incr near_count;
    Float.abs (Float.rem (Float.floor v) 2.)
  in
  let sum = cell q.x o.x +. cell q.y o.y +. cell q.z o.z in
  sum = 1. || sum = 3.

(* {1 Refraction} *)

let largest_coordinate (v : Vec3.t) = Float.max (Float.abs v.x) (Float.max (Float.abs v.y) (Float.abs v.z))

type split = { refracted : Vec3.t option; reflectance : float }

let split ~n1 ~n2 ~fresnel ~direction ~normal =
  if n1 = n2 then { refracted = Some direction; reflectance = 0. }
  else
    (* Scaled by its largest coordinate first: no square of a tiny or
       huge direction underflows or overflows. *)
    let big = largest_coordinate direction in
    let d = Vec3.unit (Vec3.v (direction.x /. big) (direction.y /. big) (direction.z /. big)) in
    let c = -.Vec3.dot d normal in
    let c = if c > 1. then 1. else if c > 0. then c else 0. in
    let eta = n1 /. n2 in
    (* Snell: sin t = eta sin i; sin^2 i = (1 - c)(1 + c) without cancellation. *)
    let sin2_t = eta *. eta *. ((1. -. c) *. (1. +. c)) in
    if sin2_t >= 1. then { refracted = None; reflectance = 1. }
    else
      let cos_t = sqrt (1. -. sin2_t) in
      let t = Vec3.add (Vec3.smul eta d) (Vec3.smul ((eta *. c) -. cos_t) normal) in
      let reflectance =
        if not fresnel then 0.
        else
          (* Schlick, with the cosine on the side of the lower index. *)
          let r0 = (n1 -. n2) /. (n1 +. n2) in
          let r0 = r0 *. r0 and x = 1. -. if n1 > n2 then cos_t else c in
          r0 +. ((1. -. r0) *. (x *. x *. x *. x *. x))
      in
      { refracted = Some t; reflectance }
