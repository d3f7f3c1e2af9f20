let max_coordinate = 1e12
let error fmt = Printf.ksprintf (fun m -> Error (`Msg m)) fmt
let min_size = 1e-30
let max_intensity = 1e6
let max_dimension = 65536
let max_pixels = 1 lsl 28
let max_depth = 64
let max_grid = 64
let max_samples = max_grid * max_grid
let max_spheres = 1_000_000
let max_triangles = 4_000_000
let max_scene_triangles = 4_000_000
let max_lights = 1000
let max_scene_bytes = 128 * 1024 * 1024
let max_form_bytes = 16 * 1024 * 1024
let max_mesh_bytes = 1024 * 1024 * 1024
let max_work = 1e12
let num = Float_text.to_string

type name = [ `Pixels | `Depth | `Samples | `Spheres | `Triangles | `Lights | `Scene_bytes | `Form_bytes | `Mesh_bytes | `Work ]

let variable = function
  | `Pixels -> "RAYTRACE_MAX_PIXELS"
  | `Depth -> "RAYTRACE_MAX_DEPTH"
  | `Samples -> "RAYTRACE_MAX_SAMPLES"
  | `Spheres -> "RAYTRACE_MAX_SPHERES"
  | `Triangles -> "RAYTRACE_MAX_TRIANGLES"
  | `Lights -> "RAYTRACE_MAX_LIGHTS"
  | `Scene_bytes -> "RAYTRACE_MAX_SCENE_BYTES"
  | `Form_bytes -> "RAYTRACE_MAX_FORM_BYTES"
  | `Mesh_bytes -> "RAYTRACE_MAX_MESH_BYTES"
  | `Work -> "RAYTRACE_MAX_WORK"

(* Values are integers; a float keeps them exact up to 2^53, far beyond
   any useful bound. *)
type t = {
  pixels : float;
  depth : float;
  samples : float;
  spheres : float;
  triangles : float;
  lights : float;
  scene_bytes : float;
  form_bytes : float;
  mesh_bytes : float;
  work : float;
}

let default =
  {
    pixels = Float.of_int max_pixels;
    depth = Float.of_int max_depth;
    samples = Float.of_int max_samples;
    spheres = Float.of_int max_spheres;
    triangles = Float.of_int max_scene_triangles;
    lights = Float.of_int max_lights;
    scene_bytes = Float.of_int max_scene_bytes;
    form_bytes = Float.of_int max_form_bytes;
    mesh_bytes = Float.of_int max_mesh_bytes;
    work = max_work;
  }

let bound l = function
  | `Pixels -> l.pixels
  | `Depth -> l.depth
  | `Samples -> l.samples
  | `Spheres -> l.spheres
  | `Triangles -> l.triangles
  | `Lights -> l.lights
  | `Scene_bytes -> l.scene_bytes
  | `Form_bytes -> l.form_bytes
  | `Mesh_bytes -> l.mesh_bytes
  | `Work -> l.work

let with_bound l n x =
  match n with
  | `Pixels -> { l with pixels = x }
  | `Depth -> { l with depth = x }
  | `Samples -> { l with samples = x }
  | `Spheres -> { l with spheres = x }
  | `Triangles -> { l with triangles = x }
  | `Lights -> { l with lights = x }
  | `Scene_bytes -> { l with scene_bytes = x }
  | `Form_bytes -> { l with form_bytes = x }
  | `Mesh_bytes -> { l with mesh_bytes = x }
  | `Work -> { l with work = x }

let names = [ `Pixels; `Depth; `Samples; `Spheres; `Triangles; `Lights; `Scene_bytes; `Form_bytes; `Mesh_bytes; `Work ]

let of_lookup lookup =
  let parse l n =
    match l with
    | Error _ as e -> e
    | Ok l -> (
        match lookup (variable n) with
        | None | Some "" -> Ok l
        | Some text -> (
            let digits = String.concat "" (String.split_on_char '_' (String.trim text)) in
            match Float_text.of_string digits with
            | Some x when x >= 1. && Float.is_integer x -> Ok (with_bound l n x)
            | _ -> Error (`Msg (Printf.sprintf "%s must be a positive integer, got %S" (variable n) text))))
  in
  List.fold_left parse (Ok default) names

