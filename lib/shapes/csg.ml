type op = Union | Intersection | Difference [@@deriving eq]

type t = { op : op; a : solid; b : solid } [@@deriving eq]
and solid =
  | Sphere of Sphere.t
  | Box of Box.t
  | Mesh of Mesh.t
  | Csg of t
  | Primitive of Shape_desc.primitive
  | Transformed of placed

and placed = { transform : Transform.t; solid : solid; own_material : Material.t option; name : string option }

let v op a b = { op; a; b }
let placed ?material ?name transform solid = Transformed { transform; solid; own_material = material; name }
let ops = [ ("union", Union); ("intersection", Intersection); ("difference", Difference) ]
let op_name op = fst (List.find (fun (_, o) -> o = op) ops)
let op_of_string s = List.assoc_opt s ops
let max_depth = 32

let sphere_material = Sphere.material

let rec fold_solids f acc = function
  | Csg c -> fold_solids f (fold_solids f acc c.a) c.b
  | Transformed p -> fold_solids f acc p.solid
  | leaf -> f acc leaf

let leaf_material = function
  | Sphere s -> sphere_material s
  | Box b -> b.material
  | Mesh m -> m.material
  | Primitive p -> Shape_desc.material p
  | Csg _ | Transformed _ -> invalid_arg "Csg.leaf_material: not a leaf"

(* Each leaf with the material it shows (the outermost enclosing
   operand's own material, as an instance's covers every surface of its
   object, else its own) and the transforms around it, innermost first. *)
let rec fold_placed f acc over frames = function
  | Csg c -> fold_placed f (fold_placed f acc over frames c.a) over frames c.b
  | Transformed p ->
      let over = match over with Some _ -> over | None -> p.own_material in
      fold_placed f acc over (p.transform :: frames) p.solid
  | leaf -> f acc (leaf, (match over with Some m -> m | None -> leaf_material leaf), frames)

let leaves c = List.rev (fold_placed (fun acc l -> l :: acc) [] None [] (Csg c))

(* Every pass over a tree recurses as deep as it nests, and no deeper:
   never along a list of its leaves (a balanced tree of 2^18 leaves nests
   18 deep, and [List.map] over its leaves overflowed the stack, the
   JavaScript one long before the native one). *)
let materials c = List.rev (fold_placed (fun acc (_, m, _) -> m :: acc) [] None [] (Csg c))

(* Whether [s] nests more than [limit] CSG forms, found without going
   deeper than [limit + 1]: a tree built in code may nest a million deep. *)
let rec deeper_than limit = function
  | Csg c -> limit <= 0 || deeper_than (limit - 1) c.a || deeper_than (limit - 1) c.b
  | Transformed p -> limit <= 0 || deeper_than (limit - 1) p.solid
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

(* A pattern lies in its object's frame, which the kernel does not carry
   patterns into (as {!Shape.validate} refuses for instances). *)
let no_pattern p =
  if List.exists (fun (m : Material.t) -> Option.is_some m.pattern) (materials (v Union p.solid p.solid)) then
    Error (`Msg "csg: a transformed operand cannot have a pattern (patterns are not carried into an object's frame yet)")
  else Ok ()

(* A texture on a leaf: the leaf's kind takes its mapping (as an object
   of that kind does, {!Shape.validate}); a mesh's uv texture needs its
   [vt], which its leaf in the kernel's table keeps ([mesh_leaf]). *)
let leaf_texture l (t : Texture_map.t) =
  let name = match l with Sphere _ -> "sphere" | Box _ -> "box" | Mesh _ -> "mesh" | Primitive p -> Shape_desc.name p | Csg _ | Transformed _ -> "csg" in
  match (l, Texture_map.mapping_for name) with
  | Mesh m, Some Texture_map.Uv when t.mapping = Texture_map.Uv && not (Mesh.has_texcoords m) ->
      Error (`Msg "csg: mesh texture mapping uv needs the mesh's texture coordinates (vt), which it has none of")
  | _, None -> Error (`Msg (Printf.sprintf "csg: a %s takes no texture; textures map onto spheres, planes, boxes and meshes" name))
  | _, Some m when m <> t.mapping ->
      Error
        (`Msg
          (Printf.sprintf "csg: %s texture mapping must be %s, got %s" name (Texture_map.mapping_name m)
             (Texture_map.mapping_name t.mapping)))
  | _, Some _ -> Ok ()

