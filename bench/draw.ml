(* How long drawing a frame takes in a Graphics window, two ways:
   - the document's plotc on Graphics itself: set_color and plot for every
     pixel (two X requests per pixel);
   - as the window draws: plotc's calls write into an array of rows, which
     goes to the X server as one image (Graphics.make_image, draw_image).
   Each time includes a round trip to the server (point_color), so that the
   server's work is counted. Prints one line per way: median and range of
   [runs] frames. Run under a display, e.g.
     xvfb-run -a -s "-screen 0 1024x768x24" \
       dune exec --profile release bench/draw.exe -- [SCENE] [RUNS] *)
let scene () =
  if Array.length Sys.argv > 1 then
    match Files.read_scene Sys.argv.(1) with
    | Ok s -> s
    | Error (`Msg m) ->
        prerr_endline m;
        exit 1
  else Result.get_ok (Scene.validate Scene.cgfs)

let runs = if Array.length Sys.argv > 2 then int_of_string Sys.argv.(2) else 9

(* Section 1 of the document, verbatim, on Graphics. *)
let plotc x' y' color =
  let open Graphics in
  let rgb (r, g, b) = rgb r g b in
  let x, y = (x' + (size_x () / 2), y' + (size_y () / 2)) in
  set_color (rgb color);
  plot x y

(* The same calls, into rows of colours (top-down). *)
let rows = ref [||]

let plotc_rows x' y' color =
  let size_x () = Array.length !rows.(0) and size_y () = Array.length !rows in
  let current = ref 0 in
  let set_color c = current := c and rgb (r, g, b) = Graphics.rgb r g b in
  let plot x y = !rows.(size_y () - 1 - y).(x) <- !current in
  let x, y = (x' + (size_x () / 2), y' + (size_y () / 2)) in
  set_color (rgb color);
  plot x y

let each_pixel img f =
  let width = Image.width img and height = Image.height img in
  for gx = Canvas.min_x width to Canvas.max_x width do
    for gy = Canvas.min_y height to Canvas.max_y height do
      f gx gy (Image.get img (Canvas.column ~width gx) (Canvas.row ~height gy))
    done
  done

let time f =
  let t0 = Unix.gettimeofday () in
  f ();
  Graphics.synchronize ();
  ignore (Graphics.point_color 0 0);
  Unix.gettimeofday () -. t0

let report name times =
  let a = Array.of_list times in
  Array.sort Float.compare a;
  Printf.printf "%-34s median %.4f s  (min %.4f, max %.4f, %d frames)\n%!" name a.(Array.length a / 2) a.(0)
    a.(Array.length a - 1) (Array.length a)

let () =
  let scene = scene () in
  let img = match Render.image scene with Ok (img, _) -> img | Error (`Msg m) -> failwith m in
  let scene = Scene.of_valid scene in
  Graphics.open_graph (Printf.sprintf " %dx%d" (Scene.width scene) (Scene.height scene));
  Graphics.resize_window (Scene.width scene) (Scene.height scene);
  Graphics.auto_synchronize false;
  Printf.printf "drawing a %dx%d frame of %s\n" (Scene.width scene) (Scene.height scene)
    (if Array.length Sys.argv > 1 then Sys.argv.(1) else "the CGFS scene");
  let direct = List.init runs (fun _ -> time (fun () -> each_pixel img plotc)) in
  let buffered =
    List.init runs (fun _ ->
        time (fun () ->
            rows := Array.init (Scene.height scene) (fun _ -> Array.make (Scene.width scene) 0);
            each_pixel img plotc_rows;
            Graphics.draw_image (Graphics.make_image !rows) 0 0))
  in
  report "plotc -> Graphics.plot per pixel" direct;
  report "plotc -> rows -> one image" buffered;
  Graphics.close_graph ()