let show_bound x = if x < 1e15 then Printf.sprintf "%.0f" x else num x

let exceeded l n what =
  Printf.sprintf "%s, more than the limit of %s (set %s to raise it)" what (show_bound (bound l n)) (variable n)

(* [Ok ()] if [x <= bound l n]; [what ()] describes [x] for the message. *)
let within l n x what = if x <= bound l n then Ok () else Error (`Msg (exceeded l n (what ())))
let max_jobs = 1024

let check_jobs n =
  if n < 1 || n > max_jobs then
    (error "--jobs must lie in [1, %d], got %d" max_jobs n)
  else Ok n

let coordinate_ok x = Float.is_finite x && Float.abs x <= max_coordinate
let size_ok x = x >= min_size && coordinate_ok x

let check_coordinate what x =
  if coordinate_ok x then Ok x
  else (error "%s must be finite and at most 1e12 in magnitude, got %s" what (num x))

let check_size what x =
  if not (x > 0.) then (error "%s must be > 0, got %s" what (num x))
  else if x < min_size then
    (error "%s must be at least 1e-30, got %s" what (num x))
  else check_coordinate what x

let check_point what (p : Vec3.t) =
  match (check_coordinate what p.x, check_coordinate what p.y, check_coordinate what p.z) with
  | Ok _, Ok _, Ok _ -> Ok p
  | (Error e, _, _ | _, Error e, _ | _, _, Error e) -> Error e

let check_dimension what n =
  if n < 1 || n > max_dimension then
    (error "canvas %s must lie in [1, %d], got %d" what max_dimension n)
  else Ok n

let pixels_within l kind w h =
  (* A float product: two header fields of a file can overflow an int. *)
  let area = Float.of_int w *. Float.of_int h in
  within l `Pixels area (fun () -> Printf.sprintf "%s %dx%d has %s pixels" kind w h (show_bound area))

let check_canvas l w h =
  match (check_dimension "width" w, check_dimension "height" h) with
  | (Error e, _ | _, Error e) -> Error e
  | Ok _, Ok _ -> pixels_within l "canvas" w h

let check_image_size l w h =
  if w < 1 || h < 1 then (error "image size %dx%d is empty" w h)
  else pixels_within l "image" w h

(* [Ok n] if [n >= lo] (else [Error (low ())]) and [n] is within bound
   [name] (else [what ()] describes [n]). *)
let bounded l name ~lo ~low ~what n =
  if n < lo then Error (`Msg (low ()))
  else match within l name (Float.of_int n) what with Ok () -> Ok n | Error e -> Error e

let max_levels = 1 lsl 20
let max_tree_levels = 4096

let check_depth l d =
  if d > max_levels then
    error "recursion depth %d is too deep: a tracer keeps a few floats per level, and takes at most %d levels \
           whatever %s says" d max_levels (variable `Depth)
  else
    bounded l `Depth ~lo:0 d
      ~low:(fun () -> Printf.sprintf "recursion depth must be >= 0, got %d" d)
      ~what:(fun () -> Printf.sprintf "recursion depth %d is too deep" d)

let check_triangles l n =
  bounded l `Triangles ~lo:0 n
    ~low:(fun () -> Printf.sprintf "a negative number of triangles: %d" n)
    ~what:(fun () -> Printf.sprintf "the scene's meshes have %d triangles in all" n)

let check_samples l n =
  bounded l `Samples ~lo:1 n
    ~low:(fun () -> Printf.sprintf "samples per pixel must be >= 1, got %d" n)
    ~what:(fun () -> Printf.sprintf "%d samples per pixel are too many" n)

let check_count l kind n =
  let noun = match kind with `Spheres -> "spheres" | `Objects -> "objects" | `Lights -> "lights" in
  let name = match kind with `Spheres | `Objects -> `Spheres | `Lights -> `Lights in
  bounded l name ~lo:0 n
    ~low:(fun () -> Printf.sprintf "a negative number of %s: %d" noun n)
    ~what:(fun () -> Printf.sprintf "the scene has %d %s" n noun)

let check_scene_bytes l n =
  bounded l `Scene_bytes ~lo:0 n
    ~low:(fun () -> Printf.sprintf "a negative size: %d" n)
    ~what:(fun () -> Printf.sprintf "the scene is %d bytes long" n)

let check_form_bytes l n =
  bounded l `Form_bytes ~lo:0 n
    ~low:(fun () -> Printf.sprintf "a negative size: %d" n)
    ~what:(fun () -> Printf.sprintf "a form of the scene is more than %d bytes long" n)

let check_mesh_bytes l file n =
  bounded l `Mesh_bytes ~lo:0 n
    ~low:(fun () -> Printf.sprintf "a negative size: %d" n)
    ~what:(fun () -> Printf.sprintf "mesh file %s is %d bytes long" file n)

(* Beyond 8 spheres the renderer walks a bounding volume hierarchy: about
   log2 n levels of boxes, each with leaves of up to 4 spheres on either
   side; 16 log2 n is a generous bound of what a ray meets on scenes that
   are not pathological. In floats: no count can overflow. *)
let spheres_per_ray n =
  let f = Float.of_int n in
  if n <= 8 then Float.max 0. f else Float.min f (16. *. Float.ceil (Float.log2 f))

(* A chain of [depth] bounces; with glass that both reflects and refracts,
   every hit may spawn two rays: a full binary tree of [depth] levels below
   the camera ray, [2^(depth+1) - 1] rays (infinity far beyond any bound,
   never an overflow). *)
let rays_per_sample ~depth ~split =
  let levels = Float.max 0. (Float.of_int depth) +. 1. in
  if split then Float.pow 2. levels -. 1. else levels

let work ?(split = false) ?(leaves = 0) ~pixels ~samples ~depth ~spheres ~lights () =
  let f = Float.of_int in
  f pixels *. f samples *. rays_per_sample ~depth ~split
  *. (spheres_per_ray spheres +. f leaves)
  *. (1. +. f lights)

(* An integer in full while it has few digits, else three of them. *)
let show_count x = if Float.is_integer x && x < 1e15 then Printf.sprintf "%.0f" x else Printf.sprintf "%.3g" x

let check_work ?(split = false) ?(leaves = 0) l ~pixels ~samples ~depth ~spheres ~lights () =
  let w = work ~split ~leaves ~pixels ~samples ~depth ~spheres ~lights () in
  within l `Work w (fun () ->
      let rays = rays_per_sample ~depth ~split in
      Printf.sprintf
        "the render needs about %s intersection tests (%d pixels x %d samples x %s rays%s x %s \
         objects per ray%s x (1 + %d lights))"
        (if Float.is_finite w then Printf.sprintf "%.3g" w else "more than 1e308")
        pixels samples
        (if Float.is_finite rays then show_count rays else "more than 1e308")
        (if split then Printf.sprintf " (a tree of depth %d: a hit on glass that reflects may spawn two rays)" depth
         else "")
        (show_count (spheres_per_ray spheres +. Float.of_int leaves))
        (if leaves > 0 then Printf.sprintf " (with %d leaves of CSG solids)" leaves else "")
        lights)

exception Work_exceeded of int

let work_budget l =
  let bound = bound l `Work in
  if bound >= Float.of_int max_int then max_int else Float.to_int bound

let work_exceeded l n =
  exceeded l `Work (Printf.sprintf "the render was stopped after %d intersection tests (objects, CSG leaves and boxes of the hierarchies)" n)
