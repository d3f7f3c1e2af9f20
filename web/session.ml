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
  mutable stopped : string option;  (** Why the current frame stopped before its end. *)
  mutable refused : string option;  (** Why the last input changed nothing, if it was refused. *)
}

let file = "scene"
let ( let* ) = Result.bind
let max_side = 4096
let max_pixel_seconds = 0.5

let limits = Limits.with_bound Limits.default `Pixels (Float.of_int (max_side * max_side))

let located m =
  let prefix = file ^ ":" in
  if String.length m >= String.length prefix && String.sub m 0 (String.length prefix) = prefix then m
  else Printf.sprintf "%s:1:1: %s" file m

(* The command line's message names the variable that raises the bound;
   the page has none. *)
let page_bounds m =
  let variable = Printf.sprintf "(set %s to raise it)" (Limits.variable `Pixels) in
  let n = String.length variable and k = String.length m in
  if k >= n && String.sub m (k - n) n = variable then
    String.sub m 0 (k - n) ^ "(the page's bound: raytrace render draws larger canvases)"
  else m

let failure_line = function
  | Stack_overflow ->
      Some (located "scene too deeply nested for the browser: its stack ran out (raytrace render renders it)")
  | Out_of_memory -> Some (located "the browser has not enough memory for this scene (raytrace render renders it)")
  | _ -> None

let exception_line e =
  match failure_line e with Some m -> m | None -> located ("internal error: " ^ Printexc.to_string e)

