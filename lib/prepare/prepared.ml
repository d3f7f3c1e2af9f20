type t = {
  n_spheres : int;
  n_objects : int;
  all_spheres : bool;
  patterned : bool;
  alternate : int array;
  pattern : float array;
  textbook_all : bool;
  index : int array;
  slot : int array;
  bvh : Bvh.t option;
  unbounded : int array;
  kind : int array;
  geom : float array;
  vertex : float array;
  at0 : int array;
  at1 : int array;
  at2 : int array;
  vnormal : float array;
  vsource : int array;
  vcorner : int array;
  extent : float array;
  csg : Csg.table;
  n_scene_objects : int;
  material : int array;
  cx : float array;
  cy : float array;
  cz : float array;
  radius : float array;
  r2 : float array;
  red : float array;
  green : float array;
  blue : float array;
  specular : float array;
  specular_zero : float array;
  reflective : float array;
  n_lights : int;
  light_kind : int array;
  light_intensity : float array;
  lx : float array;
  ly : float array;
  lz : float array;
  robust : bool;
  epsilon : float;
  depth : int;
  width : int;
  height : int;
  viewport : Viewport.t;
  camera : Camera.t;
  identity_rotation : bool;
  background : Color.t;
  primary_ocx : float array;
  primary_ocy : float array;
  primary_ocz : float array;
  primary_k3 : float array;
  max_channel : float;
  early_stop : bool;
  skips : bool;
  transparency : float array;
  refractive_index : float array;
  fresnel : bool array;
  transparent : bool;
  behind : bool;
  shadow_skip : bool;
  cull : bool;
  specular_cut : float array;
  ambient_lead : float;
  first_light : int;
  sphere4 : float array;
  primary4 : float array;
  light6 : float array;
  column_vx : float array;
  row_vy : float array;
}

let bvh_threshold = 8

(* Above this many objects, preparing collects its garbage at two points
   (see [prepare]): each costs a marking of the live heap, 6% of the
   instructions of loading and preparing grid:100000, where it saves
   little. *)
let big_scene = 1 lsl 18
let ambient = 0
let point = 1
let directional = 2

(* The most [cos ** s] can be: 1 for an exact cosine, but the tracer's
   cosine, a quotient of rounded terms, may exceed 1 by a few ulps (about
   10 u at most, u = 2^-53, by the rounding of a 3-term dot product, two
   norms and a quotient; 6 u measured), and for a huge exponent
   [(1 + 16 u) ** s] is far above 1 (about 7000 for s = 1e16, infinite
   from about 1e18 on). *)
let specular_bound s = if s = Sphere.matte then 0. else Float.pow (1. +. (8. *. epsilon_float)) s

(* The largest channel any ray can return: background, or an object's
   colour times the most light it can receive (ambient, plus each light's
   diffuse term, at most its intensity, and specular term, at most its
   intensity times [specular_bound]). Blends are convex combinations, so
   they stay below it. The margin covers the rounding of cosines and
   blends, each off by a few ulps at most. Infinite (no early stop) when a
   specular term can be. *)
let max_channel (scene : Scene.view) =
  let ambient, direct =
    List.fold_left
      (fun (a, d) l ->
        match l with
        | Light.Ambient { intensity } -> (a +. intensity, d)
        | Point { intensity; _ } | Directional { intensity; _ } -> (a, d +. intensity))
      (0., 0.) scene.lights
  in
  (* One pow per run of equal exponents: scenes repeat a few. *)
  let last_s = ref nan and last_bound = ref 0. in
  let channel (c : Color.t) s =
    if not (Float.equal s !last_s) then begin
      last_s := s;
      last_bound := specular_bound s
    end;
    Float.max c.r (Float.max c.g c.b) *. (ambient +. direct +. (direct *. !last_bound))
  in
  let bg = scene.background in
  (* A pattern's colour is an object's colour too. *)
  let channels color pattern s =
    match pattern with
    | None -> channel color s
    | Some p -> Float.max (channel color s) (channel (Pattern.color p) s)
  in
  let bound =
    (* Every material of the spheres' table is some sphere's. *)
    Array.fold_left
      (fun acc (m : Material.t) -> Float.max acc (channels m.color m.pattern m.specular))
      (Float.max bg.r (Float.max bg.g bg.b))
      (Spheres.materials scene.spheres)
  in
  let bound =
    List.fold_left
      (fun acc sh ->
        List.fold_left (fun acc (m : Material.t) -> Float.max acc (channels m.color m.pattern m.specular)) acc (Shape.materials sh))
      bound scene.shapes
  in
  (bound *. (1. +. 1e-6)) +. 1e-6

(* The largest x with x ** s certainly 0: x <= 2^(-1080 / s) gives
   x ** s <= 2^-1080, 32 times below half the smallest subnormal (2^-1075),
   so pow, accurate to within an ulp, returns 0. Two ulps lower still, for
   the rounding of this computation. For huge s the threshold approaches 1
   and must stay below it, since 1 ** s = 1. *)
let specular_zero s =
  if not (s > 0.) then 0.
  else
    let x = Float.pred (Float.pred (2. ** (-1080. /. s))) in
    if x < 1. then Float.max x 0. else 0.

(* The cosine at or below which a specular term [li cos^s] cannot change
   an intensity of at least [before] > 0: for [cos <= z], [z^s <= t], a
   quarter of [ulp before / 2] over [li]; pow is within an ulp of
   [cos^s] and the product within one of [li pow], so the term added is
   below half an ulp of the sum, which rounds back to the sum (terms are
   never negative: intensities are >= 0, so the sum only grows, and its
   ulp with it). [z] itself: [t ** (1 / s)] is within a few ulps of the
   true root, which [z^s] turns into a relative error about [2 u s],
   below 1e-9 for [s <= 1e6] (larger exponents get no cut); two ulps lower
   for good measure. *)
let negligible_cos ~before ~li s =
  if not (s > 0. && s <= 1e6 && before > 0. && li > 0.) then 0.
  else
    let _, e = Float.frexp before in
    (* [before] is in [2^(e-1), 2^e): its ulp is 2^(e-53). *)
    let t = Float.ldexp 1. (e - 53) /. 2. /. 4. /. li in
    let z = Float.pred (Float.pred (t ** (1. /. s))) in
    if z < 1. then Float.max z 0. else 0.

(* Per material [m] and light [l], at [m * n_lights + l]: the cosine at or
   below which the document's kernel adds no specular term of [l]: [cos^s]
   is 0 ([specular_zero]), or too small to change the intensity, which is
   at least the sum of the ambient lights before [l]. *)
