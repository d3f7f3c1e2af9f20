let max_coordinate = 1e12
let min_size = 1e-30
let max_intensity = 1e6
let max_dimension = 65536
let max_pixels = 1 lsl 28
let max_depth = 64
let max_jobs = 1024
let num = Float_text.to_string

let check_jobs n =
  if n < 1 || n > max_jobs then
    Error (Printf.sprintf "--jobs must lie in [1, %d], got %d" max_jobs n)
  else Ok n

let check_coordinate what x =
  if Float.is_finite x && Float.abs x <= max_coordinate then Ok x
  else Error (Printf.sprintf "%s must be finite and at most 1e12 in magnitude, got %s" what (num x))

let check_size what x =
  if not (x > 0.) then Error (Printf.sprintf "%s must be > 0, got %s" what (num x))
  else if x < min_size then
    Error (Printf.sprintf "%s must be at least 1e-30, got %s" what (num x))
  else check_coordinate what x

let check_point what (p : Vec3.t) =
  match (check_coordinate what p.x, check_coordinate what p.y, check_coordinate what p.z) with
  | Ok _, Ok _, Ok _ -> Ok p
  | (Error e, _, _ | _, Error e, _ | _, _, Error e) -> Error e

let check_dimension what n =
  if n < 1 || n > max_dimension then
    Error (Printf.sprintf "canvas %s must lie in [1, %d], got %d" what max_dimension n)
  else Ok n

let check_canvas w h =
  match (check_dimension "width" w, check_dimension "height" h) with
  | (Error e, _ | _, Error e) -> Error e
  | Ok _, Ok _ ->
      if w * h > max_pixels then
        Error
          (Printf.sprintf "canvas %dx%d has more than %d pixels" w h
             max_pixels)
      else Ok ()

let check_depth d =
  if d < 0 || d > max_depth then
    Error (Printf.sprintf "recursion depth must lie in [0, %d], got %d" max_depth d)
  else Ok d
