(** Lights (document sections 7.1 to 7.4).

    Lights are white; an intensity is a plain, non-negative float that does
    not fall off with distance. The document's advice is that the
    intensities of a scene sum to 1, else some points are overexposed. *)

(** {1:lights Lights} *)

type t = private
  | Ambient of { intensity : float }
      (** Lights every point of every object equally (7.3). *)
  | Point of { intensity : float; position : Vec3.t }
      (** Shines from [position] in every direction (7.1). *)
  | Directional of { intensity : float; direction : Vec3.t }
      (** Shines from infinitely far away: [direction] points from the
          scene {e toward} the light, and is the same vector [L] at every
          point (7.2). It need not be unit length but must not be zero. *)
(** The type for lights. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf l] prints [l] as its [light] form in the scene-file syntax,
    e.g. [(light point (intensity 0.6) (position 2 1 0))]. *)

val show : t -> string
(** [show x] is [x] formatted by {!pp}. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] are equal field by field, floats
    compared with [=]. *)

val ambient : float -> t
(** [ambient i] is [Ambient {intensity = i}]. *)

val point : float -> Vec3.t -> t
(** [point i q] is the point light of intensity [i] at [q]. *)

val directional : float -> Vec3.t -> t
(** [directional i l] is the directional light of intensity [i] toward
    [l]. *)

val intensity : t -> float
(** [intensity l] is the intensity of [l]. *)

val check_intensity : float -> (float, [> `Msg of string ]) result
(** [check_intensity i] checks [0 <= i <= Limits.max_intensity]. *)

val check_position : Vec3.t -> (Vec3.t, [> `Msg of string ]) result
(** [check_position q] checks a point light's position with
    {!Limits.check_point}. *)

val check_direction : Vec3.t -> (Vec3.t, [> `Msg of string ]) result
(** [check_direction l] checks a directional light's direction with
    {!Limits.check_point}, and that its length is at least
    {!Limits.min_size}. *)

val validate : t -> (t, [> `Msg of string ]) result
(** [validate l] is [Ok l] if the intensity, position and direction pass
    their checks, and otherwise the first error. *)

(** {1:geometry Geometry} *)

val vector : t -> Vec3.t -> Vec3.t option
(** [vector l p] is the vector [L] from point [p] toward [l] (7.1, 7.2):
    [Q - P] for a point light at [Q], the light's direction for a
    directional light, [None] for an ambient light. *)

val shadow_t_max : t -> float
(** [shadow_t_max l] is the end of the range of [t] in which an object on
    the shadow ray [P + t L] blocks [l] (7.7): [1.] for a point light (the
    light itself is at [t = 1]), [infinity] otherwise. *)

(** {1:document The document's light record}

    The document represents a light as a record with a [char] tag. These
    let code written against the document build lights of this library. *)

type point = float * float * float
(** The document's point: [(x, y, z)]. *)

type document = { k : char; i : float; v : point option }
(** The document's light: [k] is ['p'] (point), ['d'] (directional) or
    ['a'] (ambient); [i] is the intensity; [v] the position of a point
    light, the direction of a directional light, [None] for an ambient
    light. *)

val of_document : document -> (t, [> `Msg of string ]) result
(** [of_document d] is the light [d] describes, validated as by
    {!validate}. [Error] names what is wrong: an unknown tag, a missing or
    superfluous [v], an invalid number. *)

val of_document_exn : document -> t
(** [of_document_exn] is {!of_document}.
    @raise Invalid_argument with the error message on invalid records. *)

val to_document : t -> document
(** [to_document l] is [l] as the document's record;
    [of_document (to_document l) = Ok l]. *)
