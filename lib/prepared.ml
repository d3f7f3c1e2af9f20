type t = {
  n_spheres : int;
  n_objects : int;
  all_spheres : bool;
  textbook_all : bool;
  index : int array;
  slot : int array;
  bvh : Bvh.t option;
  unbounded : int array;
  kind : int array;
  geom : float array;
  extent : float array;
  twin : int array;
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
}

let bvh_threshold = 8
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
let max_channel (scene : Scene.t) =
  let light_bound ~diffuse ~specular =
    List.fold_left
      (fun acc l ->
        match l with
        | Light.Ambient { intensity } -> acc +. intensity
        | Point { intensity; _ } | Directional { intensity; _ } ->
            acc +. (intensity *. diffuse) +. (intensity *. specular))
      0. scene.lights
  in
  let channel (m : Material.t) =
    Float.max m.color.r (Float.max m.color.g m.color.b) *. light_bound ~diffuse:1. ~specular:(specular_bound m.specular)
  in
  let bg = scene.background in
  let bound =
    List.fold_left
      (fun acc (s : Sphere.t) ->
        Float.max acc (channel (Material.v ~specular:s.specular ~reflective:s.reflective s.color)))
      (Float.max bg.r (Float.max bg.g bg.b))
      scene.spheres
  in
  let bound = List.fold_left (fun acc sh -> Float.max acc (channel (Shape.material sh))) bound scene.shapes in
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

(* Per object: its kind, geometry (spheres: center and radius, in the
   first 4 floats), material, and for the hierarchy a cube around it. *)
type obj = { okind : int; ogeom : float array; mat : Material.t; bounded : bool; center : Vec3.t; half : float }

let objects (scene : Scene.t) =
  let sphere (s : Sphere.t) =
    {
      okind = Shape.sphere;
      ogeom = [| s.center.x; s.center.y; s.center.z; s.radius; 0.; 0.; 0.; 0.; 0. |];
      mat = Material.v ~specular:s.specular ~reflective:s.reflective s.color;
      bounded = true;
      center = s.center;
      half = s.radius;
    }
  in
  let shape sh =
    let g = Array.make Shape.stride 0. in
    Shape.store sh g 0;
    let center, half = if Shape.bounded sh then Shape.bounds sh else (Vec3.zero, 0.) in
    { okind = Shape.kind sh; ogeom = g; mat = Shape.material sh; bounded = Shape.bounded sh; center; half }
  in
  Array.of_list (List.map sphere scene.spheres @ List.map shape scene.shapes)

(* The first object with the same kind and geometry, for each: such twins
   are one surface, and a ray leaving one leaves both. *)
let twins (listed : obj array) =
  let first = Hashtbl.create 16 in
  Array.mapi
    (fun i o ->
      let key = (o.okind, Array.to_list o.ogeom) in
      match Hashtbl.find_opt first key with
      | Some j -> j
      | None ->
          Hashtbl.add first key i;
          i)
    listed

let prepare ?(skips = true) (scene : Scene.t) =
  (match Scene.validate scene with
  | Ok _ -> ()
  | Error (`Msg m) -> invalid_arg ("Prepared.prepare: invalid scene: " ^ m));
  let listed = objects scene in
  let n = Array.length listed in
  let n_spheres = List.length scene.spheres in
  let bounded = List.filter (fun i -> listed.(i).bounded) (List.init n Fun.id) |> Array.of_list in
  let unbounded = List.filter (fun i -> not listed.(i).bounded) (List.init n Fun.id) |> Array.of_list in
  let nb = Array.length bounded in
  let bvh =
    if skips && nb > bvh_threshold then begin
      let cx = Array.map (fun i -> listed.(i).center.x) bounded in
      let cy = Array.map (fun i -> listed.(i).center.y) bounded in
      let cz = Array.map (fun i -> listed.(i).center.z) bounded in
      let radius = Array.map (fun i -> listed.(i).half) bounded in
      let margin = Bvh.ray_box_margin ~cx ~cy ~cz ~radius scene.camera.position in
      Some (Bvh.build ~cx ~cy ~cz (Array.mapi (fun i r -> r +. margin.(i)) radius))
    end
    else None
  in
  (* Slots: the hierarchy's leaf order, then the planes; without a
     hierarchy, the scene's order. *)
  let index =
    match bvh with
    | Some b -> Array.append (Array.map (fun k -> bounded.(k)) b.order) unbounded
    | None -> Array.init n Fun.id
  in
  let slot = Array.make n 0 in
  Array.iteri (fun k i -> slot.(i) <- k) index;
  let objs = Array.map (fun i -> listed.(i)) index in
  let twin_of = twins listed in
  let lights =
    Array.of_list
      (if skips then List.filter (fun l -> Light.intensity l > 0.) scene.lights else scene.lights)
  in
  let sf f = Array.map f objs and lf f = Array.map f lights in
  let o = scene.camera.position in
  let cx = sf (fun s -> s.ogeom.(0)) and cy = sf (fun s -> s.ogeom.(1)) in
  let cz = sf (fun s -> s.ogeom.(2)) and r2 = sf (fun s -> s.ogeom.(3) *. s.ogeom.(3)) in
  let primary_ocx = Array.map (fun c -> o.x -. c) cx in
  let primary_ocy = Array.map (fun c -> o.y -. c) cy in
  let primary_ocz = Array.map (fun c -> o.z -. c) cz in
  (* Same operands in the same order as the tracer's per-ray [k3]. *)
  let primary_k3 =
    Array.init n (fun i ->
        let x = primary_ocx.(i) and y = primary_ocy.(i) and z = primary_ocz.(i) in
        ((x *. x) +. (y *. y) +. (z *. z)) -. r2.(i))
  in
  let vector l =
    match l with
    | Light.Ambient _ -> Vec3.zero
    | Point { position; _ } -> position
    | Directional { direction; _ } -> direction
  in
  let geom = Array.make (Shape.stride * n) 0. in
  Array.iteri (fun k ob -> Array.blit ob.ogeom 0 geom (Shape.stride * k) Shape.stride) objs;
  let max_channel = max_channel scene in
  {
    n_spheres;
    n_objects = n;
    all_spheres = n_spheres = n;
    textbook_all = n_spheres = n && bvh = None && scene.epsilon <> None;
    index;
    slot;
    bvh;
    unbounded = Array.map (fun i -> slot.(i)) unbounded;
    kind = sf (fun s -> s.okind);
    geom;
    extent = sf (fun s -> Array.fold_left (fun acc x -> Float.max acc (Float.abs x)) 0. s.ogeom);
    twin = Array.map (fun i -> slot.(twin_of.(i))) index;
    cx;
    cy;
    cz;
    radius = sf (fun s -> s.ogeom.(3));
    r2;
    red = sf (fun s -> s.mat.color.r);
    green = sf (fun s -> s.mat.color.g);
    blue = sf (fun s -> s.mat.color.b);
    specular = sf (fun s -> s.mat.specular);
    specular_zero = sf (fun s -> if skips then specular_zero s.mat.specular else 0.);
    reflective = sf (fun s -> s.mat.reflective);
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
    max_channel;
    early_stop = skips && Float.is_finite max_channel;
    skips;
  }
