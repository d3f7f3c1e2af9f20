type op = Union | Intersection | Difference [@@deriving eq]

type t = { op : op; a : solid; b : solid } [@@deriving eq]
and solid = Sphere of Sphere.t | Box of Box.t | Mesh of Mesh.t | Csg of t | Primitive of Shape_desc.primitive

let v op a b = { op; a; b }
let ops = [ ("union", Union); ("intersection", Intersection); ("difference", Difference) ]
let op_name op = fst (List.find (fun (_, o) -> o = op) ops)
let op_of_string s = List.assoc_opt s ops
let max_depth = 32

let sphere_material = Sphere.material

let rec fold_solids f acc = function
  | Csg c -> fold_solids f (fold_solids f acc c.a) c.b
  | leaf -> f acc leaf

let leaves c = List.rev (fold_solids (fun acc l -> l :: acc) [] (Csg c))

let leaf_material = function
  | Sphere s -> sphere_material s
  | Box b -> b.material
  | Mesh m -> m.material
  | Primitive p -> Shape_desc.material p
  | Csg _ -> invalid_arg "Csg.leaf_material: not a leaf"

(* Every pass over a tree recurses as deep as it nests, and no deeper:
   never along a list of its leaves (a balanced tree of 2^18 leaves nests
   18 deep, and [List.map] over its leaves overflowed the stack, the
   JavaScript one long before the native one). *)
let materials c = List.rev (fold_solids (fun acc l -> leaf_material l :: acc) [] (Csg c))

(* Whether [s] nests more than [limit] CSG forms, found without going
   deeper than [limit + 1]: a tree built in code may nest a million deep. *)
let rec deeper_than limit = function
  | Csg c -> limit <= 0 || deeper_than (limit - 1) c.a || deeper_than (limit - 1) c.b
  | _ -> false

(* The number of each vertex of [p] ([x y z] each), equal points one
   number, and the first vertex of each number: an open-addressing table
   of vertex numbers by their coordinates' hash ([Hashtbl.hash] makes -0
   and 0 one), in linear time, with no boxed key. *)
let points (p : float array) =
  let nv = Array.length p / 3 in
  let size = ref 16 in
  while !size < 2 * nv do
    size := 2 * !size
  done;
  let mask = !size - 1 in
  let table = Array.make !size (-1) in
  let point = Array.make nv 0 and first = Array.make (max 1 nv) 0 and n = ref 0 in
  for v = 0 to nv - 1 do
    let x = p.(3 * v) and y = p.((3 * v) + 1) and z = p.((3 * v) + 2) in
    let h = ref (Hashtbl.hash x + (65599 * (Hashtbl.hash y + (65599 * Hashtbl.hash z)))) in
    let found = ref (-1) in
    while !found < 0 do
      let i = !h land mask in
      let w = table.(i) in
      if w < 0 then begin
        table.(i) <- v;
        first.(!n) <- v;
        found := !n;
        incr n
      end
      else if p.(3 * w) = x && p.((3 * w) + 1) = y && p.((3 * w) + 2) = z then found := point.(w)
      else h := !h + 1
    done;
    point.(v) <- !found
  done;
  (point, first, !n)

(* Every edge of a closed mesh borders exactly two of its triangles.
   Edges are keyed by their endpoints' coordinates, not by vertex numbers,
   so that a file that repeats a vertex (one per face, as some exporters
   do) is still closed. Degenerate triangles are left out: no ray can hit
   them, the kernel drops them. The edges are sorted by their lower end
   into buckets (counting), and each bucket, a vertex's few edges, by the
   upper end: linear time, ints alone. A hash table of coordinate tuples
   cost a block per edge and most of the load time of a big mesh
   (docs/performance.md, "Numbers moved out of the library's comments"). *)
