(** The web page's state, free of the browser: the scene text, the view
    that the keys change, the size and samples chosen, and the frame being
    rendered.

    The page ([web/page.ml]) only reads the editor, the keys and the
    selectors, calls these functions, and paints the bands that {!step}
    returns; everything decided here runs the same natively, where the
    tests check it. Rendering is the window's: {!View} maps keys to
    cameras, {!Progressive} traces coarse blocks first, then every pixel,
    so that the finished picture is [raytrace render]'s byte for byte. *)

open Raytrace
open Raytrace_view

type t
(** The type for page states. *)

val file : string
(** [file] is ["scene"], the name that error messages give the editor's
    text: [scene:LINE:COLUMN: message]. *)

val v : now:(unit -> float) -> string -> (t, [> `Msg of string ]) result
(** [v ~now text] is the page showing the scene [text], at its own canvas
    size with one sample per pixel, its first frame started. [now ()] is
    the time in seconds (any origin), read to time frames and slices.
    [Error] if [text] is not a scene ({!edit}). *)

(** {1:input Input} *)

val edit : t -> string -> (unit, [> `Msg of string ]) result
(** [edit p text] shows the scene [text] from its own camera, at the size
    and samples chosen, and starts its frame. On [Error] (a
    [scene:LINE:COLUMN: message] from {!Scene_file.of_string}, or a render
    beyond {!Scene.check_work}), [p] is unchanged and keeps its picture. *)

val input : t -> View.input -> View.effect
(** [input p i] applies [i] to the view ({!View.handle}) and is what the
    page must do about it; a new frame is started when the effect is
    {!View.Render}. The key [a] switches between one sample and
    {!View.antialias_samples}, as in the window. *)

val set_size : t -> (int * int) option -> (unit, [> `Msg of string ]) result
(** [set_size p size] renders at [size = Some (w, h)] pixels, or at the
    scene's canvas size for [None], the viewport fitted and the camera
    kept as when the window is resized ({!View.fit}), and starts a new
    frame if that changed anything. [Error], [p] unchanged, for a canvas outside
    {!Limits.check_canvas} or a render beyond {!Scene.check_work}. *)

val set_samples : t -> int -> (unit, [> `Msg of string ]) result
(** [set_samples p n] renders with [n x n] samples per pixel, which
    the view's [antialias] then shows as on ([n > 1]) or off, and starts a new
    frame if [n] changed. [Error], [p] unchanged, unless
    [1 <= n <= Limits.max_grid] and the render is within
    {!Scene.check_work}. *)

(** {1:render Rendering} *)

val step : t -> until:float -> Progressive.band list
(** [step p ~until] traces bands of the current frame until it is
    finished or [now ()] is at least [until] (at least one band, if any is
    left), and is the bands traced, in order. The frame's statistics
    ({!last_frame}) are set when its last band is traced. *)

val bands : t -> int
(** [bands p] is the number of bands of the current frame traced so far. *)

val finished : t -> bool
(** [finished p] is [true] iff the current frame is complete. *)

val image : t -> Image.t
(** [image p] is the picture of the current frame: complete once
    {!finished}; before, the pixels traced so far ({!Progressive.image}). *)

val view : t -> View.t
(** [view p] is the view shown: [view.scene] is what is rendered. *)

val samples : t -> int
(** [samples p] is the side of the grid of samples per pixel. *)

val size : t -> (int * int) option
(** [size p] is the size chosen with {!set_size}. *)

val shown_text : t -> string
(** [shown_text p] is the scene rendered, camera moved and canvas resized,
    in the scene-file syntax ({!Scene_file.to_string}): rendered by
    [raytrace render --samples] {!samples}, it is the page's picture. *)

(** {1:frames Frames} *)

type frame = {
  width : int;  (** Pixels across. *)
  height : int;  (** Pixels down. *)
  frame_samples : int;  (** Side of the grid of samples per pixel. *)
  seconds : float;  (** From the start of the frame to its last band, painting and waiting included. *)
  trace_seconds : float;  (** Of which spent in {!step}. *)
  slices : int;  (** Calls of {!step} it took. *)
  longest_slice : float;  (** Seconds of the longest of them. *)
  rays : float;  (** Rays traced: primary, shadow and reflection. *)
}
(** The type for the statistics of a complete frame. *)

val last_frame : t -> frame option
(** [last_frame p] is the statistics of the last complete frame, if any. *)

val frame_text : frame -> string
(** [frame_text f] is one line for the page, e.g.
    ["600 x 600, 1 sample per pixel: 0.412 s (traced in 0.380 s, 5.1 M rays/s, 16 slices)"]. *)
