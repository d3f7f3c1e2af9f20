(* Ray-sphere tests done since the last [render] began, checked against
   the work bound after each column of the canvas. *)
let tests = ref 0

(* The work bound of the [render] under way, for the ray tree. *)
let tree_budget = ref max_int

let closest_intersection spheres ~origin ~direction ~t_min ~t_max =
  tests := !tests + List.length spheres;
  let closest = ref None and closest_t = ref infinity in
  List.iter
    (fun sphere ->
      let a, b, c = Sphere.quadratic sphere ~origin ~direction in
      let t1, t2 = Sphere.textbook_roots a b c in
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

(* A CSG solid's hit is a point of one of its leaves: its material, and
   the solid's outward normal there. *)
type obj = Sphere of Sphere.t | Shape of Shape.t | Mesh_triangle of Mesh.t * int | Csg_surface of Csg.t * Csg.solid * Vec3.t

let material = function
  | Sphere s -> Material.of_sphere s
  | Shape sh -> Shape.material sh
  | Mesh_triangle (m, _) -> m.material
  | Csg_surface (_, l, _) -> Csg.leaf_material l

(* The medium inside an object: a CSG solid is one medium, its first
   operand's (leftmost leaf's) material, as in the kernel. *)
let medium_material = function Csg_surface (c, _, _) -> List.hd (Csg.materials c) | obj -> material obj

(* A mesh is its triangles, in order, less the degenerate ones (no ray
   can hit them). Each object comes with its geometry as the kernel's
   routine reads it (Shape.store), made once per list of shapes: a mesh
   has thousands of triangles, and every ray tests them all. *)
let objects_of_shape = function
  | Shape.Mesh m ->
      List.filter_map
        (fun k -> if Mesh.degenerate m k then None else Some (Mesh_triangle (m, k), Shape.Triangle (Mesh.triangle m k)))
        (List.init (Mesh.triangle_count m) Fun.id)
  | sh -> [ (Shape sh, sh) ]

let table shape =
  let g = Array.make Shape.stride 0. in
  (match shape with Shape.Csg _ -> () | _ -> Shape.store shape g 0);
  g

let objects_cache = ref ([], [||])

(* Each object comes with the number of its shape in the list (a mesh's
   triangles share theirs). *)
let objects (shapes : Shape.t list) =
  match !objects_cache with
  | cached, objects when cached == shapes -> objects
  | _ ->
      let objects =
        Array.of_list
          (List.concat
             (List.mapi (fun k sh -> List.map (fun (o, s) -> (o, s, table s, k)) (objects_of_shape sh)) shapes))
      in
      objects_cache := (shapes, objects);
      objects

let scratch = Scratch.create ()

(* The roots of [shape] (stored in [g]) by its module's routine. *)
let roots shape g ~origin ~direction =
  Scratch.set_ray scratch origin direction;
  let hit =
    match shape with
    | Shape.Plane _ -> Plane.roots scratch g 0
    | Shape.Triangle _ -> Triangle.roots scratch g 0
    | Shape.Box _ -> Box.roots scratch g 0
    | Shape.Mesh _ -> invalid_arg "Literal.roots: a mesh is its triangles"
    | Shape.Csg _ -> invalid_arg "Literal.roots: a CSG solid has its own literal algorithm"
  in
  if hit then (scratch.near, scratch.far) else (infinity, infinity)

(* The spheres first, then the other shapes, each root compared with a
   strict [<]: of equal roots, the first object in that order wins. *)
(* The position of [x] in [l], by physical equality: of spheres given
   twice, the first is the one hit. *)
let position x l =
  let rec go k = function y :: rest -> if y == x then k else go (k + 1) rest | [] -> -1 in
  go 0 l

(* The closest hit with its object's number: the spheres in order, then
   the shapes, a mesh one number (the numbers of the kernel's materials,
   which name the media a ray is in). *)
(* The oracle reads spheres as the document's list. The scene's compact
   spheres are listed once per scene, not once per ray: the last list is
   kept, with the spheres it lists. *)
let last_listed = ref (Spheres.empty, [])

let sphere_list spheres =
  let from, l = !last_listed in
  if from == spheres then l
  else begin
    let l = Spheres.to_list spheres in
    last_listed := (spheres, l);
    l
  end

let closest_numbered (scene : Scene.t) ~origin ~direction ~t_min ~t_max =
  let spheres = sphere_list scene.spheres in
  let best =
    match closest_intersection spheres ~origin ~direction ~t_min ~t_max with
    | Some (sphere, t) -> Some (Sphere sphere, position sphere spheres, t)
    | None -> None
  in
  let n_spheres = Spheres.length scene.spheres in
  Array.fold_left
    (fun best (obj, shape, g, k) ->
      incr tests;
      let best_t = match best with Some (_, _, t) -> t | None -> infinity in
      match shape with
      | Shape.Csg c -> (
          match Csg.literal_hit c ~origin ~direction ~t_min ~t_max with
          | Some (t, l, n) when t < best_t -> Some (Csg_surface (c, l, n), n_spheres + k, t)
          | _ -> best)
      | _ ->
          let near, far = roots shape g ~origin ~direction in
          if near < best_t && t_min < near && near < t_max then Some (obj, n_spheres + k, near)
          else if far < best_t && t_min < far && far < t_max then Some (obj, n_spheres + k, far)
          else best)
    best (objects scene.shapes)

let closest_hit scene ~origin ~direction ~t_min ~t_max =
  Option.map (fun (obj, _, t) -> (obj, t)) (closest_numbered scene ~origin ~direction ~t_min ~t_max)

(* A sphere's normal points out of it, as in the document; a plane's or a
   triangle's, and a box's (outward), is turned toward the ray, so that
   they are lit from the side they are seen from. *)
let normal obj ~point ~direction =
  match obj with
  | Sphere sphere -> Sphere.normal sphere point
  | Shape shape ->
      let n = Shape.normal shape point in
      if Vec3.dot n direction > 0. then Vec3.neg n else n
  | Csg_surface (_, _, n) -> if Vec3.dot n direction > 0. then Vec3.neg n else n
  | Mesh_triangle (m, k) -> (
      let tri = Mesh.triangle m k in
      let n = Shape.normal (Shape.Triangle tri) point in
      let flip = Vec3.dot n direction > 0. in
      let turn n = if flip then Vec3.neg n else n in
      (* Smooth: the corners' normals interpolated at the point, on the
         side the ray sees. *)
      let g = Array.make 9 0. and vn = Array.make 9 0. in
      Triangle.store tri g 0;
      let s = Scratch.create () in
      s.px <- point.x;
      s.py <- point.y;
      s.pz <- point.z;
      match Mesh.corner_normals m k vn 0 && Triangle.smooth_normal s g 0 vn 0 3 6 with
      | true -> turn (Vec3.v s.nx s.ny s.nz)
      | false -> turn n)

(* Where an object's pattern lies ({!Shape.pattern_frame}); a mesh's, which
   scans every vertex, is kept for the mesh's next triangle. *)
let last_frame = ref None

let pattern_frame = function
  | Sphere s -> Shape.leaf_pattern_frame (Csg.Sphere s)
  | Shape sh -> Shape.pattern_frame sh
  | Csg_surface (_, l, _) -> Shape.leaf_pattern_frame l
  | Mesh_triangle (m, _) -> (
      match !last_frame with
      | Some (m', f) when m' == m -> f
      | _ ->
          let f = Shape.pattern_frame (Shape.Mesh m) in
          last_frame := Some (m, f);
          f)

(* The colour the hit shows: the material's, or its pattern's second
   colour, by the kernel's lookup. *)
let local_color obj (m : Material.t) ~origin ~direction ~point ~normal =
  match m.pattern with
  | None -> m.color
  | Some p ->
      let origin', scale, extent = pattern_frame obj in
      let table = Array.make Pattern.stride 0. in
      Pattern.store p ~origin:origin' ~scale ~extent table 0;
      let s = Scratch.create () in
      Scratch.set_ray s origin direction;
      s.px <- point.Vec3.x;
      s.py <- point.y;
      s.pz <- point.z;
      s.nx <- normal.Vec3.x;
      s.ny <- normal.y;
      s.nz <- normal.z;
      if Pattern.odd s table 0 then Pattern.color p else m.color

(* The light a shadow ray lets through transparent objects: the product
   of the transparency of each surface it crosses, nearest first, until an
   opaque one stops it (0). *)
let rec transmitted scene ~origin ~direction ~t_min ~t_max f =
  match closest_numbered scene ~origin ~direction ~t_min ~t_max with
  | None -> f
  | Some (obj, _, t) ->
      let f = f *. (medium_material obj).transparency in
      if f > 0. then transmitted scene ~origin ~direction ~t_min:t ~t_max f else f

let lighting_through ~through (scene : Scene.t) ~epsilon ~point ~normal ~view ~specular =
  let intensity = ref 0. in
  List.iter
    (fun light ->
      match Light.vector light point with
      | None -> intensity := !intensity +. Light.intensity light
      | Some l when Vec3.norm2 l = 0. ->
          (* A point light exactly at the point: L has no direction, and the
             formulas would divide by zero. The document is silent; the light
             is skipped. *)
          ()
      | Some l ->
          (* Shadow check (7.7): is any object between the point and the
             light? Through transparent objects, how much light passes? *)
          let t_max = Light.shadow_t_max light in
          let passes =
            if through then transmitted scene ~origin:point ~direction:l ~t_min:epsilon ~t_max 1.
            else if closest_hit scene ~origin:point ~direction:l ~t_min:epsilon ~t_max <> None then 0.
            else 1.
          in
          if passes > 0. then begin
            let i = Light.intensity light *. passes in
            intensity := !intensity +. Shading.diffuse ~intensity:i ~l ~n:normal;
            if specular <> Sphere.matte then
              let r = Shading.reflect l normal in
              intensity := !intensity +. Shading.specular ~intensity:i ~s:specular ~r ~v:view
          end)
    scene.lights;
  !intensity

let compute_lighting = lighting_through ~through:false

(* Iterative, so that no depth the limits allow can overflow the stack:
   the mirror rays are followed down, each level's local colour and
   reflectivity kept, then blended back up from the deepest colour, in the
   order of the document's recursion (the same floating-point operations). *)
let trace_ray (scene : Scene.t) ~epsilon ~origin ~direction ~t_min ~t_max ~depth =
  let rec follow levels ~origin ~direction ~t_min ~t_max ~depth =
    match closest_hit scene ~origin ~direction ~t_min ~t_max with
    | None -> (levels, scene.background)
    | Some (obj, t) ->
        let m = material obj in
        let point = Vec3.add origin (Vec3.smul t direction) in
        let normal = normal obj ~point ~direction in
        let view = Vec3.neg direction in
        let lighting = compute_lighting scene ~epsilon ~point ~normal ~view ~specular:m.specular in
        let local = Color.smul lighting (local_color obj m ~origin ~direction ~point ~normal) in
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
   by number, with their indices (at most [Ray_tree.media_cap]). Crossing
   a surface of object [id] gives the indices on its near and far sides
   and the media beyond it. *)
let cross media ~id ~index =
  let near = match media with (_, n) :: _ -> n | [] -> 1. in
  match media with
  | (top, _) :: under when top = id -> (near, (match under with (_, n) :: _ -> n | [] -> 1.), under)
  | _ when List.mem_assoc id media -> (near, near, List.remove_assoc id media)
  | _ -> (near, index, if List.length media < Ray_tree.media_cap then (id, index) :: media else media)

(* The colour seen along a ray at bounce [level]: the hit's local colour
   weighted [1 - r - t], the reflected ray's [wr = r + t R] and the
   refracted ray's [wt = t (1 - R)], [R] the reflectance of
   [Ray_tree.split] (1 on total internal reflection). A surface that
   changes nothing (transparency 1, the same index on both sides) is
   crossed on the same ray, without a bounce. At [level = depth], or
   without either ray, the local colour alone (section 7.8). *)
let rec shade (scene : Scene.t) ~epsilon ~origin ~direction ~t_min ~level ~media =
  (* A tree of 64 levels may have 2^64 rays: the work bound is checked at
     every hit, not only after each column. *)
  if !tests > !tree_budget then raise (Limits.Work_exceeded !tests);
  match closest_numbered scene ~origin ~direction ~t_min ~t_max:infinity with
  | None -> scene.background
  | Some (obj, id, t) ->
      let m = material obj and medium = medium_material obj in
      let near, far, beyond = cross media ~id ~index:medium.refractive_index in
      if medium.transparency = 1. && near = far then shade scene ~epsilon ~origin ~direction ~t_min:t ~level ~media:beyond
      else
        let point = Vec3.add origin (Vec3.smul t direction) in
        let normal = normal obj ~point ~direction in
        let view = Vec3.neg direction in
        let optics = Array.make Ray_tree.optics_size 0. in
        let reflectance =
          if m.transparency > 0. then begin
            let facing = if Vec3.dot normal direction <= 0. then normal else Vec3.neg normal in
            List.iteri (fun i x -> optics.(i) <- x)
              [ near; far; direction.x; direction.y; direction.z; facing.x; facing.y; facing.z ];
            Ray_tree.split optics ~fresnel:m.fresnel;
            (* A smooth triangle's normal may send the ray back to the side
               it came from: then its flat normal, turned toward the ray. *)
            (match obj with
            | Mesh_triangle (mesh, k) when mesh.smooth && optics.(11) < 1. ->
                let g = Shape.normal (Shape.Triangle (Mesh.triangle mesh k)) point in
                let t = Vec3.v optics.(8) optics.(9) optics.(10) in
                let g_dot_d = Vec3.dot g direction and g_dot_t = Vec3.dot g t in
                if not ((g_dot_d > 0. && g_dot_t > 0.) || (g_dot_d < 0. && g_dot_t < 0.)) then begin
                  let g = if g_dot_d > 0. then Vec3.neg g else g in
                  optics.(5) <- g.x;
                  optics.(6) <- g.y;
                  optics.(7) <- g.z;
                  Ray_tree.split optics ~fresnel:m.fresnel
                end
            | _ -> ());
            optics.(11)
          end
          else 0.
        in
        let wr = m.reflective +. (m.transparency *. reflectance) in
        let wt = m.transparency *. (1. -. reflectance) in
        let local () =
          Color.smul
            (lighting_through ~through:true scene ~epsilon ~point ~normal ~view ~specular:m.specular)
            (local_color obj m ~origin ~direction ~point ~normal)
        in
        if level >= scene.depth || (wr <= 0. && wt <= 0.) then local ()
        else
          let keep = 1. -. m.reflective -. m.transparency in
          let c = if keep > 0. then Color.smul keep (local ()) else Color.black in
          let c =
            if wr > 0. then
              let reflected =
                shade scene ~epsilon ~origin:point ~direction:(Shading.reflect view normal) ~t_min:epsilon
                  ~level:(level + 1) ~media
              in
              Color.add c (Color.smul wr reflected)
            else c
          in
          if wt > 0. then
            let refracted =
              shade scene ~epsilon ~origin:point ~direction:(Vec3.v optics.(8) optics.(9) optics.(10)) ~t_min:epsilon
                ~level:(level + 1) ~media:beyond
            in
            Color.add c (Color.smul wt refracted)
          else c

let transparent (scene : Scene.t) =
  Spheres.exists (fun (s : Sphere.t) -> s.transparency > 0.) scene.spheres
  || List.exists (fun sh -> List.exists (fun (m : Material.t) -> m.transparency > 0.) (Shape.materials sh)) scene.shapes

let pixel (scene : Scene.t) gx gy =
  let epsilon = Option.value scene.epsilon ~default:Scene.document_epsilon in
  let v =
    Viewport.of_canvas scene.viewport ~canvas_width:scene.width ~canvas_height:scene.height gx gy
  in
  let direction = Camera.direction scene.camera (Vec3.sub v Vec3.zero) in
  if transparent scene then shade scene ~epsilon ~origin:scene.camera.position ~direction ~t_min:1. ~level:0 ~media:[]
  else
    trace_ray scene ~epsilon ~origin:scene.camera.position ~direction ~t_min:1. ~t_max:infinity
      ~depth:scene.depth

let render ?(limits = Limits.default) valid =
  let scene = Scene.of_valid valid in
  let budget = Limits.work_budget limits in
  tests := 0;
  (* Checked after each column, and by the ray tree at every hit. *)
  Fun.protect ~finally:(fun () -> tree_budget := max_int) @@ fun () ->
  tree_budget := budget;
  let img = Image.create scene.width scene.height in
  for gx = Canvas.min_x scene.width to Canvas.max_x scene.width do
    for gy = Canvas.min_y scene.height to Canvas.max_y scene.height do
      let c = pixel scene gx gy in
      Image.set img
        (Canvas.column ~width:scene.width gx)
        (Canvas.row ~height:scene.height gy)
        (Color.to_byte c.r) (Color.to_byte c.g) (Color.to_byte c.b)
    done;
    if !tests > budget then raise (Limits.Work_exceeded !tests)
  done;
  img
