(** The [raytrace] commands, free of command-line parsing: each returns the
    process exit status ({!exit_ok}, {!exit_input}, {!exit_no_display}). *)

val exit_ok : int
(** [exit_ok] is [0]. *)

val exit_input : int
(** [exit_input] is [1]: bad input (scene, image, output path) or a failed
    render; the message is on stderr. *)

val exit_no_display : int
(** [exit_no_display] is [3]: no window could be opened. *)

val say : string -> unit
(** [say line] writes [raytrace: line] and a newline on stderr, and
    flushes it; a closed or full stderr loses the line silently. *)

val is_broken_pipe : string -> bool
(** [is_broken_pipe m] is [true] iff the message [m] is a write's
    ["Broken pipe"] ([EPIPE]), alone or after a path and [": "]: a reader
    gone. *)

val end_as_reader_gone : unit -> 'a
(** [end_as_reader_gone ()] ends the process as a Unix tool ends when the
    reader of its output goes away: killed by SIGPIPE (status 141 in a
    shell), with no message. *)

type scene_options = {
  scene : string option;  (** Scene file; [None] for the built-in scene. *)
  width : int option;
  height : int option;
  depth : int option;
}
(** The options that select and override a scene. *)

type sampling_options = {
  samples : int option;  (** [--samples N]: an [N x N] grid of rays per pixel. *)
  adaptive : int option;  (** [--adaptive T]: adaptive supersampling, threshold [T]. *)
  subsample : bool;  (** [--subsample]: CGFS's subsampling. *)
}
(** The options that choose the rays per pixel ({!Raytrace.Sampling}). *)

val view : scene_options -> jobs:int option -> int
(** [view opts ~jobs] renders the scene and shows it in a window. *)

type part_spec =
  | Tile of int * int  (** [--tile I/N]: tile [I] of [N]. *)
  | Corners of int * int * int * int  (** [--region X0,Y0,X1,Y1]. *)
(** The part of the image to render. *)

val parse_frames : string -> (int * int, [> `Msg of string ]) result
(** [parse_frames s] is [(a, b)] for [s = "A:B"] with [a <= b], or [(a, a)]
    for [s = "A"]. *)

val frame_path : string -> int -> string
(** [frame_path pattern f] is [pattern] with its first [%d] or [%0Nd]
    ([N] up to 3 digits) replaced by [f] as [printf] writes it; [pattern]
    itself if it has none. *)

val render :
  scene_options ->
  output:string option ->
  jobs:int option ->
  stats:bool ->
  quiet:bool ->
  literal:bool ->
  part:part_spec option ->
  frames:(int * int) option ->
  sampling:sampling_options ->
  int
(** [render opts ~output ~jobs ~stats ~quiet ~literal ~part ~frames ~sampling]
    renders the scene to an image file, written atomically: PNG if [output] ends in
    [.png], PPM otherwise, [-] for PPM on stdout; default: the scene's base
    name with [.ppm]. [sampling] chooses the rays per pixel; [literal] uses
    the oracle {!Raytrace.Literal}, which traces one ray per pixel. With
    [part], only that rectangle is rendered, to a part file
    ({!Raytrace.Part}, always PPM). With [frames], the frames of the scene's
    camera path, to [frame_path output f] for each frame [f]. When stderr
    is a terminal, a progress line ({!Meter}) shows how far the work has
    gone (not for [literal]); after each image, a line says what was
    written. [quiet] silences both; errors and [stats] are still
    printed. *)

val merge : string list -> output:string -> quiet:bool -> int
(** [merge parts ~output ~quiet] assembles the part files [parts] into the whole
    image ({!Raytrace.Part.merge}) and writes it to [output] (PNG or PPM by
    its name, [-] for PPM on stdout), and says so on stderr unless
    [quiet]. *)

val diff : string -> string -> max_diff:int option -> int
(** [diff a b ~max_diff] prints the difference figures of images [a] and
    [b] (PPM or PNG files, told apart by their contents); with [max_diff],
    fails if a channel differs by more. *)
