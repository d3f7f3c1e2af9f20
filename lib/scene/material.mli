(** Materials of the shapes other than spheres (document sections 7.5
    to 7.8): the colour, specular exponent and reflectivity that a sphere
    carries in its own fields. *)

type t = {
  color : Color.t;  (** Channels in [\[0, 255\]]. *)
  specular : float;  (** [s >= 0], or {!Sphere.matte} for no specular term. *)
  reflective : float;  (** Reflectivity in [\[0, 1\]]. *)
  transparency : float;  (** Transparency in [\[0, 1\]], [reflective + transparency <= 1]. *)
  refractive_index : float;  (** Index of refraction, [> 0] and finite. *)
  fresnel : bool;  (** Schlick's approximation splits the transparency. *)
  pattern : Pattern.t option;
      (** A second colour laid over [color] ({!Pattern}), or [None]. *)
}
(** The type for materials. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf m] prints [m] as the fields that give an object's material in
    the scene-file syntax: [(color r g b)], then [(specular e)],
    [(reflective r)], [(transparency t)], [(refractive-index n)],
    [(fresnel true)] and [(pattern ...)], each only when it is not the
    default. *)

val show : t -> string
(** [show x] is [x] formatted by {!pp}. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] are equal field by field, floats
    compared with [=]. *)

val same_plain : t -> t -> bool
(** [same_plain a b] is [true] iff neither [a] nor [b] has a pattern and
    their fields are equal bit for bit (so [0.] and [-0.] differ): two
    objects can share such materials without changing one bit of
    arithmetic. *)

module Plain : Hashtbl.S with type key = t
(** Hash tables keyed by materials compared with {!same_plain}: a table
    finds only materials without a pattern. *)

val v :
  ?specular:float ->
  ?reflective:float ->
  ?transparency:float ->
  ?refractive_index:float ->
  ?fresnel:bool ->
  ?pattern:Pattern.t ->
  Color.t ->
  t
(** [v ~specular ~reflective ~transparency ~refractive_index ~fresnel ~pattern color]
    is a material; [specular] defaults to {!Sphere.matte}, [reflective]
    and [transparency] to [0], [refractive_index] to [1], [fresnel] to
    [false], [pattern] to none (the fields of {!Sphere.t}). *)

val of_sphere : Sphere.t -> t
(** [of_sphere s] is the material of sphere [s]. *)

val check_color : form:string -> Color.t -> (Color.t, [> `Msg of string ]) result
(** [check_color ~form c] is {!Sphere.check_color}, its message naming [form]. *)

val check_specular : form:string -> float -> (float, [> `Msg of string ]) result
(** [check_specular ~form s] is {!Sphere.check_specular}, its message naming [form]. *)

val check_reflective : form:string -> float -> (float, [> `Msg of string ]) result
(** [check_reflective ~form r] is {!Sphere.check_reflective}, its message naming [form]. *)

val check_transparency : form:string -> float -> (float, [> `Msg of string ]) result
(** [check_transparency ~form t] is {!Sphere.check_transparency}, its message naming [form]. *)

val check_refractive_index : form:string -> float -> (float, [> `Msg of string ]) result
(** [check_refractive_index ~form n] is {!Sphere.check_refractive_index}, its message naming [form]. *)

val check_split :
  form:string -> reflective:float -> transparency:float -> (unit, [> `Msg of string ]) result
(** [check_split ~form ~reflective ~transparency] is {!Sphere.check_split}, its message naming [form]. *)

val validate : form:string -> t -> (t, [> `Msg of string ]) result
(** [validate ~form m] is [Ok m] if its fields pass the checks of
    {!Sphere.check_color}, {!Sphere.check_specular} and
    {!Sphere.check_reflective}, {!Sphere.check_transparency},
    {!Sphere.check_refractive_index} and {!Sphere.check_split}, and its
    pattern {!Pattern.validate}, and otherwise the first error, with the
    word [sphere] of their messages replaced by [form] (e.g.
    ["plane color channels must lie in [0, 255], got ..."]). *)
