(** The camera (document section 3, and CGFS's camera demo).

    The document's camera sits at the origin looking along [+z]. A camera
    here also has a position and an orientation: a 3 x 3 matrix applied to
    every ray direction, [D = M (V_x, V_y, d)], exactly as the CGFS demo
    applies its rotation. The matrix need not be exactly orthonormal (the
    demo's [0.7071] is not), but it must be invertible.

    A camera may also have a thin lens (depth of field): a disc of
    diameter [aperture] centred on the position, in the plane spanned by
    the matrix's first two columns, [M (x, y, 0)]. The ray of a lens point
    [L = M (l_x, l_y, 0)] through viewport point [V] leaves [position + L]
    towards the point that the pinhole ray [position + t M V] meets at
    [t = focal_distance / d] ([d] the viewport distance): its direction is
    [(d / f) (F - (position + L))], so that the viewport plane is still
    [t = 1] and the focal point [t = f / d]. Points at that distance
    (along the view axis, with an orthonormal matrix) are sharp; the
    others are spread over a circle that grows with [aperture]. Aperture
    [0] is the pinhole. *)

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

(** How the camera samples of a pixel draw their lens points. *)
type lens_sampling =
  | Stratified
      (** The default: the [n x n] samples of a pixel take one cell each
          of an [n x n] cut of the square mapped onto the lens (the cells
          shuffled per pixel and shifted by a per-pixel offset), and in
          it one sub-cell of the cell's own [n x n] cut, chosen so that
          the [n^2] points fall one in each of [n^2] columns and rows of
          the square (Kensler's correlated multi-jittered sampling), a
          jittered point in that, mapped onto the disc by the concentric
          map (Shirley and Chiu), which keeps areas: each point is uniform
          over the disc and the set is stratified. The centre sample of an
          odd grid takes the pixel's offset itself, the point of a
          one-sample render ({!Raytrace.Private.Camera_ray}). *)
  | Uniform
      (** Each camera sample's point drawn independently and uniformly
          over the disc (by rejection): plain Monte Carlo, kept to measure
          what stratifying gains (docs/run-time-against-error.md). *)

val equal_lens_sampling : lens_sampling -> lens_sampling -> bool
(** [equal_lens_sampling a b] is [true] iff [a] and [b] are the same. *)

type t = private {
  position : Vec3.t;
  rotation : rotation;
  aperture : float;
  focal_distance : float;
  lens_sampling : lens_sampling;
}
(** The type for cameras: where the camera is, how it is turned, the
    diameter of its lens ([0] for a pinhole), the distance of its plane
    of focus, in scene units ([1] for a pinhole), and how its lens is
    sampled ([Stratified] for a pinhole). *)

val pp : Format.formatter -> t -> unit
(** [pp ppf c] prints [c] as its [camera] form in the scene-file syntax,
    without the rotation when it is {!identity}, without the lens for a
    pinhole and without [(lens-sampling ...)] when it is [Stratified]; it
    reads back as [c]. *)

val show : t -> string
(** [show x] is [x] formatted by {!pp}. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] are equal field by field, floats
    compared with [=]. *)

val identity : rotation
(** [identity] is the identity matrix: looking along [+z] with [y] up. *)

val default : t
(** [default] is the document's camera: at the origin, oriented by
    {!identity}, a pinhole. *)

val v :
  ?rotation:rotation -> ?aperture:float -> ?focal_distance:float -> ?lens_sampling:lens_sampling -> Vec3.t -> t
(** [v ~rotation ~aperture ~focal_distance ~lens_sampling position] is a
    camera at [position] turned by [rotation] (default {!identity}), with
    a lens of diameter [aperture] (default [0.], a pinhole) focused at
    [focal_distance] (default [1.]; a pinhole's is always [1.], whatever
    is given, since it focuses everywhere) and sampled by [lens_sampling]
    (default [Stratified]; a pinhole's is always [Stratified]). Nothing is
    checked: {!validate}. *)

val position : t -> Vec3.t
(** [position c] is where [c] is, in world coordinates. *)

val rotation : t -> rotation
(** [rotation c] is the orientation matrix of [c]. *)

val aperture : t -> float
(** [aperture c] is the diameter of [c]'s lens, [0.] for a pinhole. *)

val focal_distance : t -> float
(** [focal_distance c] is the distance from [c] of its plane of focus,
    along the view axis ([1.] for a pinhole). *)

val lens_sampling : t -> lens_sampling
(** [lens_sampling c] is how [c]'s camera samples draw their lens points
    ([Stratified] for a pinhole). *)

val has_lens : t -> bool
(** [has_lens c] is [aperture c > 0.]: [c]'s rays start on a lens, and
    each camera sample draws its own point of it. *)

val look_at :
  ?up:Vec3.t ->
  ?aperture:float ->
  ?focal_distance:float ->
  ?lens_sampling:lens_sampling ->
  position:Vec3.t ->
  Vec3.t ->
  (t, [> `Msg of string ]) result
(** [look_at ~up ~aperture ~focal_distance ~position target] is the
    camera at [position] whose viewport center lies in the direction of
    [target], with [up] (default [Vec3.oy]) pointing up in the picture as
    far as it can, and the lens of {!v} (focused by default on [target]:
    [focal_distance] is [|target - position|]) sampled by [lens_sampling].
    The matrix is orthonormal.
    [Error] explains why when [target = position] or [up] is zero or
    parallel to the view direction. *)

(** {1:validation Validation} *)

val check_position : Vec3.t -> (Vec3.t, [> `Msg of string ]) result
(** [check_position p] checks {!Limits.check_point}. *)

val check_rotation : rotation -> (rotation, [> `Msg of string ]) result
(** [check_rotation m] checks that [m] is finite and invertible: a singular
    matrix would send some rays in no direction at all. *)

val check_aperture : float -> (float, [> `Msg of string ]) result
(** [check_aperture a] is [Ok a] if [a = 0.] or {!Limits.check_size}
    accepts it (NaN and infinities are refused). *)

val check_focal_distance : float -> (float, [> `Msg of string ]) result
(** [check_focal_distance f] is {!Limits.check_size}. *)

val validate : t -> (t, [> `Msg of string ]) result
(** [validate cam] checks position, rotation, aperture and focal
    distance. *)

(** {1:functions Functions} *)

val direction : t -> Vec3.t -> Vec3.t
(** [direction cam v] is the direction [D] of the primary ray through the
    viewport point [v]: [M v], each coordinate summed in the order
    [x], [y], [z]. With {!identity}, [direction cam v] is [v]. *)

val is_identity : rotation -> bool
(** [is_identity m] is [true] iff [m] is exactly {!identity}. *)

val determinant : rotation -> float
(** [determinant m] is the determinant of [m]. *)
