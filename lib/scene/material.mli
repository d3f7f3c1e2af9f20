(** Materials (document sections 7.5 to 7.8): what every object is made
    of -- a colour, a specular exponent, a reflectivity, and the optics of
    glass. One value may be shared by any number of objects of any shape
    (a sphere and a mesh alike); scene text may name one
    ([(material glass ...)]) and use it by name. *)

type t = private {
  color : Color.t;  (** Channels in [\[0, 255\]]. *)
  specular : float;  (** [s >= 0], or {!matte} for no specular term. *)
  reflective : float;  (** Reflectivity in [\[0, 1\]]. *)
  transparency : float;  (** Transparency in [\[0, 1\]], [reflective + transparency <= 1]. *)
  refractive_index : float;  (** Index of refraction, [> 0] and finite. *)
  fresnel : bool;  (** Schlick's approximation splits the transparency. *)
  pattern : Pattern.t option;
      (** A second colour laid over [color] ({!Pattern}), or [None]. *)
  texture : Texture_map.t option;
      (** An image whose colour replaces [color] ({!Texture_map}), or
          [None]. *)
}
(** The type for materials. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf m] prints [m] as the fields that give an object's material in
    the scene-file syntax: [(color r g b)], then [(specular e)],
    [(reflective r)], [(transparency t)], [(refractive-index n)],
    [(fresnel true)], [(pattern ...)] and [(texture ...)], each only when
    it is not the default. *)

val show : t -> string
(** [show x] is [x] formatted by {!pp}. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] are equal field by field, floats
    compared with [=]. *)

val same_plain : t -> t -> bool
(** [same_plain a b] is [true] iff neither [a] nor [b] has a pattern or a
    texture and
    their fields are equal bit for bit (so [0.] and [-0.] differ): two
    objects can share such materials without changing one bit of
    arithmetic. *)

module Plain : Hashtbl.S with type key = t
(** Hash tables keyed by materials compared with {!same_plain}: a table
    finds only materials without a pattern or a texture. *)

val matte : float
(** [matte] is [-1.], the specular exponent that means "no specular term"
    (as in CGFS). An exponent of [0] is not matte. *)

val v :
  ?specular:float ->
  ?reflective:float ->
  ?transparency:float ->
  ?refractive_index:float ->
  ?fresnel:bool ->
  ?pattern:Pattern.t ->
  ?texture:Texture_map.t ->
  Color.t ->
  t
(** [v ~specular ~reflective ~transparency ~refractive_index ~fresnel ~pattern ~texture color]
    is a material; [specular] defaults to {!matte}, [reflective]
    and [transparency] to [0], [refractive_index] to [1], [fresnel] to
    [false], [pattern] and [texture] to none. It is not validated: see {!validate}. *)

val update :
  ?color:Color.t ->
  ?specular:float ->
  ?reflective:float ->
  ?transparency:float ->
  ?refractive_index:float ->
  ?fresnel:bool ->
  ?pattern:Pattern.t option ->
  ?texture:Texture_map.t option ->
  t ->
  t
(** [update ~color ... m] is [m] with the given fields replaced (how a
    scene file's inline fields override a named material's); [~pattern:None]
    removes [m]'s pattern, [~texture:None] its texture. *)

(** {1:fields Fields} *)

val color : t -> Color.t
(** [color m] is [m]'s colour. *)

val specular : t -> float
(** [specular m] is [m]'s specular exponent, or {!matte}. *)

val reflective : t -> float
(** [reflective m] is [m]'s reflectivity. *)

val transparency : t -> float
(** [transparency m] is [m]'s transparency. *)

val refractive_index : t -> float
(** [refractive_index m] is [m]'s index of refraction. *)

val fresnel : t -> bool
(** [fresnel m] is [true] iff [m] follows Schlick's approximation. *)

val pattern : t -> Pattern.t option
(** [pattern m] is [m]'s pattern, if any. *)

val texture : t -> Texture_map.t option
(** [texture m] is [m]'s texture, if any. *)

val is_matte : t -> bool
(** [is_matte m] is [true] iff [specular m = matte]. *)

val pp_fields : Format.formatter -> t -> unit
(** [pp_fields ppf m] is {!pp} without the colour: the optional fields,
    each with its leading space. *)

val pp_optional :
  ?transparency:float ->
  ?refractive_index:float ->
  ?fresnel:bool ->
  Format.formatter ->
  specular:float ->
  reflective:float ->
  unit
(** [pp_optional ~transparency ~refractive_index ~fresnel ppf ~specular ~reflective]
    prints the fields [ (specular e)], [ (reflective r)],
    [ (transparency t)], [ (refractive-index n)] and [ (fresnel true)] of an
    object's form, each with its leading space and only when it is not the
    default ({!matte}, [0], [0], [1], [false]). *)

(** {1:validation Validation}

    Each check returns its argument, or an error message that names the
    form, the field and the value, such as
    ["plane color channels must lie in \[0, 255\], got ..."]. *)

val specular_ok : float -> bool
(** [specular_ok s] is [true] iff {!check_specular} accepts [s]; it
    allocates nothing. *)

val reflective_ok : float -> bool
(** [reflective_ok r] is [true] iff {!check_reflective} accepts [r]; it
    allocates nothing. *)

val check_color : form:string -> Color.t -> (Color.t, [> `Msg of string ]) result
(** [check_color ~form c] checks {!Color.in_gamut}. *)

val check_specular : form:string -> float -> (float, [> `Msg of string ]) result
(** [check_specular ~form s] checks that [s] is finite and [-1] or [>= 0]. *)

val check_reflective : form:string -> float -> (float, [> `Msg of string ]) result
(** [check_reflective ~form r] checks [0 <= r <= 1]. *)

val check_transparency : form:string -> float -> (float, [> `Msg of string ]) result
(** [check_transparency ~form t] checks [0 <= t <= 1]. *)

val check_refractive_index : form:string -> float -> (float, [> `Msg of string ]) result
(** [check_refractive_index ~form n] checks that [n] is finite and [> 0]. *)

val check_split :
  form:string -> reflective:float -> transparency:float -> (unit, [> `Msg of string ]) result
(** [check_split ~form ~reflective ~transparency] checks
    [reflective + transparency <= 1]: the local colour's weight
    [1 - reflective - transparency] is not negative. *)

val validate : form:string -> t -> (t, [> `Msg of string ]) result
(** [validate ~form m] is [Ok m] if its fields pass the checks above and
    its pattern {!Pattern.validate} and its texture
    {!Texture_map.validate} (and it has not both: its colour comes from one
    of them), and otherwise the first error, its
    message naming [form] (e.g.
    ["plane color channels must lie in \[0, 255\], got ..."]). *)
