(* The spheres, however many, are kept compactly ([Spheres], 40 bytes
   each); every other object is placed after as many spheres as came
   before it in the scene's list, so that the list's order is kept
   without a list of a million spheres. *)
type view = {
  width : int;
  height : int;
  viewport : Viewport.t;
  camera : Camera.t;
  background : Color.t;
  depth : int;
  epsilon : float option;
  spheres : Spheres.t;
  shapes : Shape.t list;  (* [placed]'s shapes, for the readers that want them alone. *)
  placed : (int * Shape.t) list;
  lights : Light.t list;
  camera_path : Camera_path.t option;
}
[@@deriving eq]

type t = view

let equal = equal_view
let view s = s

let width s = s.width
let height s = s.height
let viewport s = s.viewport
let camera s = s.camera
let background s = s.background
let depth s = s.depth
let epsilon s = s.epsilon
let lights s = s.lights
let camera_path s = s.camera_path
let spheres s = s.spheres
let placed s = s.placed
let shapes s = s.shapes

(* [iter_objects s ~sphere ~shape] walks the objects in the list's order:
   [sphere i] for sphere [i] of [s.spheres], [shape sh] for the others. *)
let iter_objects s ~sphere ~shape =
  let next = ref 0 in
  let upto j =
    while !next < j do
      sphere !next;
      incr next
    done
  in
  List.iter
    (fun (j, sh) ->
      upto j;
      shape sh)
    s.placed;
  upto (Spheres.length s.spheres)

let objects s =
  let l = ref [] in
  iter_objects s ~sphere:(fun i -> l := Shape.Sphere (Spheres.get s.spheres i) :: !l) ~shape:(fun sh -> l := sh :: !l);
  List.rev !l

let n_objects s = Spheres.length s.spheres + List.length s.placed

let with_objects s ~spheres ~placed = { s with spheres; placed; shapes = List.map snd placed }

(* One form a line, in the order a scene file is usually written; the
   parts print their own forms, so the scene and its parts print alike. *)
let pp ppf s =
  let line pp x = Format.fprintf ppf "%a\n" pp x in
  Format.fprintf ppf "(canvas (width %d) (height %d))\n" s.width s.height;
  line Viewport.pp s.viewport;
  line Camera.pp s.camera;
  Option.iter (line Camera_path.pp) s.camera_path;
  Format.fprintf ppf "(background %a)\n" Color.pp_components s.background;
  Format.fprintf ppf "(recursion-depth %d)\n" s.depth;
  Option.iter (Format.fprintf ppf "(epsilon %s)\n") (Option.map Float_text.to_string s.epsilon);
  (* A named instance prints as a [use]: its definition first, once; so
     does a named CSG operand, and the definitions those use, first. *)
  let defined = Hashtbl.create 8 in
  let define n pp x =
    if not (Hashtbl.mem defined n) then begin
      Hashtbl.add defined n ();
      Format.fprintf ppf "(define %s %a)\n" n pp x
    end
  in
  let rec in_solid = function
    | Csg.Csg c ->
        in_solid c.a;
        in_solid c.b
    | Csg.Transformed p ->
        in_solid p.solid;
        Option.iter (fun n -> define n Csg.pp_solid p.solid) p.name
    | _ -> ()
  in
  let rec in_shape = function
    | Shape.Instance { name; shape; _ } ->
        in_shape shape;
        Option.iter (fun n -> define n Shape.pp shape) name
    | Shape.Csg c -> in_solid (Csg.Csg c)
    | _ -> ()
  in
  List.iter (fun (_, sh) -> in_shape sh) s.placed;
  iter_objects s ~sphere:(fun i -> line Sphere.pp (Spheres.get s.spheres i)) ~shape:(line Shape.pp);
  List.iter (line Light.pp) s.lights

let show s = Format.asprintf "%a" pp s

let error fmt = Printf.ksprintf (fun m -> Error (`Msg m)) fmt
let error_pp fmt = Format.kasprintf (fun m -> Error (`Msg m)) fmt
let split objects =
  let b = Spheres.builder () in
  let placed =
    List.fold_left
      (fun placed -> function
        | Shape.Sphere sp ->
            Spheres.add b sp;
            placed
        | sh -> (Spheres.builder_length b, sh) :: placed)
      [] objects
  in
  (Spheres.build b, List.rev placed)

let v ?(width = 600) ?(height = 600) ?(viewport = Viewport.default) ?(camera = Camera.default)
    ?(background = Color.black) ?(depth = 3) ?epsilon ?camera_path ~objects ~lights () =
  let spheres, placed = split objects in
  { width; height; viewport; camera; background; depth; epsilon; spheres; shapes = List.map snd placed; placed; lights; camera_path }

let document_epsilon = 0.0001

let cgfs =
  let sphere ~center ~color ~specular ~reflective radius =
    Shape.Sphere (Sphere.v ~center ~radius (Material.v ~specular ~reflective color))
  in
  v ~epsilon:0.001
    ~objects:
      [
        sphere 1. ~center:(Vec3.v 0. (-1.) 3.) ~color:(Color.v 255. 0. 0.) ~specular:500.
          ~reflective:0.2;
        sphere 1. ~center:(Vec3.v (-2.) 0. 4.) ~color:(Color.v 0. 255. 0.) ~specular:10.
          ~reflective:0.4;
        sphere 1. ~center:(Vec3.v 2. 0. 4.) ~color:(Color.v 0. 0. 255.) ~specular:500.
          ~reflective:0.3;
        sphere 5000. ~center:(Vec3.v 0. (-5001.) 0.) ~color:(Color.v 255. 255. 0.)
          ~specular:1000. ~reflective:0.5;
      ]
    ~lights:
      [
        Light.ambient 0.2;
        Light.point 0.6 (Vec3.v 2. 1. 0.);
        Light.directional 0.2 (Vec3.v 1. 4. 4.);
      ]
    ()

let cgfs_camera =
  let rotation =
    Camera.
      {
        row0 = Vec3.v 0.7071 0. (-0.7071);
        row1 = Vec3.v 0. 1. 0.;
        row2 = Vec3.v 0.7071 0. 0.7071;
      }
  in
  { cgfs with camera = Camera.v ~rotation (Vec3.v 3. 0. 1.) }

let grid n =
  if n < 1 then invalid_arg "Scene.grid: n < 1";
  let k = ref 1 in
  while !k * !k < n do incr k done;
  let k = !k in
  let palette =
    [| Color.v 255. 0. 0.; Color.v 0. 255. 0.; Color.v 0. 0. 255.; Color.v 255. 255. 0.;
       Color.v 0. 255. 255.; Color.v 255. 0. 255. |]
  in
  let specular = [| -1.; 10.; 500.; 1000. |] and reflective = [| 0.; 0.2; 0.4 |] in
  let b = Spheres.builder () in
  for i = 0 to n - 1 do
    let col = i mod k and row = i / k in
    let center =
      Vec3.v (Float.of_int col -. (Float.of_int (k - 1) /. 2.)) (Float.of_int row -. 0.6) (2. *. Float.of_int k)
    in
    Spheres.add b
      (Sphere.v ~center ~radius:0.4
         (Material.v ~specular:specular.(i mod 4) ~reflective:reflective.(i mod 3) palette.(i mod 6)))
  done;
  Spheres.add b (Spheres.get cgfs.spheres 3);
  { cgfs with width = 800; height = 800; spheres = Spheres.build b }

let check_epsilon e =
  if Float.is_finite e && e >= 0. then Ok e
  else (error "epsilon must be finite and >= 0, got %s" (Float_text.to_string e))

let check_background c =
  if Color.in_gamut c then Ok c
  else (error_pp "background channels must lie in [0, 255], got %a" Color.pp c)

type valid = t

let of_valid v = v

(* Staged: [bottom v] keeps [v]'s settings alone, not its objects, so
   that a million spheres are let go while [Prepared] builds the
   hierarchy with this function at hand. *)
let bottom v =
  let settings = { v with spheres = Spheres.empty; placed = []; shapes = []; lights = []; camera_path = None } in
  fun shape ->
    let spheres, placed = split [ shape ] in
    { settings with spheres; placed; shapes = List.map snd placed }

(* Sphere by sphere, the first error first, as [Sphere.validate] finds it:
   [Error (i, e)] for sphere [i]; each material is checked once, not once
   per sphere. *)
let valid_spheres spheres =
  let checked = Array.map (Material.validate ~form:"sphere") (Spheres.materials spheres) in
  (* The checks' own predicates first: a million spheres that pass make
     no vector and no result. *)
  let ok i =
    Limits.coordinate_ok (Spheres.center_x spheres i)
    && Limits.coordinate_ok (Spheres.center_y spheres i)
    && Limits.coordinate_ok (Spheres.center_z spheres i)
    && Limits.size_ok (Spheres.radius spheres i)
    && Result.is_ok checked.(Spheres.material_index spheres i)
  in
  let rec go i =
    if i >= Spheres.length spheres then Ok ()
    else if ok i then go (i + 1)
    else
      let center = Vec3.v (Spheres.center_x spheres i) (Spheres.center_y spheres i) (Spheres.center_z spheres i) in
      match (Sphere.check_center center, Sphere.check_radius (Spheres.radius spheres i)) with
      | Error e, _ | _, Error e -> Error (i, e)
      | Ok _, Ok _ -> (
          match checked.(Spheres.material_index spheres i) with Ok _ -> go (i + 1) | Error e -> Error (i, e))
  in
  go 0

(* The first object that fails, in the list's order: sphere [i] is object
   [i + 1] plus the other objects placed before it; the [p]-th other
   object, placed after [j] spheres, is object [j + p + 1]. *)
let valid_objects s =
  let sphere_error = valid_spheres s.spheres in
  let rec shapes p = function
    | [] -> None
    | (j, sh) :: rest -> (
        match sphere_error with
        | Error (i, e) when i < j -> Some (i + p + 1, "sphere", e)
        | _ -> (
            match Shape.validate sh with
            | Ok _ -> shapes (p + 1) rest
            | Error e -> Some (j + p + 1, Shape.name sh, e)))
  in
  let first =
    match shapes 0 s.placed with
    | Some _ as found -> found
    | None -> (
        match sphere_error with
        | Ok () -> None
        | Error (i, e) -> Some (i + List.length s.placed + 1, "sphere", e))
  in
  match first with
  | None -> Ok ()
  | Some (k, name, `Msg m) -> Error (`Msg (Printf.sprintf "object %d (%s): %s" k name m))

let light_kind = function
  | Light.Ambient _ -> "ambient"
  | Point _ -> "point"
  | Directional _ -> "directional"
  | Area _ -> "area"
  | Sphere _ -> "sphere"
  | Spot _ -> "spot"

let valid_lights lights =
  let rec go k = function
    | [] -> Ok ()
    | l :: rest -> (
        match Light.validate l with
        | Ok _ -> go (k + 1) rest
        | Error (`Msg m) -> Error (`Msg (Printf.sprintf "light %d (%s): %s" k (light_kind l) m)))
  in
  go 1 lights

(* The sum of [leaf] over the leaves of a CSG solid, without recursion:
   trees may be deep. *)
let csg_sum leaf (c : Csg.t) =
  let rec sum n = function
    | [] -> n
    | Csg.Csg c :: rest -> sum n (c.a :: c.b :: rest)
    | Csg.Transformed p :: rest -> sum n (p.solid :: rest)
    | solid :: rest -> sum (n + leaf solid) rest
  in
  sum 0 [ c.a; c.b ]

(* A mesh operand's triangles are leaves, tested one by one. *)
let csg_leaves = csg_sum (function Csg.Mesh m -> Mesh.triangle_count m | _ -> 1)

(* The triangles of the scene's meshes, CSG operands included. *)
let mesh_triangles shapes =
  let of_leaf = function Csg.Mesh m -> Mesh.triangle_count m | _ -> 0 in
  (* The instances of one definition share its object: counted once. *)
  let seen = ref [] in
  let rec count n = function
    | Shape.Mesh m -> n + Mesh.triangle_count m
    | Csg c -> n + csg_sum of_leaf c
    | Instance { shape; _ } when List.memq shape !seen -> n
    | Instance { shape; _ } ->
        seen := shape :: !seen;
        count n shape
    | _ -> n
  in
  List.fold_left count 0 shapes

(* The spheres' textures take the spherical mapping (the other objects'
   are checked by [Shape.validate]). *)
let check_sphere_textures s =
  let wrong (m : Material.t) = match m.texture with Some t -> t.mapping <> Texture_map.Spherical | None -> false in
  if Array.exists wrong (Spheres.materials s.spheres) then Error (`Msg "sphere texture mapping must be spherical")
  else Ok ()

let validate ?(limits = Limits.default) s =
  let ( let* ) = Result.bind in
  let result =
    let* () = Limits.check_canvas limits s.width s.height in
    let* _ = Viewport.validate s.viewport in
    let* _ = Camera.validate s.camera in
    let* _ = check_background s.background in
    let* _ = Limits.check_depth limits s.depth in
    let* _ = match s.epsilon with Some e -> check_epsilon e | None -> Ok 0. in
    let* _ =
      Limits.check_count limits (match s.placed with [] -> `Spheres | _ :: _ -> `Objects) (n_objects s)
    in
    let* _ = Limits.check_count limits `Lights (List.length s.lights) in
    let* _ = Limits.check_triangles limits (mesh_triangles s.shapes) in
    let* () = valid_objects s in
    let* () = check_sphere_textures s in
    valid_lights s.lights
  in
  match result with Ok () -> Ok s | Error _ as e -> e

let with_overrides ?width ?height ?depth ?viewport ?camera ?camera_path ?background ?epsilon ?objects ?lights s =
  let pick o d = match o with Some x -> x | None -> d in
  let s =
    {
      s with
      width = pick width s.width;
      height = pick height s.height;
      depth = pick depth s.depth;
      viewport = pick viewport s.viewport;
      camera = pick camera s.camera;
      camera_path = pick camera_path s.camera_path;
      background = pick background s.background;
      epsilon = pick epsilon s.epsilon;
      lights = pick lights s.lights;
    }
  in
  match objects with
  | None -> s
  | Some objects ->
      let spheres, placed = split objects in
      with_objects s ~spheres ~placed

(* Only what changed is checked: the rest was validated. *)
let override ?(limits = Limits.default) ?width ?height ?depth ?viewport ?camera (s : valid) =
  let ( let* ) = Result.bind in
  let s = with_overrides ?width ?height ?depth s in
  let s = match viewport with Some viewport -> { s with viewport } | None -> s in
  let s = match camera with Some camera -> { s with camera } | None -> s in
  let given check = function Some x -> Result.map ignore (check x) | None -> Ok () in
  let checked =
    let* () = if width = None && height = None then Ok () else Limits.check_canvas limits s.width s.height in
    let* () = given (Limits.check_depth limits) depth in
    let* () = given Viewport.validate viewport in
    given Camera.validate camera
  in
  match checked with Ok () -> Ok s | Error _ as e -> e

(* The path's cameras pass Camera.validate: Camera_path.v checked every key
   and segment. *)
let at_frame (s : valid) f =
  match s.camera_path with
  | None -> Error (`Msg "the scene has no camera-path, so it has no frames to render")
  | Some path -> (
      match Camera_path.camera path f with
      | Ok camera ->
          (* A path's keys have no lens: the camera form's carries over. *)
          let camera =
            if Camera.has_lens s.camera then
              Camera.v ~rotation:camera.rotation ~aperture:s.camera.aperture ~focal_distance:s.camera.focal_distance
                ~lens_sampling:s.camera.lens_sampling camera.position
            else camera
          in
          Ok { s with camera; camera_path = None }
      | Error e -> Error e)

let check_work ?(limits = Limits.default) ?(samples = 1) ?pixels (s : valid) =
  (* No list of a million spheres' materials: each array and list is read
     where it is. *)
  let exists p =
    Array.exists p (Spheres.materials s.spheres)
    || List.exists (fun (_, sh) -> List.exists p (Shape.materials sh)) s.placed
  in
  (* A hit bounces on a reflective or a transparent surface; it may spawn
     two rays where some of the light is reflected and some refracted. *)
  let bounces = exists (fun (m : Material.t) -> m.reflective > 0. || m.transparency > 0.) in
  let split = exists (fun (m : Material.t) -> m.transparency > 0. && (m.reflective > 0. || m.fresnel)) in
  let objects, leaves =
    List.fold_left
      (fun (o, l) (_, sh) ->
        match sh with
        | Shape.Mesh m -> (o + Mesh.objects m, l)
        | Csg c -> (o + 1, l + csg_leaves c)
        | Sphere _ | Plane _ | Triangle _ | Box _ | Primitive _ | Instance _ -> (o + 1, l))
      (Spheres.length s.spheres, 0) s.placed
  in
  (* Each sample of an area or sphere light casts its own shadow ray. *)
  let lights = List.fold_left (fun n l -> match l with Light.Ambient _ -> n | _ -> n + Light.samples l) 0 s.lights in
  if s.depth > Limits.max_tree_levels && exists (fun (m : Material.t) -> m.transparency > 0.) then
    Error
      (`Msg
        (Printf.sprintf
           "recursion depth %d is too deep for a scene with transparent objects: their ray tree is followed by \
            recursion, at most %d levels"
           s.depth Limits.max_tree_levels))
  else
  Limits.check_work limits ~split ~leaves
    ~pixels:(Option.value pixels ~default:(s.width * s.height))
    ~samples ~depth:(if bounces then s.depth else 0) ~spheres:objects ~lights ()
