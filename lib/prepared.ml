type t = {
  n_spheres : int;
  index : int array;
  slot : int array;
  bvh : Bvh.t option;
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
  skips : bool;
}

let bvh_threshold = 8
let ambient = 0
let point = 1
let directional = 2

(* The largest channel any ray can return: background, or a sphere's colour
   times the most light it can receive (ambient, plus each light's diffuse
   term, at most its intensity, and specular term, likewise). Blends are
   convex combinations, so they stay below it. The margin covers the
   rounding of cosines and blends, each off by a few ulps at most. *)
let max_channel (scene : Scene.t) =
  let light_bound shiny =
    List.fold_left
      (fun acc l ->
        match l with
        | Light.Ambient { intensity } -> acc +. intensity
        | Point { intensity; _ } | Directional { intensity; _ } ->
            acc +. (intensity *. if shiny then 2. else 1.))
      0. scene.lights
  in
  let bg = scene.background in
  let bound =
    List.fold_left
      (fun acc (s : Sphere.t) ->
        let c = s.color in
        Float.max acc (Float.max c.r (Float.max c.g c.b) *. light_bound (not (Sphere.is_matte s))))
      (Float.max bg.r (Float.max bg.g bg.b))
      scene.spheres
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

let prepare ?(skips = true) scene =
  let scene = Scene.of_valid scene in
  let listed = Array.of_list scene.spheres in
  let n = Array.length listed in
  let bvh =
    if skips && n > bvh_threshold then begin
      let cx = Array.map (fun s -> s.Sphere.center.x) listed in
      let cy = Array.map (fun s -> s.Sphere.center.y) listed in
      let cz = Array.map (fun s -> s.Sphere.center.z) listed in
      let radius = Array.map (fun s -> s.Sphere.radius) listed in
      let margin = Bvh.ray_box_margin ~cx ~cy ~cz ~radius scene.camera.position in
      Some (Bvh.build ~cx ~cy ~cz (Array.mapi (fun i r -> r +. margin.(i)) radius))
    end
    else None
  in
  let index = match bvh with Some b -> b.order | None -> Array.init n Fun.id in
  let slot = Array.make n 0 in
  Array.iteri (fun k i -> slot.(i) <- k) index;
  let spheres = Array.map (fun i -> listed.(i)) index in
  let lights =
    Array.of_list
      (if skips then List.filter (fun l -> Light.intensity l > 0.) scene.lights else scene.lights)
  in
  let sf f = Array.map f spheres and lf f = Array.map f lights in
  let o = scene.camera.position in
  let cx = sf (fun s -> s.Sphere.center.x) and cy = sf (fun s -> s.center.y) in
  let cz = sf (fun s -> s.center.z) and r2 = sf (fun s -> s.radius *. s.radius) in
  let primary_ocx = Array.map (fun c -> o.x -. c) cx in
  let primary_ocy = Array.map (fun c -> o.y -. c) cy in
  let primary_ocz = Array.map (fun c -> o.z -. c) cz in
  (* Same operands in the same order as the tracer's per-ray [k3]. *)
  let primary_k3 =
    Array.init (Array.length spheres) (fun i ->
        let x = primary_ocx.(i) and y = primary_ocy.(i) and z = primary_ocz.(i) in
        ((x *. x) +. (y *. y) +. (z *. z)) -. r2.(i))
  in
  let vector l =
    match l with
    | Light.Ambient _ -> Vec3.zero
    | Point { position; _ } -> position
    | Directional { direction; _ } -> direction
  in
  {
    n_spheres = n;
    index;
    slot;
    bvh;
    cx;
    cy;
    cz;
    radius = sf (fun s -> s.radius);
    r2;
    red = sf (fun s -> s.color.r);
    green = sf (fun s -> s.color.g);
    blue = sf (fun s -> s.color.b);
    specular = sf (fun s -> s.specular);
    specular_zero = sf (fun s -> if skips then specular_zero s.specular else 0.);
    reflective = sf (fun s -> s.reflective);
    n_lights = Array.length lights;
    light_kind =
      lf (function Light.Ambient _ -> ambient | Point _ -> point | Directional _ -> directional);
    light_intensity = lf Light.intensity;
    lx = lf (fun l -> (vector l).x);
    ly = lf (fun l -> (vector l).y);
    lz = lf (fun l -> (vector l).z);
    robust = scene.epsilon = None;
    epsilon = Option.value scene.epsilon ~default:0.;
    depth = scene.depth;
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
    max_channel = max_channel scene;
    skips;
  }
