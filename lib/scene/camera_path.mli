(** Camera paths: the camera of each frame of an animation.

    A path is a sequence of keyframes in increasing frame order. Each key puts
    the camera at a [position], looking at a [look_at] target with an [up]
    direction ({!Camera.look_at}). Between two keys, position, target and up
    move linearly with the frame number; at a key's frame the camera is
    exactly the key's. Frames are integers in [\[0, max_frame\]]; a path
    defines the frames from its first key to its last, and each of them is
    checked when the path is built, so that every frame renders.

    @canonical Raytrace.Camera.Path *)

type key = {
  frame : int;  (** Frame number, in [\[0, max_frame\]]. *)
  position : Vec3.t;  (** Where the camera is. *)
  look_at : Vec3.t;  (** The point the camera looks at, [<> position]. *)
  up : Vec3.t;  (** Up in the picture, not parallel to [look_at - position]. *)
}
(** The type for keyframes. *)

val pp_key : Format.formatter -> key -> unit
(** [pp_key ppf k] prints [k] as a [key] of the scene-file syntax's
    [camera-path] form, without [up] when it is {!Vec3.oy}. *)

val show_key : key -> string
(** [show_key x] is [x] formatted by {!pp_key}. *)

val equal_key : key -> key -> bool
(** [equal_key a b] is [true] iff [a] and [b] are equal field by field, floats
    compared with [=]. *)

type t
(** The type for camera paths: at least one key, frames strictly
    increasing.

    @canonical Raytrace.Camera.Path.t *)

val pp : Format.formatter -> t -> unit
(** [pp ppf p] prints [p] as its [camera-path] form in the scene-file
    syntax, one key a line. *)

val show : t -> string
(** [show x] is [x] formatted by {!pp}. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] are equal field by field, floats
    compared with [=]. *)

val max_frame : int
(** [max_frame] is [1_000_000], the largest frame number. *)

val key : ?up:Vec3.t -> frame:int -> position:Vec3.t -> Vec3.t -> key
(** [key ~up ~frame ~position target] is the keyframe [frame] with the camera
    at [position] looking at [target]; [up] defaults to [Vec3.oy]. *)

val check_key : key -> (key, [> `Msg of string ]) result
(** [check_key k] checks that [k.frame] lies in [\[0, max_frame\]], that its
    points are within {!Limits.check_point}, and that {!Camera.look_at}
    accepts it. *)

val check_segment : key -> key -> (unit, [> `Msg of string ]) result
(** [check_segment k0 k1] checks that [k0.frame < k1.frame] and that every
    frame strictly between them has a camera: the interpolated position is
    not the interpolated target and the interpolated up is not parallel to
    the view direction. The error names the first bad frame. *)

val v : key list -> (t, [> `Msg of string ]) result
(** [v keys] is the path through [keys], after {!check_key} on each key and
    {!check_segment} on each pair of neighbours. [Error] also if [keys] is
    empty. *)

val keys : t -> key list
(** [keys p] is the keys of [p], in increasing frame order. *)

val first_frame : t -> int
(** [first_frame p] is the frame of the first key of [p]. *)

val last_frame : t -> int
(** [last_frame p] is the frame of the last key of [p]. *)

val camera : t -> int -> (Camera.t, [> `Msg of string ]) result
(** [camera p f] is the camera of frame [f]: the key's camera if a key has
    frame [f], and otherwise, between keys [k0] and [k1] with
    [t = (f - k0.frame) / (k1.frame - k0.frame)], the {!Camera.look_at}
    camera of [(1 - t) a + t b] for position, target and up, coordinate by
    coordinate. [Error] if [f] lies outside
    [\[first_frame p, last_frame p\]]. [O(log n)] for a path of [n] keys:
    the keys are found by binary search. *)
