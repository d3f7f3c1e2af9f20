(** Affine transforms of objects: scales, rotations and translations,
    composed in the order written, as scene text gives them
    ([(transform ((scale 2 1 1) (rotate-y 30) (translate 0 0 5)) OBJECT)]).

    A transform maps the object's frame to the world's. The kernel traces a
    transformed object in the object's frame: it carries the ray there
    ({!to_object}: the point by the inverse map, the direction by its
    linear part, so that a root [t] is the same number in both frames) and
    brings the normal back by the inverse transpose ({!normal_to_world}).

    Matrices are 12 floats, three rows [[a00 a01 a02 b0; a10 ...]]: the
    point [p] maps to [A p + b]. *)

(** {1:ops Operations} *)

type op =
  | Scale of Vec3.t  (** Per axis; no factor is 0 (a negative one mirrors). *)
  | Rotate_x of float  (** Degrees about the x axis, counterclockwise looking down the axis toward the origin. *)
  | Rotate_y of float  (** Degrees about the y axis. *)
  | Rotate_z of float  (** Degrees about the z axis. *)
  | Rotate of Vec3.t * float  (** Degrees about an axis through the origin (not the zero vector). *)
  | Translate of Vec3.t
(** The type for one operation. *)

(** {1:t Transforms} *)

type t
(** The type for transforms: a list of operations and the two matrices
    they make. *)

val v : op list -> (t, [> `Msg of string ]) result
(** [v ops] is the transform that applies [ops] in order, or an error
    naming the operation at fault: a scale factor of 0, a factor or angle
    that is not finite, a coordinate beyond {!Limits.check_point}, a zero
    rotation axis, or a composition whose matrices are not finite. *)

val identity : t
(** [identity] is [v []]. *)

val ops : t -> op list
(** [ops t] is [t]'s operations in the order they apply. *)

val compose : t -> t -> t
(** [compose a b] applies [a], then [b] (its operations are [ops a @ ops b]).
    @raise Invalid_argument if the composition is not finite. *)

val to_world : t -> float array
(** [to_world t] is a fresh copy of [t]'s matrix, object to world. *)

val to_object : t -> float array
(** [to_object t] is a fresh copy of the inverse matrix, world to object,
    composed from each operation's exact inverse (the reciprocal scale,
    the opposite angle, the opposite translation) in reverse order: no
    matrix is inverted numerically. *)

val point : t -> Vec3.t -> Vec3.t
(** [point t p] is [p] mapped to the world. *)

val direction : t -> Vec3.t -> Vec3.t
(** [direction t d] is [d] mapped by [t]'s linear part. *)

val normal_to_world : t -> Vec3.t -> Vec3.t
(** [normal_to_world t n] is the unit normal in the world of a surface
    whose normal in the object's frame is [n]: [n] times the inverse
    transpose of the linear part, divided by its length. *)

val bounds : t -> Vec3.t * Vec3.t -> Vec3.t * Vec3.t
(** [bounds t (lo, hi)] is a box in the world that holds the image of the
    box [lo, hi] with room for the rounding of the ray's transform: the
    eight corners mapped, their extremes taken and moved outward by
    [64 u] times their magnitude plus the box's size ([u] the unit
    roundoff). *)

val stretch : t -> float
(** [stretch t] is [||A|| ||A^-1||] (Frobenius norms, at least 1, about
    3 for a rotation): how much the transform can magnify the relative
    rounding of a point carried between the frames. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] have equal operations, floats
    bit for bit. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf t] prints [t]'s operations as scene text gives them,
    [((scale 2 1 1) (rotate-y 30))]. *)

(** {1:angles Angles} *)

val cos_sin : float -> float * float
(** [cos_sin deg] is the cosine and sine of [deg] degrees, exact (0, 1 or
    -1) at multiples of 90: a quarter turn maps a box's faces on faces. *)
