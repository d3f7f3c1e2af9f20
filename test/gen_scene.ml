open Raytrace
open QCheck.Gen

let coord lo hi = float_range lo hi
let vec lo hi = map3 Vec3.v (coord lo hi) (coord lo hi) (coord lo hi)
let channel = oneof [ return 0.; return 255.; float_range 0. 255. ]

(* Glass on one object in three: transparency up to what the
   reflectivity leaves (the edge values 1 - r and, with r = 0, 1), indices
   below and above air's, Fresnel or not. *)
let optics reflective =
  let* glass = frequencyl [ (2, false); (1, true) ] in
  if not glass then return (0., 1., false)
  else
    let room = 1. -. reflective in
    let* transparency = oneof [ return room; float_range 0. room ] in
    let* index = oneof [ return 1.; return 1.5; float_range 0.5 2.5 ] in
    let* fresnel = bool in
    (* [r + (1 - r)] may round above 1. *)
    let transparency = if reflective +. transparency > 1. then Float.pred transparency else transparency in
    return (Float.max transparency 0., index, fresnel)

let sphere =
  let* center = map3 Vec3.v (coord (-3.) 3.) (coord (-3.) 3.) (coord 2. 9.) in
  let* radius = oneof [ float_range 0.05 2.; return 1. ] in
  let* color = map3 Color.v channel channel channel in
  let* specular = oneof [ return Sphere.matte; return 0.; float_range 0. 1000. ] in
  let* reflective = oneof [ return 0.; return 1.; float_range 0. 1. ] in
  let* transparency, refractive_index, fresnel = optics reflective in
  return (Helpers.sphere ~specular ~reflective ~transparency ~refractive_index ~fresnel ~center ~radius color)

let material =
  let* color = map3 Color.v channel channel channel in
  let* specular = oneof [ return Sphere.matte; return 0.; float_range 0. 1000. ] in
  let* reflective = oneof [ return 0.; return 1.; float_range 0. 1. ] in
  let* transparency, refractive_index, fresnel = optics reflective in
  return (Material.v ~specular ~reflective ~transparency ~refractive_index ~fresnel color)

(* Planes through the scene's space, at any angle (often a floor or a
   wall), triangles and boxes in front of the camera. *)
let shape =
  let* m = material in
  let nonzero v = if Vec3.norm2 v < 1e-6 then Vec3.oy else v in
  oneof
    [
      (let* point = map3 Vec3.v (coord (-3.) 3.) (coord (-3.) 3.) (coord 2. 12.) in
       let* normal = oneof [ return Vec3.oy; return (Vec3.v 0. 0. (-1.)); map nonzero (vec (-1.) 1.) ] in
       return (Shape.Plane (Plane.v ~point ~normal m)));
      (let* v0 = map3 Vec3.v (coord (-3.) 3.) (coord (-3.) 3.) (coord 2. 9.) in
       let* e1 = vec (-2.) 2. and* e2 = vec (-2.) 2. in
       let tri = Triangle.v v0 (Vec3.add v0 e1) (Vec3.add v0 e2) m in
       return (match Triangle.validate tri with Ok t -> Shape.Triangle t | Error _ -> Shape.Triangle (Triangle.v tri.v0 (Vec3.add v0 Vec3.ox) (Vec3.add v0 Vec3.oy) tri.material)));
      (let* lo = map3 Vec3.v (coord (-3.) 3.) (coord (-3.) 3.) (coord 2. 9.) in
       let* size = map3 Vec3.v (coord 0.05 2.) (coord 0.05 2.) (coord 0.05 2.) in
       return (Shape.Box (Box.v ~min:lo ~max:(Vec3.add lo size) m)));
    ]

let light =
  let* intensity = oneof [ return 0.; float_range 0. 1. ] in
  oneof
    [
      return (Light.ambient intensity);
      map (Light.point intensity) (vec (-5.) 5.);
      map (Light.directional intensity)
        (map (fun v -> if Vec3.norm2 v = 0. then Vec3.oy else v) (vec (-1.) 1.));
    ]

(* Keys whose view direction always has z >= 1, so that no frame between
   them looks at its own position or along its up vector. *)
let camera_path =
  let key frame =
    let* position = vec (-2.) 2. in
    let* dx = coord (-1.) 1. and* dy = coord (-1.) 1. and* dz = coord 1. 3. in
    return (Camera.Path.key ~frame ~position (Vec3.add position (Vec3.v dx dy dz)))
  in
  let* first = int_range 0 5 in
  let* gaps = list_size (int_range 0 3) (int_range 1 6) in
  let frames = List.rev (List.fold_left (fun acc g -> (List.hd acc + g) :: acc) [ first ] gaps) in
  let* keys = flatten_l (List.map key frames) in
  return (match Camera.Path.v keys with Ok p -> Some p | Error _ -> None)

let gen =
  let* width = int_range 1 12 and* height = int_range 1 12 in
  let* depth = int_range 0 4 in
  let* epsilon = oneof [ return None; map Option.some (float_range 0. 0.01) ] in
  let* background = map3 Color.v channel channel channel in
  let* spheres = list_size (int_range 0 6) sphere in
  let* lights = list_size (int_range 0 4) light in
  let* shapes = oneof [ return []; list_size (int_range 1 4) shape ] in
  let* camera =
    oneof
      [
        return Camera.default;
        return (Scene.camera Scene.cgfs_camera);
        map (fun p -> Camera.v p) (vec (-0.5) 0.5);
      ]
  in
  let* camera_path = oneof [ return None; camera_path ] in
  return
    (Scene.with_overrides ~epsilon ~camera_path
       (Helpers.scene ~width ~height ~depth ?epsilon ~background ~camera ~spheres ~shapes ~lights ()))

