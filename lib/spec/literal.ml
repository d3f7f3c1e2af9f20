(* The document's algorithm, and every extension, from the definitions.
   The geometry (roots, normals, inside tests, CSG membership, mesh
   parity, refraction, pattern cells) is Literal_geometry's, which calls
   no routine of the kernel. *)
module G = Literal_geometry

(* Ray-object tests done since the last [render] began, and the bound
   they may not pass: every test is counted as it is done, and the count
   checked there. *)
let tests = ref 0
let budget = ref max_int

let tested n =
  tests := !tests + n;
  if !tests > !budget then raise (Limits.Work_exceeded !tests)

let closest_intersection spheres ~origin ~direction ~t_min ~t_max =
  let closest = ref None and closest_t = ref infinity in
  List.iter
    (fun sphere ->
      tested 1;
      let t1, t2 = G.sphere_textbook_roots sphere ~origin ~direction in
      if t1 < !closest_t && t_min < t1 && t1 < t_max then begin
        closest_t := t1;
        closest := Some sphere
      end;
      if t2 < !closest_t && t_min < t2 && t2 < t_max then begin
        closest_t := t2;
        closest := Some sphere
      end)
    spheres;
  match !closest with Some sphere -> Some (sphere, !closest_t) | None -> None

type obj =
  | Sphere of Sphere.t
  | Shape of Shape.t * Vec3.t
  | Mesh_triangle of Mesh.t * int
  | Csg_surface of Csg.t * Csg.solid * Vec3.t
  | Placed of Shape.instance * obj * Vec3.t
      (** A transformed object's surface: the surface hit in the object's
          frame, and the normal in the world. *)

let rec material = function
  | Placed ({ own_material = Some m; _ }, _, _) -> m
  | Placed (_, inner, _) -> material inner
  | Sphere s | Shape (Shape.Sphere s, _) -> Sphere.material s
  | Shape (Shape.Plane p, _) -> p.material
  | Shape (Shape.Triangle t, _) -> t.material
  | Shape (Shape.Box b, _) -> b.material
  | Shape (Shape.Primitive p, _) | Csg_surface (_, Csg.Primitive p, _) -> Shape_desc.material p
  | Shape ((Shape.Mesh _ | Shape.Csg _ | Shape.Instance _), _) -> invalid_arg "Literal.material: not a single surface"
  | Mesh_triangle (m, _) -> m.material
  | Csg_surface (_, Csg.Sphere s, _) -> Sphere.material s
  | Csg_surface (_, Csg.Box b, _) -> b.material
  | Csg_surface (_, Csg.Mesh m, _) -> m.material
  | Csg_surface (_, Csg.Transformed { own_material = Some m; _ }, _) -> m
  | Csg_surface (c, Csg.Transformed p, n) -> material (Csg_surface (c, p.solid, n))
  | Csg_surface (_, Csg.Csg _, _) -> invalid_arg "Literal.material: a CSG node is not a leaf"

(* The medium inside an object: a CSG solid is one medium, its first
   operand's (leftmost leaf's) material. *)
let rec medium_material = function
  | Csg_surface (c, _, n) -> material (Csg_surface (c, List.hd (G.leaves c), n))
  | Placed ({ own_material = Some m; _ }, _, _) -> m
  | Placed (_, inner, _) -> medium_material inner
  | obj -> material obj

(* Which of the kernel's formulas finds an object's parameter. Two
   surfaces that coincide tie exactly, but each formula rounds the
   parameter its own way (a camera ray's too: its direction's [gy / H] is
   rounded for most canvas heights), so which of two formulas' equal
   roots comes first is rounding's decision, not the scene order's. *)
let rec formula = function
  | Sphere _ | Shape (Shape.Sphere _, _) | Csg_surface (_, Csg.Sphere _, _) -> 0
  | Shape (Shape.Plane _, _) -> 1
  | Shape (Shape.Triangle _, _) | Mesh_triangle _ | Csg_surface (_, Csg.Mesh _, _) -> 2
  | Shape (Shape.Box _, _) | Csg_surface (_, Csg.Box _, _) -> 3
  | Shape (Shape.Primitive _, _) | Csg_surface (_, Csg.Primitive _, _) -> 4
  | Placed (_, inner, _) -> 8 + formula inner
  | Shape ((Shape.Mesh _ | Shape.Csg _ | Shape.Instance _), _) | Csg_surface (_, (Csg.Csg _ | Csg.Transformed _), _) -> 16

(* The objects other than spheres, each with the number of its shape in
   the scene's list (a mesh's triangles share theirs, and are listed with
   their corners), made once per list of shapes. *)
type item =
  | Plane_item of Plane.t
  | Triangle_item of Triangle.t
  | Box_item of Box.t
  | Primitive_item of Shape_desc.primitive
  | Facet_item of Mesh.t * int * Vec3.t * Vec3.t * Vec3.t
  | Csg_item of Csg.t
  | Instance_item of Shape.instance

let items_of_shape = function
  | Shape.Instance i -> [ Instance_item i ]
  | Shape.Sphere _ -> invalid_arg "Literal.items_of_shape: spheres are listed apart"
  | Shape.Plane p -> [ Plane_item p ]
  | Shape.Triangle t -> [ Triangle_item t ]
  | Shape.Box b -> [ Box_item b ]
  | Shape.Primitive p -> [ Primitive_item p ]
  | Shape.Mesh m -> List.init (Mesh.triangle_count m) (fun k -> Facet_item (m, k, Mesh.vertex m k 0, Mesh.vertex m k 1, Mesh.vertex m k 2))
  | Shape.Csg c -> [ Csg_item c ]

let items_cache = ref ([], [||])

(* Each item with its object's number in the scene's list: the [k]-th
   shape placed after [j] spheres is object [j + k]. *)
let items (placed : (int * Shape.t) list) =
  match !items_cache with
  | cached, items when cached == placed -> items
  | _ ->
      let items =
        Array.of_list (List.concat (List.mapi (fun k (j, sh) -> List.map (fun i -> (i, j + k)) (items_of_shape sh)) placed))
      in
      items_cache := (placed, items);
      items

