open Graphics

let rgb (r, g, b) = Graphics.rgb r g b

(* Section 1 of the document, verbatim. *)
let plotc x' y' color =
  let x, y = (x' + (size_x () / 2), y' + (size_y () / 2)) in
  set_color (rgb color);
  plot x y

let draw img =
  let open Raytrace in
  let width = Image.width img and height = Image.height img in
  for gx = Canvas.min_x width to Canvas.max_x width do
    for gy = Canvas.min_y height to Canvas.max_y height do
      plotc gx gy (Image.get img (Canvas.column ~width gx) (Canvas.row ~height gy))
    done
  done

let rec wait_for_quit () =
  let st = wait_next_event [ Key_pressed ] in
  if st.key = 'q' || st.key = 'Q' || st.key = '\027' then () else wait_for_quit ()

let show ~title img =
  let width = Raytrace.Image.width img and height = Raytrace.Image.height img in
  match open_graph (Printf.sprintf " %dx%d" width height) with
  | exception Graphic_failure reason -> Error (`No_display reason)
  | () -> (
      match
        set_window_title title;
        (* The window manager may have resized us; draw at our size anyway. *)
        resize_window width height;
        auto_synchronize false;
        draw img;
        synchronize ();
        prerr_endline "raytrace: drawn; press q or Escape in the window to quit";
        wait_for_quit ()
      with
      | () ->
          close_graph ();
          Ok ()
      (* Closing the window by hand ends the event loop with this error. *)
      | exception Graphic_failure _ -> Ok ())
