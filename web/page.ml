(* The web page: index.html's elements wired to Session. Everything that
   decides what is shown is in Session; this file reads events, paints the
   bands that Session.step traced, and gives the tests a small API
   (window.raytrace). *)

open Js_of_ocaml
open Raytrace
open Raytrace_view
module Session = Raytrace_web.Session
module Key = Raytrace_web.Key

let doc = Dom_html.document

(* A missing element is a bug of index.html, not of the user's input. *)
let element coerce id =
  let missing () = invalid_arg ("Page: index.html has no suitable element #" ^ id) in
  match Js.Opt.to_option (doc##getElementById (Js.string id)) with
  | None -> missing ()
  | Some e -> Js.Opt.get (coerce e) missing

let canvas = element Dom_html.CoerceTo.canvas "canvas"
let editor = element Dom_html.CoerceTo.textarea "scene"
let size_select = element Dom_html.CoerceTo.select "size"
let samples_select = element Dom_html.CoerceTo.select "samples"
let download = element Dom_html.CoerceTo.a "download"
let error_line = element Js.some "error"
let frame_line = element Js.some "frame"
let camera_line = element Js.some "camera"
let help = element Js.some "help"
let shown = element Js.some "shown"
let ctx = canvas##getContext Dom_html._2d_

let set_text (e : Dom_html.element Js.t) s = e##.textContent := Js.some (Js.string s)
let set_hidden (e : Dom_html.element Js.t) b = e##.style##.display := Js.string (if b then "none" else "")

(* Seconds, to the microsecond where the browser allows. *)
let now () : float = Js.Unsafe.meth_call (Js.Unsafe.global##.performance) "now" [||] /. 1000.

(* The canvas's pixels, RGBA, kept between frames: a new frame paints its
   coarse blocks over the last picture. *)
let pixels = ref (ctx##createImageData 1 1)

let fit_canvas w h =
  if canvas##.width <> w || canvas##.height <> h || !pixels##.width <> w || !pixels##.height <> h then begin
    canvas##.width := w;
    canvas##.height := h;
    let data = ctx##createImageData w h in
    let d = data##.data in
    for i = 0 to (w * h) - 1 do
      Dom_html.pixel_set d ((4 * i) + 3) 255
    done;
    pixels := data;
    ctx##putImageData data 0. 0.
  end

(* Copies the bands from the image into the canvas's pixels and shows the
   rows they changed. A coarse band's block shows the colour of its
   top-left pixel, as in the window. *)
let paint img bands =
  let w = Image.width img and h = Image.height img in
  let src = Typed_array.from_genarray (Bigarray.genarray_of_array1 (Image.buffer img)) in
  let dst = !pixels##.data in
  let top = ref h and bottom = ref 0 in
  let put d k =
    Dom_html.pixel_set dst d (Typed_array.unsafe_get src k);
    Dom_html.pixel_set dst (d + 1) (Typed_array.unsafe_get src (k + 1));
    Dom_html.pixel_set dst (d + 2) (Typed_array.unsafe_get src (k + 2))
  in
  List.iter
    (fun (b : Progressive.band) ->
      let last = if b.size = 1 then b.top + b.rows - 1 else min (h - 1) (b.top + b.size - 1) in
      top := min !top b.top;
      bottom := max !bottom last;
      if b.size = 1 then
        for i = b.top * w to ((last + 1) * w) - 1 do
          put (4 * i) (3 * i)
        done
      else begin
        let col = ref 0 in
        while !col < w do
          let k = 3 * ((b.top * w) + !col) in
          for row = b.top to last do
            for x = !col to min w (!col + b.size) - 1 do
              put (4 * ((row * w) + x)) k
            done
          done;
          col := !col + b.size
        done
      end)
    bands;
  if !top <= !bottom then
    ignore
      (Js.Unsafe.meth_call ctx "putImageData"
         Js.Unsafe.[| inject !pixels; inject 0; inject 0; inject 0; inject !top; inject w; inject (!bottom - !top + 1) |])

(* Work in slices of about this many seconds, then give the browser back
   its thread: it paints, and reads keys, until the next slice. *)
let slice_seconds = 0.025

let session =
  match Session.v ~now Default_scene.text with
  | Ok s -> s
  | Error (`Msg m) -> invalid_arg ("Page: the default scene does not load: " ^ m)

(* When set (the page's address ends in #hold, or the tests call hold),
   frames advance only through raytrace.advance. *)
let held = ref (Js.to_string Dom_html.window##.location##.hash = "#hold")
let scheduled = ref false
let channel = Js.Unsafe.new_obj Js.Unsafe.global##._MessageChannel [||]

(* Set when an exception escaped from the frame: it is not traced on. *)
let broken = ref false

(* The line under the editor when it says why a frame stopped or a key was
   refused, not what is wrong with the editor's text: the next frame
   clears it. *)
let transient = ref None

let say m =
  transient := Some m;
  set_text error_line m

let show_frame () =
  match (Session.stopped session, Session.last_frame session) with
  | Some m, _ ->
      set_text frame_line "Stopped: the line under the scene says why.";
      say m
  | None, Some f when Session.finished session -> set_text frame_line ("Frame: " ^ Session.frame_text f)
  | None, _ -> set_text frame_line (if !broken then "Stopped: the line under the scene says why." else "Rendering...")

(* Every event and slice runs through [guard]: whatever escapes (a
   JavaScript error, the stack or the memory running out) becomes one line
   under the editor, and the frame stops, instead of an empty line and a
   page that throws again at every slice. *)
let guard f =
  try f ()
  with e ->
    let m =
      match Js_error.of_exn e with
      | Some err when not (e = Stack_overflow || e = Out_of_memory) ->
          Session.located ("the browser failed: " ^ Js_error.name err ^ ": " ^ Js_error.message err)
      | _ -> Session.exception_line e
    in
    broken := true;
    say m;
    set_text frame_line "Stopped: the line under the scene says why."

let rec slice () =
  scheduled := false;
  guard (fun () ->
      if (not !held) && (not !broken) && not (Session.finished session) then begin
        let bands = Session.step session ~until:(now () +. slice_seconds) in
        paint (Session.image session) bands;
        if Session.finished session then show_frame () else schedule ()
      end)

and schedule () =
  (* A message to ourselves runs as soon as the browser is free, without
     the 4 ms that nested timeouts wait. *)
  if not !scheduled then begin
    scheduled := true;
    ignore (Js.Unsafe.meth_call channel##.port2 "postMessage" [| Js.Unsafe.inject 0 |])
  end

let () = Js.Unsafe.set channel##.port1 "onmessage" (Js.wrap_callback (fun _ -> slice ()))

(* Everything that follows a new frame: the canvas's size, the texts. *)
let new_frame () =
  broken := false;
  if Some (Js.to_string (Js.Opt.get error_line##.textContent (fun () -> Js.string ""))) = !transient then
    set_text error_line "";
  transient := None;
  let view = Session.view session in
  fit_canvas (Scene.width view.scene) (Scene.height view.scene);
  let p = (Scene.camera view.scene).position in
  set_text camera_line
    (Printf.sprintf "Camera at %g %g %g, recursion depth %d." p.x p.y p.z (Scene.depth view.scene));
  set_text shown (Session.shown_text session);
  samples_select##.value := Js.string (string_of_int (Session.samples session));
  show_frame ();
  schedule ()

let report = function
  | Ok () ->
      set_text error_line "";
      new_frame ()
  | Error (`Msg m) -> set_text error_line m

let on_input (i : View.input) =
  let effect = Session.input session i in
  Option.iter say (Session.refused session);
  match effect with
  | View.Render ->
      new_frame ();
      true
  | Redraw ->
      set_hidden help (not (Session.view session).help);
      true
  | Save ->
      download##click;
      true
  | Nothing | Quit -> false

let size_of_string s =
  match String.split_on_char 'x' s with
  | [ w; h ] -> ( match (int_of_string_opt w, int_of_string_opt h) with Some w, Some h -> Some (w, h) | _ -> None)
  | _ -> None

let handler f = Dom_html.handler (fun e -> guard (fun () -> f e); Js._true)

let () =
  editor##.value := Js.string Default_scene.text;
  set_hidden help true;
  editor##.oninput := handler (fun _ -> report (Session.edit session (Js.to_string editor##.value)));
  size_select##.onchange := handler (fun _ -> report (Session.set_size session (size_of_string (Js.to_string size_select##.value))));
  samples_select##.onchange :=
    handler (fun _ ->
        match int_of_string_opt (Js.to_string samples_select##.value) with
        | Some n -> report (Session.set_samples session n)
        | None -> ());
  download##.onclick :=
    handler (fun _ -> download##.href := canvas##toDataURL_type (Js.string "image/png"));
  canvas##.onkeydown :=
    Dom_html.handler (fun e ->
        let key = Js.Optdef.case e##.key (fun () -> "") Js.to_string in
        let handled = ref false in
        guard (fun () ->
            match Key.to_char key with
            | Some c when not (Js.to_bool e##.ctrlKey || Js.to_bool e##.altKey || Js.to_bool e##.metaKey) ->
                handled := on_input (View.Key c)
            | _ -> ());
        if !handled then Js._false (* handled: no scrolling by the arrows *) else Js._true);
  (* Dragging turns the camera so that the picture follows the pointer. *)
  let last = ref None in
  canvas##.onmousedown :=
    handler (fun e ->
        canvas##focus;
        last := Some (e##.clientX, e##.clientY));
  Dom_html.window##.onmouseup := handler (fun _ -> last := None);
  canvas##.onmousemove :=
    handler (fun e ->
        match !last with
        | Some (x0, y0) ->
            last := Some (e##.clientX, e##.clientY);
            ignore (on_input (View.Drag (e##.clientX - x0, y0 - e##.clientY)))
        | None -> ());
  (* For the tests (test/web/drive.js) and the curious, in the console. *)
  let state () =
    let frame = Session.last_frame session in
    let view = Session.view session in
    Js.Unsafe.obj
      Js.Unsafe.
        [|
          ("finished", inject (Js.bool (Session.finished session || !broken)));
          ("frame", inject (Js.string (match frame with Some f -> Session.frame_text f | None -> "")));
          ("seconds", inject (match frame with Some f -> f.seconds | None -> -1.));
          ("traceSeconds", inject (match frame with Some f -> f.trace_seconds | None -> -1.));
          ("slices", inject (match frame with Some f -> f.slices | None -> 0));
          ("longestSlice", inject (match frame with Some f -> f.longest_slice | None -> -1.));
          ("width", inject (Scene.width view.scene));
          ("height", inject (Scene.height view.scene));
          ("samples", inject (Session.samples session));
          ("bands", inject (Session.bands session));
          ("sliceSoFar", inject (Session.longest_slice session));
          ("error", inject error_line##.textContent);
          ("stopped", inject (Js.string (Option.value (Session.stopped session) ~default:"")));
          ("broken", inject (Js.bool !broken));
          ("shown", inject (Js.string (Session.shown_text session)));
        |]
  in
  let advance n =
    guard (fun () ->
        for _ = 1 to n do
          paint (Session.image session) (Session.step session ~until:neg_infinity)
        done;
        show_frame ())
  in
  Js.Unsafe.set Dom_html.window "raytrace"
    (Js.Unsafe.obj
       Js.Unsafe.
         [|
           ("state", inject (Js.wrap_callback state));
           ("hold", inject (Js.wrap_callback (fun b -> held := Js.to_bool b; if not !held then schedule ())));
           ("advance", inject (Js.wrap_callback advance));
         |]);
  new_frame ()