let check_closed (m : Mesh.t) =
  let p = m.positions and tri = m.triangles in
  let point, first, np = points p in
  (* Edge [c] of triangle [k], from corner [c] to the next: its ends'
     point numbers. *)
  let a k c = point.(tri.((3 * k) + c)) and b k c = point.(tri.((3 * k) + if c = 2 then 0 else c + 1)) in
  let start = Array.make (np + 1) 0 in
  for k = 0 to Mesh.triangle_count m - 1 do
    if not (Mesh.degenerate m k) then
      for c = 0 to 2 do
        let x = a k c and y = b k c in
        let lo = if x < y then x else y in
        start.(lo + 1) <- start.(lo + 1) + 1
      done
  done;
  for i = 1 to np do
    start.(i) <- start.(i) + start.(i - 1)
  done;
  let upper = Array.make (max 1 start.(np)) 0 and fill = Array.sub start 0 np in
  for k = 0 to Mesh.triangle_count m - 1 do
    if not (Mesh.degenerate m k) then
      for c = 0 to 2 do
        let x = a k c and y = b k c in
        let lo = if x < y then x else y and hi = if x < y then y else x in
        upper.(fill.(lo)) <- hi;
        fill.(lo) <- fill.(lo) + 1
      done
  done;
  let bad = ref None and found = ref false and lo = ref 0 in
  while (not !found) && !lo < np do
    let i0 = start.(!lo) and i1 = start.(!lo + 1) in
    for i = i0 + 1 to i1 - 1 do
      let x = upper.(i) and j = ref i in
      while !j > i0 && upper.(!j - 1) > x do
        upper.(!j) <- upper.(!j - 1);
        decr j
      done;
      upper.(!j) <- x
    done;
    let i = ref i0 in
    while (not !found) && !i < i1 do
      let j = ref !i in
      while !j < i1 && upper.(!j) = upper.(!i) do
        incr j
      done;
      if !j - !i <> 2 then begin
        bad := Some (!lo, upper.(!i), !j - !i);
        found := true
      end;
      i := !j
    done;
    incr lo
  done;
  match !bad with
  | None -> Ok ()
  | Some (a, b, n) ->
      let corner v = (p.(3 * first.(v)), p.((3 * first.(v)) + 1), p.((3 * first.(v)) + 2)) in
      let (ax, ay, az), (bx, by, bz) = (corner a, corner b) in
      let num = Float_text.to_string in
      Error
        (`Msg
          (Printf.sprintf
             "csg: mesh %S is not a closed solid: its edge from (%s %s %s) to (%s %s %s) borders %d triangle%s, not 2"
             m.source (num ax) (num ay) (num az) (num bx) (num by) (num bz) n (if n = 1 then "" else "s")))

let rec validate c =
  let ( let* ) = Result.bind in
  let* () =
    if deeper_than max_depth (Csg c) then Error (`Msg (Printf.sprintf "csg nested deeper than %d levels" max_depth))
    else Ok ()
  in
  let child = function
    | Sphere s -> Result.map (fun s -> Sphere s) (Sphere.validate s)
    | Box b -> Result.map (fun b -> Box b) (Box.validate b)
    | Mesh m ->
        let* _ = Material.validate ~form:"mesh" m.material in
        let* () = check_closed m in
        Ok (Mesh m)
    | Primitive p when not (Shape_desc.closed p) ->
        Error (`Msg (Printf.sprintf "csg: %s is not a closed solid" (Shape_desc.not_closed p)))
    | Primitive p -> Result.map (fun p -> Primitive p) (Shape_desc.validate p)
    | Csg c -> Result.map (fun c -> Csg c) (validate c)
  in
  let* a = child c.a in
  let* b = child c.b in
  Ok { c with a; b }

(* Bounds as [lo, hi] corners. *)
let rec solid_box = function
  | Sphere s ->
      let r = Vec3.v s.radius s.radius s.radius in
      (Vec3.sub s.center r, Vec3.add s.center r)
  | Box b -> (b.min, b.max)
  | Primitive p -> Shape_desc.bounds p
  | Mesh m ->
      let lo = Array.make 3 infinity and hi = Array.make 3 neg_infinity in
      Array.iteri
        (fun i x ->
          lo.(i mod 3) <- Float.min lo.(i mod 3) x;
          hi.(i mod 3) <- Float.max hi.(i mod 3) x)
        m.positions;
      (Vec3.v lo.(0) lo.(1) lo.(2), Vec3.v hi.(0) hi.(1) hi.(2))
  | Csg c -> (
      let (alo : Vec3.t), (ahi : Vec3.t) = solid_box c.a and (blo : Vec3.t), (bhi : Vec3.t) = solid_box c.b in
      let map2 f (p : Vec3.t) (q : Vec3.t) = Vec3.v (f p.x q.x) (f p.y q.y) (f p.z q.z) in
      match c.op with
      | Union -> (map2 Float.min alo blo, map2 Float.max ahi bhi)
      | Difference -> (alo, ahi)
      | Intersection ->
          let lo = map2 Float.max alo blo in
          (* Disjoint boxes: an empty solid, bounded by a point. *)
          (lo, map2 Float.max lo (map2 Float.min ahi bhi)))

let bounds c = solid_box (Csg c)

let extent c =
  let ext (p : Vec3.t) = Float.max (Float.abs p.x) (Float.max (Float.abs p.y) (Float.abs p.z)) in
  fold_solids
    (fun acc l ->
      let lo, hi = solid_box l in
      Float.max acc (Float.max (ext lo) (ext hi)))
    0. (Csg c)

let triangles c = fold_solids (fun n l -> match l with Mesh m -> n + Mesh.objects m | _ -> n) 0 (Csg c)

let rec pp ppf c =
  let solid ppf = function
    | Sphere s -> Sphere.pp ppf s
    | Box b -> Box.pp ppf b
    | Mesh m -> Mesh.pp_form ppf m
    | Primitive p -> Shape_desc.pp_primitive ppf p
    | Csg c -> pp ppf c
  in
  Format.fprintf ppf "(csg %s %a %a)" (op_name c.op) solid c.a solid c.b

let show c = Format.asprintf "%a" pp c

(* {1 The kernel's table} *)

let stride = Kind.stride
let union = 0
let intersection = 1
let difference = 2
let leaf_node = 3

(* Surfaces, one a leaf, of a closed kind ({!Kind.closed}): a sphere
   [cx cy cz r], a box as {!Box.store} writes it, a mesh (kind
   [Triangle]: its number in [meshes], as a float). *)

(* The intervals name the surface crossed at each end as [sf lsl
   slot_bits lor slot]: the leaf's surface [sf], and for a mesh the slot of
   the triangle in its hierarchy. Numbers then compare as the leaves' order
   does (the merge's tie rule). [slot_bits] is the table's: as few as its
   largest mesh operand needs (none without one), so that the numbers fit
   JavaScript's 32-bit integers too (a fixed 23 bits wrapped past 256
   leaves there and lost spheres of a big union). *)
let bits_for n =
  let b = ref 0 in
  while n > 1 lsl !b do incr b done;
  !b

(* A mesh leaf: its triangles' corners, in the order of its hierarchy's
   slots, as offsets in [vertex] (the mesh's own positions, not a copy),
   and the hierarchy over their boxes. *)
type mesh_leaf = {
  vertex : float array;
  corners : int array;  (** 3 per slot. *)
  nodes : float array;  (** {!Bvh.t}'s; empty for a mesh of no triangle the kernel keeps. *)
  root : int;
  depth : int;  (** Of the hierarchy: {!Bvh.t}'s. *)
  reach : float;  (** The largest magnitude of a coordinate of the mesh. *)
}

type table = {
  node_kind : int array;
  left : int array;  (** An operation's first child; a leaf's surface. *)
  right : int array;  (** An operation's second child; a mesh leaf's number in [meshes]. *)
  base : int array;  (** A node's first interval in the work arrays. *)
  surface_kind : Kind.t array;
  geom : float array;  (** [stride] floats per surface. *)
  surface_material : int array;
  meshes : mesh_leaf array;
  intervals : int;
  depth : int;  (** The deepest hierarchy of a mesh leaf. *)
  slot_bits : int;  (** Of a surface's number: see [bits_for]. *)
  surface_id : int array;  (** [sf lsl slot_bits] for each surface [sf]: a load, not a shift, per leaf test. *)
}

type builder = {
  mutable nodes : (int * int * int * int) list;  (** kind, left, right, base; reversed. *)
  mutable n_nodes : int;
  mutable surfaces : (Kind.t * float array * int) list;  (** Reversed. *)
  mutable n_surfaces : int;
  mutable meshes : mesh_leaf list;  (** Reversed. *)
  mutable n_meshes : int;
  mutable n_intervals : int;
  mutable max_depth : int;
}

let builder () =
  { nodes = []; n_nodes = 0; surfaces = []; n_surfaces = 0; meshes = []; n_meshes = 0; n_intervals = 0; max_depth = 0 }

let add_surface b kind g mat =
  b.surfaces <- (kind, g, mat) :: b.surfaces;
  b.n_surfaces <- b.n_surfaces + 1

(* A node with room for [cap] intervals; its number. *)
let add_node b kind left right cap =
  b.nodes <- (kind, left, right, b.n_intervals) :: b.nodes;
  b.n_intervals <- b.n_intervals + cap;
  b.n_nodes <- b.n_nodes + 1;
  b.n_nodes - 1

(* The hierarchy over [m]'s triangles that the kernel keeps (not
   degenerate): the only copy of the mesh is its corners' offsets, 3 ints
   a triangle; the boxes are the build's, dropped after it. *)
let mesh_leaf (m : Mesh.t) =
  let n = Mesh.objects m in
  let reach = Array.fold_left (fun acc x -> Float.max acc (Float.abs x)) 0. m.positions in
  if n = 0 then { vertex = m.positions; corners = [||]; nodes = [||]; root = 0; depth = 0; reach }
  else begin
    let kept = Array.make n 0 and j = ref 0 in
    for k = 0 to Mesh.triangle_count m - 1 do
      if not (Mesh.degenerate m k) then begin
        kept.(!j) <- k;
        incr j
      end
    done;
    let f () = Array.create_float n in
    let x0 = f () and y0 = f () and z0 = f () and x1 = f () and y1 = f () and z1 = f () in
    let box = Array.make 6 0. in
    Array.iteri
      (fun i k ->
        Mesh.box m k box;
        x0.(i) <- box.(0);
        y0.(i) <- box.(1);
        z0.(i) <- box.(2);
        x1.(i) <- box.(3);
        y1.(i) <- box.(4);
        z1.(i) <- box.(5))
      kept;
    (* Leaves of up to 16, as the scene's hierarchy has for meshes (see
       [Prepared]): a mesh's thin triangles overlap, and smaller leaves
       buy more boxes for few fewer triangle tests. *)
    let bvh = Bvh.build_boxes ~leaf_size:16 ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 () in
    let corners = Array.make (3 * n) 0 in
    Array.iteri
      (fun slot i ->
        for c = 0 to 2 do
          corners.((3 * slot) + c) <- 3 * m.triangles.((3 * kept.(i)) + c)
        done)
      bvh.order;
    { vertex = m.positions; corners; nodes = bvh.nodes; root = bvh.root; depth = bvh.depth; reach }
  end

(* Adds [s] with its leaves' materials numbered by [material] (given the
   leaf); its node and its capacity in intervals. *)
let rec add_solid b ~material s =
  match s with
  | Sphere sp ->
      let first = b.n_surfaces in
      add_surface b Kind.Sphere [| sp.center.x; sp.center.y; sp.center.z; sp.radius |] (material s);
      (add_node b leaf_node first 0 1, 1)
  | Box bx ->
      let first = b.n_surfaces in
      let g = Array.make stride 0. in
      Box.store bx g 0;
      add_surface b Kind.Box g (material s);
      (add_node b leaf_node first 0 1, 1)
  | Primitive p ->
      let first = b.n_surfaces in
      let g = Array.make stride 0. in
      Shape_desc.store p g 0;
      add_surface b (Shape_desc.kind p) g (material s);
      let cap = Kind.spans (Shape_desc.kind p) in
      (add_node b leaf_node first 0 cap, cap)
  | Mesh m ->
      let sf = b.n_surfaces and leaf = mesh_leaf m in
      let number = b.n_meshes in
      add_surface b Kind.Triangle [| Float.of_int number |] (material s);
      b.meshes <- leaf :: b.meshes;
      b.n_meshes <- number + 1;
      let n = Array.length leaf.corners / 3 in
      (* A line through the hierarchy keeps a stack of at most one node
         a level, and the nodes it pushes last. *)
      b.max_depth <- max b.max_depth leaf.depth;
      let cap = (n / 2) + 1 in
      (add_node b leaf_node sf number cap, cap)
  | Csg c ->
      let a, ca = add_solid b ~material c.a in
      let bn, cb = add_solid b ~material c.b in
      let kind = match c.op with Union -> union | Intersection -> intersection | Difference -> difference in
      (add_node b kind a bn (ca + cb), ca + cb)

let add b ~material c = fst (add_solid b ~material (Csg c))

let table b =
  let nodes = Array.of_list (List.rev b.nodes) and surfaces = Array.of_list (List.rev b.surfaces) in
  let geom = Array.make (stride * Array.length surfaces) 0. in
  Array.iteri (fun i (_, g, _) -> Array.blit g 0 geom (stride * i) (Array.length g)) surfaces;
  let slots = List.fold_left (fun m leaf -> max m (Array.length leaf.corners / 3)) 0 b.meshes in
  let slot_bits = bits_for slots in
  if Array.length surfaces > max_int lsr slot_bits then
    invalid_arg
      (Printf.sprintf "Csg.table: %d leaves with a mesh operand of %d triangles are too many for this platform's integers"
         (Array.length surfaces) slots);
  {
    node_kind = Array.map (fun (k, _, _, _) -> k) nodes;
    left = Array.map (fun (_, l, _, _) -> l) nodes;
    right = Array.map (fun (_, _, r, _) -> r) nodes;
    base = Array.map (fun (_, _, _, o) -> o) nodes;
    surface_kind = Array.map (fun (k, _, _) -> k) surfaces;
    geom;
    surface_material = Array.map (fun (_, _, m) -> m) surfaces;
    meshes = Array.of_list (List.rev b.meshes);
    intervals = b.n_intervals;
    depth = b.max_depth;
    slot_bits;
    surface_id = Array.init (Array.length surfaces) (fun sf -> sf lsl slot_bits);
  }

let empty = table (builder ())

type work = {
  t_in : float array;
  t_out : float array;
  s_in : int array;
  s_out : int array;
  count : int array;
  stack : int array;  (** The nodes of a mesh's hierarchy still to visit. *)
  mutable surface : int;
  mutable entering : bool;
  mutable tests : int;
  mutable boxes : int;
}

let work tb =
  let n = max 1 tb.intervals in
  {
    t_in = Array.make n 0.;
    t_out = Array.make n 0.;
    s_in = Array.make n 0;
    s_out = Array.make n 0;
    count = Array.make (max 1 (Array.length tb.node_kind)) 0;
    stack = Array.make ((2 * tb.depth) + 2) 0;
    surface = -1;
    entering = true;
    tests = 0;
    boxes = 0;
  }

(* The sphere at [o] in [g]: {!Sphere.roots}'s cancellation-free roots,
   the same operations on floats of the scratch record. *)
let[@inline] sphere_roots (s : Scratch.t) g o =
  let fx = s.ox -. Array.unsafe_get g o and fy = s.oy -. Array.unsafe_get g (o + 1) and fz = s.oz -. Array.unsafe_get g (o + 2) in
  let dx = s.dx and dy = s.dy and dz = s.dz in
  let radius = Array.unsafe_get g (o + 3) in
  let a = (dx *. dx) +. (dy *. dy) +. (dz *. dz) in
  let b = (fx *. dx) +. (fy *. dy) +. (fz *. dz) in
  let k = b *. (1. /. a) in
  let lx = fx -. (k *. dx) and ly = fy -. (k *. dy) and lz = fz -. (k *. dz) in
  let l2 = (lx *. lx) +. (ly *. ly) +. (lz *. lz) and r2 = radius *. radius in
  if l2 > r2 then false
  else begin
    let len = sqrt l2 in
    let sq = sqrt (a *. ((radius -. len) *. (radius +. len))) in
    let q = -.(b +. Float.copy_sign sq b) in
    if q = 0. then begin
      s.near <- 0.;
      s.far <- 0.
    end
    else begin
      let t0 = (((fx *. fx) +. (fy *. fy) +. (fz *. fz)) -. r2) /. q and t1 = q /. a in
      s.near <- (if t0 <= t1 then t0 else t1);
      s.far <- (if t0 <= t1 then t1 else t0)
    end;
    true
  end

(* One interval [near, far] of a sphere or box leaf, if it has a length:
   a ray that only touches the solid does not go in. *)
let[@inline] leaf_interval w (s : Scratch.t) node base sf hit =
  if hit && s.near < s.far then begin
    Array.unsafe_set w.t_in base s.near;
    Array.unsafe_set w.t_out base s.far;
    Array.unsafe_set w.s_in base sf;
    Array.unsafe_set w.s_out base sf;
    Array.unsafe_set w.count node 1
  end
  else Array.unsafe_set w.count node 0

(* The intervals of a leaf of a kind that a line may meet in several
   ({!Kind.spans}): its routine gives the first interval whose exit lies
   beyond [s.t_min], so it is asked again from each exit on ([s.t_min]
   moved there, then put back). Intervals that end before [s.t_min]
   change no crossing the CSG table answers for. *)
let leaf_spans w (s : Scratch.t) node base sf k g o =
  let t_min = s.t_min and n = ref 0 and go = ref true and spans = Kind.spans k in
  while !go && !n < spans do
    if Kind_dispatch.roots k s g o then begin
      if s.near < s.far then begin
        let i = base + !n in
        Array.unsafe_set w.t_in i s.near;
        Array.unsafe_set w.t_out i s.far;
        Array.unsafe_set w.s_in i sf;
        Array.unsafe_set w.s_out i sf;
        incr n
      end;
      s.t_min <- s.far
    end
    else go := false
  done;
  s.t_min <- t_min;
  Array.unsafe_set w.count node !n

(* The reciprocal of a direction coordinate for the slab test: a zero
   coordinate gets a huge finite value, not an infinity, so that the
   slab's ends are huge and of the right signs (or 0), never NaN. *)
let[@inline] slab_inverse d = if d = 0. then 1e300 else 1. /. d

(* Does the line of the ray in [s] (slab inverses [ix], [iy], [iz]) meet
   the box of the node at [o] of [nodes], grown by [pad] on every side? *)
let[@inline] line_meets (nodes : float array) (s : Scratch.t) o pad ix iy iz =
  let ox = s.ox and oy = s.oy and oz = s.oz in
  let x0 = (Array.unsafe_get nodes o -. pad -. ox) *. ix and x1 = (Array.unsafe_get nodes (o + 3) +. pad -. ox) *. ix in
  let y0 = (Array.unsafe_get nodes (o + 1) -. pad -. oy) *. iy and y1 = (Array.unsafe_get nodes (o + 4) +. pad -. oy) *. iy in
  let z0 = (Array.unsafe_get nodes (o + 2) -. pad -. oz) *. iz and z1 = (Array.unsafe_get nodes (o + 5) +. pad -. oz) *. iz in
  let enter_x = if x0 < x1 then x0 else x1 and exit_x = if x0 < x1 then x1 else x0 in
  let enter_y = if y0 < y1 then y0 else y1 and exit_y = if y0 < y1 then y1 else y0 in
  let enter_z = if z0 < z1 then z0 else z1 and exit_z = if z0 < z1 then z1 else z0 in
  let enter = if enter_x > enter_y then enter_x else enter_y in
  let enter = if enter > enter_z then enter else enter_z in
  let exit = if exit_x < exit_y then exit_x else exit_y in
  let exit = if exit < exit_z then exit else exit_z in
  enter <= exit

(* A mesh's crossings are kept in order in its node's own room for
   intervals, where they are paired: crossing [j] is the entry of interval
   [base + j / 2] for an even [j], its exit for an odd one. A node has
   room for [n / 2 + 1] intervals, [n] its triangles. *)
let[@inline] crossing_t w base j =
  if j land 1 = 0 then Array.unsafe_get w.t_in (base + (j lsr 1)) else Array.unsafe_get w.t_out (base + (j lsr 1))

let[@inline] crossing_surface w base j =
  if j land 1 = 0 then Array.unsafe_get w.s_in (base + (j lsr 1)) else Array.unsafe_get w.s_out (base + (j lsr 1))

let[@inline] set_crossing w base j t id =
  if j land 1 = 0 then begin
    Array.unsafe_set w.t_in (base + (j lsr 1)) t;
    Array.unsafe_set w.s_in (base + (j lsr 1)) id
  end
  else begin
    Array.unsafe_set w.t_out (base + (j lsr 1)) t;
    Array.unsafe_set w.s_out (base + (j lsr 1)) id
  end

(* Crossing [t] of the surface [id] kept in order among the [n] of the
   node at [base] (insertion: a line crosses few triangles). *)
let[@inline] insert w base n t id =
  let j = ref n in
  while !j > 0 && crossing_t w base (!j - 1) > t do
    set_crossing w base !j (crossing_t w base (!j - 1)) (crossing_surface w base (!j - 1));
    decr j
  done;
  set_crossing w base !j t id

(* The boxes of the hierarchy grow by [2^-47 (reach + |O|)], 64 u of the
   largest coordinate of the corners or of the ray's origin: the triangle
   test moves each corner into the ray's frame with an error below [8 u]
   of that, and decides exactly on the moved corners; the slab test errs
   by a few u of it. So the grown box of every triangle that
   {!Triangle.crosses} reports is met by the line, and none is missed: a
   crossing missed would turn the parity, inside for outside, along the
   whole line. *)
let pad_scale = 0x1p-47

(* A closed mesh: its crossings along the whole line (the triangles of the
   boxes of its hierarchy that the line meets), each counted once
   ({!Triangle.crosses}: an even number), in order, paired as in, out, in,
   out... An empty pair (a ray that touches the surface) is dropped, and a
   pair that starts where the last one ended (a ray that touches it from
   inside) extends it. An odd count, which the rule excludes, would drop
   the last. *)
let mesh_intervals tb w (s : Scratch.t) node base =
  let sf = Array.unsafe_get tb.left node in
  let leaf = Array.unsafe_get tb.meshes (Array.unsafe_get tb.right node) in
  let g = leaf.vertex and corners = leaf.corners and nodes = leaf.nodes in
  let n = ref 0 in
  if Array.length corners > 0 then begin
    let axes = Triangle.shear s in
    let kx = Triangle.axis_x axes and ky = Triangle.axis_y axes and kz = Triangle.axis_z axes in
    let ix = slab_inverse s.dx and iy = slab_inverse s.dy and iz = slab_inverse s.dz in
    let reach = Float.max (Float.abs s.ox) (Float.max (Float.abs s.oy) (Float.abs s.oz)) in
    let pad = pad_scale *. (leaf.reach +. reach) in
    let stack = w.stack and sp = ref 1 and boxes = ref 0 and tests = ref 0 in
    Array.unsafe_set stack 0 leaf.root;
    while !sp > 0 do
      decr sp;
      let o = Array.unsafe_get stack !sp in
      incr boxes;
      if line_meets nodes s o pad ix iy iz then begin
        let tag = truncate (Array.unsafe_get nodes (o + 7)) and link = truncate (Array.unsafe_get nodes (o + 6)) in
        if tag > 0 then begin
          tests := !tests + tag;
          for slot = link to link + tag - 1 do
            let c = 3 * slot in
            if
              Triangle.crosses_at s g (Array.unsafe_get corners c) (Array.unsafe_get corners (c + 1))
                (Array.unsafe_get corners (c + 2)) kx ky kz
            then begin
              insert w base !n s.near (Array.unsafe_get tb.surface_id sf lor slot);
              incr n
            end
          done
        end
        else begin
          Array.unsafe_set stack !sp link;
          Array.unsafe_set stack (!sp + 1) (o + Bvh.node_floats);
          sp := !sp + 2
        end
      end
    done;
    w.tests <- w.tests + !tests;
    w.boxes <- w.boxes + !boxes
  end;
  (* Pairs compacted in place: pair [j] moves to [m <= j]. *)
  let m = ref 0 in
  for j = 0 to (!n / 2) - 1 do
    let k = base + j in
    let t0 = Array.unsafe_get w.t_in k and t1 = Array.unsafe_get w.t_out k in
    if !m > 0 && Array.unsafe_get w.t_out (base + !m - 1) = t0 then begin
      Array.unsafe_set w.t_out (base + !m - 1) t1;
      Array.unsafe_set w.s_out (base + !m - 1) (Array.unsafe_get w.s_out k)
    end
    else if t0 < t1 then begin
      Array.unsafe_set w.t_in (base + !m) t0;
      Array.unsafe_set w.t_out (base + !m) t1;
      Array.unsafe_set w.s_in (base + !m) (Array.unsafe_get w.s_in k);
      Array.unsafe_set w.s_out (base + !m) (Array.unsafe_get w.s_out k);
      incr m
    end
  done;
  Array.unsafe_set w.count node !m

(* The intervals of node [node], operation [op] on children [na] and [nb]
   (their intervals computed): a sweep over both lists' ends in order,
   tracking whether the ray is inside each child, that records where the
   operation's answer changes. An interval that opens where the last one
   closed extends it (touching solids make one), one that closes where it
   opened is dropped (a ray that only touches). Of two ends at the same
   [t], [a]'s is taken first, and the point belongs to the surface of the
   lower number, the leaf further left, whichever end changes the answer
   (as in {!literal_hit}, which takes the first crossing at that [t]). *)
let merge w op node base na nb ba bb =
  let ca = 2 * Array.unsafe_get w.count na and cb = 2 * Array.unsafe_get w.count nb in
  let ia = ref 0 and ib = ref 0 and in_a = ref false and in_b = ref false and inside = ref false and n = ref 0 in
  let tie_t = ref nan and tie_sf = ref 0 in
  while !ia < ca || !ib < cb do
    let ta =
      if !ia >= ca then infinity
      else if !ia land 1 = 0 then Array.unsafe_get w.t_in (ba + (!ia lsr 1))
      else Array.unsafe_get w.t_out (ba + (!ia lsr 1))
    in
    let tb =
      if !ib >= cb then infinity
      else if !ib land 1 = 0 then Array.unsafe_get w.t_in (bb + (!ib lsr 1))
      else Array.unsafe_get w.t_out (bb + (!ib lsr 1))
    in
    let from_a = !ib >= cb || (!ia < ca && ta <= tb) in
    let t = if from_a then ta else tb in
    let sf =
      if from_a then
        if !ia land 1 = 0 then Array.unsafe_get w.s_in (ba + (!ia lsr 1)) else Array.unsafe_get w.s_out (ba + (!ia lsr 1))
      else if !ib land 1 = 0 then Array.unsafe_get w.s_in (bb + (!ib lsr 1))
      else Array.unsafe_get w.s_out (bb + (!ib lsr 1))
    in
    (* Each list's ends strictly increase: a tie is one end of each. *)
    let sf = if t = !tie_t && !tie_sf < sf then !tie_sf else sf in
    tie_t := t;
    tie_sf := sf;
    if from_a then begin
      in_a := not !in_a;
      incr ia
    end
    else begin
      in_b := not !in_b;
      incr ib
    end;
    let r =
      if op = union then !in_a || !in_b else if op = intersection then !in_a && !in_b else !in_a && not !in_b
    in
    if r <> !inside then begin
      inside := r;
      let k = base + !n in
      if r then begin
        if !n > 0 && Array.unsafe_get w.t_out (k - 1) = t then decr n
        else begin
          Array.unsafe_set w.t_in k t;
          Array.unsafe_set w.s_in k sf
        end
      end
      else if Array.unsafe_get w.t_in k < t then begin
        Array.unsafe_set w.t_out k t;
        Array.unsafe_set w.s_out k sf;
        incr n
      end
    end
  done;
  Array.unsafe_set w.count node !n

(* A CSG leaf is closed ({!Kind.closed}), and its triangles are flat:
   {!add_solid} makes no other. *)
let not_a_leaf () = invalid_arg "Csg: a leaf of a kind that is not closed"

let[@warning "-11"] rec eval tb w (s : Scratch.t) node =
  let k = Array.unsafe_get tb.node_kind node and base = Array.unsafe_get tb.base node in
  if k = leaf_node then begin
    (* The CSG table's dispatch on a leaf's kind. *)
    let sf = Array.unsafe_get tb.left node in
    match Array.unsafe_get tb.surface_kind sf with
    | Kind.Sphere ->
        w.tests <- w.tests + 1;
        leaf_interval w s node base (Array.unsafe_get tb.surface_id sf) (sphere_roots s tb.geom (stride * sf))
    | Kind.Box ->
        w.tests <- w.tests + 1;
        leaf_interval w s node base (Array.unsafe_get tb.surface_id sf) (Box.roots s tb.geom (stride * sf))
    | Kind.Triangle -> mesh_intervals tb w s node base
    | Kind.Plane | Kind.Smooth_triangle | Kind.Csg -> not_a_leaf ()
    | k ->
        (* Every other closed kind, by the kernel's dispatch. *)
        w.tests <- w.tests + 1;
        if Kind.spans k = 1 then
          leaf_interval w s node base (Array.unsafe_get tb.surface_id sf) (Kind_dispatch.roots k s tb.geom (stride * sf))
        else leaf_spans w s node base (Array.unsafe_get tb.surface_id sf) k tb.geom (stride * sf)
  end
  else begin
    let na = Array.unsafe_get tb.left node and nb = Array.unsafe_get tb.right node in
    eval tb w s na;
    (* An intersection or difference with nothing of its first child is
       empty: its second child need not be tested. *)
    if Array.unsafe_get w.count na = 0 && k <> union then Array.unsafe_set w.count node 0
    else begin
      eval tb w s nb;
      merge w k node base na nb (Array.unsafe_get tb.base na) (Array.unsafe_get tb.base nb)
    end
  end

let roots tb w (s : Scratch.t) root =
  eval tb w s root;
  let base = Array.unsafe_get tb.base root and n = Array.unsafe_get w.count root in
  let t_min = s.t_min in
  let i = ref 0 and found = ref false in
  while (not !found) && !i < n do
    let k = base + !i in
    let t_in = Array.unsafe_get w.t_in k in
    if t_in > t_min then begin
      s.near <- t_in;
      w.surface <- Array.unsafe_get w.s_in k;
      w.entering <- true;
      found := true
    end
    else begin
      let t_out = Array.unsafe_get w.t_out k in
      if t_out > t_min then begin
        s.near <- t_out;
        w.surface <- Array.unsafe_get w.s_out k;
        w.entering <- false;
        found := true
      end
      else incr i
    end
  done;
  if not !found then s.near <- infinity;
  s.far <- s.near;
  !found

let[@warning "-11"] normal tb w (s : Scratch.t) =
  let sf = w.surface lsr tb.slot_bits in
  let o = stride * sf in
  (match Array.unsafe_get tb.surface_kind sf with
  | Kind.Sphere ->
      let g = tb.geom in
      let nx = s.px -. Array.unsafe_get g o and ny = s.py -. Array.unsafe_get g (o + 1) and nz = s.pz -. Array.unsafe_get g (o + 2) in
      let inv = 1. /. sqrt ((nx *. nx) +. (ny *. ny) +. (nz *. nz)) in
      s.nx <- nx *. inv;
      s.ny <- ny *. inv;
      s.nz <- nz *. inv
  | Kind.Box -> Box.hit_normal s tb.geom o
  | Kind.Triangle ->
      let leaf = tb.meshes.(truncate tb.geom.(o)) and c = 3 * (w.surface land ((1 lsl tb.slot_bits) - 1)) in
      Triangle.normal_at s leaf.vertex leaf.corners.(c) leaf.corners.(c + 1) leaf.corners.(c + 2)
  | Kind.Plane | Kind.Smooth_triangle | Kind.Csg -> not_a_leaf ()
  | k -> Kind_dispatch.normal k s tb.geom o);
  (* Outward from the solid: against the ray where it enters, along it
     where it leaves. This turns a subtracted solid's normal around. *)
  let along = (s.nx *. s.dx) +. (s.ny *. s.dy) +. (s.nz *. s.dz) > 0. in
  if along <> not w.entering then begin
    s.nx <- -.s.nx;
    s.ny <- -.s.ny;
    s.nz <- -.s.nz
  end

let material tb w = Array.unsafe_get tb.surface_material (w.surface lsr tb.slot_bits)
let entering w = w.entering
let take_tests w =
  let n = w.tests in
  w.tests <- 0;
  n

let take_boxes w =
  let n = w.boxes in
  w.boxes <- 0;
  n

let[@inline] pending w = w.tests + w.boxes

(* {1 The literal algorithm} *)

type tree = Leaf of int | Node of op * tree * tree

let literal_hit c ~origin ~direction ~t_min ~t_max =
  let leaves = Array.of_list (leaves c) in
  let rec tree next = function
    | Csg c ->
        let a, next = tree next c.a in
        let b, next = tree next c.b in
        (Node (c.op, a, b), next)
    | _ -> (Leaf next, next + 1)
  in
  let tree, _ = tree 0 (Csg c) in
  (* Every crossing of every leaf's surface with the line: (t, leaf,
     triangle), by the primitives' own routines. *)
  let crossings =
    Array.mapi
      (fun i leaf ->
        match leaf with
        | Sphere s ->
            let near, far = Sphere.roots s ~origin ~direction in
            if near < far then [ (near, i, -1); (far, i, -1) ] else []
        | Box b ->
            let near, far = Box.intersect b ~origin ~direction in
            if near < far then [ (near, i, -1); (far, i, -1) ] else []
        | Primitive p -> (
            match Shape_desc.literal p ~origin ~direction with
            | [ (near, _); (far, _) ] when near < far -> [ (near, i, 0); (far, i, 1) ]
            | _ -> [])
        | Mesh m ->
            let xs =
              List.filter_map
                (fun k ->
                  if Mesh.degenerate m k then None
                  else
                    let t = Triangle.crossing (Mesh.triangle m k) ~origin ~direction in
                    if t < infinity then Some (t, i, k) else None)
                (List.init (Mesh.triangle_count m) Fun.id)
            in
            let xs = List.stable_sort (fun (a, _, _) (b, _, _) -> Float.compare a b) xs in
            (* An odd count: the last crossing does not count. *)
            if List.length xs mod 2 = 1 then List.filteri (fun j _ -> j < List.length xs - 1) xs else xs
        | Csg _ -> assert false)
      leaves
  in
  (* Is parameter [t] inside leaf [i], just before it or just after? *)
  let inside_leaf i ~after t =
    match crossings.(i) with
    | [] -> false
    | xs -> (
        match leaves.(i) with
        | Mesh _ ->
            let n = List.length (List.filter (fun (x, _, _) -> if after then x <= t else x < t) xs) in
            n mod 2 = 1
        | _ ->
            let near, _, _ = List.hd xs and far, _, _ = List.nth xs 1 in
            if after then near <= t && t < far else near < t && t <= far)
  in
  let rec inside ~after t = function
    | Leaf i -> inside_leaf i ~after t
    | Node (op, a, b) -> (
        let a = inside ~after t a and b = inside ~after t b in
        match op with Union -> a || b | Intersection -> a && b | Difference -> a && not b)
  in
  let all =
    List.stable_sort (fun (a, _, _) (b, _, _) -> Float.compare a b) (List.rev (Array.fold_left (fun acc l -> List.rev_append l acc) [] crossings))
  in
  let boundary =
    List.find_opt
      (fun (t, _, _) -> t > t_min && inside ~after:false t tree <> inside ~after:true t tree)
      all
  in
  match boundary with
  | Some (t, i, k) when t < t_max ->
      let entering = inside ~after:true t tree in
      let point = Vec3.add origin (Vec3.smul t direction) in
      let sc = Scratch.create () in
      sc.px <- point.x;
      sc.py <- point.y;
      sc.pz <- point.z;
      let g = Array.make stride 0. in
      let n =
        match leaves.(i) with
        | Sphere s -> Sphere.normal s point
        | Box b ->
            Box.store b g 0;
            Scratch.set_ray sc origin direction;
            sc.near <- t;
            Box.hit_normal sc g 0;
            Vec3.v sc.nx sc.ny sc.nz
        | Mesh m ->
            Triangle.store (Mesh.triangle m k) g 0;
            Triangle.normal sc g 0;
            Vec3.v sc.nx sc.ny sc.nz
        | Primitive p -> snd (List.nth (Shape_desc.literal p ~origin ~direction) k)
        | Csg _ -> assert false
      in
      let along = Vec3.dot n direction > 0. in
      let n = if along <> not entering then Vec3.neg n else n in
      Some (t, leaves.(i), n)
  | _ -> None