let crowd =
  let* base = gen in
  let* n = int_range 9 80 in
  let* cluster = map3 Vec3.v (coord (-2.) 2.) (coord (-2.) 2.) (coord 3. 8.) in
  let* spread = oneof [ return 0.5; return 3.; return 10. ] in
  let* spheres =
    list_repeat n
      (let* s = sphere in
       let* offset = vec (-.spread) spread in
       return (Sphere.v ~center:(Vec3.add cluster offset) ~radius:s.radius s.material))
  in
  (* Duplicates (ties between equal roots), a sphere inside another, a huge
     ground, a sphere around the camera. *)
  let* dup = bool and* ground = bool and* around = oneof [ return false; return false; return true ] in
  let spheres =
    match spheres with
    | a :: b :: rest ->
        let nested = Sphere.v ~center:a.center ~radius:(a.radius *. 0.5) b.material in
        (if dup then [ a; a; nested ] else [ a; nested ]) @ rest
    | l -> l
  in
  let spheres =
    if ground then spheres @ [ Helpers.sphere ~center:(Vec3.v 0. (-5001.) 0.) ~radius:5000. ~reflective:0.3 Color.white ]
    else spheres
  in
  let spheres = if around then Helpers.sphere ~center:Vec3.zero ~radius:0.5 Color.white :: spheres else spheres in
  (* Shapes in the hierarchy too, sometimes with a duplicate. *)
  let* shapes = oneof [ return []; list_size (int_range 1 12) shape ] in
  let* dup_shape = bool in
  let shapes = match shapes with s :: rest when dup_shape -> s :: s :: rest | l -> l in
  return (Helpers.with_objects ~spheres ~shapes:(Scene.shapes base @ shapes) base)

let shrink (s : Scene.t) =
  QCheck.Iter.(
    map (fun spheres -> Helpers.with_objects ~spheres s) (QCheck.Shrink.list (Helpers.scene_spheres s))
    <+> map (fun shapes -> Helpers.with_objects ~shapes s) (QCheck.Shrink.list (Scene.shapes s))
    <+> map (fun lights -> Scene.with_overrides ~lights s) (QCheck.Shrink.list (Scene.lights s)))

let arbitrary = QCheck.make ~print:Scene_file.to_string ~shrink gen

(* A checker on about half the objects, drawn from [rand] (not QCheck's
   generator: the scenes of [gen] stay what they were). *)
let with_patterns rand (s : Scene.t) =
  let pattern () =
    if Random.State.bool rand then None
    else
      let channel () = Float.of_int (Random.State.int rand 256) in
      let size = 0.05 +. Random.State.float rand 2. in
      Some (Pattern.checker ~size (Color.v (channel ()) (channel ()) (channel ())))
  in
  let material (m : Material.t) = Material.update ~pattern:(pattern ()) m in
  let shape = function
    | Shape.Sphere sp -> Shape.Sphere (Helpers.with_sphere_material sp (fun m -> Material.update ~pattern:(pattern ()) m))
    | Plane p -> Shape.Plane (Plane.v ~point:p.point ~normal:p.normal (material p.material))
    | Triangle t -> Triangle (Triangle.v t.v0 t.v1 t.v2 (material t.material))
    | Box b -> Box (Box.v ~min:b.min ~max:b.max (material b.material))
    | (Mesh _ | Csg _ | Primitive _ | Instance _) as m -> m
  in
  Scene.with_overrides ~objects:(List.map shape (Scene.objects s)) s

(* [s] with a random image texture on about half of its spheres, planes
   and boxes (the kinds a texture maps onto without a file's [vt]): 1 to
   5 pixels a side of random colours, a plane's copies 0.05 to 2 wide;
   an object with a pattern keeps it. *)
let with_textures rand (s : Scene.t) =
  let texture mapping =
    if Random.State.bool rand then None
    else
      let w = 1 + Random.State.int rand 5 and h = 1 + Random.State.int rand 5 in
      let image = Image.Texture.v ~width:w ~height:h (String.init (3 * w * h) (fun _ -> Char.chr (Random.State.int rand 256))) in
      let size = 0.05 +. Random.State.float rand 2. in
      Some (Material.Texture.v ~size ~file:"random.ppm" mapping image)
  in
  let material mapping (m : Material.t) =
    if Option.is_some m.pattern then m else Material.update ~texture:(texture mapping) m
  in
  let shape = function
    | Shape.Sphere sp -> Shape.Sphere (Helpers.with_sphere_material sp (material Material.Texture.Spherical))
    | Plane p -> Shape.Plane (Plane.v ~point:p.point ~normal:p.normal (material Material.Texture.Planar p.material))
    | Box b -> Box (Box.v ~min:b.min ~max:b.max (material Material.Texture.Box b.material))
    | (Triangle _ | Mesh _ | Csg _ | Primitive _ | Instance _) as m -> m
  in
  Scene.with_overrides ~objects:(List.map shape (Scene.objects s)) s

