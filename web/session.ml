open Raytrace
open Raytrace_view

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
let ( let* ) = Result.bind

let check_work samples (view : View.t) = Scene.check_work ~samples:(samples * samples) view.valid
let check_canvas w h = Limits.check_canvas Limits.default w h

let restart p =
  p.render <- Progressive.create ~samples:p.samples p.view.valid;
  p.started <- p.now ();
  p.trace_seconds <- 0.;
  p.slices <- 0;
  p.bands <- 0;
  p.longest_slice <- 0.

(* Shows [view] with [samples] from now on, if that render is allowed. *)
let commit p view ~size ~samples =
  let* () = check_work samples view in
  p.view <- view;
  p.size <- size;
  p.samples <- samples;
  restart p;
  Ok ()

(* [view] at [w x h], as the window resizes: the camera stays. *)
let resized view (w, h) =
  let* () = check_canvas w h in
  Ok (fst (View.handle view (View.Resize (w, h))))

(* [view] with its antialiasing flag saying whether [samples > 1], as the
   window's would after the key [a]. *)
let flagged (view : View.t) samples =
  if (samples > 1) <> view.antialias then fst (View.handle view (View.Key 'a')) else view

let v ~now text =
  let* scene = Scene_file.of_string ~file text in
  let view = View.v scene in
  let* () = check_work 1 view in
  let p =
    {
      now;
      size = None;
      samples = 1;
      view;
      render = Progressive.create view.valid;
      started = 0.;
      trace_seconds = 0.;
      slices = 0;
      bands = 0;
      longest_slice = 0.;
      last_frame = None;
    }
  in
  restart p;
  Ok p

let edit p text =
  let* scene = Scene_file.of_string ~file text in
  let view = View.v scene in
  let* view = match p.size with None -> Ok view | Some size -> resized view size in
  commit p (flagged view p.samples) ~size:p.size ~samples:p.samples

let set_size p size =
  if size = p.size then Ok ()
  else
    let base = p.view.base in
    let* view = resized p.view (Option.value size ~default:(base.width, base.height)) in
    commit p view ~size ~samples:p.samples

let set_samples p n =
  if n = p.samples then Ok ()
  else if n < 1 || n > Limits.max_grid then
    Error (`Msg (Printf.sprintf "samples per pixel must lie in [1, %d], got %d" Limits.max_grid n))
  else commit p (flagged p.view n) ~size:p.size ~samples:n

let input p i =
  let view, effect = View.handle p.view i in
  match effect with
  | View.Render -> (
      let samples =
        if view.antialias = p.view.antialias then p.samples else if view.antialias then View.antialias_samples else 1
      in
      match commit p view ~size:p.size ~samples with Ok () -> effect | Error _ -> View.Nothing)
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
  let c = Private.Trace.counters (Progressive.tracer p.render) in
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
