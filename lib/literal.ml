(* Ray-sphere tests done since the last [render] began, checked against
   the work bound after each column of the canvas. *)
let tests = ref 0

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

let compute_lighting (scene : Scene.t) ~epsilon ~point ~normal ~view ~specular =
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
          (* Shadow check (7.7): is any sphere between the point and the light? *)
          let shadowed =
            closest_intersection scene.spheres ~origin:point ~direction:l ~t_min:epsilon
              ~t_max:(Light.shadow_t_max light)
            <> None
          in
          if not shadowed then begin
            let i = Light.intensity light in
            intensity := !intensity +. Shading.diffuse ~intensity:i ~l ~n:normal;
            if specular <> Sphere.matte then
              let r = Shading.reflect l normal in
              intensity := !intensity +. Shading.specular ~intensity:i ~s:specular ~r ~v:view
          end)
    scene.lights;
  !intensity

(* Iterative, so that no depth the limits allow can overflow the stack:
   the mirror rays are followed down, each level's local colour and
   reflectivity kept, then blended back up from the deepest colour, in the
   order of the document's recursion (the same floating-point operations). *)
let trace_ray (scene : Scene.t) ~epsilon ~origin ~direction ~t_min ~t_max ~depth =
  let rec follow levels ~origin ~direction ~t_min ~t_max ~depth =
    match closest_intersection scene.spheres ~origin ~direction ~t_min ~t_max with
    | None -> (levels, scene.background)
    | Some (sphere, t) ->
        let point = Vec3.add origin (Vec3.smul t direction) in
        let normal = Sphere.normal sphere point in
        let view = Vec3.neg direction in
        let lighting =
          compute_lighting scene ~epsilon ~point ~normal ~view ~specular:sphere.specular
        in
        let local = Color.smul lighting sphere.color in
        if sphere.reflective <= 0. || depth <= 0 then (levels, local)
        else
          let mirror = Shading.reflect view normal in
          follow ((sphere.reflective, local) :: levels) ~origin:point ~direction:mirror
            ~t_min:epsilon ~t_max:infinity ~depth:(depth - 1)
  in
  let levels, deepest = follow [] ~origin ~direction ~t_min ~t_max ~depth in
  List.fold_left
    (fun reflected (reflective, local) -> Color.blend ~reflective ~local ~reflected)
    deepest levels

let pixel (scene : Scene.t) gx gy =
  let epsilon = Option.value scene.epsilon ~default:Scene.document_epsilon in
  let v =
    Viewport.of_canvas scene.viewport ~canvas_width:scene.width ~canvas_height:scene.height gx gy
  in
  let direction = Camera.direction scene.camera (Vec3.sub v Vec3.zero) in
  trace_ray scene ~epsilon ~origin:scene.camera.position ~direction ~t_min:1. ~t_max:infinity
    ~depth:scene.depth

let render ?(limits = Limits.default) valid =
  let scene = Scene.of_valid valid in
  let budget = Limits.work_budget limits in
  tests := 0;
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