(* Sphere [i]'s number in the scene's list: [i] plus the shapes before it. *)
let sphere_number (placed : (int * Shape.t) list) i = List.fold_left (fun n (j, _) -> if j <= i then n + 1 else n) i placed

(* The position of [x] in [l], by physical equality: of spheres given
   twice, the first is the one hit. *)
let position x l =
  let rec go k = function y :: rest -> if y == x then k else go (k + 1) rest | [] -> -1 in
  go 0 l

(* The scene's compact spheres are listed once per scene, not once per
   ray: the last list is kept, with the spheres it lists. *)
let last_listed = ref (Spheres.empty, [])

let sphere_list spheres =
  let from, l = !last_listed in
  if from == spheres then l
  else begin
    let l = Spheres.to_list spheres in
    last_listed := (spheres, l);
    l
  end

(* {1 Transforms, this module's own way}

   The matrix of a transform from its operations, composed here (the
   kernel's [Transform] composes each operation's exact inverse instead),
   and its inverse by the adjugate over the determinant. Rows of
   [[a b c tx]]. *)

let rotation_matrix (axis : Vec3.t) deg =
  (* The angle's cosine and sine are the definition's: exact at quarter turns. *)
  let c, s = Transform.cos_sin deg in
  let a = Vec3.unit axis in
  let cross = [| 0.; -.a.z; a.y; a.z; 0.; -.a.x; -.a.y; a.x; 0. |] in
  let outer = [| a.x *. a.x; a.x *. a.y; a.x *. a.z; a.y *. a.x; a.y *. a.y; a.y *. a.z; a.z *. a.x; a.z *. a.y; a.z *. a.z |] in
  (* R = c I + s [a]x + (1 - c) a a^T. *)
  Array.init 12 (fun k ->
      let r = k / 4 and col = k mod 4 in
      if col = 3 then 0.
      else
        let j = (3 * r) + col in
        (if r = col then c else 0.) +. (s *. cross.(j)) +. ((1. -. c) *. outer.(j)))

let op_matrix = function
  | Transform.Scale v -> [| v.x; 0.; 0.; 0.; 0.; v.y; 0.; 0.; 0.; 0.; v.z; 0. |]
  | Translate v -> [| 1.; 0.; 0.; v.x; 0.; 1.; 0.; v.y; 0.; 0.; 1.; v.z |]
  | Rotate_x a -> rotation_matrix Vec3.ox a
  | Rotate_y a -> rotation_matrix Vec3.oy a
  | Rotate_z a -> rotation_matrix Vec3.oz a
  | Rotate (axis, a) -> rotation_matrix axis a

let at m r c = m.((4 * r) + c)

(* [then_ m n] is [m] applied after [n]. *)
let then_ m n =
  Array.init 12 (fun k ->
      let r = k / 4 and c = k mod 4 in
      (at m r 0 *. at n 0 c) +. (at m r 1 *. at n 1 c) +. (at m r 2 *. at n 2 c) +. if c = 3 then at m r 3 else 0.)

let world_matrix t = List.fold_left (fun m op -> then_ (op_matrix op) m) (op_matrix (Transform.Scale (Vec3.v 1. 1. 1.))) (Transform.ops t)

let inverse m =
  let a i j = at m i j in
  let cof i j =
    let r0 = if i = 0 then 1 else 0 and r1 = if i = 2 then 1 else 2 in
    let c0 = if j = 0 then 1 else 0 and c1 = if j = 2 then 1 else 2 in
    let minor = (a r0 c0 *. a r1 c1) -. (a r0 c1 *. a r1 c0) in
    if (i + j) mod 2 = 0 then minor else -.minor
  in
  let det = (a 0 0 *. cof 0 0) +. (a 0 1 *. cof 0 1) +. (a 0 2 *. cof 0 2) in
  (* The inverse's linear part is the adjugate (the transposed cofactors)
     over the determinant; its translation takes the inverse's linear part
     to minus the translation. *)
  let l = Array.init 9 (fun k -> cof (k mod 3) (k / 3) /. det) in
  let t r = -.((l.(3 * r) *. a 0 3) +. (l.((3 * r) + 1) *. a 1 3) +. (l.((3 * r) + 2) *. a 2 3)) in
  Array.init 12 (fun k -> let r = k / 4 and c = k mod 4 in if c = 3 then t r else l.((3 * r) + c))

let affine_point m (p : Vec3.t) =
  Vec3.v
    ((at m 0 0 *. p.x) +. (at m 0 1 *. p.y) +. (at m 0 2 *. p.z) +. at m 0 3)
    ((at m 1 0 *. p.x) +. (at m 1 1 *. p.y) +. (at m 1 2 *. p.z) +. at m 1 3)
    ((at m 2 0 *. p.x) +. (at m 2 1 *. p.y) +. (at m 2 2 *. p.z) +. at m 2 3)

let linear m (d : Vec3.t) =
  Vec3.v
    ((at m 0 0 *. d.x) +. (at m 0 1 *. d.y) +. (at m 0 2 *. d.z))
    ((at m 1 0 *. d.x) +. (at m 1 1 *. d.y) +. (at m 1 2 *. d.z))
    ((at m 2 0 *. d.x) +. (at m 2 1 *. d.y) +. (at m 2 2 *. d.z))

let transposed m (n : Vec3.t) =
  Vec3.v
    ((at m 0 0 *. n.x) +. (at m 1 0 *. n.y) +. (at m 2 0 *. n.z))
    ((at m 0 1 *. n.x) +. (at m 1 1 *. n.y) +. (at m 2 1 *. n.z))
    ((at m 0 2 *. n.x) +. (at m 1 2 *. n.y) +. (at m 2 2 *. n.z))

(* A CSG operand's transform, this module's own way: the ray into its
   frame, and a normal from it by the inverse transpose. *)
let carry_into tr origin direction =
  let inv = inverse (world_matrix tr) in
  (affine_point inv origin, linear inv direction)

let normal_out tr n = Vec3.unit (transposed (inverse (world_matrix tr)) n)

(* An object's normal at a point, as [normal] below finds it (defined
   after the roots): set once [normal] is. *)