(* [f ()], or the line that says why the browser could not do it. *)
let guarded f =
  match f () with
  | r -> r
  | exception e -> ( match failure_line e with Some m -> Error (`Msg m) | None -> raise e)

let error m = Error (`Msg (located m))
let check_work samples (view : View.t) =
  Result.map_error (fun (`Msg m) -> `Msg (located m)) (Scene.check_work ~limits ~samples:(samples * samples) view.valid)

let check_canvas w h =
  Result.map_error (fun (`Msg m) -> `Msg (located (page_bounds m))) (Limits.check_canvas limits w h)

(* A texture is one of the example scenes', by the name they give it; a
   page reads no other file. *)
let load_texture path =
  match List.assoc_opt path Example_textures.files with
  | Some text -> (
      match Image.Ppm.of_string ~limits text with
      | Ok img -> Ok (Image.Texture.of_image img)
      | Error (`Msg m) -> Error (`Msg (Printf.sprintf "cannot read texture file %s: %s" path m)))
  | None ->
      Error
        (`Msg
          (Printf.sprintf "cannot read texture file %s: the page reads no files; its textures are the example scenes' %s" path
             (String.concat " and " (List.map fst Example_textures.files))))

let of_string text =
  Result.map_error (fun (`Msg m) -> `Msg (page_bounds m)) (Scene_file.of_string ~limits ~load_texture ~file text)

let restart p render =
  p.render <- render;
  p.stopped <- None;
  p.started <- p.now ();
  p.trace_seconds <- 0.;
  p.slices <- 0;
  p.bands <- 0;
  p.longest_slice <- 0.

(* Shows [view] with [samples] from now on, if that render is allowed. *)
let commit p view ~size ~samples =
  let* () = check_work samples view in
  let render = Progressive.create ~samples view.valid in
  p.view <- view;
  p.size <- size;
  p.samples <- samples;
  restart p render;
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
  guarded @@ fun () ->
  let* scene = of_string text in
  let view = View.v scene in
  let* () = check_work 1 view in
  let render = Progressive.create view.valid in
  let p =
    {
      now;
      size = None;
      samples = 1;
      view;
      render;
      started = 0.;
      trace_seconds = 0.;
      slices = 0;
      bands = 0;
      longest_slice = 0.;
      last_frame = None;
      stopped = None;
      refused = None;
    }
  in
  restart p render;
  Ok p

(* Each input is [guarded] whole: a scene that passes the parser may
   still run the browser's stack out later (preparing a CSG tree). *)
let edit p text =
  guarded @@ fun () ->
  let* scene = of_string text in
  let view = View.v scene in
  let* view = match p.size with None -> Ok view | Some size -> resized view size in
  commit p (flagged view p.samples) ~size:p.size ~samples:p.samples

let set_size p size =
  guarded @@ fun () ->
  if size = p.size then Ok ()
  else
    let base = p.view.base in
    let* view = resized p.view (Option.value size ~default:(Scene.width base, Scene.height base)) in
    commit p view ~size ~samples:p.samples

let set_samples p n =
  guarded @@ fun () ->
  if n = p.samples then Ok ()
  else if n < 1 || n > Limits.max_grid then error (Printf.sprintf "samples per pixel must lie in [1, %d], got %d" Limits.max_grid n)
  else commit p (flagged p.view n) ~size:p.size ~samples:n

let input p i =
  let view, effect = View.handle p.view i in
  match effect with
  | View.Render -> (
      let samples =
        if view.antialias = p.view.antialias then p.samples else if view.antialias then View.antialias_samples else 1
      in
      match guarded (fun () -> commit p view ~size:p.size ~samples) with
      | Ok () ->
          p.refused <- None;
          effect
      | Error (`Msg m) ->
          p.refused <- Some m;
          View.Nothing)
  | _ ->
      p.refused <- None;
      p.view <- view;
      effect

let refused p = p.refused

let finished p = Progressive.finished p.render || p.stopped <> None

let stopped p =
  match p.stopped with Some _ as s -> s | None -> Option.map located (Progressive.stopped p.render)
let image p = Progressive.image p.render
let view p = p.view
let samples p = p.samples
let size p = p.size
let last_frame p = p.last_frame
let bands p = p.bands
let longest_slice p = p.longest_slice
let shown_text p = Scene_file.to_string p.view.scene

let rays p =
  let c = Private.Trace.counters (Progressive.tracer p.render) in
  Float.of_int c.primary +. Float.of_int c.shadow +. Float.of_int c.reflection

(* A slice ends at a pixel's end once [until] is past. A pixel that
   alone takes longer than [max_pixel_seconds] (a deep glass tree) cannot
   be cut, and tracing it again would take as long: the frame stops. *)
let step p ~until =
  if finished p then []
  else
  let t0 = p.now () in
  let too_slow = ref false in
  let deadline = Float.max until t0 +. max_pixel_seconds in
  let poll = function
    | Progressive.Between_pixels -> p.now () >= until
    | Inside_pixel ->
        too_slow := p.now () >= deadline;
        !too_slow
  in
  let poll = if until = neg_infinity then None else Some poll in
  let rec go acc =
    if finished p then acc
    else
      match Progressive.advance ?poll p.render with
      | Done -> acc
      | Paused ->
          if !too_slow then
            p.stopped <-
              Some
                (located
                   (Printf.sprintf
                      "one pixel takes more than %g s to trace, too long for the page to stay responsive: the frame \
                       stops here (raytrace render renders it)"
                      max_pixel_seconds));
          acc
      | Band band -> if p.now () >= until then band :: acc else go (band :: acc)
  in
  let bands =
    match go [] with
    | acc -> List.rev acc
    | exception e -> (
        match failure_line e with
        | Some m ->
            p.stopped <- Some m;
            []
        | None -> raise e)
  in
  let t1 = p.now () in
  p.slices <- p.slices + 1;
  p.bands <- p.bands + List.length bands;
  p.trace_seconds <- p.trace_seconds +. (t1 -. t0);
  p.longest_slice <- Float.max p.longest_slice (t1 -. t0);
  if Progressive.finished p.render && stopped p = None then begin
    let scene = p.view.scene in
    p.last_frame <-
      Some
        {
          width = (Scene.width scene);
          height = (Scene.height scene);
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