let specular_cut ~skips (materials : Material.t array) (lights : Light.t array) =
  let n_lights = Array.length lights in
  let before = Array.make n_lights 0. in
  for l = 1 to n_lights - 1 do
    before.(l) <- (match lights.(l - 1) with Light.Ambient { intensity } -> before.(l - 1) +. intensity | _ -> before.(l - 1))
  done;
  (* Per exponent, not per material: a million materials share a few. *)
  let cuts = Hashtbl.create 16 in
  let cut s l =
    match Hashtbl.find_opt cuts (s, l) with
    | Some c -> c
    | None ->
        let c = Float.max (specular_zero s) (negligible_cos ~before:before.(l) ~li:(Light.intensity lights.(l)) s) in
        Hashtbl.add cuts (s, l) c;
        c
  in
  Array.init
    (Array.length materials * n_lights)
    (fun k ->
      let s = materials.(k / n_lights).specular and l = k mod n_lights in
      if s = Sphere.matte then infinity else if not skips then 0. else cut s l)

(* The sum of the ambient lights that come first, added from 0 in order
   as the tracer adds them, and the index of the first other light. *)
let ambient_lead (lights : Light.t array) =
  let sum = ref 0. and l = ref 0 in
  while !l < Array.length lights && (match lights.(!l) with Light.Ambient _ -> true | _ -> false) do
    sum := !sum +. Light.intensity lights.(!l);
    incr l
  done;
  (!sum, !l)

(* The objects in scene order: the spheres, then each shape, a mesh giving
   one object per triangle (less its degenerate ones, which no ray can
   hit). [iter_shapes] calls [single k sh] for the shapes' objects [k]
   but the meshes', and [mesh k m] for each mesh, [k] the object of its
   first triangle that is not degenerate, and is the number of objects;
   the spheres are objects [0] to [n_spheres - 1], read from the scene's
   arrays. *)
let iter_shapes ~n_spheres (scene : Scene.view) ~single ~mesh =
  let k = ref n_spheres in
  List.iter
    (fun sh ->
      match sh with
      | Shape.Mesh m ->
          mesh !k m;
          k := !k + Mesh.objects m
      | _ ->
          single !k sh;
          incr k)
    scene.shapes;
  !k

(* Objects are numbered above spheres first; the kernel's numbers
   ([index], [slot]: ties, hits) count them in the scene's list. [rank]
   maps the one to the other, where they differ (a shape placed before a
   sphere). *)
let in_list_order ~n_spheres (scene : Scene.view) ~index ~slot =
  if List.for_all (fun (j, _) -> j = n_spheres) scene.placed then (index, slot)
  else begin
    let n = Array.length slot in
    let rank = Array.make n 0 and r = ref 0 and sphere = ref 0 and k = ref n_spheres in
    let next a =
      rank.(!a) <- !r;
      incr r;
      incr a
    in
    let spheres_upto j = while !sphere < j do next sphere done in
    List.iter
      (fun (j, sh) ->
        spheres_upto j;
        for _ = 1 to match sh with Shape.Mesh m -> Mesh.objects m | _ -> 1 do next k done)
      scene.placed;
    spheres_upto n_spheres;
    let listed = Array.make n 0 in
    Array.iteri (fun k i -> listed.(rank.(k)) <- i) slot;
    (Array.map (fun k -> rank.(k)) index, listed)
  end

(* Identical spheres, by the first of them in scene order. Only the first
   gets a slot: the others have the same roots, so the first wins every
   tie (it comes first) and blocks every shadow ray they would block; and
   a ray leaving one leaves them all, which the robust mode's exact
   handling of the sphere a ray leaves must see (or an identical twin,
   with a root of about 1e-16 there, would shadow it). The result lists
   each sphere that has an earlier twin, then that twin, [k; first] at [2 j]
   and [2 j + 1], in no particular order: few, or none, which a child process
   sends back at little cost ([twin_table] makes the table). *)