let inner_normal_ref : (obj -> point:Vec3.t -> direction:Vec3.t -> Vec3.t) ref = ref (fun _ ~point:_ ~direction:_ -> Vec3.zero)
let inner_normal obj ~point ~direction = !inner_normal_ref obj ~point ~direction

(* Ray-object searches whose answer rounding may decide (see the .mli). *)
let dependent = ref 0
let rounding_dependent () = !dependent

(* The roots of an item, nearer first, each with its object. *)
let rec item_roots ~continued item ~origin ~direction ~t_min ~t_max =
  match item with
  | Instance_item i -> (
      (* The ray in the object's frame, by this module's own inverse; [t]
         is the same number in both frames. *)
      let m = world_matrix i.transform in
      let inv = inverse m in
      let o = affine_point inv origin and d = linear inv direction in
      match inner_closest ~continued i.shape ~origin:o ~direction:d ~t_min ~t_max with
      | None -> []
      | Some (key, inner) ->
          let point = Vec3.add o (Vec3.smul key.G.t d) in
          let n = inner_normal inner ~point ~direction:d in
          (* Normals by the inverse transpose. *)
          [ (key, Placed (i, inner, Vec3.unit (transposed inv n))) ])
  | Plane_item p -> (
      tested 1;
      match G.plane_key p ~origin ~direction with Some k -> [ (k, Shape (Shape.Plane p, G.plane_normal p)) ] | None -> [])
  | Triangle_item tri -> (
      tested 1;
      match G.triangle_hit ~origin ~direction tri.v0 tri.v1 tri.v2 with
      | Some k -> [ (k, Shape (Shape.Triangle tri, G.triangle_normal tri.v0 tri.v1 tri.v2)) ]
      | None -> [])
  | Facet_item (m, k, a, b, c) -> (
      tested 1;
      match G.triangle_hit ~origin ~direction a b c with Some key -> [ (key, Mesh_triangle (m, k)) ] | None -> [])
  | Box_item b -> (
      tested 1;
      match G.box_hit b ~origin ~direction with
      | Some h -> [ (h.enter, Shape (Shape.Box b, h.enter_normal)); (h.exit, Shape (Shape.Box b, h.exit_normal)) ]
      | None -> [])
  | Primitive_item p ->
      (* The kind's own literal crossings, from its definition. *)
      tested 1;
      List.map (fun (t, n) -> (G.key_of_float t, Shape (Shape.Primitive p, n))) (Shape_desc.literal p ~origin ~direction)
  | Csg_item c -> (
      match G.csg_hit ~continued ~tested ~into:carry_into ~out:normal_out c ~origin ~direction ~t_min ~t_max with
      | Some h -> [ (h.key, Csg_surface (c, h.leaf, h.normal)) ]
      | None -> [])

(* The closest hit in range of an instance's object (in its frame). *)
and inner_closest ~continued shape ~origin ~direction ~t_min ~t_max =
  match shape with
  | Shape.Sphere s -> (
      match closest_intersection [ s ] ~origin ~direction ~t_min ~t_max with
      | Some (s, t) -> Some (G.key_of_float t, Sphere s)
      | None -> None)
  | _ ->
      List.fold_left
        (fun best item ->
          let in_range ((t : G.key), _) =
            G.in_range ~continued ~t_min ~t_max t
            && match best with Some (b, _) -> G.compare_keys t b < 0 | None -> true
          in
          match List.find_opt in_range (item_roots ~continued item ~origin ~direction ~t_min ~t_max) with
          | Some hit -> Some hit
          | None -> best)
        None (items_of_shape shape)

(* The closest hit with its object's number in the scene's list, a mesh
   one number (the numbers name the media a ray is in). Roots are ordered
   exactly: of equal roots, the first object in the list wins. *)
let closest_numbered ?(continued = false) (scene : Scene.view) ~origin ~direction ~t_min ~t_max =
  let near0, ties0 = G.undecided () in
  (* A camera ray's origin is the camera's own value, continued or not:
     every other ray leaves a computed point. *)
  let secondary = origin != scene.camera.position in
  let cross_tie = ref false in

  let spheres = sphere_list scene.spheres in
  let best =
    match closest_intersection spheres ~origin ~direction ~t_min ~t_max with
    | Some (sphere, t) -> Some (Sphere sphere, sphere_number scene.placed (position sphere spheres), G.key_of_float t)
    | None -> None
  in
  let best =
    G.from_origin ~computed:secondary origin @@ fun () ->
    Array.fold_left
      (fun best (item, id) ->
        let in_range ((t : G.key), obj) =
          G.in_range ~continued ~t_min ~t_max t
          &&
          match best with
          | Some (best_obj, best_id, b) ->
              let c = G.compare_keys t b in
              if c = 0 && formula obj <> formula best_obj then cross_tie := true;
              c < 0 || (c = 0 && id < best_id)
          | None -> true
        in
        match List.find_opt in_range (item_roots ~continued item ~origin ~direction ~t_min ~t_max) with
        | Some (t, obj) -> Some (obj, id, t)
        | None -> best)
      best (items scene.placed)
  in
  let near1, ties1 = G.undecided () in
  if near1 > near0 || !cross_tie || (secondary && ties1 > ties0) then incr dependent;
  Option.map (fun (obj, id, (t : G.key)) -> (obj, id, t.t)) best

let closest_hit scene ~origin ~direction ~t_min ~t_max =
  Option.map (fun (obj, _, t) -> (obj, t)) (closest_numbered scene ~origin ~direction ~t_min ~t_max)

(* A corner's normal, divided by its length, if it has one that can be. *)
let corner_normal (m : Mesh.t) k c =
  let j = m.triangle_normals.((3 * k) + c) in
  if j < 0 then None
  else
    let n = Vec3.v m.normals.(3 * j) m.normals.((3 * j) + 1) m.normals.((3 * j) + 2) in
    let l = Vec3.norm n in
    if l > 0. && Float.is_finite l && Float.is_finite (1. /. l) then Some (Vec3.smul (1. /. l) n) else None

let turn n direction = if Vec3.dot n direction > 0. then Vec3.neg n else n

(* A sphere's normal points out of it, as in the document; the others'
   are turned toward the ray, so that they are lit from the side they are
   seen from. A smooth triangle's is turned as its flat normal is. *)
let normal obj ~point ~direction =
  match obj with
  | Sphere sphere -> G.sphere_normal sphere point
  | Shape (_, n) | Csg_surface (_, _, n) | Placed (_, _, n) -> turn n direction
  | Mesh_triangle (m, k) -> (
      let a = Mesh.vertex m k 0 and b = Mesh.vertex m k 1 and c = Mesh.vertex m k 2 in
      let n = G.triangle_normal a b c in
      let flip = Vec3.dot n direction > 0. in
      let turned n = if flip then Vec3.neg n else n in
      let smooth =
        if not m.smooth then None
        else
          match (corner_normal m k 0, corner_normal m k 1, corner_normal m k 2) with
          | Some na, Some nb, Some nc -> G.smooth_normal a b c (na, nb, nc) point
          | _ -> None
      in
      match smooth with Some s -> turned s | None -> turned n)

let () = inner_normal_ref := normal

(* {1 Pattern frames} *)

let largest (v : Vec3.t) = Float.max (Float.abs v.x) (Float.max (Float.abs v.y) (Float.abs v.z))
let sphere_frame (s : Sphere.t) = (Vec3.zero, 1., largest s.center +. s.radius)
let box_frame (b : Box.t) = (b.min, 1., Float.max (largest b.min) (largest b.max))

(* A described kind's frame: its stored floats' largest magnitude, as
   the scene's documentation defines it for every kind but the sphere,
   box and mesh. *)
let primitive_frame p =
  let g = Array.make Kind.stride 0. in
  Shape_desc.store p g 0;
  (Vec3.zero, 1., Array.fold_left (fun e x -> Float.max e (Float.abs x)) 0. g)

(* A mesh's frame scans every vertex: kept for the mesh's next triangle. *)
let last_frame = ref None

let mesh_frame (m : Mesh.t) =
  match !last_frame with
  | Some (m', f) when m' == m -> f
  | _ ->
      let f = (m.translate, m.scale, Array.fold_left (fun e x -> Float.max e (Float.abs x)) 0. m.positions) in
      last_frame := Some (m, f);
      f

(* Where an object's pattern lies: its origin and scale, and its largest
   coordinate (docs/scene-format.md, Patterns). *)
let pattern_frame = function
  | Sphere s | Shape (Shape.Sphere s, _) | Csg_surface (_, Csg.Sphere s, _) -> sphere_frame s
  | Shape (Shape.Plane p, _) -> (Vec3.zero, 1., Float.max (largest p.point) (largest (Vec3.unit p.normal)))
  | Shape (Shape.Triangle t, _) -> (Vec3.zero, 1., Float.max (largest t.v0) (Float.max (largest t.v1) (largest t.v2)))
  | Shape (Shape.Box b, _) | Csg_surface (_, Csg.Box b, _) -> box_frame b
  | Mesh_triangle (m, _) | Csg_surface (_, Csg.Mesh m, _) -> mesh_frame m
  | Shape (Shape.Primitive p, _) | Csg_surface (_, Csg.Primitive p, _) -> primitive_frame p
  | Shape ((Shape.Mesh _ | Shape.Csg _ | Shape.Instance _), _) | Csg_surface (_, (Csg.Csg _ | Csg.Transformed _), _) | Placed _ -> invalid_arg "Literal.pattern_frame"

(* {1 Textures} *)

(* The texture coordinates of [point] on [obj] (in its own frame: a
   placed object's is looked up there, [local_color]; a CSG solid's
   sphere or box leaf's in the solid's frame, a mesh leaf's as its
   triangle, [texture_point]), by the mappings' definitions
   (Texture_map); a mesh's corner without a [vt] counts as [(0, 0)]. *)
let rec texture_uv obj (tex : Texture_map.t) point =
  match obj with
  | Sphere s | Shape (Shape.Sphere s, _) | Csg_surface (_, Csg.Sphere s, _) -> Texture_map.spherical ~center:s.center point
  | Shape (Shape.Plane p, _) -> Texture_map.planar ~point:p.point ~normal:p.normal ~size:tex.size point
  | Shape (Shape.Box b, _) | Csg_surface (_, Csg.Box b, _) ->
      let _, u, v = Texture_map.box ~min:b.min ~max:b.max point in
      (u, v)
  | Mesh_triangle (m, k) ->
      let b1, b2 = Texture_map.barycentric (Mesh.vertex m k 0) (Mesh.vertex m k 1) (Mesh.vertex m k 2) point in
      let corner c =
        let j = m.triangle_texcoords.((3 * k) + c) in
        if j < 0 then (0., 0.) else (m.texcoords.(2 * j), m.texcoords.((2 * j) + 1))
      in
      Texture_map.interpolate ~b1 ~b2 (corner 0) (corner 1) (corner 2)
  | Csg_surface (c, Csg.Transformed p, n) -> texture_uv (Csg_surface (c, p.solid, n)) tex point
  | Shape _ | Csg_surface _ | Placed _ -> invalid_arg "Literal.texture_uv: a texture on an object that takes none"

(* The image's colour at the hit: its bilinear lookup at the point's
   coordinates, with the mapping's wraps. *)
let texture_color obj (tex : Texture_map.t) point =
  let u, v = texture_uv obj tex point in
  let wrap_u, wrap_v = Texture_map.wraps tex.mapping in
  Texture.color ~wrap_u ~wrap_v tex.image u v

(* Where a texture looks [point] up, and on what: on a CSG leaf inside
   transformed operands, in their frame, the ray carried through their
   transforms, outermost first, to the same [t] (Csg.literal_hit's
   lines); on a CSG mesh leaf, its triangle there. The leaf is found by
   physical equality: one placed twice in a solid is taken at its first
   place. *)
let texture_point obj ~t ~origin ~direction point =
  match obj with
  | Csg_surface (c, leaf, _) -> (
      (* A leaf shown with another material comes wrapped in an identity
         placement (Literal_geometry.shown). *)
      let leaf = match leaf with Csg.Transformed p -> p.solid | l -> l in
      let on_line origin direction =
        (* A mesh leaf's texture lies on its triangle crossed at [t]: the
           first the line crosses there, its key's [t] that number. *)
        let point = Vec3.add origin (Vec3.smul t direction) in
        match leaf with
        | Csg.Mesh m ->
            let crossed k =
              let a = Mesh.vertex m k 0 and b = Mesh.vertex m k 1 and c = Mesh.vertex m k 2 in
              (not (Mesh.degenerate m k))
              && G.triangle_crossing ~origin ~direction a b c
              && (G.triangle_key ~origin ~direction a b c).t = t
            in
            let k = List.find_opt crossed (List.init (Mesh.triangle_count m) Fun.id) in
            (Option.fold ~none:obj ~some:(fun k -> Mesh_triangle (m, k)) k, point)
        | _ -> (obj, point)
      in
      match List.find_opt (fun (l, _, _) -> l == leaf) (Csg.leaves c) with
      | Some (_, _, (_ :: _ as frames)) ->
          let origin, direction =
            List.fold_left
              (fun (o, d) (tr : Transform.t) ->
                let inv = inverse (world_matrix tr) in
                (affine_point inv o, linear inv d))
              (origin, direction) (List.rev frames)
          in
          on_line origin direction
      | _ -> (fst (on_line origin direction), point))
  | _ -> (obj, point)

(* The colour the hit at [t] shows: the material's, its pattern's second
   colour, or its texture's. A transformed object's pattern or texture
   lies in its frame
   (docs/scene-format.md, Patterns): the ray carried there by this
   module's own inverse, the point at the same [t] on it, and the
   surface's normal there; the frame is the surface's (an instance's own
   material's pattern lies where the surface's own would). *)
let rec local_color obj (m : Material.t) ~t ~origin ~direction ~point ~normal =
  match (m.pattern, obj) with
  | None, Placed _ when Option.is_none m.texture -> m.color
  | _, Placed (i, inner, _) ->
      let inv = inverse (world_matrix i.transform) in
      let origin = affine_point inv origin and direction = linear inv direction in
      let point = Vec3.add origin (Vec3.smul t direction) in
      let normal = inner_normal inner ~point ~direction in
      local_color inner m ~t ~origin ~direction ~point ~normal
  | None, _ -> (
      match m.texture with
      | Some tex ->
          let obj, point = texture_point obj ~t ~origin ~direction point in
          texture_color obj tex point
      | None -> m.color)
  | Some p, _ ->
      let near0, _ = G.undecided () in
      let odd = G.odd p ~frame:(pattern_frame obj) ~origin ~direction ~point ~normal in
      if fst (G.undecided ()) > near0 then incr dependent;
      if odd then Pattern.color p else m.color

(* The light a shadow ray lets through transparent objects: the product
   of the transparency of each surface it crosses, nearest first, until an
   opaque one stops it (0). *)
let rec transmitted ?(continued = false) scene ~origin ~direction ~t_min ~t_max f =
  match closest_numbered ~continued scene ~origin ~direction ~t_min ~t_max with
  | None -> f
  | Some (obj, _, t) ->
      let f = f *. (medium_material obj).transparency in
      if f > 0. then transmitted ~continued:true scene ~origin ~direction ~t_min:t ~t_max f else f

(* The point lights that light [light] numbered [number] in the scene's
   list stands for at [point], as (intensity, vector from [point]): itself
   for a point or directional light; for an area or sphere light its
   samples, and for a spotlight itself scaled, or nothing outside its cone
   (Light, "Sample points", transcribed here from the definition). *)
let light_samples ~key ~number light point =
  let hl = Sample_key.key key number in
  match light with
  | Light.Ambient _ -> []
  | Point { intensity; position } -> [ (intensity, Vec3.sub position point) ]
  | Directional { intensity; direction } -> [ (intensity, direction) ]
  | Area { intensity; corner; edge1; edge2; samples_u = u; samples_v = v; adaptive = _; sampling } ->
      let i = intensity /. Float.of_int (u * v) in
      let sigma = Sample_key.permute (Sample_key.key hl (-1)) ~n:v
      and tau = Sample_key.permute (Sample_key.key hl (-2)) ~n:u in
      let below_1 x = if x < 1. then x else Float.pred 1. in
      let uv = Float.of_int (u * v) in
      List.concat
        (List.init u (fun a ->
             List.init v (fun b ->
                 let h = Sample_key.key hl ((a * v) + b) in
                 let s, t =
                   match sampling with
                   | Light.Stratified ->
                       ( below_1 ((Float.of_int ((a * v) + sigma b) +. Sample_key.unit h) /. uv),
                         below_1 ((Float.of_int ((b * u) + tau a) +. Sample_key.unit (Sample_key.mix h)) /. uv) )
                   | Uniform -> (Sample_key.unit h, Sample_key.unit (Sample_key.mix h))
                 in
                 let q = Vec3.add (Vec3.add corner (Vec3.smul s edge1)) (Vec3.smul t edge2) in
                 (i, Vec3.sub q point))))
  | Sphere { intensity; position; radius; samples = n } ->
      let toward = Vec3.sub position point in
      if Vec3.norm toward = 0. then []
      else
        let w = Vec3.unit toward in
        let a = if Float.abs w.x > 0.9 then Vec3.oy else Vec3.ox in
        let e1 = Vec3.unit (Vec3.cross a w) in
        let e2 = Vec3.cross w e1 in
        let c = Light.sectors n in
        let q = (n + c - 1) / c in
        let r = Sample_key.unit (Sample_key.key hl (-1)) in
        List.init n (fun j ->
            let h = Sample_key.key hl j in
            let rho = radius *. sqrt (Sample_key.stratum (Sample_key.key h 0) ~n j) in
            let a = j mod c and b = Sample_key.permute (Sample_key.key hl (-2)) ~n:q (j / c) in
            let phi =
              2. *. Float.pi
              *. (r +. ((Float.of_int a +. ((Float.of_int b +. Sample_key.unit (Sample_key.key h 1)) /. Float.of_int q)) /. Float.of_int c))
            in
            let q = Vec3.add (Vec3.add position (Vec3.smul (rho *. cos phi) e1)) (Vec3.smul (rho *. sin phi) e2) in
            (intensity /. Float.of_int n, Vec3.sub q point))
  | Spot { intensity; position; direction; angle; falloff } ->
      let l = Vec3.sub position point in
      let dist = Vec3.norm l in
      (* theta <= angle, compared as cosines. *)
      let cos_off = -.Vec3.dot l (Vec3.unit direction) /. dist in
      if dist > 0. && cos_off >= Float.cos (angle *. Float.pi /. 180.) then [ (intensity *. (cos_off ** falloff), l) ]
      else []

(* An adaptive area light's corners seen from [point]: [`Seen] if every
   corner's shadow ray passes freely (a factor of exactly 1), [`Hidden]
   if every one is stopped (0), [`Doubt] otherwise (Light, "Penumbra-only
   sampling"). *)
let corners ~passes light point =
  match light with
  | Light.Area { corner; edge1; edge2; _ } when Light.corners_first light ->
      let at a b = Vec3.sub (Vec3.add (Vec3.add corner (Vec3.smul a edge1)) (Vec3.smul b edge2)) point in
      let f = List.map passes [ at 0. 0.; at 1. 0.; at 0. 1.; at 1. 1. ] in
      if List.for_all (fun x -> x = 1.) f then `Seen else if List.for_all (fun x -> x = 0.) f then `Hidden else `Doubt
  | _ -> `Doubt

let lighting_through ?(key = 0) ~through (scene : Scene.view) ~epsilon ~point ~normal ~view ~specular =
  let intensity = ref 0. in
  (* How much of a light at [point + l] reaches [point]: 0 or 1, or
     through glass the product of the transparencies crossed. *)
  let passes l =
    if through then transmitted scene ~origin:point ~direction:l ~t_min:epsilon ~t_max:1. 1.
    else if closest_hit scene ~origin:point ~direction:l ~t_min:epsilon ~t_max:1. <> None then 0.
    else 1.
  in
  List.iteri
    (fun number light ->
      match (light, corners ~passes light point) with
      | Light.Ambient _, _ -> intensity := !intensity +. Light.intensity light
      | _, `Hidden -> ()
      | _, verdict ->
          List.iter
            (fun (li, l) ->
              if Vec3.norm2 l = 0. then
                (* A point light exactly at the point: L has no direction,
                   and the formulas would divide by zero. The document is
                   silent; the light is skipped. *)
                ()
              else begin
                (* Shadow check (7.7): is any object between the point and
                   the light? Through transparent objects, how much light
                   passes? *)
                let t_max = Light.shadow_t_max light in
                let passes =
                  if verdict = `Seen then 1.
                  else if through then transmitted scene ~origin:point ~direction:l ~t_min:epsilon ~t_max 1.
                  else if closest_hit scene ~origin:point ~direction:l ~t_min:epsilon ~t_max <> None then 0.
                  else 1.
                in
                if passes > 0. then begin
                  let i = li *. passes in
                  intensity := !intensity +. Shading.diffuse ~intensity:i ~l ~n:normal;
                  if specular <> Sphere.matte then
                    let r = Shading.reflect l normal in
                    intensity := !intensity +. Shading.specular ~intensity:i ~s:specular ~r ~v:view
                end
              end)
            (light_samples ~key ~number light point))
    scene.lights;
  !intensity

let compute_lighting ?key = lighting_through ?key ~through:false

(* Iterative, so that no depth the limits allow can overflow the stack:
   the mirror rays are followed down, each level's local colour and
   reflectivity kept, then blended back up from the deepest colour, in the
   order of the document's recursion (the same floating-point operations). *)
let trace_ray ?key (scene : Scene.view) ~epsilon ~origin ~direction ~t_min ~t_max ~depth =
  let rec follow levels ~origin ~direction ~t_min ~t_max ~depth =
    match closest_hit scene ~origin ~direction ~t_min ~t_max with
    | None -> (levels, scene.background)
    | Some (obj, t) ->
        let m = material obj in
        let point = Vec3.add origin (Vec3.smul t direction) in
        let normal = normal obj ~point ~direction in
        let view = Vec3.neg direction in
        let lighting = compute_lighting ?key scene ~epsilon ~point ~normal ~view ~specular:m.specular in
        let local = Color.smul lighting (local_color obj m ~t ~origin ~direction ~point ~normal) in
        if m.reflective <= 0. || depth <= 0 then (levels, local)
        else
          let mirror = Shading.reflect view normal in
          follow ((m.reflective, local) :: levels) ~origin:point ~direction:mirror
            ~t_min:epsilon ~t_max:infinity ~depth:(depth - 1)
  in
  let levels, deepest = follow [] ~origin ~direction ~t_min ~t_max ~depth in
  List.fold_left
    (fun reflected (reflective, local) -> Color.blend ~reflective ~local ~reflected)
    deepest levels

(* Transparency (the book's chapter "Extending the Raytracer"), as a
   recursion. [media] lists the objects the ray is inside, innermost first,
   by number, with their indices; at most 16 nest (docs/scene-format.md).
   Crossing a surface of object [id] gives the indices on its near and far
   sides and the media beyond it. *)
let media_cap = 16

let cross media ~id ~index =
  let near = match media with (_, n) :: _ -> n | [] -> 1. in
  match media with
  | (top, _) :: under when top = id -> (near, (match under with (_, n) :: _ -> n | [] -> 1.), under)
  | _ when List.mem_assoc id media -> (near, near, List.remove_assoc id media)
  | _ -> (near, index, if List.length media < media_cap then (id, index) :: media else media)

(* Snell and Schlick at a hit; a smooth triangle's normal may send the
   refracted ray back to the side it came from: then its flat normal,
   turned toward the ray, splits it. *)
let optics obj (m : Material.t) ~near ~far ~direction ~normal =
  let facing = if Vec3.dot normal direction <= 0. then normal else Vec3.neg normal in
  let sp = G.split ~n1:near ~n2:far ~fresnel:m.fresnel ~direction ~normal:facing in
  match (obj, sp.refracted) with
  | Mesh_triangle (mesh, k), Some t when mesh.smooth ->
      let g = G.triangle_normal (Mesh.vertex mesh k 0) (Mesh.vertex mesh k 1) (Mesh.vertex mesh k 2) in
      let g_dot_d = Vec3.dot g direction and g_dot_t = Vec3.dot g t in
      if (g_dot_d > 0. && g_dot_t > 0.) || (g_dot_d < 0. && g_dot_t < 0.) then sp
      else G.split ~n1:near ~n2:far ~fresnel:m.fresnel ~direction ~normal:(if g_dot_d > 0. then Vec3.neg g else g)
  | _ -> sp

(* The colour seen along a ray at bounce [level]: the hit's local colour
   weighted [1 - r - t], the reflected ray's [wr = r + t R] and the
   refracted ray's [wt = t (1 - R)], [R] the reflectance (1 on total
   internal reflection). A surface that changes nothing (transparency 1,
   the same index on both sides) is crossed on the same ray, without a
   bounce. At [level = depth], or without either ray, the local colour
   alone (section 7.8). *)
let rec shade ?(continued = false) ?key (scene : Scene.view) ~epsilon ~origin ~direction ~t_min ~level ~media =
  match closest_numbered ~continued scene ~origin ~direction ~t_min ~t_max:infinity with
  | None -> scene.background
  | Some (obj, id, t) ->
      let m = material obj and medium = medium_material obj in
      let near, far, beyond = cross media ~id ~index:medium.refractive_index in
      if medium.transparency = 1. && near = far then shade ~continued:true ?key scene ~epsilon ~origin ~direction ~t_min:t ~level ~media:beyond
      else
        let point = Vec3.add origin (Vec3.smul t direction) in
        let normal = normal obj ~point ~direction in
        let view = Vec3.neg direction in
        let sp =
          if m.transparency > 0. then optics obj m ~near ~far ~direction ~normal
          else { G.refracted = None; reflectance = 0. }
        in
        let wr = m.reflective +. (m.transparency *. sp.reflectance) in
        let wt = m.transparency *. (1. -. sp.reflectance) in
        let local () =
          Color.smul
            (lighting_through ?key ~through:true scene ~epsilon ~point ~normal ~view ~specular:m.specular)
            (local_color obj m ~t ~origin ~direction ~point ~normal)
        in
        if level >= scene.depth || (wr <= 0. && wt <= 0.) then local ()
        else
          let keep = 1. -. m.reflective -. m.transparency in
          let c = if keep > 0. then Color.smul keep (local ()) else Color.black in
          let c =
            if wr > 0. then
              let reflected =
                shade ?key scene ~epsilon ~origin:point ~direction:(Shading.reflect view normal) ~t_min:epsilon
                  ~level:(level + 1) ~media
              in
              Color.add c (Color.smul wr reflected)
            else c
          in
          match sp.refracted with
          | Some direction when wt > 0. ->
              let refracted = shade ?key scene ~epsilon ~origin:point ~direction ~t_min:epsilon ~level:(level + 1) ~media:beyond in
              Color.add c (Color.smul wt refracted)
          | _ -> c

let transparent (scene : Scene.view) =
  Spheres.exists (fun (s : Sphere.t) -> s.material.transparency > 0.) scene.spheres
  || List.exists (fun sh -> List.exists (fun (m : Material.t) -> m.transparency > 0.) (Shape.materials sh)) scene.shapes

(* The thin lens, from its definition (Camera). [Uniform]: a point of the
   unit disc for the camera sample keyed [key], the first pair of its
   numbers that falls inside, [(0, 0)] if none of 32 does. *)
let uniform_lens_point key =
  let h = Sample_key.key key (-1) in
  let rec pair k =
    if k >= 32 then (0., 0.)
    else
      let u = (2. *. Sample_key.unit (Sample_key.key h (2 * k))) -. 1. in
      let v = (2. *. Sample_key.unit (Sample_key.key h ((2 * k) + 1))) -. 1. in
      if (u *. u) +. (v *. v) < 1. then (u, v) else pair (k + 1)
  in
  pair 0

(* [Stratified]: sample [(i, j)] of the [n x n] grid of pixel [(gx, gy)]
   takes cell [pi k] ([k = j n + i]) of the [n x n] cut of the unit
   square, [pi] the pixel's permutation with the centre of an odd grid
   sent to cell 0; in cell [(ci, cj)], the sub-cell [(sigma cj, tau ci)]
   of its own [n x n] cut, [sigma] and [tau] the pixel's permutations of
   [0 .. n - 1] that fix 0 (correlated multi-jittering); a point jittered
   in that sub-cell (the centre: cell 0's corner), shifted by the pixel's offset [u0] modulo 1; then Shirley and
   Chiu's concentric map onto the disc, written here with [sin] and [cos]
   (the kernel's polynomials agree to rounding). *)
let stratified_lens_point ~key ~gx ~gy ~n ~i ~j =
  let hp = Sample_key.pixel ~col:gx ~row:gy ~sample:(-1) in
  let u0 = (Sample_key.unit (Sample_key.key hp 0), Sample_key.unit (Sample_key.key hp 1)) in
  let k = (j * n) + i in
  let centre = if n mod 2 = 1 then Some ((n / 2 * n) + (n / 2)) else None in
  let u, v =
    match centre with
    | Some c when k = c -> u0
    | _ ->
        let perm = Sample_key.permute (Sample_key.key hp 2) in
        let cell =
          match centre with
          | Some c -> 1 + perm ~n:((n * n) - 1) (if k < c then k else k - 1)
          | None -> perm ~n:(n * n) k
        in
        let h = Sample_key.key key (-1) in
        let fixing_0 hs r = if r = 0 then 0 else 1 + Sample_key.permute hs ~n:(n - 1) (r - 1) in
        let ci = cell mod n and cj = cell / n in
        let sx = fixing_0 (Sample_key.key hp 3) cj and sy = fixing_0 (Sample_key.key hp 4) ci in
        let jitter a s hj = (Float.of_int ((a * n) + s) +. Sample_key.unit hj) /. Float.of_int (n * n) in
        let wrap z = if z >= 1. then z -. 1. else z in
        (wrap (jitter ci sx h +. fst u0), wrap (jitter cj sy (Sample_key.mix h) +. snd u0))
  in
  let a = (2. *. u) -. 1. and b = (2. *. v) -. 1. in
  if a = 0. && b = 0. then (0., 0.)
  else if Float.abs a > Float.abs b then
    let phi = Float.pi /. 4. *. (b /. a) in
    (a *. cos phi, a *. sin phi)
  else
    let phi = (Float.pi /. 2.) -. (Float.pi /. 4. *. (a /. b)) in
    (b *. cos phi, b *. sin phi)

(* The camera sample's lens point: [lens] is [(gx, gy, n, i, j)], its
   pixel, its grid's side and its place in the grid. *)
let lens_point (cam : Camera.t) ~key ~lens:(gx, gy, n, i, j) =
  match cam.lens_sampling with
  | Camera.Uniform -> uniform_lens_point key
  | Camera.Stratified -> stratified_lens_point ~key ~gx ~gy ~n ~i ~j

(* The camera ray through viewport point [v]: from the camera's position
   (the value itself, which [closest_numbered] recognises) for a pinhole;
   with a lens, from [position + M (r u, r w, 0)] towards the point
   [position + (f / d) M v] where the pinhole ray meets the plane of
   focus, scaled so that [t = 1] is the viewport plane. *)
let camera_ray (scene : Scene.view) ~key ~lens v =
  let cam = scene.camera in
  let direction = Camera.direction cam v in
  if not (Camera.has_lens cam) then (cam.position, direction)
  else
    let f = Camera.focal_distance cam and d = Viewport.distance scene.viewport in
    let focus = Vec3.add cam.position (Vec3.smul (f /. d) direction) in
    let u, w = lens_point cam ~key ~lens in
    let r = Camera.aperture cam /. 2. in
    let origin = Vec3.add cam.position (Camera.direction cam (Vec3.v (r *. u) (r *. w) 0.)) in
    (origin, Vec3.smul (d /. f) (Vec3.sub focus origin))

let camera_colour (scene : Scene.view) ~key ~lens v =
  let epsilon = Option.value scene.epsilon ~default:Scene.document_epsilon in
  let origin, direction = camera_ray scene ~key ~lens v in
  if transparent scene then shade ~key scene ~epsilon ~origin ~direction ~t_min:1. ~level:0 ~media:[]
  else trace_ray ~key scene ~epsilon ~origin ~direction ~t_min:1. ~t_max:infinity ~depth:scene.depth

let pixel (scene : Scene.view) gx gy =
  let v =
    Viewport.of_canvas scene.viewport ~canvas_width:scene.width ~canvas_height:scene.height gx gy
  in
  camera_colour scene ~key:(Sample_key.camera ~gx ~gy ~di:0 ~dj:0) ~lens:(gx, gy, 1, 0, 0) v

let sample (scene : Scene.view) gx gy ~i ~j ~n =
  let offset k = ((Float.of_int k +. 0.5) /. Float.of_int n) -. 0.5 in
  let v =
    Viewport.of_canvas_f scene.viewport ~canvas_width:scene.width ~canvas_height:scene.height
      (Float.of_int gx +. offset i) (Float.of_int gy +. offset j)
  in
  camera_colour scene ~key:(Sample_key.camera ~gx ~gy ~di:((2 * i) + 1 - n) ~dj:((2 * j) + 1 - n)) ~lens:(gx, gy, n, i, j) v

let render ?(limits = Limits.default) valid =
  let scene = Scene.view (Scene.of_valid valid) in
  tests := 0;
  Fun.protect ~finally:(fun () -> budget := max_int) @@ fun () ->
  budget := Limits.work_budget limits;
  let img = Image.create scene.width scene.height in
  for gx = Canvas.min_x scene.width to Canvas.max_x scene.width do
    for gy = Canvas.min_y scene.height to Canvas.max_y scene.height do
      let c = pixel scene gx gy in
      Image.set img
        (Canvas.column ~width:scene.width gx)
        (Canvas.row ~height:scene.height gy)
        (Color.to_byte c.r) (Color.to_byte c.g) (Color.to_byte c.b)
    done
  done;
  img

(* The public entry points take scenes; the last scene's view is kept,
   so that its lists (and the items made of them) are the same from one
   pixel to the next. *)
let last_view = ref None

let view s =
  match !last_view with
  | Some (s', v) when s' == s -> v
  | _ ->
      let v = Scene.view s in
      last_view := Some (s, v);
      v

let closest_hit scene = closest_hit (view scene)
let compute_lighting ?key scene = compute_lighting ?key (view scene)
let trace_ray ?key scene = trace_ray ?key (view scene)
let pixel scene = pixel (view scene)
let sample scene = sample (view scene)
