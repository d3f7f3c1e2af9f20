(** The camera (document section 3, and CGFS's camera demo).

    The document's camera sits at the origin looking along [+z]. A camera
    here also has a position and an orientation: a 3 x 3 matrix applied to
    every ray direction, [D = M (V_x, V_y, d)], exactly as the CGFS demo
    applies its rotation. The matrix need not be exactly orthonormal (the
    demo's [0.7071] is not), but it must be invertible. *)

(** {1:cameras Cameras} *)

type rotation = { row0 : Vec3.t; row1 : Vec3.t; row2 : Vec3.t }
(** The type for orientation matrices, by rows: the direction of the ray
    through viewport point [v] is [(<v, row0>, <v, row1>, <v, row2>)]. *)

val pp_rotation : Format.formatter -> rotation -> unit
(** [pp_rotation ppf m] prints [m] as the [rotation] field of the scene-file
    syntax: [(rotation (a b c) (d e f) (g h i))], by rows. *)

val show_rotation : rotation -> string
(** [show_rotation x] is [x] formatted by {!pp_rotation}. *)

val equal_rotation : rotation -> rotation -> bool
(** [equal_rotation a b] is [true] iff [a] and [b] are equal field by field, floats
    compared with [=]. *)

type t = private { position : Vec3.t; rotation : rotation }
(** The type for cameras: where the camera is, and how it is turned. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf c] prints [c] as its [camera] form in the scene-file syntax,
    without the rotation when it is {!identity}. *)

val show : t -> string
(** [show x] is [x] formatted by {!pp}. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] are equal field by field, floats
    compared with [=]. *)

val identity : rotation
(** [identity] is the identity matrix: looking along [+z] with [y] up. *)

val default : t
(** [default] is the document's camera: at the origin, oriented by
    {!identity}. *)

val v : ?rotation:rotation -> Vec3.t -> t
(** [v ~rotation position] is a camera at [position] turned by [rotation]
    (default {!identity}). *)

val position : t -> Vec3.t
(** [position c] is where [c] is, in world coordinates. *)

val rotation : t -> rotation
(** [rotation c] is the orientation matrix of [c]. *)

val look_at : ?up:Vec3.t -> position:Vec3.t -> Vec3.t -> (t, [> `Msg of string ]) result
(** [look_at ~up ~position target] is the camera at [position] whose
    viewport center lies in the direction of [target], with [up] (default
    [Vec3.oy]) pointing up in the picture as far as it can. The matrix is
    orthonormal. [Error] explains why when [target = position] or [up] is
    zero or parallel to the view direction. *)

(** {1:validation Validation} *)

val check_position : Vec3.t -> (Vec3.t, [> `Msg of string ]) result
(** [check_position p] checks {!Limits.check_point}. *)

val check_rotation : rotation -> (rotation, [> `Msg of string ]) result
(** [check_rotation m] checks that [m] is finite and invertible: a singular
    matrix would send some rays in no direction at all. *)

val validate : t -> (t, [> `Msg of string ]) result
(** [validate cam] checks position and rotation. *)

(** {1:functions Functions} *)

val direction : t -> Vec3.t -> Vec3.t
(** [direction cam v] is the direction [D] of the primary ray through the
    viewport point [v]: [M v], each coordinate summed in the order
    [x], [y], [z]. With {!identity}, [direction cam v] is [v]. *)

val is_identity : rotation -> bool
(** [is_identity m] is [true] iff [m] is exactly {!identity}. *)

val determinant : rotation -> float
(** [determinant m] is the determinant of [m]. *)
