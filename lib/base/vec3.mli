(** Vectors and points of three-dimensional space.

    Coordinates are world units in the document's left-handed frame: [x] to
    the right, [y] up, [z] away from the camera. Vectors are immutable,
    all-float records, which OCaml stores unboxed. *)

(** {1:vectors Vectors} *)

type t = { x : float; y : float; z : float }
(** The type for vectors and points. *)

val v : float -> float -> float -> t
(** [v x y z] is the vector [(x, y, z)]. *)

val zero : t
(** [zero] is [(0, 0, 0)], the document's origin [O]. *)

val ox : t
(** [ox] is the unit vector [(1, 0, 0)]. *)

val oy : t
(** [oy] is the unit vector [(0, 1, 0)]. *)

val oz : t
(** [oz] is the unit vector [(0, 0, 1)], the document's camera orientation. *)

(** {1:functions Functions} *)

val add : t -> t -> t
(** [add u v] is [u + v], coordinate-wise. *)

val sub : t -> t -> t
(** [sub u v] is [u - v], coordinate-wise; [sub p q] is the vector from [q]
    to [p]. *)

val neg : t -> t
(** [neg v] is [-v]. *)

val smul : float -> t -> t
(** [smul k v] is [k v], each coordinate times [k]. *)

val dot : t -> t -> float
(** [dot u v] is the inner product [<u, v>], summed in the order
    [x], [y], [z] (the order fixes the rounding, and so the image bytes). *)

val cross : t -> t -> t
(** [cross u v] is the cross product [u x v]. *)

val norm2 : t -> float
(** [norm2 v] is [<v, v>], the squared length of [v]. *)

val norm : t -> float
(** [norm v] is [sqrt <v, v>], the length of [v]. *)

val unit : t -> t
(** [unit v] is [v / |v|], of length 1 up to rounding. A zero vector gives
    NaN coordinates: callers reject zero vectors first. *)

val is_finite : t -> bool
(** [is_finite v] is [true] iff no coordinate is NaN or infinite. *)

val to_tuple : t -> float * float * float
(** [to_tuple v] is [(v.x, v.y, v.z)], the document's point type. *)

val of_tuple : float * float * float -> t
(** [of_tuple (x, y, z)] is [v x y z]. *)

(** {1:predicates Predicates and comparisons} *)

val equal : t -> t -> bool
(** [equal u v] is [true] iff the coordinates are equal as floats ([nan] is
    not equal to itself). *)

val equal_f : (float -> float -> bool) -> t -> t -> bool
(** [equal_f eq u v] is [true] iff [eq] holds on each pair of coordinates. *)

val compare : t -> t -> int
(** [compare u v] orders vectors lexicographically with [Float.compare]. *)

(** {1:operators Operators} *)

val ( + ) : t -> t -> t
(** [u + v] is [add u v]. *)

val ( - ) : t -> t -> t
(** [u - v] is [sub u v]. *)

val ( * ) : float -> t -> t
(** [k * v] is [smul k v]. *)

(** {1:fmt Formatters} *)

val pp : Format.formatter -> t -> unit
(** [pp ppf v] prints [v] as [(x y z)] with the shortest decimal that reads
    back as the same float, the syntax of scene files. *)

val show : t -> string
(** [show v] is [v] formatted by {!pp}. *)

val pp_components : Format.formatter -> t -> unit
(** [pp_components ppf v] prints [v] as {!pp} does, without the
    parentheses: [x y z], as the fields of scene forms write points. *)
