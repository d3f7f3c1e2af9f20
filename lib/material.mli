(** Materials of the shapes other than spheres (document sections 7.5
    to 7.8): the colour, specular exponent and reflectivity that a sphere
    carries in its own fields. *)

type t = {
  color : Color.t;  (** Channels in [\[0, 255\]]. *)
  specular : float;  (** [s >= 0], or {!Sphere.matte} for no specular term. *)
  reflective : float;  (** Reflectivity in [\[0, 1\]]. *)
  pattern : Pattern.t option;
      (** A second colour laid over [color] ({!Pattern}), or [None]. *)
}
(** The type for materials. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf m] prints [m] as the fields that give an object's material in
    the scene-file syntax: [(color r g b)], then [(specular e)],
    [(reflective r)] and [(pattern ...)] each only when it is not the
    default. *)

val show : t -> string
(** [show x] is [x] formatted by {!pp}. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] are equal field by field, floats
    compared with [=]. *)

val v : ?specular:float -> ?reflective:float -> ?pattern:Pattern.t -> Color.t -> t
(** [v ~specular ~reflective ~pattern color] is a material; [specular]
    defaults to {!Sphere.matte}, [reflective] to [0], [pattern] to none. *)

val check_color : form:string -> Color.t -> (Color.t, [> `Msg of string ]) result
(** [check_color ~form c] is {!Sphere.check_color}, its message naming [form]. *)

val check_specular : form:string -> float -> (float, [> `Msg of string ]) result
(** [check_specular ~form s] is {!Sphere.check_specular}, its message naming [form]. *)

val check_reflective : form:string -> float -> (float, [> `Msg of string ]) result
(** [check_reflective ~form r] is {!Sphere.check_reflective}, its message naming [form]. *)

val validate : form:string -> t -> (t, [> `Msg of string ]) result
(** [validate ~form m] is [Ok m] if its fields pass the checks of
    {!Sphere.check_color}, {!Sphere.check_specular} and
    {!Sphere.check_reflective} and its pattern {!Pattern.validate}, and otherwise the first error, with the
    word [sphere] of their messages replaced by [form] (e.g.
    ["plane color channels must lie in [0, 255], got ..."]). *)