let sphere_twins ~cx ~cy ~cz ~radius ~n_spheres =
  (* Equal as [Float.compare] has it: -0. is 0. (adding 0. maps it there),
     and the scene holds no nan. *)
  let bits x = Int64.bits_of_float (x +. 0.) in
  (* Coordinates such as 2.5 have only zeros in their low bits: fold the
     high ones down before the mask takes the low ones. In Int64, not int:
     compiled to JavaScript, ints have 32 bits, and [lsr 32] would fold
     nothing (every such sphere would hash alike). *)
  let[@inline] mix h x =
    let h = Int64.add h (bits x) in
    let h = Int64.mul (Int64.logxor h (Int64.shift_right_logical h 32)) 0x2545f4914f6cdd1dL in
    Int64.logxor h (Int64.shift_right_logical h 29)
  in
  let hash k = Int64.to_int (mix (mix (mix (mix 0L cx.(k)) cy.(k)) cz.(k)) radius.(k)) in
  let same i k = cx.(i) = cx.(k) && cy.(i) = cy.(k) && cz.(i) = cz.(k) && radius.(i) = radius.(k) in
  (* A hash, not a sort: most scenes have no twins, and sorting ten
     thousand spheres cost more than the rest of the preparation. One
     table over a million spheres made every look-up a cache and TLB miss
     (0.15 s): the spheres are first sorted by the hash's low bits into
     buckets of about a thousand (two passes in order, a counting sort),
     then each bucket goes through a table that stays in the cache,
     keeping each entry's whole hash, so that only equal hashes compare
     spheres. Counting sorts are stable: a bucket keeps scene order, and
     the first of equal spheres is the one in the table. *)
  let bucket_bits = ref 0 in
  while n_spheres lsr !bucket_bits > 1024 do
    incr bucket_bits
  done;
  let bucket_bits = !bucket_bits in
  let buckets = 1 lsl bucket_bits in
  let start = Array.make (buckets + 1) 0 in
  for k = 0 to n_spheres - 1 do
    let b = (hash k land (buckets - 1)) + 1 in
    start.(b) <- start.(b) + 1
  done;
  let largest = ref 0 in
  for b = 1 to buckets do
    largest := max !largest start.(b);
    start.(b) <- start.(b) + start.(b - 1)
  done;
  let next = Array.sub start 0 buckets in
  let sorted = Array.make n_spheres 0 and sorted_hash = Array.make n_spheres 0 in
  for k = 0 to n_spheres - 1 do
    let h = hash k in
    let b = h land (buckets - 1) in
    let p = next.(b) in
    sorted.(p) <- k;
    sorted_hash.(p) <- h;
    next.(b) <- p + 1
  done;
  (* Open addressing, linear probing, on the hash's bits above the
     bucket's; emptied after each bucket by the slots it took. *)
  let size = ref 16 in
  while !size < 2 * !largest do
    size := 2 * !size
  done;
  let mask = !size - 1 in
  let entry = Array.make !size (-1) and entry_hash = Array.make !size 0 in
  let taken = Array.make !largest 0 in
  let twins = ref [] in
  for b = 0 to buckets - 1 do
    let n_taken = ref 0 in
    for p = start.(b) to start.(b + 1) - 1 do
      let k = sorted.(p) and h = sorted_hash.(p) in
      let j = ref ((h lsr bucket_bits) land mask) in
      while entry.(!j) >= 0 && not (entry_hash.(!j) = h && same entry.(!j) k) do
        j := (!j + 1) land mask
      done;
      if entry.(!j) < 0 then begin
        entry.(!j) <- k;
        entry_hash.(!j) <- h;
        taken.(!n_taken) <- !j;
        incr n_taken
      end
      else twins := (k, entry.(!j)) :: !twins
    done;
    for i = 0 to !n_taken - 1 do
      entry.(taken.(i)) <- -1
    done
  done;
  let twins = Array.of_list !twins in
  let pairs = Array.make (2 * Array.length twins) 0 in
  Array.iteri
    (fun j (k, first) ->
      pairs.(2 * j) <- k;
      pairs.((2 * j) + 1) <- first)
    twins;
  pairs

(* The twins of [n] objects as a table: [t.(k)] is the first of object
   [k]'s twins ([k] itself if it has none), from [sphere_twins]'s pairs;
   empty if there are none: a million spheres leave 8 MB more for the
   hierarchy. *)
let twin_table pairs n =
  if Array.length pairs = 0 then [||]
  else begin
    let t = Array.make n 0 in
    for k = 0 to n - 1 do
      t.(k) <- k
    done;
    for j = 0 to (Array.length pairs / 2) - 1 do
      t.(pairs.(2 * j)) <- pairs.((2 * j) + 1)
    done;
    t
  end

(* [a.(i) <- a.(index.(i))] for every [i] and every array [a] of
   [floats] and [ints], [index] a permutation of [0 .. length a - 1]: each
   array gathered into [scratch], of at least as many floats, then copied
   back. The loads are independent: following the permutation's cycles in
   place made each wait for the one before, 4 times slower for a million
   spheres. The ints (below 2^53: exact as floats) go through the same
   scratch: an int array of a million more would raise the peak by 8 MB,
   and its making (filled twice) start a slice of the major collection. *)
let gather_in_place index ~scratch:fs ~(floats : float array array) ~(ints : int array array) =
  let n = Array.length index in
  if Array.length fs < n then invalid_arg "Prepared.gather_in_place: scratch";
  Array.iter
    (fun (a : float array) ->
      for i = 0 to n - 1 do
        Array.unsafe_set fs i a.(index.(i))
      done;
      Array.blit fs 0 a 0 n)
    floats;
  Array.iter
    (fun (a : int array) ->
      for i = 0 to n - 1 do
        Array.unsafe_set fs i (Float.of_int a.(index.(i)))
      done;
      for i = 0 to n - 1 do
        a.(i) <- Float.to_int (Array.unsafe_get fs i)
      done)
    ints

module Materials = Material.Plain

let[@inline] fmax (a : float) b = if a > b then a else b
let[@inline] fmin (a : float) b = if a < b then a else b

(* The cube around a shape (not a sphere): its center and half side. *)
let single_bounds sh = if Shape.bounded sh then Shape.bounds sh else (Vec3.zero, 0.)

(* [half_box ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 bounds i cx cy cz hx hy hz] writes
   at [i] the center [(cx, cy, cz)] to [x0], [y0], [z0] and the half sides
   [(hx, hy, hz)] to [x1], [y1], [z1] of a box, and grows [bounds] by the
   cube around it (its half side the largest of [hx], [hy], [hz]), as
   {!Bvh.margin_terms} grows its bounds by each sphere. *)
let[@inline] half_box ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 (bounds : float array) i cx cy cz hx hy hz =
  Array.unsafe_set x0 i cx;
  Array.unsafe_set y0 i cy;
  Array.unsafe_set z0 i cz;
  Array.unsafe_set x1 i hx;
  Array.unsafe_set y1 i hy;
  Array.unsafe_set z1 i hz;
  let r = fmax hx (fmax hy hz) in
  bounds.(0) <- fmin bounds.(0) (cx -. r);
  bounds.(1) <- fmin bounds.(1) (cy -. r);
  bounds.(2) <- fmin bounds.(2) (cz -. r);
  bounds.(3) <- fmax bounds.(3) (cx +. r);
  bounds.(4) <- fmax bounds.(4) (cy +. r);
  bounds.(5) <- fmax bounds.(5) (cz +. r)

(* [mesh_half_boxes ... bounds ~all ~first ~bounded ~nb ~pos m k] is
   [half_box] for each triangle of [m] but the degenerate ones, objects
   [k] on, that [bounded] holds from [!pos] on (every one from [first]
   on, if [all]), its
   box found from its corners as {!Mesh.box} finds it; it advances [pos]
   past them. *)
let mesh_half_boxes ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 (bounds : float array) ~all ~first ~bounded ~nb ~pos (m : Mesh.t) k =
  let p = m.positions and tri = m.triangles in
  let b0 = ref bounds.(0) and b1 = ref bounds.(1) and b2 = ref bounds.(2) in
  let b3 = ref bounds.(3) and b4 = ref bounds.(4) and b5 = ref bounds.(5) in
  let k = ref k and i = ref !pos in
  for t = 0 to Mesh.triangle_count m - 1 do
    if not (Mesh.degenerate m t) then begin
      if !i < nb && (if all then !k >= first else bounded.(!i) = !k) then begin
        let i0 = 3 * tri.(3 * t) and i1 = 3 * tri.((3 * t) + 1) and i2 = 3 * tri.((3 * t) + 2) in
        let ux = p.(i0) and vx = p.(i1) and wx = p.(i2) in
        let uy = p.(i0 + 1) and vy = p.(i1 + 1) and wy = p.(i2 + 1) in
        let uz = p.(i0 + 2) and vz = p.(i1 + 2) and wz = p.(i2 + 2) in
        let lx = fmin ux (fmin vx wx) and hx = fmax ux (fmax vx wx) in
        let ly = fmin uy (fmin vy wy) and hy = fmax uy (fmax vy wy) in
        let lz = fmin uz (fmin vz wz) and hz = fmax uz (fmax vz wz) in
        (* As [half_box] has them, from [Mesh.box]'s box. *)
        let cx = 0.5 *. (lx +. hx) and cy = 0.5 *. (ly +. hy) and cz = 0.5 *. (lz +. hz) in
        let ex = 0.5 *. (hx -. lx) and ey = 0.5 *. (hy -. ly) and ez = 0.5 *. (hz -. lz) in
        let j = !i in
        x0.(j) <- cx;
        y0.(j) <- cy;
        z0.(j) <- cz;
        x1.(j) <- ex;
        y1.(j) <- ey;
        z1.(j) <- ez;
        let r = fmax ex (fmax ey ez) in
        b0 := fmin !b0 (cx -. r);
        b1 := fmin !b1 (cy -. r);
        b2 := fmin !b2 (cz -. r);
        b3 := fmax !b3 (cx +. r);
        b4 := fmax !b4 (cy +. r);
        b5 := fmax !b5 (cz +. r);
        i := j + 1
      end;
      incr k
    end
  done;
  bounds.(0) <- !b0;
  bounds.(1) <- !b1;
  bounds.(2) <- !b2;
  bounds.(3) <- !b3;
  bounds.(4) <- !b4;
  bounds.(5) <- !b5;
  pos := !i

(* For a scene with a mesh: the boxes of the [nb] objects [bounded]
   (increasing object numbers; objects [first] to [first + nb - 1] if
   [all]), as [build_boxes] takes them, each padded by its
   [Bvh.ray_box_margin]. A sphere's is its cube (its center and radius
   in [cx] to [radius], by object); another shape's its cube too, found
   again; a mesh's triangle's is its box (half of it along each axis:
   triangles are slivers, far thinner than their cube along two), found
   from its corners once: its center and half sides are written where
   its box will be, and the margin's terms found meanwhile, from the
   cubes around the boxes (the largest half side, [0.5 dx] or another:
   halving is exact, and the largest of the halves is half the largest);
   then each box is padded where it is, with no array of margins, centers
   or half sides of a million triangles between, and no second reading
   of the corners. *)
let mesh_boxes ~n_spheres (scene : Scene.view) ~all ~first ~bounded ~nb ~cx ~cy ~cz ~radius =
  (* Every element is written below. *)
  let f () = Array.create_float nb in
  let x0 = f () and y0 = f () and z0 = f () and x1 = f () and y1 = f () and z1 = f () in
  let p = scene.camera.position in
  let bounds = [| p.x; p.y; p.z; p.x; p.y; p.z |] in
  let pos = ref 0 in
  let next k = !pos < nb && if all then k >= first else bounded.(!pos) = k in
  for k = 0 to n_spheres - 1 do
    if next k then begin
      let h = radius.(k) in
      half_box ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 bounds !pos cx.(k) cy.(k) cz.(k) h h h;
      incr pos
    end
  done;
  (* A mesh's triangles in a loop of their own: no call through a
     closure, and the bounds in registers, for each of millions. *)
  ignore
    (iter_shapes ~n_spheres scene
       ~single:(fun k sh ->
         if next k then begin
           let (c : Vec3.t), h = single_bounds sh in
           half_box ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 bounds !pos c.x c.y c.z h h h;
           incr pos
         end)
       ~mesh:(fun k m -> mesh_half_boxes ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 bounds ~all ~first ~bounded ~nb ~pos m k));
  let terms = Bvh.margin_of_bounds bounds in
  for i = 0 to nb - 1 do
    let hx = x1.(i) and hy = y1.(i) and hz = z1.(i) in
    let m = Bvh.margin terms (fmax hx (fmax hy hz)) in
    let cx = x0.(i) and cy = y0.(i) and cz = z0.(i) in
    x0.(i) <- cx -. (hx +. m);
    y0.(i) <- cy -. (hy +. m);
    z0.(i) <- cz -. (hz +. m);
    x1.(i) <- cx +. (hx +. m);
    y1.(i) <- cy +. (hy +. m);
    z1.(i) <- cz +. (hz +. m)
  done;
  (x0, y0, z0, x1, y1, z1)

(* The [count] numbers [k] of [0 .. n - 1] for which [p k] holds, in
   order. *)
let indices_where n count p =
  let a = Array.make count 0 and j = ref 0 in
  for k = 0 to n - 1 do
    if p k then begin
      a.(!j) <- k;
      incr j
    end
  done;
  a

let prepare_scene ~skips ?beside scene =
  let scene = Scene.view (Scene.of_valid scene) in
  let n_spheres = Spheres.length scene.spheres in
  let n = iter_shapes ~n_spheres scene ~single:(fun _ _ -> ()) ~mesh:(fun _ _ -> ()) in
  (* Per object, in scene order: kind, material, and a cube around it
     (center, half side) for the hierarchy. *)
  let any_mesh = List.exists (function Shape.Mesh _ -> true | _ -> false) scene.shapes in
  (* A big mesh's loading left garbage (the OBJ reader's blocks, the
     positions before their placement) as big as the mesh, in pieces the
     arrays below do not fit in: compacted now, the heap is the mesh's
     arrays and grows from there (the 1M-triangle knot's peak goes from
     275 to 235 MB, for 40 ms). *)
  (* So does a big mesh as a CSG operand, in a scene of few objects
     (docs/performance.md, issue 29). *)
  let csg_triangles = List.fold_left (fun t -> function Shape.Csg c -> t + Csg.triangles c | _ -> t) 0 scene.shapes in
  if (any_mesh && n > big_scene) || csg_triangles > big_scene then Gc.compact ();
  let okind = Array.make n Shape.sphere and omat = Array.make n 0 in
  (* A scene with a mesh has these for its spheres alone: the boxes of
     its shapes, found again from their geometry when the hierarchy is
     built ([mesh_boxes]), take no 56 bytes a triangle meanwhile. *)
  let nc = if any_mesh then n_spheres else n in
  (* Every element is written below: the spheres' by
     [Spheres.blit_fields], the other shapes' by [set]. *)
  let f () = Array.create_float nc in
  let ocx = f () and ocy = f () and ocz = f () and ohalf = f () in
  let materials = ref [] and n_materials = ref 0 in
  (* With each patterned material, where its pattern lies: [frame ()] is
     the object's [Shape.pattern_frame], asked only then (a mesh's scans
     every vertex). *)
  let frames = ref [] in
  let add_material (m : Material.t) frame =
    materials := m :: !materials;
    (match m.pattern with Some p -> frames := (!n_materials, p, frame ()) :: !frames | None -> ());
    incr n_materials;
    !n_materials - 1
  in
  (* Equal materials share one: a million spheres use a dozen. Equal bit
     for bit, so that sharing changes no arithmetic. Plain ones only: a
     pattern lies in its object's frame, and a transparent material names
     its object's medium (Ray_tree). *)
  let known = Materials.create 64 in
  let new_material (m : Material.t) frame =
    if Option.is_some m.pattern || m.transparency > 0. then add_material m frame
    else
      match Materials.find_opt known m with
      | Some i -> i
      | None ->
          let i = add_material m frame in
          Materials.add known m i;
          i
  in
  (* The smooth meshes' normals, divided by their lengths once for all
     the corners that share them. *)
  (* The triangles' vertices, in one array: each mesh's placed positions
     at its base, then the lone triangles, 9 floats each. *)
  let mesh_bases, n_vertex =
    List.fold_left
      (fun (bases, n) sh -> match sh with Shape.Mesh m -> ((m, n) :: bases, n + Array.length m.positions) | _ -> (bases, n))
      ([], 0) scene.shapes
  in
  let n_lone = List.length (List.filter (function Shape.Triangle _ -> true | _ -> false) scene.shapes) in
  let vertex =
    match mesh_bases with
    | [ (m, _) ] when n_lone = 0 -> m.positions
    | _ ->
        let v = Array.make (n_vertex + (9 * n_lone)) 0. in
        List.iter (fun ((m : Mesh.t), b) -> Array.blit m.positions 0 v b (Array.length m.positions)) mesh_bases;
        v
  in
  let vertex_base m = List.assq m mesh_bases in
  (* Where each smooth mesh's corners name their normals by their vertices'
     numbers (an OBJ file's [f 1//1 2//2 3//3]), the unit normals lie
     parallel to [vertex], and a corner's normal is where its vertex is:
     no table of the corners' normals. *)
  let follow =
    List.for_all
      (function Shape.Mesh m when m.smooth -> m.triangle_normals == m.triangles || m.triangle_normals = m.triangles | _ -> true)
      scene.shapes
  in
  let vnormal =
    Array.make
      (if follow then
         if List.exists (function Shape.Mesh m -> m.smooth | _ -> false) scene.shapes then Array.length vertex else 0
       else List.fold_left (fun a sh -> match sh with Shape.Mesh m when m.smooth -> a + Array.length m.normals | _ -> a) 0 scene.shapes)
      nan
  in
  let next_normal = ref 0 in
  (* The offset in [vnormal] of the normals of the mesh whose run of
     triangles starts at object [k]. *)
  let normal_base = Hashtbl.create 8 in
  (* A mesh's triangles come in a run: one material for the run. *)
  let last_mesh = ref None in
  (* CSG solids go to their own table: the root node of object [k]'s. Each
     leaf has its material; the object's is its first leaf's. *)
  let csg = Csg.builder () and csg_root = Hashtbl.create 8 in
  (* A leaf's pattern lies where the leaf's would as an object of its own. *)

  let add_csg k c =
    let first = ref (-1) in
    let material leaf =
      (* Not shared: the first leaf's number names the solid's medium. *)
      let i = add_material (Csg.leaf_material leaf) (fun () -> Shape.leaf_pattern_frame leaf) in
      if !first < 0 then first := i;
      i
    in
    Hashtbl.replace csg_root k (Csg.add csg ~material c);
    !first
  in
  let set k kind mat (c : Vec3.t) h =
    okind.(k) <- kind;
    omat.(k) <- mat;
    if k < nc then begin
      ocx.(k) <- c.x;
      ocy.(k) <- c.y;
      ocz.(k) <- c.z;
      ohalf.(k) <- h
    end
  in
  (* The spheres' plain materials are distinct in their table: the first
     sphere of each finds or makes the prepared material, the others
     reuse its number (what [new_material] would find). *)
  let spheres = scene.spheres in
  let sphere_materials = Spheres.materials spheres in
  let shared = Array.make (Array.length sphere_materials) (-1) in
  (* Each sphere's material, first as its index in the spheres' table. *)
  Spheres.blit_fields spheres ~x:ocx ~y:ocy ~z:ocz ~radius:ohalf ~material:omat;
  for k = 0 to n_spheres - 1 do
    let j = omat.(k) in
    omat.(k) <-
      (if shared.(j) >= 0 then shared.(j)
       else
         let m = sphere_materials.(j) in
         let i = new_material m (fun () -> Shape.leaf_pattern_frame (Csg.Sphere (Spheres.get spheres k))) in
         if Option.is_none m.pattern && not (m.transparency > 0.) then shared.(j) <- i;
         i)
  done;
  let max_channel = max_channel scene in
  (* The spheres are copied: from here on [prepare] holds none of the
     scene's, and a caller that holds the scene no longer either (the
     renderers) lets them go while the hierarchy is built (40 MB for a
     million spheres). *)
  let scene = { scene with spheres = Spheres.empty } in
  ignore
    (iter_shapes ~n_spheres scene
       ~single:(fun k sh ->
         let c, h = single_bounds sh in
         let mat = match sh with Shape.Csg c -> add_csg k c | _ -> new_material (Shape.material sh) (fun () -> Shape.pattern_frame sh) in
         set k (Shape.kind sh) mat c h)
       ~mesh:(fun k m ->
         (* A mesh given twice in a row (the same value) is one run: one
            material, its normals once. *)
         let mat, base =
           match !last_mesh with
           | Some (m', i, base) when m' == m -> (i, base)
           | _ ->
               let i = new_material m.material (fun () -> Shape.pattern_frame (Shape.Mesh m)) in
               let base = if follow then vertex_base m else !next_normal in
               if m.smooth then begin
                 (* Parallel to [vertex], the normals that no vertex number names are not needed. *)
                 let nn = Array.length m.normals / 3 in
                 for j = 0 to (if follow then min nn (Array.length m.positions / 3) else nn) - 1 do
                   ignore (Mesh.unit_normal m j vnormal (base + (3 * j)))
                 done;
                 next_normal := base + Array.length m.normals;
                 Hashtbl.replace normal_base k base
               end;
               last_mesh := Some (m, i, base);
               (i, base)
         in
         (* Smooth where every corner has a normal that could be divided
            by its length ([Mesh.corner_normals]). *)
         let tn = m.triangle_normals in
         let usable t c =
           let j = tn.((3 * t) + c) in
           j >= 0 && not (Float.is_nan vnormal.(base + (3 * j)))
         in
         (* [set]'s arrays, written here in a loop of the mesh's own: it
            has millions of triangles. *)
         let k = ref k in
         for t = 0 to Mesh.triangle_count m - 1 do
           if not (Mesh.degenerate m t) then begin
             okind.(!k) <- (if m.smooth && usable t 0 && usable t 1 && usable t 2 then Shape.smooth_triangle else Shape.triangle);
             omat.(!k) <- mat;
             incr k
           end
         done));
  let materials = Array.of_list (List.rev !materials) in
  (* A patterned material's second colour is a material of its own, after
     the scene's: the tracer picks one of the two indices, so that the
     colour channels stay in the arrays they are read from. *)
  let n_own = Array.length materials in
  let alternate = if !frames = [] then [||] else Array.make n_own (-1) in
  let pattern = Array.make (if !frames = [] then 0 else Pattern.stride * n_own) 0. in
  let extra =
    List.mapi
      (fun j (i, p, (origin, scale, extent)) ->
        alternate.(i) <- n_own + j;
        Pattern.store p ~origin ~scale ~extent pattern (Pattern.stride * i);
        Material.update ~color:(Pattern.color p) ~pattern:None materials.(i))
      (List.rev !frames)
  in
  let materials = Array.append materials (Array.of_list extra) in
  (* The objects kept (each sphere but the twins of earlier ones) that are
     bounded, in scene order, for the hierarchy, their number, the first
     of them, and the planes. Where every object is kept and bounded (no
     twins, no planes: the big scenes), or, in a scene with a mesh, the
     bounded objects follow each other (the planes before the mesh, or
     after it), [bounded] is empty: they are objects [first] to [first +
     nb - 1], and no array of a million numbers is made, read through
     (the slots' objects), or marked by the collections. *)
  let select twin_of =
    let kept k = Array.length twin_of = 0 || twin_of.(k) = k in
    let is_bounded k = kept k && okind.(k) <> Shape.plane in
    let nb = ref 0 and planes = ref [] in
    for k = 0 to n - 1 do
      if kept k then if okind.(k) = Shape.plane then planes := k :: !planes else incr nb
    done;
    let unbounded = Array.of_list (List.rev !planes) in
    (* The first and the last bounded object, looked for from each end. *)
    let first = ref 0 and last = ref (n - 1) in
    if any_mesh && !nb > 0 && !nb < n then begin
      while not (is_bounded !first) do incr first done;
      while not (is_bounded !last) do decr last done
    end;
    if !nb = n then ([||], unbounded, n, 0)
    else if any_mesh && !nb > 0 && !last - !first + 1 = !nb then ([||], unbounded, !nb, !first)
    else begin
      (indices_where n !nb is_bounded, unbounded, !nb, 0)
    end
  in
  (* A big scene's loading left garbage in pieces (the text's windows, the
     spheres' blocks, which the caller no longer holds: see below), too
     small for the hierarchy's arrays of a million: compacted now, the heap
     does not grow past them; after the hierarchy, a collection lets the
     slot-order arrays reuse its build's arrays. For a million spheres the
     render's peak goes from 293 to 235 MB, for 5% of the time of loading
     and preparing. A mesh's scene was compacted above, before the
     per-object arrays: here a compaction would only move them, and where
     spheres are few there is no garbage yet to collect before the
     hierarchy (the 1M-triangle knot peaks as high without it: 0.03 s
     less, and the collection after it is cheaper). *)
  let collections = ref 0 in
  let collect () =
    if n > big_scene then begin
      if !collections > 0 then Gc.full_major ()
      else if not any_mesh then (if n_spheres > n / 2 then Gc.compact () else Gc.full_major ())
      else if n_spheres > n / 2 then Gc.full_major ();
      incr collections
    end
  in
  (* The boxes of the [nb] objects [bounded] (from [first] on, if it is
     empty), each padded by its margin, as [Bvh.build_boxes] takes them;
     [None] without a hierarchy. *)
  let boxes (bounded, _, nb, first) =
    if not (skips && nb > bvh_threshold) then None
    else
      let all = Array.length bounded = 0 in
      if any_mesh then Some (mesh_boxes ~n_spheres scene ~all ~first ~bounded ~nb ~cx:ocx ~cy:ocy ~cz:ocz ~radius:ohalf)
      else begin
      (* [among], not copies of the arrays: a million objects make 8 MB an array. *)
      let terms =
        if all then Bvh.margin_terms ~cx:ocx ~cy:ocy ~cz:ocz ~radius:ohalf scene.camera.position
        else Bvh.margin_terms ~among:bounded ~cx:ocx ~cy:ocy ~cz:ocz ~radius:ohalf scene.camera.position
      in
      (* Each box padded by its margin, in a loop: [Array.mapi]'s
         function would return each float boxed. *)
      let f () = Array.create_float nb in
      let x0 = f () and y0 = f () and z0 = f () and x1 = f () and y1 = f () and z1 = f () in
      for i = 0 to nb - 1 do
        let k = if all then i else bounded.(i) in
        let e = ohalf.(k) +. Bvh.margin terms ohalf.(k) in
        x0.(i) <- ocx.(k) -. e;
        y0.(i) <- ocy.(k) -. e;
        z0.(i) <- ocz.(k) -. e;
        x1.(i) <- ocx.(k) +. e;
        y1.(i) <- ocy.(k) +. e;
        z1.(i) <- ocz.(k) +. e
      done;
      Some (x0, y0, z0, x1, y1, z1)
    end
  in
  let find_twins () = sphere_twins ~cx:ocx ~cy:ocy ~cz:ocz ~radius:ohalf ~n_spheres in
  (* With two cores, a child finds a big scene's twins while this process
     selects and pads the boxes as if there were none: twins are rare,
     and where a child finds some, their selection and boxes are made
     again (twins are exact copies: the margins' terms would be the same,
     but the boxes are of fewer objects). *)
  let twins_beside =
    match beside with
    | Some (b : Bvh.beside) when n_spheres >= b.min_objects -> Some (fun () -> b.beside find_twins)
    | _ -> None
  in
  let twin_of, (bounded, unbounded, nb, first), boxes =
    match twins_beside with
    | None ->
        let twin_of = twin_table (find_twins ()) n in
        let selected = select twin_of in
        collect ();
        (twin_of, selected, boxes selected)
    | Some start -> (
        (* Started before the collection: started after it, the child
           shares the compacted heap, and writing the boxes there copied
           its pages (0.03-0.04 s more for a million spheres). *)
        let wait = start () in
        let selected = select [||] in
        collect ();
        let guess = boxes selected in
        let pairs = match wait () with Some pairs -> pairs | None -> find_twins () in
        match pairs with
        | [||] -> ([||], selected, guess)
        | _ ->
            let twin_of = twin_table pairs n in
            let selected = select twin_of in
            (twin_of, selected, boxes selected))
  in
  let kept k = Array.length twin_of = 0 || twin_of.(k) = k in
  let all_bounded = nb = n in
  (* The build's six arrays of boxes, which it leaves in slot order and
     does not keep: arrays of floats of their length made below are made
     in their memory, not taken from the system once more (a million
     spheres peak 40 MB lower than with new arrays, the garbage
     collector finding no room for them among the freed ones). *)
  let spare = ref [] in
  let bvh =
    match boxes with
    | None -> None
    | Some (x0, y0, z0, x1, y1, z1) ->
      (* Leaves of up to 16, where the surface area heuristic finds no
         cheaper split: a mesh's thin triangles overlap, and below 16 more
         boxes buy no fewer triangle tests (the 1M-triangle knot: 26.6 M
         box tests for 28.9 M triangle tests with leaves of 4, 13.8 M for
         30.7 M with 16, its trace 15-20% faster, 26 MB less at the peak).
         The grids of spheres (grid-100, grid:1000000, tiny-spheres)
         build the same trees as with 4. The image never depends on the
         tree (see [Trace.better]). *)
      let b = Bvh.build_boxes ?beside ~leaf_size:16 ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 () in
      (* Spheres alone, each with a slot: below, [floats] asks for arrays
         of their number. Otherwise the build's arrays are let go, for
         the arrays of other lengths made below. *)
      if scene.shapes = [] && nb = n then spare := [ x0; y0; z0; x1; y1; z1 ];
      Some b
  in
  (* An array of [len] floats, every one of which the caller writes. *)
  let floats len =
    match !spare with
    | a :: rest when Array.length a = len ->
        spare := rest;
        a
    | _ -> Array.create_float len
  in
  (* Slots: the hierarchy's leaf order, then the planes; without a
     hierarchy, the scene's order. *)
  collect ();
  let index =
    match bvh with
    (* Every object in the hierarchy: its order is the slots' ([index] is
       only read), not copied. *)
    | Some b when all_bounded -> b.order
    | Some b ->
        let nb = Array.length b.order in
        let index = Array.make (nb + Array.length unbounded) 0 in
        if Array.length bounded = 0 then
          for i = 0 to nb - 1 do
            index.(i) <- first + b.order.(i)
          done
        else
          for i = 0 to nb - 1 do
            index.(i) <- bounded.(b.order.(i))
          done;
        Array.blit unbounded 0 index nb (Array.length unbounded);
        index
    | None when all_bounded ->
        let index = Array.make n 0 in
        for k = 0 to n - 1 do
          index.(k) <- k
        done;
        index
    | None ->
        let m = ref 0 in
        for k = 0 to n - 1 do
          if kept k then incr m
        done;
        indices_where n !m kept
  in
  let n_kept = Array.length index in
  (* Spheres alone, without twins: [index] orders every object, and the
     per-object arrays, put in slot order where they are, are the
     tracer's (no second array of a million). Not for meshes: their slot
     order is far from the scene's, and moving in place along its cycles
     cost more than the copies. *)
  let in_place = n_kept = n && scene.shapes = [] in
  let slot = Array.make n 0 in
  (* Otherwise each slot's kind and material, in the walk that finds the
     slots: one read of [index], the three random accesses of a slot's
     object side by side. *)
  let kind, material =
    if in_place then begin
      for i = 0 to n_kept - 1 do
        slot.(index.(i)) <- i
      done;
      (okind, omat)
    end
    else begin
      let kind = Array.make n_kept 0 and material = Array.make n_kept 0 in
      for i = 0 to n_kept - 1 do
        let k = index.(i) in
        slot.(k) <- i;
        Array.unsafe_set kind i okind.(k);
        Array.unsafe_set material i omat.(k)
      done;
      (kind, material)
    end
  in
  Array.iteri (fun k first -> if first <> k then slot.(k) <- slot.(first)) twin_of;
  (* Geometry and sphere data, written in slot order. *)
  let stride = Shape.stride in
  (* Spheres alone need no table of shapes. *)
  let shapes_len = if scene.shapes = [] then 0 else n_kept in
  (* Triangles are read from [vertex]; the other shapes, few, have [geom]. *)
  let n_geom =
    List.length (List.filter (function Shape.Triangle _ | Shape.Mesh _ -> false | _ -> true) scene.shapes)
  in
  let geom = Array.make (stride * n_geom) 0. and extent = Array.make n_geom 0. in
  (* Three arrays, not one of three ints a slot: made after the
     hierarchy, each fits where one of its build's arrays was (the
     1M-triangle knot peaks 24 MB lower). *)
  let at0 = Array.make shapes_len 0 and at1 = Array.make shapes_len 0 and at2 = Array.make shapes_len 0 in
  let next_geom = ref 0 and next_lone = ref n_vertex in
  let any_smooth = Array.exists (fun k -> k = Shape.smooth_triangle) okind in
  let vnormal = if any_smooth then vnormal else [||] in
  let vcorner = if any_smooth && not follow then Array.make (3 * n_kept) 0 else [||] in
  let sphere_len = if n_spheres > 0 then n_kept else 0 in
  (* [okind] is all spheres here: no need to gather it. *)
  let cx, cy, cz, radius =
    if in_place && List.length !spare >= 5 then begin
      (* Into four of the build's arrays, in one walk of [index]; the
         scene-order arrays then serve the arrays made below. *)
      let cx = floats n and cy = floats n and cz = floats n and radius = floats n in
      for i = 0 to n - 1 do
        let k = index.(i) in
        cx.(i) <- ocx.(k);
        cy.(i) <- ocy.(k);
        cz.(i) <- ocz.(k);
        radius.(i) <- ohalf.(k)
      done;
      let scratch = floats n in
      gather_in_place index ~scratch ~floats:[||] ~ints:[| omat |];
      spare := scratch :: ocx :: ocy :: ocz :: ohalf :: !spare;
      (cx, cy, cz, radius)
    end
    else if in_place then begin
      gather_in_place index ~scratch:(floats n_kept) ~floats:[| ocx; ocy; ocz; ohalf |] ~ints:[| omat |];
      (ocx, ocy, ocz, ohalf)
    end
    else (Array.make sphere_len 0., Array.make sphere_len 0., Array.make sphere_len 0., Array.make sphere_len 0.)
  in
  let extent_of i =
    let e = ref 0. in
    for j = stride * i to (stride * i) + stride - 1 do
      e := fmax !e (Float.abs geom.(j))
    done;
    extent.(i) <- !e
  in
  let run = ref None in
  ignore
    (iter_shapes ~n_spheres scene
       ~single:(fun k sh ->
         let i = slot.(k) in
         match sh with
         | Shape.Triangle tri ->
             let o = !next_lone in
             Triangle.store tri vertex o;
             at0.(i) <- o;
             at1.(i) <- o + 3;
             at2.(i) <- o + 6;
             next_lone := o + 9
         | _ -> (
             let g = !next_geom in
             incr next_geom;
             at0.(i) <- g;
             match sh with
             | Shape.Csg c ->
                 geom.(stride * g) <- Float.of_int (Hashtbl.find csg_root k);
                 extent.(g) <- Csg.extent c
             | _ ->
                 Shape.store sh geom (stride * g);
                 extent_of g))
       ~mesh:(fun k m ->
         let vb = vertex_base m and tri = m.triangles in
         let base =
           match !run with
           | Some (m', base) when m' == m -> base
           | _ ->
               let base = Option.value (Hashtbl.find_opt normal_base k) ~default:0 in
               run := Some (m, base);
               base
         in
         let k = ref k in
         for t = 0 to Mesh.triangle_count m - 1 do
           if not (Mesh.degenerate m t) then begin
             let i = slot.(!k) in
             at0.(i) <- vb + (3 * tri.(3 * t));
             at1.(i) <- vb + (3 * tri.((3 * t) + 1));
             at2.(i) <- vb + (3 * tri.((3 * t) + 2));
             if any_smooth && not follow then
               for c = 0 to 2 do
                 vcorner.((3 * i) + c) <- base + (3 * max 0 m.triangle_normals.((3 * t) + c))
               done;
             incr k
           end
         done));
  (* The spheres' [set] wrote their centers and radii in scene order:
     into slot order by [index], with no second walk of the scene. *)
  if not in_place then
  for i = 0 to sphere_len - 1 do
    let k = index.(i) in
    if okind.(k) = Shape.sphere then begin
      cx.(i) <- ocx.(k);
      cy.(i) <- ocy.(k);
      cz.(i) <- ocz.(k);
      radius.(i) <- ohalf.(k)
    end
  done;
  let lights =
    Array.of_list
      (if skips then List.filter (fun l -> Light.intensity l > 0.) scene.lights else scene.lights)
  in
  let lf f = Array.map f lights and mf f = Array.map f materials in
  let o = scene.camera.position in
  (* Loops, not [Array.map]: its function returns each float boxed, 10
     million words for a million spheres. *)
  let r2 = floats sphere_len in
  let primary_ocx = floats sphere_len in
  let primary_ocy = floats sphere_len in
  let primary_ocz = floats sphere_len in
  let primary_k3 = floats sphere_len in
  spare := [];
  for i = 0 to sphere_len - 1 do
    let r = radius.(i) in
    r2.(i) <- r *. r;
    let x = o.x -. cx.(i) and y = o.y -. cy.(i) and z = o.z -. cz.(i) in
    primary_ocx.(i) <- x;
    primary_ocy.(i) <- y;
    primary_ocz.(i) <- z;
    (* Same operands in the same order as the tracer's per-ray [k3]. *)
    primary_k3.(i) <- ((x *. x) +. (y *. y) +. (z *. z)) -. (r *. r)
  done;
  let vector l =
    match l with
    | Light.Ambient _ -> Vec3.zero
    | Point { position; _ } -> position
    | Directional { direction; _ } -> direction
  in
  let transparent = Array.exists (fun (m : Material.t) -> m.transparency > 0.) materials in
  (* The document's own scenes: spheres of plain materials (no pattern, no
     glass), few enough for no hierarchy, in the document's mode. *)
  let textbook_all = scene.shapes = [] && alternate = [||] && (not transparent) && bvh = None && scene.epsilon <> None in
  (* The triangles' vertices in the order the leaves read them
     (Vertex_order); the normals stay where they are. *)
  let vertex, vsource =
    if bvh = None || Array.length vertex = 0 then (vertex, [||]) else Vertex_order.gather ~kind ~vertex at0 at1 at2
  in
  let unbounded = Array.map (fun i -> slot.(i)) unbounded in
  let index, slot = in_list_order ~n_spheres scene ~index ~slot in
  {
    n_spheres;
    n_objects = n_kept;
    all_spheres = scene.shapes = [] && alternate = [||];
    patterned = alternate <> [||];
    alternate;
    pattern;
    textbook_all;
    index;
    slot;
    bvh;
    unbounded;
    kind;
    geom;
    vertex;
    at0;
    at1;
    at2;
    vnormal;
    vsource;
    vcorner;
    extent;
    csg = Csg.table csg;
    n_scene_objects = n;
    material;
    cx;
    cy;
    cz;
    radius;
    r2;
    red = mf (fun m -> m.Material.color.r);
    green = mf (fun m -> m.color.g);
    blue = mf (fun m -> m.color.b);
    specular = mf (fun m -> m.specular);
    specular_zero = mf (fun m -> if skips then specular_zero m.specular else 0.);
    reflective = mf (fun m -> m.reflective);
    n_lights = Array.length lights;
    light_kind =
      lf (function Light.Ambient _ -> ambient | Point _ -> point | Directional _ -> directional);
    light_intensity = lf Light.intensity;
    lx = lf (fun l -> (vector l).x);
    ly = lf (fun l -> (vector l).y);
    lz = lf (fun l -> (vector l).z);
    robust = scene.epsilon = None;
    epsilon = Option.value scene.epsilon ~default:0.;
    (* Nothing bounces off a scene without mirrors or glass, whatever its
       depth: the tracer then keeps storage for no level it cannot reach
       (a depth of [max_int] would overflow its size). *)
    depth =
      (if Array.exists (fun (m : Material.t) -> m.reflective > 0. || m.transparency > 0.) materials then scene.depth
       else 0);
    width = scene.width;
    height = scene.height;
    viewport = scene.viewport;
    camera = scene.camera;
    identity_rotation = Camera.is_identity scene.camera.rotation;
    background = scene.background;
    primary_ocx;
    primary_ocy;
    primary_ocz;
    primary_k3;
    max_channel;
    early_stop = skips && Float.is_finite max_channel;
    skips;
    transparency = mf (fun m -> m.transparency);
    refractive_index = mf (fun m -> m.refractive_index);
    fresnel = mf (fun m -> m.fresnel);
    transparent;
    behind = skips;
    shadow_skip = skips;
    cull = skips;
    (* The viewport coordinates of each column and row of pixel centres,
       by the operations [Trace]'s primary ray does for any point. *)
    (* The document's kernel reads a sphere, a camera ray's constants and a
       light from one array each: fewer pointers to keep in registers. *)
    specular_cut = specular_cut ~skips materials lights;
    ambient_lead = fst (ambient_lead lights);
    first_light = snd (ambient_lead lights);
    sphere4 =
      (if textbook_all then
         Array.init (4 * n_kept) (fun k ->
             let i = k / 4 in
             match k mod 4 with 0 -> cx.(i) | 1 -> cy.(i) | 2 -> cz.(i) | _ -> r2.(i))
       else [||]);
    primary4 =
      (if textbook_all then
         Array.init (4 * n_kept) (fun k ->
             let i = k / 4 in
             match k mod 4 with 0 -> primary_ocx.(i) | 1 -> primary_ocy.(i) | 2 -> primary_ocz.(i) | _ -> primary_k3.(i))
       else [||]);
    light6 =
      Array.concat
        (List.map
           (fun l ->
             let v = vector l in
             [|
               (match l with Light.Ambient _ -> 0. | Point _ -> 1. | Directional _ -> infinity);
               Light.intensity l;
               v.x;
               v.y;
               v.z;
               sqrt ((v.x *. v.x) +. (v.y *. v.y) +. (v.z *. v.z));
             |])
           (Array.to_list lights));
    column_vx =
      Array.init scene.width (fun c ->
          Float.of_int (Canvas.x_of_column ~width:scene.width c) *. scene.viewport.width /. Float.of_int scene.width);
    row_vy =
      Array.init scene.height (fun r ->
          Float.of_int (r - (scene.height / 2)) *. scene.viewport.height /. Float.of_int scene.height);
  }

(* The major heap grows by 256 MB of address space at a time while a big
   scene is prepared, not by 15% of its size: the pieces freed between
   the default's many chunks are each smaller than an array of a million
   floats, so that every such array took new memory (grid:1000000 peaked
   at 247 MB, 208 MB with this). A chunk costs memory only where it is
   written. *)
let big_increment = 32 * 1024 * 1024

let prepare ?(skips = true) ?beside scene =
  let s = Scene.view (Scene.of_valid scene) in
  let objects =
    List.fold_left
      (fun a sh -> match sh with Shape.Mesh m -> a + Mesh.triangle_count m | _ -> a + 1)
      (Spheres.length s.spheres) s.shapes
  in
  if objects <= big_scene then prepare_scene ~skips ?beside scene
  else begin
    let gc = Gc.get () in
    Gc.set { gc with major_heap_increment = big_increment };
    Fun.protect ~finally:(fun () -> Gc.set { (Gc.get ()) with major_heap_increment = gc.major_heap_increment })
      (fun () -> prepare_scene ~skips ?beside scene)
  end

type kernel_skip = Behind | Shadow_rays | Culling | Negligible_terms

let without k p =
  match k with
  | Behind -> { p with behind = false }
  | Shadow_rays -> { p with shadow_skip = false }
  | Culling -> { p with cull = false }
  | Negligible_terms ->
      {
        p with
        specular_cut =
          Array.mapi
            (fun k cut -> if p.specular.(k / max 1 p.n_lights) = Sphere.matte then cut else p.specular_zero.(k / max 1 p.n_lights))
            p.specular_cut;
      }