let check_textures ?texture c =
  List.fold_left
    (fun acc (l, (m : Material.t), _) ->
      match acc with
      | Error _ -> acc
      | Ok () -> (
          match (match texture with Some _ -> texture | None -> m.texture) with
          | None -> Ok ()
          | Some t -> leaf_texture l t))
    (Ok ()) (leaves c)

let rec validate c =
  let ( let* ) = Result.bind in
  let* () =
    if deeper_than max_depth (Csg c) then Error (`Msg (Printf.sprintf "csg nested deeper than %d levels (transforms count)" max_depth))
    else Ok ()
  in
  let rec child = function
    | Transformed p ->
        let* solid = child p.solid in
        let* () = no_pattern p in
        let* _ =
          match p.own_material with Some m -> Result.map Option.some (Material.validate ~form:"transform" m) | None -> Ok None
        in
        Ok (Transformed { p with solid })
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
  | Transformed p -> Transform.bounds p.transform (solid_box p.solid)
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
  (* A transformed operand's box in the world, not its leaves' in their
     own frames. *)
  let rec go acc = function
    | Csg c -> go (go acc c.a) c.b
    | l ->
        let lo, hi = solid_box l in
        Float.max acc (Float.max (ext lo) (ext hi))
  in
  go 0. (Csg c)

let triangles c = fold_solids (fun n l -> match l with Mesh m -> n + Mesh.objects m | _ -> n) 0 (Csg c)

let rec pp ppf c = Format.fprintf ppf "(csg %s %a %a)" (op_name c.op) pp_solid c.a pp_solid c.b

and pp_solid ppf = function
  | Sphere s -> Sphere.pp ppf s
  | Box b -> Box.pp ppf b
  | Mesh m -> Mesh.pp_form ppf m
  | Primitive p -> Shape_desc.pp_primitive ppf p
  | Csg c -> pp ppf c
  | Transformed { transform; solid; own_material; name } -> (
      (* As {!Shape.pp} prints an instance: a named one as the [use] of its
         definition (which {!Scene.pp} prints first). *)
      let pp_material ppf = function Some m -> Format.fprintf ppf " %a" Material.pp m | None -> () in
      match name with
      | Some n -> Format.fprintf ppf "(use %s (transform %a)%a)" n Transform.pp transform pp_material own_material
      | None -> Format.fprintf ppf "(transform %a %a%a)" Transform.pp transform pp_solid solid pp_material own_material)

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
  uv : float array;
      (** The [vt] of each slot's corners, [u v] for each in [corners]'
          order, 6 floats a slot (a corner without one: [0 0], as a plain
          mesh's, {!Prepared}); empty for a mesh without [vt]. *)
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
  frames : float array;
      (** 12 floats per transformed operand: the world-to-object matrix
          ({!Transform.to_object}) of all the transforms around it,
          composed, so that every level carries the world's ray itself. *)
  surface_frame : int array;  (** The frame of each surface's innermost transformed operand; [-1] for none. *)
  frame_depth : int;  (** The most transformed operands nested in one another. *)
}

type builder = {
  mutable nodes : (int * int * int * int) list;  (** kind, left, right, base; reversed. *)
  mutable n_nodes : int;
  mutable surfaces : (Kind.t * float array * int * int) list;  (** Kind, geometry, material, frame; reversed. *)
  mutable frames : float array list;  (** Reversed. *)
  mutable n_frames : int;
  mutable frame_depth : int;
  mutable n_surfaces : int;
  mutable meshes : mesh_leaf list;  (** Reversed. *)
  mutable n_meshes : int;
  mutable n_intervals : int;
  mutable max_depth : int;
}

let builder () =
  {
    nodes = [];
    n_nodes = 0;
    surfaces = [];
    n_surfaces = 0;
    frames = [];
    n_frames = 0;
    frame_depth = 0;
    meshes = [];
    n_meshes = 0;
    n_intervals = 0;
    max_depth = 0;
  }

(* The frame in which the leaves being added lie: [index] in [frames]
   ([-1] for the world), the composed transform, the material that covers
   them, and how many transformed operands enclose them. *)
type frame = { index : int; composed : Transform.t; over : Material.t option; level : int }

let world = { index = -1; composed = Transform.identity; over = None; level = 0 }

let add_surface b fr kind g mat =
  b.surfaces <- (kind, g, mat, fr.index) :: b.surfaces;
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
  if n = 0 then { vertex = m.positions; corners = [||]; nodes = [||]; root = 0; depth = 0; reach; uv = [||] }
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
    let uv = if Mesh.has_texcoords m then Array.make (6 * n) 0. else [||] in
    if Mesh.has_texcoords m then Array.iteri (fun slot i -> Mesh.store_texcoords m kept.(i) uv (6 * slot)) bvh.order;
    { vertex = m.positions; corners; nodes = bvh.nodes; root = bvh.root; depth = bvh.depth; reach; uv }
  end

(* Adds [s] with its leaves' materials numbered by [material] (given the
   leaf); its node and its capacity in intervals. *)
let rec add_solid b ~material fr s =
  let mat s = material s (match fr.over with Some m -> m | None -> leaf_material s) in
  match s with
  | Sphere sp ->
      let first = b.n_surfaces in
      add_surface b fr Kind.Sphere [| sp.center.x; sp.center.y; sp.center.z; sp.radius |] (mat s);
      (add_node b leaf_node first 0 1, 1)
  | Box bx ->
      let first = b.n_surfaces in
      let g = Array.make stride 0. in
      Box.store bx g 0;
      add_surface b fr Kind.Box g (mat s);
      (add_node b leaf_node first 0 1, 1)
  | Primitive p ->
      let first = b.n_surfaces in
      let g = Array.make stride 0. in
      Shape_desc.store p g 0;
      add_surface b fr (Shape_desc.kind p) g (mat s);
      let cap = Kind.spans (Shape_desc.kind p) in
      (add_node b leaf_node first 0 cap, cap)
  | Mesh m ->
      let sf = b.n_surfaces and leaf = mesh_leaf m in
      let number = b.n_meshes in
      add_surface b fr Kind.Triangle [| Float.of_int number |] (mat s);
      b.meshes <- leaf :: b.meshes;
      b.n_meshes <- number + 1;
      let n = Array.length leaf.corners / 3 in
      (* A line through the hierarchy keeps a stack of at most one node
         a level, and the nodes it pushes last. *)
      b.max_depth <- max b.max_depth leaf.depth;
      let cap = (n / 2) + 1 in
      (add_node b leaf_node sf number cap, cap)
  | Csg c ->
      let a, ca = add_solid b ~material fr c.a in
      let bn, cb = add_solid b ~material fr c.b in
      let kind = match c.op with Union -> union | Intersection -> intersection | Difference -> difference in
      (add_node b kind a bn (ca + cb), ca + cb)
  | Transformed p ->
      (* The object's frame from the world's: the transform, then those
         around it. *)
      let composed = Transform.compose p.transform fr.composed in
      let index = b.n_frames in
      b.frames <- Transform.to_object composed :: b.frames;
      b.n_frames <- index + 1;
      let level = fr.level + 1 in
      b.frame_depth <- max b.frame_depth level;
      let over = match fr.over with Some _ -> fr.over | None -> p.own_material in
      let child, cap = add_solid b ~material { index; composed; over; level } p.solid in
      (* A leaf of a surface of kind [Instance] holding the frame's number
         (see [eval_placed]), that shares its child's intervals: [eval]
         copies only the count. *)
      let sf = b.n_surfaces in
      add_surface b world Kind.Instance [| Float.of_int index |] (-1);
      let _, _, _, child_base = List.hd b.nodes in
      b.nodes <- (leaf_node, sf, child, child_base) :: b.nodes;
      b.n_nodes <- b.n_nodes + 1;
      (b.n_nodes - 1, cap)

let add b ~material c = fst (add_solid b ~material world (Csg c))

let table b =
  let nodes = Array.of_list (List.rev b.nodes) and surfaces = Array.of_list (List.rev b.surfaces) in
  let geom = Array.make (stride * Array.length surfaces) 0. in
  Array.iteri (fun i (_, g, _, _) -> Array.blit g 0 geom (stride * i) (Array.length g)) surfaces;
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
    surface_kind = Array.map (fun (k, _, _, _) -> k) surfaces;
    geom;
    surface_material = Array.map (fun (_, _, m, _) -> m) surfaces;
    meshes = Array.of_list (List.rev b.meshes);
    intervals = b.n_intervals;
    depth = b.max_depth;
    slot_bits;
    surface_id = Array.init (Array.length surfaces) (fun sf -> sf lsl slot_bits);
    frames = Array.concat (List.rev b.frames);
    surface_frame = Array.map (fun (_, _, _, f) -> f) surfaces;
    frame_depth = b.frame_depth;
  }

let empty = table (builder ())

type work = {
  t_in : float array;
  t_out : float array;
  s_in : int array;
  s_out : int array;
  count : int array;
  stack : int array;  (** The nodes of a mesh's hierarchy still to visit. *)
  rays : float array;
      (** 12 floats a level of transformed operands: the ray and its
          triangle-test frame ([Scratch]'s [sx] .. [okz]) of the frame
          around, put back when the operand is done; level 0 is the
          world's. *)
  mutable level : int;  (** Of the transformed operand being traced. *)
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
    rays = Array.make (12 * (tb.frame_depth + 1)) 0.;
    level = 0;
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

(* The ray of [s] and its triangle-test frame, saved in [r] at [o]: a
   transformed operand changes them, and the traversal around the CSG
   solid reads them after ([Triangle.shear]'s, found once per ray). *)
let[@inline] save r o (s : Scratch.t) =
  Array.unsafe_set r o s.ox;
  Array.unsafe_set r (o + 1) s.oy;
  Array.unsafe_set r (o + 2) s.oz;
  Array.unsafe_set r (o + 3) s.dx;
  Array.unsafe_set r (o + 4) s.dy;
  Array.unsafe_set r (o + 5) s.dz;
  Array.unsafe_set r (o + 6) s.sx;
  Array.unsafe_set r (o + 7) s.sy;
  Array.unsafe_set r (o + 8) s.sz;
  Array.unsafe_set r (o + 9) s.okx;
  Array.unsafe_set r (o + 10) s.oky;
  Array.unsafe_set r (o + 11) s.okz

let[@inline] restore r o (s : Scratch.t) =
  s.ox <- Array.unsafe_get r o;
  s.oy <- Array.unsafe_get r (o + 1);
  s.oz <- Array.unsafe_get r (o + 2);
  s.dx <- Array.unsafe_get r (o + 3);
  s.dy <- Array.unsafe_get r (o + 4);
  s.dz <- Array.unsafe_get r (o + 5);
  s.sx <- Array.unsafe_get r (o + 6);
  s.sy <- Array.unsafe_get r (o + 7);
  s.sz <- Array.unsafe_get r (o + 8);
  s.okx <- Array.unsafe_get r (o + 9);
  s.oky <- Array.unsafe_get r (o + 10);
  s.okz <- Array.unsafe_get r (o + 11)

(* The world's ray, saved at the start of [r], into [s] in the frame of
   the matrix at [o] of [m], as the kernel carries a ray into an
   instance: the origin by the world-to-object matrix, the direction by
   its linear part, not renormalised, so that a root [t] is the same
   number in both frames. *)
let[@inline] carry m o r (s : Scratch.t) =
  let x = Array.unsafe_get r 0 and y = Array.unsafe_get r 1 and z = Array.unsafe_get r 2 in
  let dx = Array.unsafe_get r 3 and dy = Array.unsafe_get r 4 and dz = Array.unsafe_get r 5 in
  let a00 = Array.unsafe_get m o and a01 = Array.unsafe_get m (o + 1) and a02 = Array.unsafe_get m (o + 2) in
  let a10 = Array.unsafe_get m (o + 4) and a11 = Array.unsafe_get m (o + 5) and a12 = Array.unsafe_get m (o + 6) in
  let a20 = Array.unsafe_get m (o + 8) and a21 = Array.unsafe_get m (o + 9) and a22 = Array.unsafe_get m (o + 10) in
  s.ox <- (a00 *. x) +. (a01 *. y) +. (a02 *. z) +. Array.unsafe_get m (o + 3);
  s.oy <- (a10 *. x) +. (a11 *. y) +. (a12 *. z) +. Array.unsafe_get m (o + 7);
  s.oz <- (a20 *. x) +. (a21 *. y) +. (a22 *. z) +. Array.unsafe_get m (o + 11);
  s.dx <- (a00 *. dx) +. (a01 *. dy) +. (a02 *. dz);
  s.dy <- (a10 *. dx) +. (a11 *. dy) +. (a12 *. dz);
  s.dz <- (a20 *. dx) +. (a21 *. dy) +. (a22 *. dz)

(* A transformed operand: a leaf node whose surface, of kind [Instance]
   (no solid's kind here), holds its frame's number, and whose [right] is
   its child, so that [eval]'s other paths are as they were (one more arm
   in the leaves' jump table). It calls [eval] through a reference, set
   once: a group of mutually recursive functions made [Csg.roots] bigger
   where the traversal inlines it. *)
let eval_ref : (table -> work -> Scratch.t -> int -> unit) ref = ref (fun _ _ _ _ -> ())

let[@inline never] eval_placed tb w (s : Scratch.t) node sf =
  let child = Array.unsafe_get tb.right node in
  let level = w.level in
  save w.rays (12 * level) s;
  (* The world's ray (level 0's, just saved if this is the outermost
     operand) carried by the composed matrix. *)
  carry tb.frames (12 * truncate (Array.unsafe_get tb.geom (stride * sf))) w.rays s;
  w.level <- level + 1;
  !eval_ref tb w s child;
  w.level <- level;
  restore w.rays (12 * level) s;
  Array.unsafe_set w.count node (Array.unsafe_get w.count child)

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
    | Kind.Instance -> eval_placed tb w s node sf
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


let () = eval_ref := eval

(* Not inlined: inlined into the traversal's [shape_roots], it made the
   traversal's shape tests too big for OCaml to inline into its loops,
   which then cost the scenes of boxes and planes more than the gate
   allows (docs/performance.md, "Round 3: transformed CSG operands"). *)
let[@inline never] roots tb w (s : Scratch.t) root =
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

let[@warning "-11"] leaf_normal tb w (s : Scratch.t) sf =
  let o = stride * sf in
  match Array.unsafe_get tb.surface_kind sf with
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
  | k -> Kind_dispatch.normal k s tb.geom o

(* A transformed operand's surface: the ray carried into its frame as
   [eval] carried it (the same bits), the hit point there at the same
   [t], the surface's normal there, brought to the world by the inverse
   transpose of the linear part (the transpose of the world-to-object
   matrix's) and divided by its length; the world's ray and point put
   back. *)
let[@inline never] framed_normal (tb : table) w (s : Scratch.t) sf f =
  let r = w.rays in
  save r 0 s;
  let px = s.px and py = s.py and pz = s.pz in
  let m = tb.frames and o = 12 * f in
  carry m o r s;
  let t = s.near in
  s.px <- s.ox +. (s.dx *. t);
  s.py <- s.oy +. (s.dy *. t);
  s.pz <- s.oz +. (s.dz *. t);
  leaf_normal tb w s sf;
  Scratch.normal_to_world s m o;
  restore r 0 s;
  s.px <- px;
  s.py <- py;
  s.pz <- pz

let normal tb w (s : Scratch.t) =
  let sf = w.surface lsr tb.slot_bits in
  let f = Array.unsafe_get tb.surface_frame sf in
  if f < 0 then leaf_normal tb w s sf else framed_normal tb w s sf f;
  (* Outward from the solid: against the ray where it enters, along it
     where it leaves. This turns a subtracted solid's normal around. *)
  let along = (s.nx *. s.dx) +. (s.ny *. s.dy) +. (s.nz *. s.dz) > 0. in
  if along <> not w.entering then begin
    s.nx <- -.s.nx;
    s.ny <- -.s.ny;
    s.nz <- -.s.nz
  end

let material tb w = Array.unsafe_get tb.surface_material (w.surface lsr tb.slot_bits)
let geometry tb = tb.geom
let surface_offset tb w = stride * (w.surface lsr tb.slot_bits)

let texcoords (tb : table) w (s : Scratch.t) =
  let leaf = Array.unsafe_get tb.meshes (truncate (Array.unsafe_get tb.geom (surface_offset tb w))) in
  let slot = w.surface land ((1 lsl tb.slot_bits) - 1) and c = leaf.corners in
  (* Without [vt] (which [check_textures] refuses): [(0, 0)], as a
     corner without one, rather than a read past the array. *)
  if Array.length leaf.uv = 0 then begin
    s.tu <- 0.;
    s.tv <- 0.
  end
  else
    Triangle.texcoords_at s leaf.vertex (Array.unsafe_get c (3 * slot)) (Array.unsafe_get c ((3 * slot) + 1))
      (Array.unsafe_get c ((3 * slot) + 2)) leaf.uv (6 * slot)

(* As [framed_normal] carries it: the ray saved at the start of
   [w.rays], put back by [leave_surface_frame]. *)
let enter_surface_frame tb w (s : Scratch.t) =
  let f = Array.unsafe_get tb.surface_frame (w.surface lsr tb.slot_bits) in
  if f >= 0 then begin
    save w.rays 0 s;
    carry tb.frames (12 * f) w.rays s
  end

let leave_surface_frame tb w (s : Scratch.t) =
  if Array.unsafe_get tb.surface_frame (w.surface lsr tb.slot_bits) >= 0 then restore w.rays 0 s

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
  let placed = Array.of_list (leaves c) in
  let leaves = Array.map (fun (l, _, _) -> l) placed in
  (* Each leaf's line in its own frame: the world's carried through the
     transforms around it, outermost first; [t] is the same in each. *)
  let lines =
    Array.map
      (fun (_, _, frames) ->
        List.fold_left
          (fun (o, d) tr ->
            let m = Transform.to_object tr in
            let row k (v : Vec3.t) = (m.(4 * k) *. v.x) +. (m.((4 * k) + 1) *. v.y) +. (m.((4 * k) + 2) *. v.z) in
            ( Vec3.v (row 0 o +. m.(3)) (row 1 o +. m.(7)) (row 2 o +. m.(11)),
              Vec3.v (row 0 d) (row 1 d) (row 2 d) ))
          (origin, direction) (List.rev frames))
      placed
  in
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
        let origin, direction = lines.(i) in
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
        | Csg _ | Transformed _ -> assert false)
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
      let world_direction = direction in
      let origin, direction = lines.(i) in
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
        | Csg _ | Transformed _ -> assert false
      in
      let _, _, frames = placed.(i) in
      let n = List.fold_left (fun n tr -> Transform.normal_to_world tr n) n frames in
      let direction = world_direction in
      let along = Vec3.dot n direction > 0. in
      let n = if along <> not entering then Vec3.neg n else n in
      Some (t, leaves.(i), n)
  | _ -> None
