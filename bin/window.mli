(** The Graphics window: the interactive, progressive view of a scene.

    The window opens at the canvas size and shows a coarse picture at once,
    refined pass by pass ({!Raytrace.Progressive}) to the full image, which
    is {!Raytrace.Render.image}'s byte for byte. It traces in small steps
    and reads the keyboard, the pointer and its own size between them, so
    it never freezes; what each input does is {!Raytrace.View.handle}'s.
    The full-resolution pixels are drawn with the document's
    centered-origin {!plotc} (section 1). After each full frame, the title
    and a line on stderr give its time and rays per second. *)

val plotc : int -> int -> int * int * int -> unit
(** [plotc x' y' color] plots [color] at canvas coordinates [(x', y')],
    the origin in the middle of the window and [y] up: the document's
    [plotc], verbatim. Its [set_color], [rgb], [plot], [size_x] and
    [size_y] write to the window's frame buffer, which is sent to the X
    server one band of rows at a time. *)

val run :
  limits:Raytrace.Limits.t ->
  name:string ->
  scene_file:string option ->
  jobs:int ->
  Raytrace.Scene.valid ->
  (unit, [ `No_display of string | `Msg of string ]) result
(** [run ~limits ~name ~scene_file ~jobs scene] opens a window titled after [name],
    renders [scene] in it and answers keys until the user presses [q] or
    Escape or closes the window. With [jobs > 1], the full-resolution
    passes are traced by [jobs] processes, a band of rows at a time. [s] saves next to [scene_file] (in the
    current directory when [None]; {!Raytrace_view.View.save_paths}).
    [`No_display] if no window can be opened (no X server), with the
    reason; [`Msg] if the connection to the display is lost. Canvas
    sizes and depths stay within [limits]. *)
