open Raytrace

type frame = {
  width : int;
  height : int;
  frame_samples : int;
  seconds : float;
  trace_seconds : float;
  slices : int;
  longest_slice : float;
  rays : float;
}

type t = {
  now : unit -> float;
  mutable size : (int * int) option;
  mutable samples : int;
  mutable view : View.t;
  mutable render : Progressive.t;
  mutable started : float;
  mutable trace_seconds : float;
  mutable slices : int;
  mutable bands : int;
  mutable longest_slice : float;
  mutable last_frame : frame option;
}

let file = "scene"

let check_work samples (view : View.t) =
  Scene.check_work ~samples:(samples * samples) view.scene

let restart p =
  p.render <- Progressive.create ~samples:p.samples p.view.scene;
  p.started <- p.now ();
  p.trace_seconds <- 0.;
  p.slices <- 0;
  p.bands <- 0;
  p.longest_slice <- 0.

(* The view of [scene] at [size], its antialiasing flag saying whether
   [samples > 1], as the window's would after the same keys. *)
let view_of scene ~size ~samples =
  let view = View.v scene in
  let view =
    match size with
    | None -> Ok view
    | Some (w, h) -> (
        match Limits.check_canvas w h with
        | Error m -> Error (`Msg m)
        | Ok () -> Ok (fst (View.handle view (View.Resize (w, h)))))
  in
  Result.map (fun view -> if samples > 1 then fst (View.handle view (View.Key 'a')) else view) view

let v ~now text =
  match Scene_file.of_string ~file text with
  | Error e -> Error e
  | Ok scene -> (
      match view_of scene ~size:None ~samples:1 with
      | Error e -> Error e
      | Ok view -> (
          match check_work 1 view with
          | Error e -> Error e
          | Ok () ->
              let p =
                {
                  now;
                  size = None;
                  samples = 1;
                  view;
                  render = Progressive.create view.scene;
                  started = 0.;
                  trace_seconds = 0.;
                  slices = 0;
                  bands = 0;
                  longest_slice = 0.;
                  last_frame = None;
                }
              in
              restart p;
              Ok p))


(* Shows [scene] at [size] with [samples], if the render is allowed. *)
let show p scene ~size ~samples =
  match view_of scene ~size ~samples with
  | Error e -> Error e
  | Ok view -> (
      match check_work samples view with
      | Error e -> Error e
      | Ok () ->
          p.view <- view;
          p.size <- size;
          p.samples <- samples;
          restart p;
          Ok ())

let edit p text =
  match Scene_file.of_string ~file text with
  | Error e -> Error e
  | Ok scene -> show p scene ~size:p.size ~samples:p.samples

let set_size p size =
  if size = p.size then Ok ()
  else
    match size with
    | None -> show p p.view.base ~size ~samples:p.samples
    | Some (w, h) -> (
        match Limits.check_canvas w h with
        | Error m -> Error (`Msg m)
        | Ok () -> (
            (* As the window resizes: the camera moved so far stays. *)
            let view, _ = View.handle p.view (View.Resize (w, h)) in
            match check_work p.samples view with
            | Error e -> Error e
            | Ok () ->
                p.view <- view;
                p.size <- size;
                restart p;
                Ok ()))

let set_samples p n =
  if n = p.samples then Ok ()
  else if n < 1 || n > Limits.max_grid then
    Error (`Msg (Printf.sprintf "samples per pixel must lie in [1, %d], got %d" Limits.max_grid n))
  else
    let view = if (n > 1) <> p.view.antialias then fst (View.handle p.view (View.Key 'a')) else p.view in
    match check_work n view with
    | Error e -> Error e
    | Ok () ->
        p.view <- view;
        p.samples <- n;
        restart p;
        Ok ()

let input p i =
  let view, effect = View.handle p.view i in
  let samples =
    if view.antialias = p.view.antialias then p.samples
    else if view.antialias then View.antialias_samples
    else 1
  in
  match effect with
  | View.Render -> (
      match check_work samples view with
      | Error _ -> View.Nothing
      | Ok () ->
          p.view <- view;
          p.samples <- samples;
          restart p;
          effect)
  | _ ->
      p.view <- view;
      effect

let finished p = Progressive.finished p.render
let image p = Progressive.image p.render
let view p = p.view
let samples p = p.samples
let size p = p.size
let last_frame p = p.last_frame
let bands p = p.bands
let shown_text p = Scene_file.to_string p.view.scene

let rays p =
  let c = Trace.counters (Progressive.tracer p.render) in
  Float.of_int c.primary +. Float.of_int c.shadow +. Float.of_int c.reflection

let step p ~until =
  let t0 = p.now () in
  let rec go acc =
    match Progressive.step p.render with
    | None -> acc
    | Some band -> if p.now () >= until then band :: acc else go (band :: acc)
  in
  let bands = List.rev (go []) in
  let t1 = p.now () in
  if bands <> [] then begin
    p.slices <- p.slices + 1;
    p.bands <- p.bands + List.length bands;
    p.trace_seconds <- p.trace_seconds +. (t1 -. t0);
    p.longest_slice <- Float.max p.longest_slice (t1 -. t0);
    if finished p then
      let scene = p.view.scene in
      p.last_frame <-
        Some
          {
            width = scene.width;
            height = scene.height;
            frame_samples = p.samples;
            seconds = t1 -. p.started;
            trace_seconds = p.trace_seconds;
            slices = p.slices;
            longest_slice = p.longest_slice;
            rays = rays p;
          }
  end;
  bands

let frame_text f =
  Printf.sprintf "%d x %d, %s per pixel: %.3f s (traced in %.3f s, %.1f M rays/s, %d slice%s)" f.width f.height
    (if f.frame_samples = 1 then "1 sample" else Printf.sprintf "%d x %d samples" f.frame_samples f.frame_samples)
    f.seconds f.trace_seconds
    (if f.trace_seconds > 0. then f.rays /. f.trace_seconds /. 1e6 else 0.)
    f.slices
    (if f.slices = 1 then "" else "s")
