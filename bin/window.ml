open Raytrace

(* Graphics does not report the arrow keys (they have no character); this
   asks Xlib to give them the characters of [View.arrow_left] ... *)
external bind_arrows : string -> bool = "raytrace_bind_arrows"

(* The size of the X screen, (0, 0) if there is no display. *)
external screen_size : unit -> int * int = "raytrace_screen_size"

(* The window's pixels, kept here and sent to the X server in bulk.
   Graphics.plot sends two requests per pixel (a colour change and a point):
   a 600 x 600 frame took half as long to draw that way as to trace, and
   four times as long as sent as one image (bench/draw.ml; docs/window.md). The document's plotc draws here, through the same calls. *)
module Frame = struct
  let width = ref 0
  let height = ref 0
  let pixels = ref [||] (* rows top-down, as Graphics.make_image takes them *)
  let current = ref Graphics.black

  (* Rows [!dirty_top .. !dirty_bottom] have changed since the last flush. *)
  let dirty_top = ref max_int
  let dirty_bottom = ref (-1)

  let resize w h =
    width := w;
    height := h;
    pixels := Array.init h (fun _ -> Array.make w Graphics.black);
    dirty_top := max_int;
    dirty_bottom := -1

  let size_x () = !width
  let size_y () = !height
  let rgb (r, g, b) = Graphics.rgb r g b
  let set_color c = current := c

  (* Graphics coordinates: the origin at the bottom-left corner. *)
  let plot x y =
    if x >= 0 && x < !width && y >= 0 && y < !height then begin
      let row = !height - 1 - y in
      !pixels.(row).(x) <- !current;
      if row < !dirty_top then dirty_top := row;
      if row > !dirty_bottom then dirty_bottom := row
    end

  let flush () =
    if !dirty_top <= !dirty_bottom then begin
      let rows = Array.sub !pixels !dirty_top (!dirty_bottom - !dirty_top + 1) in
      Graphics.draw_image (Graphics.make_image rows) 0 (!height - 1 - !dirty_bottom);
      dirty_top := max_int;
      dirty_bottom := -1
    end

  let flush_all () =
    dirty_top := 0;
    dirty_bottom := !height - 1;
    flush ()

  (* A coarse block, image column [col], row [row] at its top-left: drawn at
     once (cheap) and remembered for a later full flush. *)
  let block col row size c =
    let w = min size (!width - col) and h = min size (!height - row) in
    for r = row to row + h - 1 do
      Array.fill !pixels.(r) col w c
    done;
    Graphics.set_color c;
    Graphics.fill_rect col (!height - row - h) w h
end

(* Section 1 of the document, verbatim: the origin in the middle of the
   window, y up. Its set_color, rgb, plot and size_x/size_y are Frame's. *)
let plotc x' y' color =
  let open Frame in
  let x, y = (x' + (size_x () / 2), y' + (size_y () / 2)) in
  set_color (rgb color);
  plot x y

(* Bands of the progressive render, drawn: a coarse band as blocks, a band
   of the last pass pixel by pixel through plotc. *)
let draw_band img (band : Progressive.band) =
  let width = Image.width img and height = Image.height img in
  if band.size = 1 then
    for row = band.top to band.top + band.rows - 1 do
      let gy = Canvas.y_of_row ~height row in
      for gx = Canvas.min_x width to Canvas.max_x width do
        plotc gx gy (Image.get img (Canvas.column ~width gx) row)
      done
    done
  else begin
    let col = ref 0 in
    while !col < width do
      Frame.block !col band.top band.size (Frame.rgb (Image.get img !col band.top));
      col := !col + band.size
    done
  end

let overlay lines =
  let line_h = 14 and pad = 6 in
  let w = 8 + List.fold_left (fun m l -> max m (6 * String.length l)) 0 lines in
  let h = (line_h * List.length lines) + (2 * pad) in
  let top = Frame.size_y () - 8 in
  Graphics.set_color (Graphics.rgb 24 24 24);
  Graphics.fill_rect 8 (top - h) (w + (2 * pad)) h;
  Graphics.set_color Graphics.white;
  List.iteri
    (fun i l ->
      Graphics.moveto (8 + pad) (top - pad - (line_h * (i + 1)) + 3);
      Graphics.draw_string l)
    lines

(* A round trip to the server: when it returns, every request sent before
   has been carried out, so drawing times include the server's work. *)
let sync_server () = ignore (Graphics.point_color 0 0)

type session = {
  name : string;
  scene_file : string option;
  jobs : int;
  mutable shared : Progressive.workers option;  (** For [jobs > 1], at the frame's size. *)
  mutable row_s : float;  (** Seconds per row of the last full-resolution band. *)
  mutable rows : int;  (** Rows of the last full-resolution band. *)
  mutable paused_s : float;  (** Seconds spent on the band that [work] paused, if one is. *)
  mutable failure_told : bool;
  mutable view : View.t;
  mutable render : Progressive.t;
  mutable started : float;  (** When the frame began. *)
  mutable trace_s : float;  (** Seconds spent tracing this frame. *)
  mutable plot_s : float;  (** Seconds spent plotting its full-resolution pass. *)
  mutable preview_s : float;  (** Seconds spent drawing its coarse passes. *)
  mutable save_pending : bool;
  mutable drag : (int * int) option;  (** Pointer position while a button is held. *)
  mutable seen : int * int;  (** The window's size when [poll] last read it. *)
  mutable quit : bool;
}

(* A closed or full stderr loses the line; the window goes on. *)
let log fmt = Printf.ksprintf (fun s -> try prerr_endline ("raytrace: " ^ s) with Sys_error _ -> ()) fmt

let start_frame s =
  let scene = s.view.scene in
  if (Scene.width scene) <> Frame.size_x () || (Scene.height scene) <> Frame.size_y () then begin
    Frame.resize (Scene.width scene) (Scene.height scene);
    s.shared <- None
  end;
  if s.jobs > 1 && Option.is_none s.shared && not s.failure_told then begin
    match Progressive_workers.v ~jobs:s.jobs ~width:(Scene.width scene) ~height:(Scene.height scene) with
    | shared -> s.shared <- Some shared
    | exception ((Failure _ | Unix.Unix_error _) as e) ->
        s.failure_told <- true;
        let why = match e with Unix.Unix_error (err, _, _) -> Unix.error_message err | e -> Printexc.to_string e in
        log "no memory to share with worker processes (%s); tracing in this process" why
  end;
  s.render <- Progressive.create ~limits:s.view.limits ~samples:(View.samples s.view) ?workers:s.shared s.view.valid;
  s.rows <- 1;
  s.paused_s <- 0.;
  s.started <- Unix.gettimeofday ();
  s.trace_s <- 0.;
  s.plot_s <- 0.;
  s.preview_s <- 0.

let show_overlay s = if s.view.help then overlay (View.help_lines s.view)

let save s =
  let img = Progressive.image s.render in
  let exists = Sys.file_exists in
  let ppm, scene_path = View.save_paths ~scene_file:s.scene_file ~exists in
  match Files.write_ppm ppm img with
  | Error (`Msg m) -> log "cannot save: %s" m
  | Ok () -> (
      match
        File_io.write_atomic scene_path (fun oc -> output_string oc (Scene_file.to_string s.view.scene))
      with
      | Error (`Msg m) -> log "saved %s, but cannot write its scene: %s" ppm m
      | Ok () ->
          log "saved %s (%dx%d)%s and its scene %s" ppm (Image.width img) (Image.height img)
            (if s.view.antialias then Printf.sprintf ", antialiased %dx%d," View.antialias_samples View.antialias_samples
             else "")
            scene_path)

let finish_frame s =
  let t0 = Unix.gettimeofday () in
  sync_server ();
  s.plot_s <- s.plot_s +. (Unix.gettimeofday () -. t0);
  let c = Trace.counters (Progressive.tracer s.render) in
  let rays = Float.of_int (c.primary + c.shadow + c.reflection) in
  let seconds = Unix.gettimeofday () -. s.started in
  let rays_per_s = if s.trace_s > 0. then rays /. s.trace_s else 0. in
  let scene = s.view.scene in
  Graphics.set_window_title (View.title ~name:s.name ~frame:((Scene.width scene), (Scene.height scene), seconds, rays_per_s) ());
  let n = View.samples s.view in
  log "drawn %dx%d%s in %.3f s: traced in %.3f s (%.1f M rays/s), plotted in %.3f s, previews in %.3f s" (Scene.width scene)
    (Scene.height scene)
    (if n > 1 then Printf.sprintf " antialiased %dx%d" n n else "")
    seconds s.trace_s (rays_per_s /. 1e6) s.plot_s s.preview_s;
  if s.save_pending then begin
    s.save_pending <- false;
    save s
  end

let apply s input =
  let view, effect = View.handle s.view input in
  s.view <- view;
  match effect with
  | View.Nothing -> `None
  | Render -> `Render
  | Redraw -> `Redraw
  | Save ->
      s.save_pending <- true;
      `Save
  | Quit ->
      s.quit <- true;
      `None

(* Reads every input that arrived since the last call. *)
let poll s =
  let render = ref false and redraw = ref false and saving = ref false in
  let note = function
    | `Render -> render := true
    | `Redraw -> redraw := true
    | `Save -> saving := true
    | `None -> ()
  in
  let w = Graphics.size_x () and h = Graphics.size_y () in
  s.seen <- (w, h);
  note (apply s (View.Resize (w, h)));
  while (not s.quit) && Graphics.key_pressed () do
    note (apply s (View.Key (Graphics.read_key ())))
  done;
  (if Graphics.button_down () then begin
     let x, y = Graphics.mouse_pos () in
     (match s.drag with
     | Some (x0, y0) -> note (apply s (View.Drag (x - x0, y - y0)))
     | None -> log "turning with the pointer");
     s.drag <- Some (x, y)
   end
   else s.drag <- None);
  if !render then start_frame s
  else if !redraw then begin
    Frame.flush_all ();
    show_overlay s;
    Graphics.synchronize ()
  end;
  (* The picture saved is the one the keys before [s] asked for. *)
  if !saving then
    if Progressive.finished s.render then begin
      s.save_pending <- false;
      save s
    end
    else log "saving once this frame is complete"

(* Whether something came that [poll] must read: a key, the button
   pressed, released or dragged, or a new size. Cheap (Graphics reads what
   the X server sent, without a round trip): [work] asks it every few
   milliseconds of tracing, inside pixels too, since a pixel of a deep
   glass scene can take seconds. *)
let input_pending s =
  Graphics.key_pressed ()
  || Graphics.button_down () <> Option.is_some s.drag
  || (Option.is_some s.drag && Some (Graphics.mouse_pos ()) <> s.drag)
  || (Graphics.size_x (), Graphics.size_y ()) <> s.seen

(* Traces and draws bands for about [slice] seconds, then shows them; it
   pauses the band at once, even inside a pixel, when input comes. A
   full-resolution band gets as many rows as fit in a slice, by the speed
   of the last one, but at most twice as many as the last one: rows of sky
   are quick. Workers are forked anew for each band, which costs a few
   milliseconds (more on a busy machine): their bands are 5 slices long.
   They cannot be paused: rows slower than such a band (a glass scene's;
   the coarse passes tell) are traced here, one band a row. *)
let work s ~slice =
  let t_end = Unix.gettimeofday () +. slice in
  let img = Progressive.image s.render in
  let band_s = if s.jobs > 1 then 5. *. slice else slice in
  let poll = function
    | Progressive.Between_pixels -> input_pending s || Unix.gettimeofday () >= t_end
    | Inside_pixel -> input_pending s
  in
  let continue = ref true in
  while !continue do
    let t0 = Unix.gettimeofday () in
    let rows =
      if s.row_s > band_s then 1 else max s.jobs (min (2 * s.rows) (truncate (Float.min 1e6 (band_s /. s.row_s))))
    in
    match Progressive.advance ~rows ~poll s.render with
    | Done -> continue := false
    | Paused ->
        let t = Unix.gettimeofday () -. t0 in
        s.trace_s <- s.trace_s +. t;
        s.paused_s <- s.paused_s +. t;
        continue := false
    | Band band ->
        let t1 = Unix.gettimeofday () in
        (* A coarse band of blocks of [size] traces about one pixel in
           [size] of a row: it tells the speed of the rows to come. *)
        s.row_s <- Float.max 1e-7 ((s.paused_s +. t1 -. t0) *. Float.of_int band.size /. Float.of_int band.rows);
        s.paused_s <- 0.;
        if band.size = 1 then s.rows <- band.rows;
        draw_band img band;
        let t2 = Unix.gettimeofday () in
        s.trace_s <- s.trace_s +. (t1 -. t0);
        if band.size = 1 then s.plot_s <- s.plot_s +. (t2 -. t1) else s.preview_s <- s.preview_s +. (t2 -. t1);
        if t2 >= t_end then continue := false
  done;
  let t0 = Unix.gettimeofday () in
  Frame.flush ();
  show_overlay s;
  Graphics.synchronize ();
  s.plot_s <- s.plot_s +. (Unix.gettimeofday () -. t0);
  (match Progressive.failure s.render with
  | Some m when not s.failure_told ->
      s.failure_told <- true;
      log "%s; tracing in this process from now on" m;
      s.shared <- None
  | _ -> ());
  (match Progressive.stopped s.render with Some m -> log "%s; the frame is incomplete" m | None -> ());
  if Progressive.finished s.render then finish_frame s

let rec loop s =
  poll s;
  if not s.quit then begin
    if Progressive.finished s.render then Unix.sleepf 0.01 else work s ~slice:0.02;
    loop s
  end

let keys_summary =
  "arrows or Shift+W A S D move, Shift+Q E or drag turn, + - depth, a antialiasing, r render, s save, h help, \
   q quit"

(* Images made by [Graphics.make_image] are X pixmaps that their GC
   finalizer frees through the display: one collected after [close_graph]
   frees it through a closed display, a segmentation fault (seen on [q] with
   small canvases, whose images stay in the minor heap). Frame keeps no
   image, so a full collection here frees them all while the display is
   open. *)
let close () =
  Gc.full_major ();
  Graphics.close_graph ()

let run ~limits ~name ~scene_file ~jobs valid =
  let scene = Scene.of_valid valid in
  (* Graphics flushes the display on a SIGALRM timer of its own. *)
  Signals.leave_alone Sys.sigalrm;
  (* A window larger than the screen cannot be seen whole, and a very large
     one makes the server fail to allocate it (an Xlib error): refused. *)
  let screen_w, screen_h = screen_size () in
  if screen_w > 0 && ((Scene.width scene) > screen_w || (Scene.height scene) > screen_h) then
    Error
      (`No_display
        (Printf.sprintf "the X screen is %dx%d pixels, too small for the %dx%d canvas" screen_w screen_h
           (Scene.width scene) (Scene.height scene)))
  else
  match Graphics.open_graph (Printf.sprintf " %dx%d" (Scene.width scene) (Scene.height scene)) with
  | exception Graphics.Graphic_failure reason ->
      (* Graphics says "Cannot open display " with an empty name when
         DISPLAY is unset: say what is wrong. *)
      let unset = match Sys.getenv_opt "DISPLAY" with None | Some "" -> true | Some _ -> false in
      Error (`No_display (if unset then "DISPLAY is not set" else reason))
  | () -> (
      match
        Graphics.set_window_title (View.title ~name ());
        (* The window manager may have resized us; start at our size. *)
        Graphics.resize_window (Scene.width scene) (Scene.height scene);
        Graphics.auto_synchronize false;
        if not (bind_arrows (String.init 4 (fun i -> Char.chr (Char.code View.arrow_left + i)))) then
          log "the arrow keys are not available; use Shift+W A S D";
        log "keys: %s" keys_summary;
        let s =
          {
            name;
            scene_file;
            jobs;
            shared = None;
            row_s = 1e-3;
            rows = 1;
            paused_s = 0.;
            failure_told = false;
            view = View.v ~limits valid;
            render = Progressive.create valid;
            started = 0.;
            trace_s = 0.;
            plot_s = 0.;
            preview_s = 0.;
            save_pending = false;
            drag = None;
            seen = ((Scene.width scene), (Scene.height scene));
            quit = false;
          }
        in
        start_frame s;
        loop s
      with
      | () ->
          close ();
          Ok ()
      (* Closing the window by hand ends the event loop with this error. *)
      | exception Graphics.Graphic_failure "graphic screen not opened" -> Ok ()
      | exception Graphics.Graphic_failure reason -> Error (`Msg ("lost the window: " ^ reason)))
