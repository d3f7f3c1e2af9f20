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
    text: [scene:LINE:COLUMN: message]. Every message of this module is
    such a line; one that has no place in the text (a render beyond
    the work bound, a frame stopped) is placed at [1:1]. *)

val located : string -> string
(** [located m] is [m] if it begins with [scene:], and otherwise
    [scene:1:1: m]. *)

val exception_line : exn -> string
(** [exception_line e] is the line that the page shows for an exception
    that escaped: its stack ran out ([Stack_overflow], which is also what
    JavaScript's "Maximum call stack size exceeded" becomes), its memory,
    or another, named. *)

val max_side : int
(** [max_side] is [4096]: the page renders canvases of at most
    [max_side x max_side] pixels (the [`Pixels] bound of {!limits}). A
    larger one would need gigabytes of canvas and image in the browser
    (a [16384 x 16384] canvas is 1 GiB of RGBA), and minutes of tracing
    that cannot be cancelled: the page refuses it with a positioned
    line, as the command line refuses a canvas beyond its bounds. *)

val limits : Limits.t
(** [limits] is {!Limits.default} with the [`Pixels] bound
    [max_side * max_side]: the bounds of every scene the page renders. *)

val max_pixel_seconds : float
(** [max_pixel_seconds] is [0.5]: the longest one pixel may take to
    trace before {!step} stops the frame ({!stopped}). *)

val v : now:(unit -> float) -> string -> (t, [> `Msg of string ]) result
(** [v ~now text] is the page showing the scene [text], at its own canvas
    size with one sample per pixel, its first frame started. [now ()] is
    the time in seconds (any origin), read to time frames and slices.
    [Error] if [text] is not a scene ({!edit}). *)

(** {1:input Input} *)

val edit : t -> string -> (unit, [> `Msg of string ]) result
(** [edit p text] shows the scene [text] from its own camera, at the size
    and samples chosen, and starts its frame. On [Error] (a
    [scene:LINE:COLUMN: message] from {!Scene_file.of_string} within
    {!limits}, a render beyond {!Scene.check_work}, or a scene that the
    browser's stack or memory cannot prepare), [p] is unchanged and keeps
    its picture. A page reads no files: a texture's file must be one of
    the example scenes' images, built in ({!Example_textures.files}: the
    scene [scenes/globe.scene] renders as it is), and any other is an
    error at its name that says so; a mesh's file is refused likewise
    ({!Scene_file.of_string}'s default). *)

val input : t -> View.input -> View.effect
(** [input p i] applies [i] to the view ({!View.handle}) and is what the
    page must do about it; a new frame is started when the effect is
    {!View.Render}. The key [a] switches between one sample and
    {!View.antialias_samples}, as in the window. A render that the
    bounds refuse (the key [+] past the work bound) is {!View.Nothing},
    and {!refused} says why. *)

val refused : t -> string option
(** [refused p] is why the last {!input} changed nothing, if the bounds
    refused the render it asked for: a [scene:1:1: message] line. *)

val set_size : t -> (int * int) option -> (unit, [> `Msg of string ]) result
(** [set_size p size] renders at [size = Some (w, h)] pixels, or at the
    scene's canvas size for [None], the viewport fitted and the camera
    kept as when the window is resized ({!View.fit}), and starts a new
    frame if that changed anything. [Error], [p] unchanged, for a canvas outside
    {!Limits.check_canvas} of {!limits} or a render beyond {!Scene.check_work}. *)

val set_samples : t -> int -> (unit, [> `Msg of string ]) result
(** [set_samples p n] renders with [n x n] samples per pixel, which
    the view's [antialias] then shows as on ([n > 1]) or off, and starts a new
    frame if [n] changed. [Error], [p] unchanged, unless
    [1 <= n <= Limits.max_grid] and the render is within
    {!Scene.check_work}. *)

(** {1:render Rendering} *)

val step : t -> until:float -> Progressive.band list
(** [step p ~until] traces the current frame until it is finished or
    [now ()] is at least [until], and is the bands finished, in order:
    [now ()] is read between bands and every few milliseconds of tracing
    ({!Progressive.advance}), so a slice ends at the end of a pixel soon
    after [until] even when a band takes seconds (a row of a glass
    scene), and is then maybe no band. A pixel that alone takes more than
    {!max_pixel_seconds} past [until] stops the frame, as do the work
    bound and the browser's stack or memory running out ({!stopped}).
    [step p ~until:neg_infinity] traces one band, whatever it takes
    (the tests' [raytrace.advance]). The frame's statistics ({!last_frame}) are set when its last band is
    traced. *)

val stopped : t -> string option
(** [stopped p] is why the current frame stopped before its end, if it
    did: a [scene:LINE:COLUMN: message] line. It is then {!finished}. *)

val bands : t -> int
(** [bands p] is the number of bands of the current frame traced so far. *)

val longest_slice : t -> float
(** [longest_slice p] is the seconds of the longest call of {!step} for
    the current frame so far: the longest the page has not answered. *)

val finished : t -> bool
(** [finished p] is [true] iff the current frame is complete, or
    {!stopped}. *)

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
