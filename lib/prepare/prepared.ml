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
  kind : Kind.t array;
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
  light_number : int array;
  light_geom : float array;
  light_su : int array;
  light_sv : int array;
  light_adaptive : bool array;
  light_uniform : bool array;
  soft_lights : bool;
  umbra_skip : bool;
  casters : float array;
  sampled : bool;
  specular_cut : float array;
  ambient_lead : float;
  first_light : int;
  sphere4 : float array;
  primary4 : float array;
  light6 : float array;
  column_vx : float array;
  row_vy : float array;
  instances : instances;
  materials : Material.t array;
  texture_of : int array;
  texture_table : int array;
  texture_size : float array;
  texels : Image.buffer array;
  uv : float array;
}

and instances = {
  bottoms : t array;
  bottom : int array;
  to_object : float array;
  material_map : int array array;
  placed_alternate : int array;
}

let bvh_threshold = 8

(* Above this many objects, preparing collects its garbage at two points
   ([collect]): each costs a marking of the live heap, which below it
   saves little (docs/performance.md, "Numbers moved out of prepare's
   comments"). *)
let big_scene = 1 lsl 18
let ambient = 0
let point = 1
let directional = 2
let area = 3
let sphere = 4
let spot = 5
let light_stride = 10
let textured_material = -2
let texture_stride = 4
let spherical = 0
let planar = 1
let box_mapping = 2
let uv_mapping = 3

(* {1 The scene's objects}

   The one step that reads the scene's objects: the steps after it read
   [objects] and the scene's settings and lights ([settings]), never the
   scene's lists of objects, so that a change of the scene's
   representation changes this section alone. *)

(* The objects in the order of ties, numbered: the spheres are objects [0]
   to [n_spheres - 1], then come the shapes, a mesh giving one object per
   triangle but its degenerate ones, which no ray can hit. *)
type objects = {
  n : int;  (* The number of objects. *)
  n_spheres : int;
  spheres : Spheres.t;  (* [Spheres.empty] once they are copied ([prepare_scene]). *)
  shapes : Shape.t list;  (* The objects after the spheres, in order. *)
  placed : (int * Shape.t) list;  (* [shapes], each with the number of spheres before it in the list. *)
  any_mesh : bool;
  csg_triangles : int;  (* The triangles of the meshes inside CSG solids. *)
}

(* [iter_shapes o ~single ~mesh] calls [single k sh] for the shapes'
   objects [k] but the meshes', and [mesh k m] for each mesh, [k] the
   object of its first triangle that is not degenerate, and is the number
   of objects. *)
let iter_shapes o ~single ~mesh =
  let k = ref o.n_spheres in
  List.iter
    (fun sh ->
      match sh with
      | Shape.Mesh m ->
          mesh !k m;
          k := !k + Mesh.objects m
      | _ ->
          single !k sh;
          incr k)
    o.shapes;
  !k

(* The scene's shapes and placed shapes (the same, in the same order),
   each flat mesh held without its normals ([Mesh.flat_view]: nothing
   here reads them), so that they go with the scene once its caller lets
   go of it, before the hierarchy's build: 12 MB for a million normals. *)
let flat_views (scene : Scene.view) =
  let flat = function Shape.Mesh m -> (not m.smooth) && Array.length m.normals > 0 | _ -> false in
  if List.exists flat scene.shapes && List.compare_lengths scene.shapes scene.placed = 0
     && List.for_all2 (fun sh (_, p) -> sh == p) scene.shapes scene.placed
  then
    let placed = List.map (fun (j, sh) -> match sh with Shape.Mesh m when flat sh -> (j, Shape.Mesh (Mesh.flat_view m)) | _ -> (j, sh)) scene.placed in
    (List.map snd placed, placed)
  else (scene.shapes, scene.placed)

let read_objects (scene : Scene.view) =
  let shapes, placed = flat_views scene in
  let o =
    {
      n = 0;
      n_spheres = Spheres.length scene.spheres;
      spheres = scene.spheres;
      shapes;
      placed;
      any_mesh = List.exists (function Shape.Mesh _ -> true | _ -> false) scene.shapes;
      csg_triangles = List.fold_left (fun t -> function Shape.Csg c -> t + Csg.triangles c | _ -> t) 0 scene.shapes;
    }
  in
  { o with n = iter_shapes o ~single:(fun _ _ -> ()) ~mesh:(fun _ _ -> ()) }

(* The scene without its objects: what the steps read of it after
   [read_objects]. *)
let settings (scene : Scene.view) = { scene with spheres = Spheres.empty; shapes = []; placed = [] }

(* The objects of [scene], each triangle of a mesh counted: known before
   [read_objects], to choose the collector's settings ([prepare]). *)
let object_count (s : Scene.view) =
  List.fold_left
    (fun a sh -> match sh with Shape.Mesh m -> a + Mesh.triangle_count m | _ -> a + 1)
    (Spheres.length s.spheres) s.shapes

(* The most [cos ** s] can be: 1 for an exact cosine, but the tracer's
   cosine, a quotient of rounded terms, may exceed 1 by a few ulps (about
   10 u at most, u = 2^-53, by the rounding of a 3-term dot product, two
   norms and a quotient), and for a huge exponent
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
let max_channel (scene : Scene.view) o =
  let ambient, direct =
    List.fold_left
      (fun (a, d) l ->
        match l with
        | Light.Ambient { intensity } -> (a +. intensity, d)
        | Point { intensity; _ } | Directional { intensity; _ } | Area { intensity; _ } | Sphere { intensity; _ }
        | Spot { intensity; _ } ->
            (* An area or sphere light's samples share its intensity; a
               spotlight's cone scales it by at most 1. *)
            (a, d +. intensity))
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
  (* A texture's colours replace the material's: its brightest channel,
     found once per image. *)
  let brightest = ref [] in
  let texture_channel (t : Texture_map.t) =
    match List.assq_opt t.image !brightest with
    | Some c -> c
    | None ->
        let b = Texture.channels t.image and c = ref 0 in
        for k = 0 to Bigarray.Array1.dim b - 1 do
          let x = Bigarray.Array1.unsafe_get b k in
          if x > !c then c := x
        done;
        let c = Float.of_int !c in
        brightest := (t.image, c) :: !brightest;
        c
  in
  (* A pattern's colour is an object's colour too. *)
  let channels (m : Material.t) =
    let s = m.specular in
    match (m.pattern, m.texture) with
    | None, None -> channel m.color s
    | Some p, _ -> Float.max (channel m.color s) (channel (Pattern.color p) s)
    | None, Some t ->
        let c = texture_channel t in
        channel (Color.v c c c) s
  in
  let bound =
    (* Every material of the spheres' table is some sphere's. *)
    Array.fold_left
      (fun acc (m : Material.t) -> Float.max acc (channels m))
      (Float.max bg.r (Float.max bg.g bg.b))
      (Spheres.materials o.spheres)
  in
  let bound =
    List.fold_left
      (fun acc sh ->
        List.fold_left (fun acc (m : Material.t) -> Float.max acc (channels m)) acc (Shape.materials sh))
      bound o.shapes
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
  (* A hash, not a sort: most scenes have no twins, and sorting the
     spheres cost more than the rest of the preparation. One table over a
     million spheres made every look-up a cache and TLB miss: the
     spheres are first sorted by the hash's low bits into
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
   place made each wait for the one before, several times slower. The
   ints (below 2^53: exact as floats) go through the same scratch: an int
   array of a million more would raise the peak by 8 MB, and its making
   (filled twice) start a slice of the major collection. *)
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

(* How far from the camera's position a camera ray may start: the lens's
   radius, stretched by the longest row of the matrix, which bounds each
   coordinate of [M (l_x, l_y, 0)]. A camera ray starts within this of the
   position, and the boxes' margins must cover it as they cover the
   position. [0.] for a pinhole: its bounds unchanged. *)
let lens_reach (c : Camera.t) =
  if not (Camera.has_lens c) then 0.
  else
    let m = c.rotation in
    0.5 *. c.aperture *. Float.max (Vec3.norm m.row0) (Float.max (Vec3.norm m.row1) (Vec3.norm m.row2))

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

(* The margin of an instance's box [b] ([instance_half_box]): a cube's of
   its largest half side, times its transform's stretch (the rounding of
   the ray carried into its frame, seen in the world: see
   [Prepared.instance_box] in the interface). *)
let instance_margin terms (b : float array) = Bvh.margin terms (fmax b.(3) (fmax b.(4) b.(5))) *. b.(6)

(* The position of object [k] in [bounded] (increasing). *)
let slot_of (bounded : int array) k =
  let rec find lo hi =
    if lo >= hi then lo
    else
      let mid = (lo + hi) / 2 in
      if bounded.(mid) < k then find (mid + 1) hi else find lo mid
  in
  find 0 (Array.length bounded)

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
let mesh_boxes ~mterms o (scene : Scene.view) ~all ~first ~bounded ~nb ~cx ~cy ~cz ~radius ~oboxes =
  (* Every element is written below. *)
  let f () = Array.create_float nb in
  let x0 = f () and y0 = f () and z0 = f () and x1 = f () and y1 = f () and z1 = f () in
  let p = scene.camera.position and e = lens_reach scene.camera in
  let bounds = [| p.x -. e; p.y -. e; p.z -. e; p.x +. e; p.y +. e; p.z +. e |] in
  let pos = ref 0 in
  let next k = !pos < nb && if all then k >= first else bounded.(!pos) = k in
  for k = 0 to o.n_spheres - 1 do
    if next k then begin
      let h = radius.(k) in
      half_box ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 bounds !pos cx.(k) cy.(k) cz.(k) h h h;
      incr pos
    end
  done;
  (* A mesh's triangles in a loop of their own: no call through a
     closure, and the bounds in registers, for each of millions. *)
  ignore
    (iter_shapes o
       ~single:(fun k sh ->
         if next k then begin
           (match Hashtbl.find_opt oboxes k with
           | Some b -> half_box ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 bounds !pos b.(0) b.(1) b.(2) b.(3) b.(4) b.(5)
           | None ->
               let (c : Vec3.t), h = single_bounds sh in
               half_box ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 bounds !pos c.x c.y c.z h h h);
           incr pos
         end)
       ~mesh:(fun k m -> mesh_half_boxes ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 bounds ~all ~first ~bounded ~nb ~pos m k));
  let terms = Bvh.margin_of_bounds bounds in
  mterms := Some terms;
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
  (* The instances' boxes padded again, by their own margin: few. *)
  Hashtbl.iter
    (fun k b ->
      let i = if all then k - first else slot_of bounded k in
      let m = instance_margin terms b in
      x0.(i) <- b.(0) -. (b.(3) +. m);
      y0.(i) <- b.(1) -. (b.(4) +. m);
      z0.(i) <- b.(2) -. (b.(5) +. m);
      x1.(i) <- b.(0) +. (b.(3) +. m);
      y1.(i) <- b.(1) +. (b.(4) +. m);
      z1.(i) <- b.(2) +. (b.(5) +. m))
    oboxes;
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

(* {1 The steps of [prepare_scene]}

   Each does one job, in the order [prepare_scene] calls them. Per-object
   arrays are in object order ([read_objects]'s numbering) until [slots],
   in slot order after it. *)

(* {2 Per object, in object order} *)

(* The cubes around the objects (center, half side) for the hierarchy's
   boxes, which hold the spheres' centers and radii too. A scene with a
   mesh has them for its spheres alone: the boxes of its shapes, found
   again from their geometry when the hierarchy is built ([mesh_boxes]),
   take no 56 bytes a triangle meanwhile. *)
type cubes = {
  ocx : float array;
  ocy : float array;
  ocz : float array;
  ohalf : float array;
  oboxes : (int, float array) Hashtbl.t;
      (* Object [k]'s center, half sides and transform's stretch, if it
         is an instance ([instance_half_box]): its box, not its cube.
         Empty in a scene without instances. *)
  mutable mterms : Bvh.margin option;
      (* The margins' terms of a mesh's boxes ([mesh_boxes]), for the
         leaves cut by planes ([cut_leaves]). *)
}

let cubes o =
  let nc = if o.any_mesh then o.n_spheres else o.n in
  (* Every element is written below: the spheres' by
     [Spheres.blit_fields], the other shapes' by [shape_objects]. *)
  let f () = Array.create_float nc in
  let ocx = f () and ocy = f () and ocz = f () and ohalf = f () in
  { ocx; ocy; ocz; ohalf; oboxes = Hashtbl.create 0; mterms = None }

(* {2 Materials} *)

(* The prepared scene's materials, numbered as the objects are read. *)
type frame = Vec3.t * float * float

type registry = {
  mutable added : Material.t list;  (* The last first. *)
  mutable count : int;
  mutable frames : (int * Pattern.t * frame) list;
      (* Each patterned material's number, pattern and object's frame. *)
  mutable placed : (int * Pattern.t * frame) list;
      (* The same for the patterns looked up in an instance's object frame. *)
  every_frame : bool;
      (* A bottom level: the frame of every material is kept ([plain]),
         for the patterns its instances give it. *)
  mutable plain : (int * frame) list;
  known : int Materials.t;
}

let registry ~every_frame = { added = []; count = 0; frames = []; placed = []; every_frame; plain = []; known = Materials.create 64 }

(* A new material: [frame ()] is its object's [Shape.pattern_frame], asked
   only if it has a pattern (a mesh's scans every vertex), or in a bottom
   level (one object). *)
let add_material r (m : Material.t) frame =
  r.added <- m :: r.added;
  (match m.pattern with
  | Some p -> r.frames <- (r.count, p, frame ()) :: r.frames
  | None -> if r.every_frame then r.plain <- (r.count, frame ()) :: r.plain);
  r.count <- r.count + 1;
  r.count - 1

(* A material seen through an instance, whose pattern, if any, lies in
   the object's frame [frame]: the kernel looks it up on the ray carried
   there, with [Prepared.instances]'s [placed_alternate]. *)
let placed_material r (m : Material.t) frame =
  match m.pattern with
  | None -> None
  | Some p ->
      r.added <- m :: r.added;
      r.placed <- (r.count, p, frame) :: r.placed;
      r.count <- r.count + 1;
      Some (r.count - 1)

(* Equal materials share one: a million spheres use a dozen. Equal bit
   for bit, so that sharing changes no arithmetic. Plain ones only: a
   pattern lies in its object's frame, and a transparent material names
   its object's medium (Ray_tree). *)
let new_material r (m : Material.t) frame =
  if Option.is_some m.pattern || m.transparency > 0. then add_material r m frame
  else
    match Materials.find_opt r.known m with
    | Some i -> i
    | None ->
        let i = add_material r m frame in
        Materials.add r.known m i;
        i

(* The materials, the [alternate] of each and the patterns. A patterned
   material's second colour is a material of its own, after the scene's:
   the tracer picks one of the two indices, so that the colour channels
   stay in the arrays they are read from. *)
let material_table r =
  let materials = Array.of_list (List.rev r.added) in
  let n_own = Array.length materials in
  let n = n_own + List.length r.frames + List.length r.placed in
  (* Over every material, the second colours' too: the kernel asks the
     world's table about a material an instance's pattern chose. *)
  let alternates l = if l = [] then [||] else Array.make n (-1) in
  (* A textured material's colour is looked up where a pattern's is: a
     textured scene has an [alternate], which marks its textured
     materials, so that the tracer takes the same path, and a hit on an
     untextured material there asks nothing more than before. *)
  let textured = List.exists (fun (m : Material.t) -> Option.is_some m.texture) r.added in
  let alternate = if textured && r.frames = [] then Array.make n (-1) else alternates r.frames in
  Array.iteri (fun i (m : Material.t) -> if Option.is_some m.texture then alternate.(i) <- textured_material) materials;
  let placed = alternates r.placed in
  let pattern = Array.make (if r.frames = [] && r.placed = [] && not r.every_frame then 0 else Pattern.stride * n_own) 0. in
  (* A bottom level's frames: its instances' patterns lie there. *)
  List.iter (fun (i, (origin, scale, extent)) -> Pattern.store_frame ~origin ~scale ~extent pattern (Pattern.stride * i)) r.plain;
  let second alternate j (i, p, (origin, scale, extent)) =
    alternate.(i) <- n_own + j;
    Pattern.store p ~origin ~scale ~extent pattern (Pattern.stride * i);
    Material.update ~color:(Pattern.color p) ~pattern:None materials.(i)
  in
  let extra = List.mapi (second alternate) (List.rev r.frames) in
  let n_world = List.length extra in
  let extra' = List.mapi (fun j f -> second placed (n_world + j) f) (List.rev r.placed) in
  (Array.concat [ materials; Array.of_list extra; Array.of_list extra' ], alternate, placed, pattern)

(* {2 Textures} *)

let mapping_code = function
  | Texture_map.Spherical -> spherical
  | Planar -> planar
  | Box -> box_mapping
  | Uv -> uv_mapping

(* Each material's texture number, and the textures: a texture that
   several materials show (a named material on many objects) is one, an
   image that several textures show (one file, which the reader reads
   once) is one, found by physical equality. *)
let texture_tables (materials : Material.t array) =
  if not (Array.exists (fun (m : Material.t) -> Option.is_some m.texture) materials) then ([||], [||], [||], [||])
  else begin
    let entries = ref [] and n = ref 0 and images = ref [] and n_images = ref 0 in
    let image_number img =
      match List.find_opt (fun (i, _) -> i == img) !images with
      | Some (_, k) -> k
      | None ->
          images := (img, !n_images) :: !images;
          incr n_images;
          !n_images - 1
    in
    let same (a : Texture_map.t) (b : Texture_map.t) = a.image == b.image && a.mapping = b.mapping && Float.equal a.size b.size in
    let texture_of =
      Array.map
        (fun (m : Material.t) ->
          match m.texture with
          | None -> -1
          | Some t -> (
              match List.find_opt (fun (t', _) -> same t' t) !entries with
              | Some (_, k) -> k
              | None ->
                  entries := (t, !n) :: !entries;
                  incr n;
                  !n - 1))
        materials
    in
    let table = Array.make (texture_stride * !n) 0 and size = Array.make !n 1. in
    List.iter
      (fun ((t : Texture_map.t), k) ->
        let o = texture_stride * k in
        table.(o) <- image_number t.image;
        table.(o + 1) <- Texture.width t.image;
        table.(o + 2) <- Texture.height t.image;
        table.(o + 3) <- mapping_code t.mapping;
        size.(k) <- t.size)
      (List.rev !entries);
    (* [images] holds the last number first. *)
    let texels = Array.of_list (List.rev_map (fun (img, _) -> Texture.channels img) !images) in
    (texture_of, table, size, texels)
  end

(* Per slot, the [vt] of the corners of each triangle of a mesh whose
   material has a uv texture, in the order of its corners (the order of
   [at0], [at1], [at2]); empty when no such mesh. In a bottom level
   ([every_frame]), of every mesh with [vt]: an instance's own material
   may lay a uv texture on it. *)
let uv_table ~every_frame o (sl_slot : int array) n_slots =
  let uv_mesh = function
    | Shape.Mesh (m : Mesh.t) -> (
        Mesh.has_texcoords m
        && (every_frame || match m.material.texture with Some { mapping = Texture_map.Uv; _ } -> true | _ -> false))
    | _ -> false
  in
  if not (List.exists uv_mesh o.shapes) then [||]
  else begin
    let uv = Array.make (6 * n_slots) 0. in
    ignore
      (iter_shapes o
         ~single:(fun _ _ -> ())
         ~mesh:(fun k m ->
           if uv_mesh (Shape.Mesh m) then begin
             let k = ref k in
             for t = 0 to Mesh.triangle_count m - 1 do
               if not (Mesh.degenerate m t) then begin
                 let i = sl_slot.(!k) in
                 if i >= 0 && i < n_slots then Mesh.store_texcoords m t uv (6 * i);
                 incr k
               end
             done
           end));
    uv
  end

(* {2 Vertices and normals} *)

type vertices = {
  vertex : float array;
      (* The triangles' vertices: each mesh's placed positions at its base
         (a scene's one mesh's own array, not a copy), then the lone
         triangles, 9 floats each, from [lone_base]. *)
  bases : (Mesh.t * int) list;  (* Each mesh's base. *)
  lone_base : int;
  follow : bool;
      (* Each smooth mesh's corners name their normals by their vertices'
         numbers (an OBJ file's [f 1//1 2//2 3//3]): the unit normals lie
         parallel to [vertex], and a corner's normal is where its vertex
         is: no table of the corners' normals. *)
  vnormal : float array;
      (* The smooth meshes' normals, divided by their lengths once for all
         the corners that share them ([mesh_run] writes them). *)
}

let vertices o =
  let bases, lone_base =
    List.fold_left
      (fun (bases, n) sh -> match sh with Shape.Mesh m -> ((m, n) :: bases, n + Array.length m.positions) | _ -> (bases, n))
      ([], 0) o.shapes
  in
  let n_lone = List.length (List.filter (function Shape.Triangle _ -> true | _ -> false) o.shapes) in
  let vertex =
    match bases with
    | [ (m, _) ] when n_lone = 0 -> m.positions
    | _ ->
        let v = Array.make (lone_base + (9 * n_lone)) 0. in
        List.iter (fun ((m : Mesh.t), b) -> Array.blit m.positions 0 v b (Array.length m.positions)) bases;
        v
  in
  let follow =
    List.for_all
      (function Shape.Mesh m when m.smooth -> m.triangle_normals == m.triangles || m.triangle_normals = m.triangles | _ -> true)
      o.shapes
  in
  let vnormal =
    Array.make
      (if follow then
         if List.exists (function Shape.Mesh m -> m.smooth | _ -> false) o.shapes then Array.length vertex else 0
       else List.fold_left (fun a sh -> match sh with Shape.Mesh m when m.smooth -> a + Array.length m.normals | _ -> a) 0 o.shapes)
      nan
  in
  { vertex; bases; lone_base; follow; vnormal }

let vertex_base v m = List.assq m v.bases

(* {2 Kinds, materials and cubes of the objects} *)

(* The spheres' materials, centers and radii (their kind is already
   [Kind.Sphere]). The spheres' plain materials are distinct in their
   table: the first sphere of each finds or makes the prepared material,
   the others reuse its number (what [new_material] would find). *)
let sphere_objects o r omat c =
  let spheres = o.spheres in
  let sphere_materials = Spheres.materials spheres in
  let shared = Array.make (Array.length sphere_materials) (-1) in
  (* Each sphere's material, first as its index in the spheres' table. *)
  Spheres.blit_fields spheres ~x:c.ocx ~y:c.ocy ~z:c.ocz ~radius:c.ohalf ~material:omat;
  for k = 0 to o.n_spheres - 1 do
    let j = omat.(k) in
    omat.(k) <-
      (if shared.(j) >= 0 then shared.(j)
       else
         let m = sphere_materials.(j) in
         let i = new_material r m (fun () -> Shape.leaf_pattern_frame (Csg.Sphere (Spheres.get spheres k))) in
         if Option.is_none m.pattern && not (m.transparency > 0.) then shared.(j) <- i;
         i)
  done

(* {2 Instances}

   Each instance is a number in the table of instances: its bottom level
   (the prepared scene of its object, one per object however many
   instances share it: compared physically), its world-to-object matrix,
   and its materials in this scene's numbering. *)
type instancing = {
  mutable objects : (Shape.t * int) list;  (* Each bottom's object, and its number. *)
  mutable bottoms_rev : t list;
  mutable rows : (int * float array * int array) list;  (* Reversed: bottom, matrix, materials. *)
  mutable count : int;
  numbers : (int, int) Hashtbl.t;  (* Object [k]'s instance number. *)
  bottom_of : Shape.t -> t;
}

let instancing bottom_of = { objects = []; bottoms_rev = []; rows = []; count = 0; numbers = Hashtbl.create 8; bottom_of }

(* Adds object [k]'s instance [i]; its material number in this scene. *)
let add_instance r inst k (i : Shape.instance) =
  let b =
    match List.assq_opt i.shape inst.objects with
    | Some b -> b
    | None ->
        let b = List.length inst.objects in
        inst.objects <- (i.shape, b) :: inst.objects;
        inst.bottoms_rev <- inst.bottom_of i.shape :: inst.bottoms_rev;
        b
  in
  let bottom = List.nth inst.bottoms_rev (List.length inst.bottoms_rev - 1 - b) in
  (* The frame of the bottom level's material [j] (its object's, or its
     CSG leaf's): where a pattern on it lies. A second colour's material
     there ([j] past the frames) is never a hit's. *)
  let frame j = if Pattern.stride * j < Array.length bottom.pattern then Pattern.frame bottom.pattern (Pattern.stride * j) else (Vec3.zero, 1., 0.) in
  let plain () = invalid_arg "Prepared: a plain material has no frame" in
  let placed m j = match placed_material r m (frame j) with Some k -> k | None -> new_material r m plain in
  let map =
    match i.own_material with
    | Some m when Option.is_some m.pattern ->
        (* Its pattern on each surface of the object, in that surface's frame. *)
        Array.init (max 1 (Array.length bottom.materials)) (placed m)
    | Some m ->
        let j = new_material r m plain in
        Array.make (max 1 (Array.length bottom.materials)) j
    | None -> Array.mapi (fun j m -> placed m j) bottom.materials
  in
  inst.rows <- (b, Transform.to_object i.transform, map) :: inst.rows;
  Hashtbl.replace inst.numbers k inst.count;
  inst.count <- inst.count + 1;
  map.(0)

(* The bottom level of the instance [add_instance] added last (its row is
   the first: a thousand instances, no walk down the list). *)
let last_bottom inst =
  let b, _, _ = List.hd inst.rows in
  List.nth inst.bottoms_rev (List.length inst.bottoms_rev - 1 - b)

(* The box in the world of instance [i] whose bottom level is [bottom]
   (see [Prepared.instance_box] in the interface for why it holds every
   hit the bottom level reports): the root box of the bottom level's
   hierarchy (its object's box where it has none), its eight corners
   carried by the transform and rounded outward ([Transform.bounds]). *)
let instance_box (bottom : t) (i : Shape.instance) =
  let ((lo : Vec3.t), (hi : Vec3.t)) as box =
    match bottom.bvh with
    | Some b when Array.length bottom.unbounded = 0 ->
        let n = b.nodes and o = b.root in
        (Vec3.v n.(o) n.(o + 1) n.(o + 2), Vec3.v n.(o + 3) n.(o + 4) n.(o + 5))
    | _ -> Shape.box_bounds i.shape
  in
  let (lo' : Vec3.t), (hi' : Vec3.t) = Transform.bounds i.transform box in
  (* The corners' rounding, bounded from the terms of each product:
     [Transform.bounds]'s room scales with the world's coordinates, and a
     translation that brings a far object near the origin rounds at the
     scale of the translation. *)
  let m = Transform.to_world i.transform in
  let terms = ref 0. in
  List.iter
    (fun (x, y, z) ->
      for r = 0 to 2 do
        let o = 4 * r in
        let sum = Float.abs (m.(o) *. x) +. Float.abs (m.(o + 1) *. y) +. Float.abs (m.(o + 2) *. z) +. Float.abs m.(o + 3) in
        terms := Float.max !terms sum
      done)
    [ (lo.x, lo.y, lo.z); (lo.x, lo.y, hi.z); (lo.x, hi.y, lo.z); (lo.x, hi.y, hi.z); (hi.x, lo.y, lo.z); (hi.x, lo.y, hi.z); (hi.x, hi.y, lo.z); (hi.x, hi.y, hi.z) ];
  let room = 8. *. epsilon_float *. !terms in
  (Vec3.v (lo'.x -. room) (lo'.y -. room) (lo'.z -. room), Vec3.v (hi'.x +. room) (hi'.y +. room) (hi'.z +. room))

(* [instance_box] as its center, its half sides [hx, hy, hz] and its
   transform's stretch, in 7 floats, each half side grown an ulp at a time
   until the center minus it and plus it, rounded, hold the box (as
   [Shape.bounds] grows a cube's). *)
let instance_half_box bottom (i : Shape.instance) =
  let (lo : Vec3.t), (hi : Vec3.t) = instance_box bottom i in
  let c = Vec3.smul 0.5 (Vec3.add lo hi) in
  let half c lo hi =
    let rec grow h = if c -. h <= lo && c +. h >= hi then h else grow (Float.succ h) in
    grow (Float.max (c -. lo) (hi -. c))
  in
  [| c.x; c.y; c.z; half c.x lo.x hi.x; half c.y lo.y hi.y; half c.z lo.z hi.z; Transform.stretch i.transform |]

let instance_table inst placed_alternate =
  let rows = Array.of_list (List.rev inst.rows) in
  {
    bottoms = Array.of_list (List.rev inst.bottoms_rev);
    bottom = Array.map (fun (b, _, _) -> b) rows;
    to_object = Array.concat (List.map (fun (_, m, _) -> m) (Array.to_list rows));
    material_map = Array.map (fun (_, _, m) -> m) rows;
    placed_alternate;
  }

(* CSG solids go to their own table; [roots] maps object [k] to its
   solid's root node. *)
type solids = { builder : Csg.builder; roots : (int, int) Hashtbl.t }

(* Adds object [k]'s solid [c]: each leaf has its material (a leaf's
   pattern lies where the leaf's would as an object of its own); the
   object's is its first leaf's. *)
let add_csg r s k c =
  let first = ref (-1) in
  let material leaf m =
    (* Not shared: the first leaf's number names the solid's medium. [m]
       is the leaf's own, or a transformed operand's around it. *)
    let i = add_material r m (fun () -> Shape.leaf_pattern_frame leaf) in
    if !first < 0 then first := i;
    i
  in
  Hashtbl.replace s.roots k (Csg.add s.builder ~material c);
  !first

(* A mesh's triangles come in a run: one material for the run. A mesh
   given twice in a row (the same value) is one run: one material, its
   normals once. [normal_base] maps the first object of a smooth mesh's
   run to the offset of its normals in [vnormal]. *)
type runs = {
  mutable last : (Mesh.t * int * int) option;  (* The mesh, its material, its normals' base. *)
  mutable next_normal : int;
  normal_base : (int, int) Hashtbl.t;
}

(* The material and the normals' base of mesh [m]'s run from object [k],
   its normals divided by their lengths if it starts a run. *)
let mesh_run r v runs k (m : Mesh.t) =
  match runs.last with
  | Some (m', i, base) when m' == m -> (i, base)
  | _ ->
      let i = new_material r m.material (fun () -> Shape.pattern_frame (Shape.Mesh m)) in
      let base = if v.follow then vertex_base v m else runs.next_normal in
      if m.smooth then begin
        (* Parallel to [vertex], the normals that no vertex number names are not needed. *)
        let nn = Array.length m.normals / 3 in
        for j = 0 to (if v.follow then min nn (Array.length m.positions / 3) else nn) - 1 do
          ignore (Mesh.unit_normal m j v.vnormal (base + (3 * j)))
        done;
        runs.next_normal <- base + Array.length m.normals;
        Hashtbl.replace runs.normal_base k base
      end;
      runs.last <- Some (m, i, base);
      (i, base)

(* The kinds and materials of mesh [m]'s objects from [k], in a loop of
   the mesh's own: it has millions of triangles. *)
let mesh_objects r v runs okind omat k (m : Mesh.t) =
  let mat, base = mesh_run r v runs k m in
  (* Smooth where every corner has a normal that could be divided by its
     length ([Mesh.corner_normals]). *)
  let tn = m.triangle_normals in
  let usable t c =
    let j = tn.((3 * t) + c) in
    j >= 0 && not (Float.is_nan v.vnormal.(base + (3 * j)))
  in
  let k = ref k in
  for t = 0 to Mesh.triangle_count m - 1 do
    if not (Mesh.degenerate m t) then begin
      okind.(!k) <- (if m.smooth && usable t 0 && usable t 1 && usable t 2 then Kind.Smooth_triangle else Kind.Triangle);
      omat.(!k) <- mat;
      incr k
    end
  done

(* The kinds, materials and cubes of the objects after the spheres; the
   result is the base of each smooth mesh's normals ([runs.normal_base]). *)
let shape_objects o r v s inst okind omat c =
  let runs = { last = None; next_normal = 0; normal_base = Hashtbl.create 8 } in
  ignore
    (iter_shapes o
       ~single:(fun k sh ->
         okind.(k) <- Shape.kind sh;
         omat.(k) <-
           (match sh with
           | Shape.Csg cs -> add_csg r s k cs
           | Shape.Instance i -> add_instance r inst k i
           | _ -> new_material r (Shape.material sh) (fun () -> Shape.pattern_frame sh));
         let (center : Vec3.t), h =
           match sh with
           | Shape.Instance i ->
               (* After [add_instance]: its bottom level is prepared. *)
               let b = instance_half_box (last_bottom inst) i in
               Hashtbl.replace c.oboxes k b;
               (Vec3.v b.(0) b.(1) b.(2), Float.max b.(3) (Float.max b.(4) b.(5)))
           | _ -> single_bounds sh
         in
         if k < Array.length c.ocx then begin
           c.ocx.(k) <- center.x;
           c.ocy.(k) <- center.y;
           c.ocz.(k) <- center.z;
           c.ohalf.(k) <- h
         end)
       ~mesh:(mesh_objects r v runs okind omat));
  runs.normal_base

(* {2 Twins and the hierarchy} *)

(* The objects kept (each sphere but the twins of earlier ones) that are
   bounded, in object order, for the hierarchy, their number [nb], the
   first of them, and the planes ([unbounded]). Where every object is kept
   and bounded (no twins, no planes: the big scenes), or, in a scene with
   a mesh, the bounded objects follow each other (the planes before the
   mesh, or after it), [bounded] is empty: they are objects [first] to
   [first + nb - 1], and no array of a million numbers is made, read
   through (the slots' objects), or marked by the collections. *)
type selection = { bounded : int array; unbounded : int array; nb : int; first : int }

let[@inline] kept twin_of k = Array.length twin_of = 0 || twin_of.(k) = k

let select o okind twin_of =
  let n = o.n in
  let is_bounded k = kept twin_of k && Kind.bounded okind.(k) in
  let nb = ref 0 and planes = ref [] in
  for k = 0 to n - 1 do
    if kept twin_of k then if not (Kind.bounded okind.(k)) then planes := k :: !planes else incr nb
  done;
  let unbounded = Array.of_list (List.rev !planes) in
  (* The first and the last bounded object, looked for from each end. *)
  let first = ref 0 and last = ref (n - 1) in
  if o.any_mesh && !nb > 0 && !nb < n then begin
    while not (is_bounded !first) do incr first done;
    while not (is_bounded !last) do decr last done
  end;
  if !nb = n then { bounded = [||]; unbounded; nb = n; first = 0 }
  else if o.any_mesh && !nb > 0 && !last - !first + 1 = !nb then { bounded = [||]; unbounded; nb = !nb; first = !first }
  else { bounded = indices_where n !nb is_bounded; unbounded; nb = !nb; first = 0 }

(* A big scene's loading left garbage in pieces (the text's windows, the
   spheres' blocks, which the caller no longer holds: see
   [prepare_scene]), too small for the hierarchy's arrays of a million:
   compacted before the hierarchy, the heap does not grow past them; after
   it, a collection lets the slot-order arrays reuse its build's arrays. A
   mesh's scene was compacted before its per-object arrays
   ([compact_after_loading]): here a compaction would only move them, and
   where spheres are few there is no garbage yet to collect before the
   hierarchy. [collections] counts the calls. *)
let collect o collections =
  if o.n > big_scene then begin
    if !collections > 0 then Gc.full_major ()
    else if not o.any_mesh then (if o.n_spheres > o.n / 2 then Gc.compact () else Gc.full_major ())
    else if o.n_spheres > o.n / 2 then Gc.full_major ();
    incr collections
  end

(* A big mesh's loading left garbage (the OBJ reader's blocks, the
   positions before their placement) as big as the mesh, in pieces the
   per-object arrays do not fit in: compacted before them, the heap is
   the mesh's arrays and grows from there. So does a big mesh as a CSG
   operand, in a scene of few objects. *)
let compact_after_loading o =
  if (o.any_mesh && o.n > big_scene) || o.csg_triangles > big_scene then Gc.compact ()

(* The boxes of the selected objects, each padded by its margin, as
   [Bvh.build_boxes] takes them; [None] without a hierarchy. *)
let boxes ~skips o (scene : Scene.view) c sel =
  if not (skips && sel.nb > bvh_threshold) then None
  else
    let all = Array.length sel.bounded = 0 and nb = sel.nb and bounded = sel.bounded in
    let { ocx; ocy; ocz; ohalf; _ } = c in
    if o.any_mesh then
      let mterms = ref None in
      let b = mesh_boxes ~mterms o scene ~all ~first:sel.first ~bounded ~nb ~cx:ocx ~cy:ocy ~cz:ocz ~radius:ohalf ~oboxes:c.oboxes in
      c.mterms <- !mterms;
      Some b
    else begin
      (* [among], not copies of the arrays: a million objects make 8 MB an array. *)
      let terms =
        let reach = lens_reach scene.camera in
        if all then Bvh.margin_terms ~reach ~cx:ocx ~cy:ocy ~cz:ocz ~radius:ohalf scene.camera.position
        else Bvh.margin_terms ~among:bounded ~reach ~cx:ocx ~cy:ocy ~cz:ocz ~radius:ohalf scene.camera.position
      in
      (* Each box padded by its margin, in a loop: [Array.mapi]'s
         function would return each float boxed. *)
      let f () = Array.create_float nb in
      let x0 = f () and y0 = f () and z0 = f () and x1 = f () and y1 = f () and z1 = f () in
      if Hashtbl.length c.oboxes = 0 then
        for i = 0 to nb - 1 do
          let k = if all then i else bounded.(i) in
          let e = ohalf.(k) +. Bvh.margin terms ohalf.(k) in
          x0.(i) <- ocx.(k) -. e;
          y0.(i) <- ocy.(k) -. e;
          z0.(i) <- ocz.(k) -. e;
          x1.(i) <- ocx.(k) +. e;
          y1.(i) <- ocy.(k) +. e;
          z1.(i) <- ocz.(k) +. e
        done
      else
        for i = 0 to nb - 1 do
          let k = if all then i else bounded.(i) in
          let h = ohalf.(k) in
          let hx, hy, hz, m =
            match Hashtbl.find_opt c.oboxes k with
            | Some b -> (b.(3), b.(4), b.(5), instance_margin terms b)
            | None -> (h, h, h, Bvh.margin terms h)
          in
          x0.(i) <- ocx.(k) -. (hx +. m);
          y0.(i) <- ocy.(k) -. (hy +. m);
          z0.(i) <- ocz.(k) -. (hz +. m);
          x1.(i) <- ocx.(k) +. (hx +. m);
          y1.(i) <- ocy.(k) +. (hy +. m);
          z1.(i) <- ocz.(k) +. (hz +. m)
        done;
      Some (x0, y0, z0, x1, y1, z1)
    end

(* The twins ([twin_table]), the selection and the boxes. With two cores,
   a child finds a big scene's twins while this process selects and pads
   the boxes as if there were none: twins are rare, and where a child
   finds some, their selection and boxes are made again (twins are exact
   copies: the margins' terms would be the same, but the boxes are of
   fewer objects). *)
let twins_and_boxes ~skips ?beside o scene okind c collections =
  let find_twins () = sphere_twins ~cx:c.ocx ~cy:c.ocy ~cz:c.ocz ~radius:c.ohalf ~n_spheres:o.n_spheres in
  match (beside : Bvh.beside option) with
  | Some b when o.n_spheres >= b.min_objects && b.idle () -> (
      (* Started before the collection: started after it, the child
         shares the compacted heap, and writing the boxes there copied
         its pages. *)
      let wait = b.beside find_twins in
      let selected = select o okind [||] in
      collect o collections;
      let guess = boxes ~skips o scene c selected in
      let pairs = match wait () with Some pairs -> pairs | None -> find_twins () in
      match pairs with
      | [||] -> ([||], selected, guess)
      | _ ->
          let twin_of = twin_table pairs o.n in
          let selected = select o okind twin_of in
          (twin_of, selected, boxes ~skips o scene c selected))
  | _ ->
      let twin_of = twin_table (find_twins ()) o.n in
      let selected = select o okind twin_of in
      collect o collections;
      (twin_of, selected, boxes ~skips o scene c selected)

(* The build's six arrays of boxes, which it leaves in slot order and
   does not keep: arrays of floats of their length made after it are made
   in their memory, not taken from the system once more (the garbage
   collector would find no room for them among the freed ones). *)
type pool = { mutable spare : float array list }

(* An array of [len] floats, every one of which the caller writes. *)
let floats pool len =
  match pool.spare with
  | a :: rest when Array.length a = len ->
      pool.spare <- rest;
      a
  | _ -> Array.create_float len

(* The hierarchy over [boxes]; with [reuse] (spheres alone, each with a
   slot: the arrays of their number made later fit the boxes'), the
   boxes' arrays go to [pool]; otherwise they are let go, for the arrays
   of other lengths made later, but with [scratch] (every object in the
   hierarchy) one of them, [slots]'s scratch. *)
let hierarchy ?beside ~reuse ~scratch ~instances pool boxes =
  match boxes with
  | None -> None
  | Some (x0, y0, z0, x1, y1, z1) ->
      (* Where instances are most of the objects, leaves of one: the
         heuristic prices a test as one box test, but an instance's is a
         walk of its bottom level's hierarchy (tens of box tests and
         more), and a leaf of 16 instances walked 16 of them
         (docs/performance.md, "Round 3: a thousand instances"). *)
      let leaf_size = if instances then 1 else 16 in
      (* Leaves of up to 16, where the surface area heuristic finds no
         cheaper split: a mesh's thin triangles overlap, and below 16 more
         boxes buy no fewer triangle tests (docs/performance.md, issue
         15's fifth round). The grids of spheres build the same trees as with 4.
         The image never depends on the tree (see [Trace.better]). *)
      let b = Bvh.build_boxes ?beside ~leaf_size ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 () in
      if reuse then pool.spare <- [ x0; y0; z0; x1; y1; z1 ] else if scratch then pool.spare <- [ x0 ];
      Some b

(* {2 Slots} *)

(* The object in each slot: the hierarchy's leaf order, then the planes;
   without a hierarchy, the objects kept, in order. *)
let index_of_slots o (bvh : Bvh.t option) sel twin_of =
  let n = o.n in
  match bvh with
  (* Every object in the hierarchy: its order is the slots' ([index] is
     only read), not copied. *)
  | Some b when sel.nb = n -> b.order
  | Some b ->
      let nb = Array.length b.order in
      let index = Array.make (nb + Array.length sel.unbounded) 0 in
      if Array.length sel.bounded = 0 then
        for i = 0 to nb - 1 do
          index.(i) <- sel.first + b.order.(i)
        done
      else
        for i = 0 to nb - 1 do
          index.(i) <- sel.bounded.(b.order.(i))
        done;
      Array.blit sel.unbounded 0 index nb (Array.length sel.unbounded);
      index
  | None when sel.nb = n ->
      let index = Array.make n 0 in
      for k = 0 to n - 1 do
        index.(k) <- k
      done;
      index
  | None ->
      let m = ref 0 in
      for k = 0 to n - 1 do
        if kept twin_of k then incr m
      done;
      indices_where n !m (kept twin_of)

type slots = {
  index : int array;
  slot : int array;
  kind : Kind.t array;  (* By slot. *)
  material : int array;  (* By slot. *)
  in_place : bool;
      (* Spheres alone, without twins: [index] orders every object, and
         the per-object arrays, put in slot order where they are, are the
         tracer's (no second array of a million). Not for meshes: their
         slot order is far from the object order, and moving in place
         along its cycles cost more than the copies. *)
}

(* A kind as a number, and back: [kinds.(kind_code k) = k]. *)
let kind_code : Kind.t -> int = function
  | Sphere -> 0
  | Triangle -> 1
  | Smooth_triangle -> 2
  | Plane -> 3
  | Box -> 4
  | Csg -> 5
  | Cylinder -> 6
  | Disk -> 7
  | Cone -> 8
  | Torus -> 9
  | Instance -> 10

let kinds =
  let a = Array.make (List.length Kind.all) Kind.Sphere in
  List.iter (fun k -> a.(kind_code k) <- k) Kind.all;
  a

(* The slot of each object ([slot]; a twin's is its first's) and each
   slot's kind and material. *)
let slots o pool index okind omat twin_of =
  let n = o.n and n_kept = Array.length index in
  let in_place = n_kept = n && o.shapes = [] in
  let slot = Array.make n 0 in
  (* A mesh's objects each with a slot, and a scratch (a box array of
     the build, [hierarchy]): [okind] and [omat] put in slot order where
     they are, through the scratch, not copied into two more arrays (16
     MB for a million triangles, made where the peak is). *)
  let gathered = (not in_place) && n_kept = n && Array.length twin_of = 0 && List.exists (fun a -> Array.length a = n) pool.spare in
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
    else if gathered then begin
      let fs = floats pool n in
      for i = 0 to n - 1 do
        let k = index.(i) in
        slot.(k) <- i;
        Array.unsafe_set fs i (Float.of_int (kind_code okind.(k)))
      done;
      for i = 0 to n - 1 do
        okind.(i) <- kinds.(truncate (Array.unsafe_get fs i))
      done;
      gather_in_place index ~scratch:fs ~floats:[||] ~ints:[| omat |];
      (okind, omat)
    end
    else begin
      let kind = Array.make n_kept Kind.Sphere and material = Array.make n_kept 0 in
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
  { index; slot; kind; material; in_place }

(* {2 Geometry, in slot order} *)

type geometry = {
  geom : float array;
  extent : float array;
  at0 : int array;
  at1 : int array;
  at2 : int array;
  vcorner : int array;
}

(* The shapes' arrays, by slot, to be written by [store_geometry]. *)
let geometry_arrays o sl ~any_smooth ~follow =
  let n_kept = Array.length sl.index in
  (* Spheres alone need no table of shapes. *)
  let shapes_len = if o.shapes = [] then 0 else n_kept in
  (* Triangles are read from [vertex]; the other shapes, few, have [geom]. *)
  let n_geom = List.length (List.filter (function Shape.Triangle _ | Shape.Mesh _ -> false | _ -> true) o.shapes) in
  let geom = Array.make (Kind.stride * n_geom) 0. and extent = Array.make n_geom 0. in
  (* Three arrays, not one of three ints a slot: made after the
     hierarchy, each fits where one of its build's arrays was. *)
  let at0 = Array.make shapes_len 0 and at1 = Array.make shapes_len 0 and at2 = Array.make shapes_len 0 in
  let vcorner = if any_smooth && not follow then Array.make (3 * n_kept) 0 else [||] in
  { geom; extent; at0; at1; at2; vcorner }

(* The slots of mesh [m]'s triangles from object [k]: their corners'
   offsets in [vertex], and in [vnormal] (in [vcorner]) where the normals
   do not follow the vertices. [run] holds the last mesh and the base of
   its normals. *)
let store_mesh v normal_base sl g ~any_smooth run k (m : Mesh.t) =
  let vb = vertex_base v m and tri = m.triangles in
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
      let i = sl.slot.(!k) in
      g.at0.(i) <- vb + (3 * tri.(3 * t));
      g.at1.(i) <- vb + (3 * tri.((3 * t) + 1));
      g.at2.(i) <- vb + (3 * tri.((3 * t) + 2));
      if any_smooth && not v.follow then
        for c = 0 to 2 do
          g.vcorner.((3 * i) + c) <- base + (3 * max 0 m.triangle_normals.((3 * t) + c))
        done;
      incr k
    end
  done

(* Each shape's geometry where its slot says: a lone triangle's corners
   in [vertex], and their offsets; a mesh's ([store_mesh]); another
   shape's in [geom] and [extent] (a CSG solid's root node in [geom]). *)
let store_geometry o v s inst normal_base sl g ~any_smooth =
  let stride = Kind.stride in
  let next_geom = ref 0 and next_lone = ref v.lone_base in
  let extent_of i =
    let e = ref 0. in
    for j = stride * i to (stride * i) + stride - 1 do
      e := fmax !e (Float.abs g.geom.(j))
    done;
    g.extent.(i) <- !e
  in
  ignore
    (iter_shapes o
       ~single:(fun k sh ->
         let i = sl.slot.(k) in
         match sh with
         | Shape.Triangle tri ->
             let o = !next_lone in
             Triangle.store tri v.vertex o;
             g.at0.(i) <- o;
             g.at1.(i) <- o + 3;
             g.at2.(i) <- o + 6;
             next_lone := o + 9
         | _ -> (
             let j = !next_geom in
             incr next_geom;
             g.at0.(i) <- j;
             match sh with
             | Shape.Csg c ->
                 g.geom.(stride * j) <- Float.of_int (Hashtbl.find s.roots k);
                 g.extent.(j) <- Csg.extent c
             | Shape.Instance i ->
                 g.geom.(stride * j) <- Float.of_int (Hashtbl.find inst.numbers k);
                 (* The hit point's rounding grows with the world's
                    coordinates and with how much the transform can
                    stretch a relative error ([Transform.stretch]). *)
                 let (lo : Vec3.t), (hi : Vec3.t) = Shape.box_bounds sh in
                 let big (p : Vec3.t) = Float.max (Float.abs p.x) (Float.max (Float.abs p.y) (Float.abs p.z)) in
                 g.extent.(j) <- Float.max (big lo) (big hi) *. Transform.stretch i.transform
             | _ ->
                 Shape.store sh g.geom (stride * j);
                 extent_of j))
       ~mesh:(store_mesh v normal_base sl g ~any_smooth (ref None)))

(* The spheres' data by slot (empty without spheres; [0.] for the slots
   of other shapes). *)
type spheres_by_slot = {
  cx : float array;
  cy : float array;
  cz : float array;
  radius : float array;
  r2 : float array;
  primary_ocx : float array;
  primary_ocy : float array;
  primary_ocz : float array;
  primary_k3 : float array;
}

(* The spheres' centers and radii by slot, from [c]. *)
let sphere_arrays o pool sl c =
  let n = o.n and n_kept = Array.length sl.index and index = sl.index in
  let { ocx; ocy; ocz; ohalf; _ } = c in
  if sl.in_place && List.length pool.spare >= 5 then begin
    (* Into four of the build's arrays, in one walk of [index]; the
       object-order arrays then serve the arrays made later. *)
    let cx = floats pool n and cy = floats pool n and cz = floats pool n and radius = floats pool n in
    for i = 0 to n - 1 do
      let k = index.(i) in
      cx.(i) <- ocx.(k);
      cy.(i) <- ocy.(k);
      cz.(i) <- ocz.(k);
      radius.(i) <- ohalf.(k)
    done;
    let scratch = floats pool n in
    gather_in_place index ~scratch ~floats:[||] ~ints:[| sl.material |];
    pool.spare <- scratch :: ocx :: ocy :: ocz :: ohalf :: pool.spare;
    (cx, cy, cz, radius)
  end
  else if sl.in_place then begin
    gather_in_place index ~scratch:(floats pool n_kept) ~floats:[| ocx; ocy; ocz; ohalf |] ~ints:[| sl.material |];
    (ocx, ocy, ocz, ohalf)
  end
  else begin
    let sphere_len = if o.n_spheres > 0 then n_kept else 0 in
    let cx = Array.make sphere_len 0. and cy = Array.make sphere_len 0. in
    let cz = Array.make sphere_len 0. and radius = Array.make sphere_len 0. in
    for i = 0 to sphere_len - 1 do
      let k = index.(i) in
      (* The slot's kind: [okind] may be in slot order ([slots]). *)
      if sl.kind.(i) = Kind.Sphere then begin
        cx.(i) <- ocx.(k);
        cy.(i) <- ocy.(k);
        cz.(i) <- ocz.(k);
        radius.(i) <- ohalf.(k)
      end
    done;
    (cx, cy, cz, radius)
  end

(* The spheres' squared radii and the constants of camera rays, by slot;
   the pool is emptied. *)
let camera_constants pool (eye : Vec3.t) (cx, cy, cz, radius) =
  let len = Array.length cx in
  (* Loops, not [Array.map]: its function returns each float boxed. *)
  let r2 = floats pool len in
  let primary_ocx = floats pool len in
  let primary_ocy = floats pool len in
  let primary_ocz = floats pool len in
  let primary_k3 = floats pool len in
  pool.spare <- [];
  for i = 0 to len - 1 do
    let r = radius.(i) in
    r2.(i) <- r *. r;
    let x = eye.x -. cx.(i) and y = eye.y -. cy.(i) and z = eye.z -. cz.(i) in
    primary_ocx.(i) <- x;
    primary_ocy.(i) <- y;
    primary_ocz.(i) <- z;
    (* Same operands in the same order as the tracer's per-ray [k3]. *)
    primary_k3.(i) <- ((x *. x) +. (y *. y) +. (z *. z)) -. (r *. r)
  done;
  { cx; cy; cz; radius; r2; primary_ocx; primary_ocy; primary_ocz; primary_k3 }

(* Objects are numbered above spheres first; the kernel's numbers
   ([index], [slot]: ties, hits) count them in the scene's list. [rank]
   maps the one to the other, where they differ (a shape placed before a
   sphere). *)
let in_list_order o ~index ~slot =
  if List.for_all (fun (j, _) -> j = o.n_spheres) o.placed then (index, slot)
  else begin
    let n = Array.length slot in
    let rank = Array.make n 0 and r = ref 0 and sphere = ref 0 and k = ref o.n_spheres in
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
      o.placed;
    spheres_upto o.n_spheres;
    let listed = Array.make n 0 in
    Array.iteri (fun k i -> listed.(rank.(k)) <- i) slot;
    (Array.map (fun k -> rank.(k)) index, listed)
  end

(* With [prepare]'s [cut]: the hierarchy with its leaves of a mesh's
   triangles cut by a plane where the surface area heuristic finds it
   pays ([Bvh.split_leaves]):
   the long thin triangles of a fine mesh, whose boxes are far bigger
   than they are, tested only where the ray meets the box of their part
   on the side it crosses. Each part's box is padded by twice its
   triangle's margin ([mesh_boxes] pads the whole triangle's box by one:
   a cut corner's rounding is a few units in the last place of the
   coordinates, far below it), so that a ray that hits a triangle meets
   the box of a part that holds the hit, as it met the triangle's box.
   Slots are shared, not copied: both sides' leaves name slots of the
   same range, and a ray that meets both tests their common triangles
   twice (the same answer twice). *)
let cut_leaves bvh c ~kind ~vertex g =
  match (bvh, c.mterms) with
  | Some b, Some margin ->
      let n = Array.length kind in
      let triangle s = s < n && Kind.is_triangle kind.(s) in
      Some (Bvh.split_leaves b ~triangle ~vertex ~at0:g.at0 ~at1:g.at1 ~at2:g.at2 ~margin)
  | _ -> bvh

(* {2 The prepared scene} *)

(* The [light_stride] floats of a light's geometry in [light_geom]. *)
let light_geom l =
  let v3 (v : Vec3.t) = [ v.x; v.y; v.z ] in
  let fields =
    match l with
    | Light.Area { corner; edge1; edge2; _ } -> v3 corner @ v3 edge1 @ v3 edge2
    | Sphere { position; radius; _ } -> v3 position @ [ radius ]
    | Spot { position; direction; angle; falloff; _ } ->
        (* The cone's edge as a cosine: the kernel compares cosines. *)
        v3 position @ v3 (Vec3.unit direction) @ [ Float.cos (angle *. Float.pi /. 180.); falloff ]
    | Ambient _ | Point _ | Directional _ -> []
  in
  Array.of_list (fields @ List.init (light_stride - List.length fields) (fun _ -> 0.))

(* A light's point or vector in [lx], [ly], [lz]: a point light's, sphere
   light's or spotlight's position, an area light's corner, a directional
   light's direction. *)
let light_vector = function
  | Light.Ambient _ -> Vec3.zero
  | Point { position; _ } | Sphere { position; _ } | Spot { position; _ } -> position
  | Area { corner; _ } -> corner
  | Directional { direction; _ } -> direction

(* A light's code in [light_kind]. *)
let light_kind = function
  | Light.Ambient _ -> ambient
  | Point _ -> point
  | Directional _ -> directional
  | Area _ -> area
  | Sphere _ -> sphere
  | Spot _ -> spot

(* The document's kernel's six floats a light ([Prepared.light6]). *)
let light6 lights =
  Array.concat
    (List.map
       (fun l ->
         let v = light_vector l in
         [|
           (match l with Light.Ambient _ -> 0. | Directional _ -> infinity | _ -> 1.);
           Light.intensity l;
           v.x;
           v.y;
           v.z;
           sqrt ((v.x *. v.x) +. (v.y *. v.y) +. (v.z *. v.z));
         |])
       (Array.to_list lights))

(* The record, from the steps' results; the lights' and the materials'
   arrays made here. *)
let assemble ~skips (scene : Scene.view) o ~max_channel ~materials ~alternate ~pattern ~bvh ~unbounded ~csg ~instances sl g sp
    ~vertex ~vsource ~vnormal ~uv ~casters =
  (* Each light with its place in the scene's list, which keys its
     samples (Light, "Sample points"): dropping a dark light changes no
     other light's numbers. *)
  let numbered =
    Array.of_list
      (List.filter (fun (_, l) -> (not skips) || Light.intensity l > 0.) (List.mapi (fun k l -> (k, l)) scene.lights))
  in
  let lights = Array.map snd numbered in
  let lf f = Array.map f lights and mf f = Array.map f materials in
  let soft = Array.exists (function Light.Ambient _ | Point _ | Directional _ -> false | _ -> true) lights in
  let transparent = Array.exists (fun (m : Material.t) -> m.transparency > 0.) materials in
  (* The document's own scenes: spheres of plain materials (no pattern, no
     glass), few enough for no hierarchy, in the document's mode. *)
  let textbook_all =
    o.shapes = [] && alternate = [||] && (not transparent) && bvh = None && scene.epsilon <> None
    && (not (Camera.has_lens scene.camera)) && not soft
  in
  let texture_of, texture_table, texture_size, texels = texture_tables materials in
  let n_kept = Array.length sl.index in
  let index, slot = in_list_order o ~index:sl.index ~slot:sl.slot in
  {
    n_spheres = o.n_spheres;
    n_objects = n_kept;
    all_spheres = o.shapes = [] && alternate = [||];
    patterned = alternate <> [||];
    alternate;
    pattern;
    textbook_all;
    index;
    slot;
    bvh;
    unbounded = Array.map (fun i -> sl.slot.(i)) unbounded;
    kind = sl.kind;
    geom = g.geom;
    vertex;
    at0 = g.at0;
    at1 = g.at1;
    at2 = g.at2;
    vnormal;
    vsource;
    vcorner = g.vcorner;
    extent = g.extent;
    csg;
    n_scene_objects = o.n;
    material = sl.material;
    cx = sp.cx;
    cy = sp.cy;
    cz = sp.cz;
    radius = sp.radius;
    r2 = sp.r2;
    red = mf (fun m -> m.Material.color.r);
    green = mf (fun m -> m.color.g);
    blue = mf (fun m -> m.color.b);
    specular = mf (fun m -> m.specular);
    specular_zero = mf (fun m -> if skips then specular_zero m.specular else 0.);
    reflective = mf (fun m -> m.reflective);
    n_lights = Array.length lights;
    light_kind = lf light_kind;
    light_number = Array.map fst numbered;
    light_geom = Array.concat (List.map light_geom (Array.to_list lights));
    light_su = lf (function Light.Area { samples_u; _ } -> samples_u | Sphere { samples; _ } -> samples | _ -> 1);
    light_sv = lf (function Light.Area { samples_v; _ } -> samples_v | _ -> 1);
    light_adaptive = lf Light.corners_first;
    light_uniform = lf (function Light.Area { sampling = Uniform; _ } -> true | _ -> false);
    light_intensity = lf Light.intensity;
    lx = lf (fun l -> (light_vector l).x);
    ly = lf (fun l -> (light_vector l).y);
    lz = lf (fun l -> (light_vector l).z);
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
    primary_ocx = sp.primary_ocx;
    primary_ocy = sp.primary_ocy;
    primary_ocz = sp.primary_ocz;
    primary_k3 = sp.primary_k3;
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
    (* A lens draws a point of its disc per camera sample; an area or
       sphere light, points of its surface. *)
    sampled = Camera.has_lens scene.camera || Array.exists Light.sampled lights;
    soft_lights = soft;
    umbra_skip = skips;
    casters;
    specular_cut = specular_cut ~skips materials lights;
    ambient_lead = fst (ambient_lead lights);
    first_light = snd (ambient_lead lights);
    (* The document's kernel reads a sphere, a camera ray's constants and a
       light from one array each: fewer pointers to keep in registers. *)
    sphere4 =
      (if textbook_all then
         Array.init (4 * n_kept) (fun k ->
             let i = k / 4 in
             match k mod 4 with 0 -> sp.cx.(i) | 1 -> sp.cy.(i) | 2 -> sp.cz.(i) | _ -> sp.r2.(i))
       else [||]);
    primary4 =
      (if textbook_all then
         Array.init (4 * n_kept) (fun k ->
             let i = k / 4 in
             match k mod 4 with
             | 0 -> sp.primary_ocx.(i)
             | 1 -> sp.primary_ocy.(i)
             | 2 -> sp.primary_ocz.(i)
             | _ -> sp.primary_k3.(i))
       else [||]);
    light6 = light6 lights;
    (* The viewport coordinates of each column and row of pixel centres,
       by the operations [Trace]'s primary ray does for any point. *)
    column_vx =
      Array.init scene.width (fun c ->
          Float.of_int (Canvas.x_of_column ~width:scene.width c) *. scene.viewport.width /. Float.of_int scene.width);
    row_vy =
      Array.init scene.height (fun r ->
          Float.of_int (r - (scene.height / 2)) *. scene.viewport.height /. Float.of_int scene.height);
    instances;
    materials;
    texture_of;
    texture_table;
    texture_size;
    texels;
    uv;
  }

(* {2 The blockers' boxes, for the test that a point sees a light whole} *)

(* At most this many objects are each a box of [casters]; a scene of more
   takes its hierarchy's nodes at depth [caster_depth] (at most 16). *)
let max_casters = 16
let caster_depth = 4

(* The boxes ([lo], [hi]) of the scene's bounded objects, if at most
   [max_casters]: an axis-aligned box its own corners, any other object
   [Shape.box_bounds] (a sphere's cube), each grown by the margin of
   {!Bvh.ray_box_margin} for a sphere of its largest half side, the one
   the hierarchy's boxes take: no hit test of the kernel reports a hit
   outside (the textbook quadratic's rounding near a small sphere's
   outline above all). Made before the objects are let go; [None] for
   more objects, and for a scene with an instance, whose hits the kernel
   finds in a carried frame (its box's margin, {!instance_box}, is the
   hierarchy's: such a scene takes the nodes' boxes, or no test). *)
let object_casters (scene : Scene.view) =
  let bounded = List.filter Shape.bounded scene.shapes in
  let instance = function Shape.Instance _ -> true | _ -> false in
  if Spheres.length scene.spheres + List.length bounded > max_casters || List.exists instance bounded then None
  else
    let sp = scene.spheres in
    let spheres =
      List.init (Spheres.length sp) (fun i ->
          let r = Spheres.radius sp i and x = Spheres.center_x sp i and y = Spheres.center_y sp i and z = Spheres.center_z sp i in
          (Vec3.v (x -. r) (y -. r) (z -. r), Vec3.v (x +. r) (y +. r) (z +. r)))
    in
    let shape = function Shape.Box b -> (b.Box.min, b.Box.max) | s -> Shape.box_bounds s in
    let boxes = spheres @ List.map shape bounded in
    (* [D] and [M] of the margin: the boxes and the camera's lens. *)
    let reach = lens_reach scene.camera and (c : Vec3.t) = scene.camera.position in
    let b = [| c.x -. reach; c.y -. reach; c.z -. reach; c.x +. reach; c.y +. reach; c.z +. reach |] in
    List.iter
      (fun ((lo : Vec3.t), (hi : Vec3.t)) ->
        b.(0) <- Float.min b.(0) lo.x;
        b.(1) <- Float.min b.(1) lo.y;
        b.(2) <- Float.min b.(2) lo.z;
        b.(3) <- Float.max b.(3) hi.x;
        b.(4) <- Float.max b.(4) hi.y;
        b.(5) <- Float.max b.(5) hi.z)
      boxes;
    let terms = Bvh.margin_of_bounds b in
    let grown ((lo : Vec3.t), (hi : Vec3.t)) =
      let h = 0.5 *. Float.max (hi.x -. lo.x) (Float.max (hi.y -. lo.y) (hi.z -. lo.z)) in
      let e = Bvh.margin terms h in
      (Vec3.v (lo.x -. e) (lo.y -. e) (lo.z -. e), Vec3.v (hi.x +. e) (hi.y +. e) (hi.z +. e))
    in
    Some (List.map grown boxes)

(* The hierarchy's nodes at depth [caster_depth] (and its leaves above
   it): together they hold every bounded object. *)
let node_casters b =
  let box k = (Vec3.v (Bvh.lo b k 0) (Bvh.lo b k 1) (Bvh.lo b k 2), Vec3.v (Bvh.hi b k 0) (Bvh.hi b k 1) (Bvh.hi b k 2)) in
  let rec walk k d acc = if d = caster_depth || Bvh.tag b k >= 1 then box k :: acc else walk (k + 1) (d + 1) (walk (Bvh.link b k) (d + 1) acc) in
  walk 0 0 []

let largest (v : Vec3.t) = Float.max (Float.abs v.x) (Float.max (Float.abs v.y) (Float.abs v.z))

(* [casters] as {!t} documents it: the boxes in centre and half-side
   form, each half side grown by [2^-30] times the largest magnitude [M]
   of a coordinate of all of them (plus one), which covers the rounding
   of every hit the kernel reports in them; [M] first. *)
let casters ~skips ~few_casters (scene : Scene.view) bvh =
  let boxes = match (few_casters, bvh) with Some l, _ -> Some l | None, Some b -> Some (node_casters b) | None, None -> None in
  match boxes with
  | Some boxes when skips && List.exists Light.sampled scene.lights ->
      let m = List.fold_left (fun m ((lo : Vec3.t), (hi : Vec3.t)) -> Float.max m (Float.max (largest lo) (largest hi))) 0. boxes in
      let pad = (m +. 1.) *. 0x1p-30 in
      let a = Array.make (1 + (6 * List.length boxes)) m in
      List.iteri
        (fun i ((lo : Vec3.t), (hi : Vec3.t)) ->
          let o = 1 + (6 * i) in
          a.(o) <- 0.5 *. (lo.x +. hi.x);
          a.(o + 1) <- 0.5 *. (lo.y +. hi.y);
          a.(o + 2) <- 0.5 *. (lo.z +. hi.z);
          a.(o + 3) <- (0.5 *. (hi.x -. lo.x)) +. pad;
          a.(o + 4) <- (0.5 *. (hi.y -. lo.y)) +. pad;
          a.(o + 5) <- (0.5 *. (hi.z -. lo.z)) +. pad)
        boxes;
      a
  | _ -> [||]

(* The steps in order. Each big array is let go as soon as no step needs
   it any more: the steps' results are taken apart here, not held whole. *)
let rec prepare_scene ?(every_frame = false) ?(cut = false) ~skips ?beside scene =
  (* The settings alone: the objects of [scene] are let go below. *)
  let bottom_scene = Scene.bottom scene in
  let scene = Scene.view (Scene.of_valid scene) in
  let o = read_objects scene in
  let few_casters = if skips && List.exists Light.sampled scene.lights then object_casters scene else None in
  let scene = settings scene in
  compact_after_loading o;
  (* Per object, in object order: kind, material, and the cube around it. *)
  let okind = Array.make o.n Kind.Sphere and omat = Array.make o.n 0 in
  let c = cubes o in
  let r = registry ~every_frame in
  let v = vertices o in
  let s = { builder = Csg.builder (); roots = Hashtbl.create 8 } in
  sphere_objects o r omat c;
  let max_channel = max_channel scene o in
  (* The spheres are copied: from here on [prepare] holds none of the
     scene's, and a caller that holds the scene no longer either (the
     renderers) lets them go while the hierarchy is built. *)
  let o = { o with spheres = Spheres.empty } in
  let inst = instancing (bottom ~skips bottom_scene) in
  let normal_base = shape_objects o r v s inst okind omat c in
  let materials, alternate, placed, pattern = material_table r in
  (* The hierarchy over the bounded objects kept, then the slots. *)
  let collections = ref 0 in
  let twin_of, sel, boxes = twins_and_boxes ~skips ?beside o scene okind c collections in
  let pool = { spare = [] } in
  let bvh =
    hierarchy ?beside ~reuse:(o.shapes = [] && sel.nb = o.n) ~scratch:(sel.nb = o.n) ~instances:(2 * Hashtbl.length c.oboxes >= sel.nb)
      pool boxes
  in
  collect o collections;
  let unbounded = sel.unbounded in
  let sl = slots o pool (index_of_slots o bvh sel twin_of) okind omat twin_of in
  (* The scratch, if [slots] took none, let go. *)
  if not sl.in_place then pool.spare <- [];
  (* Geometry and sphere data, in slot order. *)
  let any_smooth = Array.exists (fun k -> k = Kind.Smooth_triangle) okind in
  let vnormal = if any_smooth then v.vnormal else [||] in
  let g = geometry_arrays o sl ~any_smooth ~follow:v.follow in
  let sp = camera_constants pool scene.camera.position (sphere_arrays o pool sl c) in
  store_geometry o v s inst normal_base sl g ~any_smooth;
  (* The triangles' vertices in the order the leaves read them
     (Vertex_order); the normals stay where they are. *)
  let vertex, vsource =
    if bvh = None || Array.length v.vertex = 0 then (v.vertex, [||])
    else Vertex_order.gather ~sources:any_smooth ~kind:sl.kind ~vertex:v.vertex g.at0 g.at1 g.at2
  in
  let bvh = if cut then cut_leaves bvh c ~kind:sl.kind ~vertex g else bvh in
  let uv = uv_table ~every_frame o sl.slot (Array.length sl.kind) in
  let casters = casters ~skips ~few_casters scene bvh in
  assemble ~skips scene o ~max_channel ~materials ~alternate ~pattern ~bvh ~unbounded ~csg:(Csg.table s.builder)
    ~instances:(instance_table inst placed) sl g sp ~vertex ~vsource ~vnormal ~uv ~casters

(* The bottom level of an instance: its object alone, prepared as a scene
   of the top's mode (epsilon) with no lights; the kernel traces it in
   the object's frame. *)
and bottom ~skips bottom_scene shape =
  prepare_scene ~every_frame:true ~skips (bottom_scene shape)

(* The major heap grows by 256 MB of address space at a time while a big
   scene is prepared, not by 15% of its size: the pieces freed between
   the default's many chunks are each smaller than an array of a million
   floats, so that every such array took new memory (docs/performance.md,
   "Numbers moved out of prepare's comments"). A chunk costs memory only
   where it is written. *)
let big_increment = 32 * 1024 * 1024

let prepare ?(skips = true) ?cut ?beside scene =
  if object_count (Scene.view (Scene.of_valid scene)) <= big_scene then prepare_scene ?cut ~skips ?beside scene
  else begin
    let gc = Gc.get () in
    Gc.set { gc with major_heap_increment = big_increment };
    Fun.protect ~finally:(fun () -> Gc.set { (Gc.get ()) with major_heap_increment = gc.major_heap_increment })
      (fun () -> prepare_scene ?cut ~skips ?beside scene)
  end

type kernel_skip = Behind | Shadow_rays | Culling | Negligible_terms | Umbra | Whole_light

let without k p =
  match k with
  | Behind -> { p with behind = false }
  | Shadow_rays -> { p with shadow_skip = false }
  | Culling -> { p with cull = false }
  | Umbra -> { p with umbra_skip = false }
  | Whole_light -> { p with casters = [||] }
  | Negligible_terms ->
      {
        p with
        specular_cut =
          Array.mapi
            (fun k cut -> if p.specular.(k / max 1 p.n_lights) = Sphere.matte then cut else p.specular_zero.(k / max 1 p.n_lights))
            p.specular_cut;
      }
