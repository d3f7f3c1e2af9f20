type t = { samples : int; adaptive : int option; subsample : bool }

let max_samples = Limits.max_grid
let max_threshold = 255
let msg fmt = Printf.ksprintf (fun m -> Error (`Msg m)) fmt

let even_message samples =
  Printf.sprintf
    "adaptive sampling needs an odd number of samples >= 3, whose grid has the pixel's centre in its middle (or, under a \
     lens, any number >= 2), got %d"
    samples

let v ?(samples = 1) ?adaptive ?(subsample = false) () =
  if samples < 1 || samples > max_samples then
    msg "samples must lie in [1, %d] (an N x N grid per pixel), got %d" max_samples samples
  else
    match adaptive with
    | Some th when th < 0 || th > max_threshold ->
        msg "the adaptive threshold must lie in [0, %d], got %d" max_threshold th
    | Some _ when samples < 2 -> msg "%s" (even_message samples)
    | _ when subsample && samples > 1 ->
        msg "subsampling traces one ray per pixel: it cannot be combined with samples > 1"
    | _ -> Ok { samples; adaptive; subsample }

let one = { samples = 1; adaptive = None; subsample = false }
let is_one s = s.samples = 1 && not s.subsample
let averaging s = s.samples > 1

let to_string s =
  let n = s.samples in
  match s.adaptive with
  | Some th -> Printf.sprintf "adaptive %dx%d t=%d" n n th
  | None -> if s.subsample then "subsampled" else Printf.sprintf "%dx%d" n n
