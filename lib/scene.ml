type t = {
  width : int;
  height : int;
  viewport : Viewport.t;
  camera : Camera.t;
  background : Color.t;
  depth : int;
  epsilon : float option;
  spheres : Sphere.t list;
  lights : Light.t list;
}
[@@deriving show, eq]

let v ?(width = 600) ?(height = 600) ?(viewport = Viewport.default) ?(camera = Camera.default)
    ?(background = Color.black) ?(depth = 3) ?epsilon ~spheres ~lights () =
  { width; height; viewport; camera; background; depth; epsilon; spheres; lights }

let document_epsilon = 0.0001

let cgfs =
  let sphere ~center ~color ~specular ~reflective radius =
    Sphere.v ~specular ~reflective ~center ~radius color
  in
  v ~epsilon:0.001
    ~spheres:
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

let check_epsilon e =
  if Float.is_finite e && e >= 0. then Ok e
  else Error (Printf.sprintf "epsilon must be finite and >= 0, got %s" (Float_text.to_string e))

let check_background c =
  if Color.in_gamut c then Ok c
  else Error (Format.asprintf "background channels must lie in [0, 255], got %a" Color.pp c)

let validate s =
  let ( let* ) = Result.bind in
  let rec all check = function
    | [] -> Ok ()
    | x :: rest ->
        let* _ = check x in
        all check rest
  in
  let result =
    let* () = Limits.check_canvas s.width s.height in
    let* _ = Viewport.validate s.viewport in
    let* _ = Camera.validate s.camera in
    let* _ = check_background s.background in
    let* _ = Limits.check_depth s.depth in
    let* _ = match s.epsilon with Some e -> check_epsilon e | None -> Ok 0. in
    let* _ = Limits.check_count `Spheres (List.length s.spheres) in
    let* _ = Limits.check_count `Lights (List.length s.lights) in
    let* () = all Sphere.validate s.spheres in
    all Light.validate s.lights
  in
  match result with Ok () -> Ok s | Error m -> Error (`Msg m)

let with_overrides ?width ?height ?depth s =
  let pick o d = match o with Some x -> x | None -> d in
  { s with width = pick width s.width; height = pick height s.height; depth = pick depth s.depth }

let check_work ?(samples = 1) s =
  let depth = if List.exists (fun (sp : Sphere.t) -> sp.reflective > 0.) s.spheres then s.depth else 0 in
  let lights = List.length (List.filter (function Light.Ambient _ -> false | _ -> true) s.lights) in
  match
    Limits.check_work ~pixels:(s.width * s.height) ~samples ~depth ~spheres:(List.length s.spheres) ~lights
  with
  | Ok () -> Ok ()
  | Error m -> Error (`Msg m)
