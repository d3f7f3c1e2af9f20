(** The [raytrace] commands, free of command-line parsing: each returns the
    process exit status ({!exit_ok}, {!exit_input}, {!exit_no_display}). *)

val exit_ok : int
(** [exit_ok] is [0]. *)

val exit_input : int
(** [exit_input] is [1]: bad input (scene, image, output path) or a failed
    render; the message is on stderr. *)

val exit_no_display : int
(** [exit_no_display] is [3]: no window could be opened. *)

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

val view : scene_options -> jobs:int option -> sampling:sampling_options -> int
(** [view opts ~jobs ~sampling] renders the scene and shows it in a
    window. *)

val render :
  scene_options ->
  output:string option ->
  jobs:int option ->
  stats:bool ->
  literal:bool ->
  sampling:sampling_options ->
  int
(** [render opts ~output ~jobs ~stats ~literal ~sampling] renders the
    scene to a PPM file ([-] for stdout; default: the scene's base name
    with [.ppm]), written atomically. [literal] uses the oracle
    {!Raytrace.Literal}, which traces one ray per pixel only. *)

val diff : string -> string -> max_diff:int option -> int
(** [diff a b ~max_diff] prints the difference figures of images [a] and
    [b]; with [max_diff], fails if a channel differs by more. *)
