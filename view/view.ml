type t = { base : Scene.t; scene : Scene.t; valid : Scene.valid; limits : Limits.t; antialias : bool; help : bool }

let v ?(limits = Limits.default) valid =
  let scene = Scene.of_valid valid in
  { base = scene; scene; valid; limits; antialias = false; help = false }

let antialias_samples = 3
let samples view = if view.antialias then antialias_samples else 1

type input = Key of char | Drag of int * int | Resize of int * int
type effect = Nothing | Render | Redraw | Save | Quit

(* Graphics reports only keys that have a character; the window rebinds the
   arrows to these, which no Latin-1 key produces (C1 control codes). *)
let arrow_left = '\x80'
let arrow_up = '\x81'
let arrow_right = '\x82'
let arrow_down = '\x83'

(* Camera motion. *)

let move_step (scene : Scene.t) = 0.5 *. (Scene.viewport scene).distance
let turn_step = Float.pi /. 36.

(* The column of the matrix that [pick] selects: where that camera axis points. *)
let column (m : Camera.rotation) pick = Vec3.v (pick m.row0) (pick m.row1) (pick m.row2)

(* [cam] moved to [position] and turned by [rotation]: its lens goes with
   it, so that the window and the page keep a scene's depth of field. *)
let posed (cam : Camera.t) ~rotation position =
  Camera.v ~rotation ~aperture:cam.aperture ~focal_distance:cam.focal_distance position

let move ~right ~forward (cam : Camera.t) =
  let r = Vec3.unit (column cam.rotation (fun (v : Vec3.t) -> v.x)) in
  let f = Vec3.unit (column cam.rotation (fun (v : Vec3.t) -> v.z)) in
  posed cam ~rotation:cam.rotation Vec3.(cam.position + (right * r) + (forward * f))

let yaw a (cam : Camera.t) =
  (* R_y(a) M: rows 0 and 2 mix, row 1 (the y of every direction) stays. *)
  let c = cos a and s = sin a in
  let m = cam.rotation in
  let rotation =
    Camera.{ row0 = Vec3.((c * m.row0) + (s * m.row2)); row1 = m.row1; row2 = Vec3.((c * m.row2) - (s * m.row0)) }
  in
  posed cam ~rotation cam.position

let pitch a (cam : Camera.t) =
  (* M R_x(a): in each row, the y and z entries mix. *)
  let c = cos a and s = sin a in
  let row (r : Vec3.t) = Vec3.v r.x ((c *. r.y) -. (s *. r.z)) ((s *. r.y) +. (c *. r.z)) in
  let m = cam.rotation in
  posed cam ~rotation:Camera.{ row0 = row m.row0; row1 = row m.row1; row2 = row m.row2 } cam.position

let drag_angles (scene : Scene.t) dx dy =
  let vp = (Scene.viewport scene) in
  let per_x = vp.width /. (Float.of_int (Scene.width scene) *. vp.distance) in
  let per_y = vp.height /. (Float.of_int (Scene.height scene) *. vp.distance) in
  (-.Float.of_int dx *. per_x, -.Float.of_int dy *. per_y)

(* Window size. *)

let fit (base : Scene.t) ~width ~height =
  let vp = Scene.viewport base in
  if width = Scene.width base && height = Scene.height base then vp
  else
    let w = Float.of_int width and h = Float.of_int height in
    let gw = Float.of_int (Scene.width base) and gh = Float.of_int (Scene.height base) in
    let k = Float.max (gw /. w) (gh /. h) in
    Viewport.v ~width:(vp.width *. (k *. w /. gw)) ~height:(vp.height *. (k *. h /. gh)) ~distance:vp.distance

(* Input. *)

(* Only what changed is checked: the rest of the scene was validated. *)
let overridden view ?width ?height ?depth ?viewport ?camera () =
  match Scene.override ~limits:view.limits ?width ?height ?depth ?viewport ?camera view.valid with
  | Ok valid -> ({ view with valid; scene = Scene.of_valid valid }, Render)
  | Error _ -> (view, Nothing)

let with_camera view camera = overridden view ~camera ()

let moved view ~right ~forward =
  let step = move_step view.scene in
  with_camera view (move ~right:(right *. step) ~forward:(forward *. step) (Scene.camera view.scene))

let turned view ~yaw:y ~pitch:p = with_camera view (pitch p (yaw y (Scene.camera view.scene)))

let with_depth view delta =
  let depth = (Scene.depth view.scene) + delta in
  if depth < 0 || depth > Limits.max_depth then (view, Nothing) else overridden view ~depth ()

let resized view width height =
  let scene = view.scene in
  if width = (Scene.width scene) && height = (Scene.height scene) then (view, Nothing)
  else
    match Limits.check_canvas view.limits width height with
    | Error _ -> (view, Nothing)
    | Ok () -> overridden view ~width ~height ~viewport:(fit view.base ~width ~height) ()

let key view c =
  if c = arrow_up || c = 'W' then moved view ~right:0. ~forward:1.
  else if c = arrow_down || c = 'S' then moved view ~right:0. ~forward:(-1.)
  else if c = arrow_left || c = 'A' then moved view ~right:(-1.) ~forward:0.
  else if c = arrow_right || c = 'D' then moved view ~right:1. ~forward:0.
  else
    match c with
    | 'Q' | '<' | ',' -> turned view ~yaw:(-.turn_step) ~pitch:0.
    | 'E' | '>' | '.' -> turned view ~yaw:turn_step ~pitch:0.
    | '+' | '=' -> with_depth view 1
    | '-' | '_' -> with_depth view (-1)
    | 'a' -> ({ view with antialias = not view.antialias }, Render)
    | 'r' -> (view, Render)
    | 's' -> (view, Save)
    | 'h' -> ({ view with help = not view.help }, Redraw)
    | 'q' | '\027' -> (view, Quit)
    | _ -> (view, Nothing)

let handle view = function
  | Key c -> key view c
  | Drag (0, 0) -> (view, Nothing)
  | Drag (dx, dy) ->
      let y, p = drag_angles view.scene dx dy in
      turned view ~yaw:y ~pitch:p
  | Resize (w, h) -> resized view w h

(* Text. *)

let title ~name ?frame () =
  match frame with
  | None -> Printf.sprintf "raytrace: %s - h: help" name
  | Some (w, h, seconds, rays_per_s) ->
      Printf.sprintf "raytrace: %s - %dx%d in %.3f s, %.1f M rays/s - h: help" name w h seconds
        (rays_per_s /. 1e6)

let help_lines view =
  let s = view.scene in
  let p = (Scene.camera s).position in
  [
    "arrows, W A S D   move (Shift for letters)";
    "Q E, < >, drag    turn";
    Printf.sprintf "+ -               recursion depth (now %d)" (Scene.depth s);
    Printf.sprintf "a                 antialiasing %dx%d (now %s)" antialias_samples antialias_samples
      (if view.antialias then "on" else "off");
    "r                 render again";
    "s                 save as PPM (and scene)";
    "h                 hide this help";
    "q, Escape         quit";
    Printf.sprintf "camera at %.3g %.3g %.3g" p.x p.y p.z;
  ]

let save_paths ~scene_file ~exists =
  let dir, base =
    match scene_file with
    | None -> (Filename.current_dir_name, "cgfs")
    | Some f -> (Filename.dirname f, Filename.remove_extension (Filename.basename f))
  in
  let paths n =
    let stem = Filename.concat dir (Printf.sprintf "%s-%d" base n) in
    (stem ^ ".ppm", stem ^ ".scene")
  in
  let rec first n =
    let ppm, scene = paths n in
    if exists ppm || exists scene then first (n + 1) else (ppm, scene)
  in
  first 1
