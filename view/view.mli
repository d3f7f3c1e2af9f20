(** The interactive view: what the window shows and what each key does
    to it, free of any drawing.

    A view is the scene as loaded (its {e base}) and the scene as shown:
    the base seen from the current camera, with the current recursion
    depth, at the window's size. {!handle} maps one input (a key, a drag of
    the pointer, a new window size) to the next view and to what the window
    must do about it. The Graphics front end ([bin/window.ml]) only reads
    inputs, calls {!handle} and draws; everything decided here is tested
    without a display.

    Keys are the characters Graphics reports. Letters that move the camera
    are upper case (Shift held: [W A S D], [Q E]) because the lower-case
    letters are commands ([a], [s], [q] ...); the arrow keys, which Graphics
    does not report, arrive as the characters {!arrow_left} ...
    {!arrow_down} (the window asks X to send them so). *)

(** {1:views Views} *)

type t = private {
  base : Scene.t;  (** The scene as loaded: its canvas and viewport fix the field of view. *)
  scene : Scene.t;
      (** The scene shown: [base] with the current camera and depth, the
          window's size as canvas and the viewport {!fit} to it. *)
  valid : Scene.valid;  (** [scene], validated: what the renderer takes. *)
  limits : Limits.t;  (** The bounds the canvas and depth stay within. *)
  antialias : bool;  (** Whether pixels are averaged over {!antialias_samples}{^2} samples. *)
  help : bool;  (** Whether the help overlay is shown. *)
}
(** The type for views. *)

val v : ?limits:Limits.t -> Scene.valid -> t
(** [v ~limits scene] is the view of [scene] as loaded: its camera, depth
    and canvas size, no antialiasing, no help. Canvas sizes and depths
    stay within [limits] (default {!Raytrace.Limits.default}). *)

val samples : t -> int
(** [samples view] is the side of the grid of samples per pixel: [1], or
    {!antialias_samples} when [view.antialias]. *)

val antialias_samples : int
(** [antialias_samples] is [3]: with antialiasing, each pixel is the mean
    of a 3 x 3 grid of samples ({!Raytrace.Private.Antialias}). *)

(** {1:input Input} *)

type input =
  | Key of char  (** A key, as Graphics reports it. *)
  | Drag of int * int
      (** [Drag (dx, dy)]: the pointer moved by [dx] pixels to the right
          and [dy] pixels up with a button held. *)
  | Resize of int * int  (** [Resize (w, h)]: the window is now [w x h] pixels. *)
(** The type for inputs. *)

type effect =
  | Nothing  (** Nothing changed (an unbound key, an impossible move). *)
  | Render  (** The picture changed: render it again. *)
  | Redraw  (** Only the overlay changed: draw the picture again. *)
  | Save  (** Save the picture ({!save_paths}). *)
  | Quit  (** Close the window. *)
(** The type for what the window must do after an input. *)

val handle : t -> input -> t * effect
(** [handle view input] is the view after [input] and what to do about
    it:
    - arrows, [W] [S] (forward, back), [A] [D] (left, right): move the
      camera by {!move_step} along its own axes;
    - [Q], [<] or [,] and [E], [>] or [.]: turn left or right by
      {!turn_step} about the vertical axis;
    - [Drag (dx, dy)]: turn so that the picture follows the pointer
      ({!drag_angles});
    - [+] or [=], [-] or [_]: recursion depth up or down by one, within
      [\[0, Limits.max_depth\]];
    - [a]: antialiasing on or off; [r]: render again; [s]: {!Save};
      [h]: help on or off; [q] or Escape: {!Quit};
    - [Resize (w, h)]: canvas [w x h], viewport {!fit} to it.
    A move or turn that would take the camera outside
    {!Raytrace.Limits.max_coordinate}, a depth beyond its bounds, a resize to the
    current size or to an invalid canvas, and any other key give
    {!Nothing} and [view] unchanged. *)

val arrow_left : char
(** [arrow_left] is ['\x80'], the character the window receives for the
    left arrow key (and the keypad's). *)

val arrow_up : char
(** [arrow_up] is ['\x81'], for the up arrow. *)

val arrow_right : char
(** [arrow_right] is ['\x82'], for the right arrow. *)

val arrow_down : char
(** [arrow_down] is ['\x83'], for the down arrow. *)

(** {1:camera Camera motion} *)

val move_step : Scene.t -> float
(** [move_step scene] is [0.5] times the viewport distance [d] of
    [scene], in world units: one key press moves the camera by that much,
    whatever the scale of the scene. *)

val turn_step : float
(** [turn_step] is [pi / 36] radians (5 degrees): one key press turns the
    camera by that much. *)

val move : right:float -> forward:float -> Camera.t -> Camera.t
(** [move ~right ~forward cam] is [cam] moved by [right] world units along
    its unit right axis [M (1, 0, 0) / |M (1, 0, 0)|] and [forward] along
    its unit view axis [M (0, 0, 1) / |M (0, 0, 1)|]; the orientation and
    the lens ([Camera.aperture], [Camera.focal_distance]) are unchanged,
    as they are by {!yaw} and {!pitch}. *)

val yaw : float -> Camera.t -> Camera.t
(** [yaw a cam] is [cam] turned by [a] radians about the world's vertical
    axis [y], to the right for [a > 0]: its matrix becomes [R_y(a) M]
    with [R_y(a)] sending [(0, 0, 1)] to [(sin a, 0, cos a)]. *)

val pitch : float -> Camera.t -> Camera.t
(** [pitch a cam] is [cam] tilted by [a] radians about its own right axis,
    upward for [a > 0]: its matrix becomes [M R_x(a)] with [R_x(a)]
    sending [(0, 0, 1)] to [(0, sin a, cos a)]. *)

val drag_angles : Scene.t -> int -> int -> float * float
(** [drag_angles scene dx dy] is the [(yaw, pitch)] in radians for a drag
    of [(dx, dy)] pixels: [-dx] and [-dy] times the angle of one pixel at
    the viewport's center, [V_w / (G_w d)] horizontally and
    [V_h / (G_h d)] vertically, so that the picture follows the pointer. *)

(** {1:canvas Window size} *)

val fit : Scene.t -> width:int -> height:int -> Viewport.t
(** [fit base ~width ~height] is the viewport for a [width x height]
    canvas that keeps the pixels of [base] the same shape and shows at
    least all that [base] shows: [V_w' = V_w k w / G_w] and
    [V_h' = V_h k h / G_h] with [k = max (G_w / w) (G_h / h)], [d]
    unchanged. At [base]'s own size it is [base.viewport] exactly. *)

(** {1:text Text} *)

val title : name:string -> ?frame:int * int * float * float -> unit -> string
(** [title ~name ~frame:(w, h, seconds, rays_per_s) ()] is the window
    title: ["raytrace: "] and [name], then, after a full frame of
    [w x h] pixels, its time in seconds and its rays per second, and a
    reminder of the help key. ASCII only. *)

val help_lines : t -> string list
(** [help_lines view] are the lines of the help overlay: every key and
    what it does, with the current depth, antialiasing and camera
    position. *)

val save_paths : scene_file:string option -> exists:(string -> bool) -> string * string
(** [save_paths ~scene_file ~exists] is [(ppm, scene)], the files that
    [s] writes: [DIR/BASE-N.ppm] and [DIR/BASE-N.scene] where [DIR] and
    [BASE] are the directory and extension-less name of [scene_file]
    (["."] and ["cgfs"] for the built-in scene) and [N >= 1] is the
    smallest number for which [exists] holds for neither file. *)
