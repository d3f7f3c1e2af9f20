(** The bounds that inputs must respect.

    Beyond these, a render would lose all precision, exhaust memory or run
    for years; scenes and command lines outside them are refused up front
    with a message that names the bound. *)

val max_coordinate : float
(** [max_coordinate] is [1e12]: the largest magnitude of a coordinate, a
    radius or a viewport dimension. Squares of larger values approach the
    range where sums of squares lose every digit of a unit-sized sphere. *)

val min_size : float
(** [min_size] is [1e-30]: the smallest radius, viewport dimension or
    directional-light vector length. Squares and products of smaller values
    underflow and would turn into division by zero. *)

val max_intensity : float
(** [max_intensity] is [1e6]: the largest light intensity, so that sums of
    intensities times colours can never overflow to infinity. *)

val max_dimension : int
(** [max_dimension] is [65536]: the largest canvas width or height. *)

val max_pixels : int
(** [max_pixels] is [268435456] ([2^28], 768 MiB of RGB): the largest
    canvas area. *)

val max_depth : int
(** [max_depth] is [64]: the largest recursion depth. Each level multiplies
    the weight of the reflected colour by at most 1, but deeper recursion
    only costs time. *)

val max_jobs : int
(** [max_jobs] is [1024]: the most worker processes a render forks. *)

val check_jobs : int -> (int, string) result
(** [check_jobs n] is [Ok n] if [1 <= n <= max_jobs]. *)

val check_coordinate : string -> float -> (float, string) result
(** [check_coordinate what x] is [Ok x] if [x] is finite with
    [|x| <= max_coordinate], and otherwise [Error] naming [what]. *)

val check_size : string -> float -> (float, string) result
(** [check_size what x] is [Ok x] if [min_size <= x <= max_coordinate],
    and otherwise [Error] naming [what] ("sphere radius", ...). *)

val check_point : string -> Vec3.t -> (Vec3.t, string) result
(** [check_point what p] is {!check_coordinate} on each coordinate. *)

val check_dimension : string -> int -> (int, string) result
(** [check_dimension what n] is [Ok n] if [1 <= n <= max_dimension], and
    otherwise [Error] naming the canvas's [what] ("width", "height"). *)

val check_canvas : int -> int -> (unit, string) result
(** [check_canvas w h] is [Ok ()] if [1 <= w, h <= max_dimension] and
    [w * h <= max_pixels]. *)

val check_depth : int -> (int, string) result
(** [check_depth d] is [Ok d] if [0 <= d <= max_depth]. *)
