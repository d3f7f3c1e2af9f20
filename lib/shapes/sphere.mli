(** Spheres (document sections 5 and 6.1).

    A sphere is the set of points [P] with [<P - C, P - C> = r^2], made of
    a {!Material.t} like every other object. *)

(** {1:spheres Spheres} *)

type t = private {
  center : Vec3.t;  (** [C], in world units. *)
  radius : float;  (** [r > 0], in world units. *)
  material : Material.t;
}
(** The type for spheres: read its fields, make one with {!v}. *)

val v : center:Vec3.t -> radius:float -> Material.t -> t
(** [v ~center ~radius m] is the sphere of center [center] and radius
    [radius] made of [m]. It is not validated: see {!validate} ([radius > 0]
    and finite, the center within {!Limits}). *)

val center : t -> Vec3.t
(** [center s] is [C], in world units. *)

val radius : t -> float
(** [radius s] is [r], in world units. *)

val material : t -> Material.t
(** [material s] is the material of [s]. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf s] prints [s] as its [sphere] form in the scene-file syntax,
    the material's optional fields only when they are not the defaults
    ({!Material.pp}). *)

val show : t -> string
(** [show x] is [x] formatted by {!pp}. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] have equal centers, radii and
    materials, floats compared with [=]. *)

val matte : float
(** [matte] is {!Material.matte}. *)

val is_matte : t -> bool
(** [is_matte s] is {!Material.is_matte} of [s]'s material. *)

(** {1:validation Validation}

    Each check returns its argument, or an error message that names the
    field and the value, such as ["sphere radius must be > 0, got -1"]. *)

val check_center : Vec3.t -> (Vec3.t, [> `Msg of string ]) result
(** [check_center c] checks {!Limits.check_point}. *)

val check_radius : float -> (float, [> `Msg of string ]) result
(** [check_radius r] checks [Limits.min_size <= r <= Limits.max_coordinate]. *)

val check_color : Color.t -> (Color.t, [> `Msg of string ]) result
(** [check_color c] checks {!Color.in_gamut} ({!Material.check_color}, naming [sphere]). *)

val check_specular : float -> (float, [> `Msg of string ]) result
(** [check_specular s] checks that [s] is finite and [-1] or [>= 0]. *)

val check_reflective : float -> (float, [> `Msg of string ]) result
(** [check_reflective r] checks [0 <= r <= 1]. *)

val extent : t -> float
(** [extent s] is [max |c_x| |c_y| |c_z| + r]: no coordinate of a point
    of [s] is larger in magnitude (for [Pattern.store]). *)
val check_transparency : float -> (float, [> `Msg of string ]) result
(** [check_transparency t] checks [0 <= t <= 1]. *)

val check_refractive_index : float -> (float, [> `Msg of string ]) result
(** [check_refractive_index n] checks that [n] is finite and [> 0]. *)

val check_split : reflective:float -> transparency:float -> (unit, [> `Msg of string ]) result
(** [check_split ~reflective ~transparency] checks
    [reflective + transparency <= 1]: the local colour's weight
    [1 - reflective - transparency] is not negative. *)

val validate : t -> (t, [> `Msg of string ]) result
(** [validate s] is [Ok s] if its center, its radius and its material
    ({!Material.validate}) pass their checks, and otherwise the first
    error. *)

(** {1:geometry Geometry} *)

val quadratic : t -> origin:Vec3.t -> direction:Vec3.t -> float * float * float
(** [quadratic s ~origin:o ~direction:d] is [(a, b, c)] of section 6.1,
    whose roots [t] are where the ray [P = O + t D] meets [s]:
    [a = <D, D>], [b = 2 <CO, D>], [c = <CO, CO> - r^2] with [CO = O - C]. *)

val textbook_roots : float -> float -> float -> float * float
(** [textbook_roots a b c] is [(t1, t2)] with
    [t1,2 = (-b +- sqrt (b^2 - 4ac)) / 2a], the document's formula, or
    [(infinity, infinity)] when the discriminant is negative. It loses
    digits when [b^2] is much larger than [4ac] and when the discriminant is
    small: it is here as the document's formula, not for robust use. *)

val roots : t -> origin:Vec3.t -> direction:Vec3.t -> float * float
(** [roots s ~origin:o ~direction:d] is [(t_near, t_far)], [t_near <= t_far],
    the parameters where the ray [P = O + t D] meets [s], or
    [(infinity, infinity)] if it misses; a tangent ray gives a double root.
    It avoids the two cancellations of the textbook formula (Ray Tracing
    Gems, chapter 7): the discriminant is [r^2 - |l|^2], where
    [l = CO - (<CO, D> / <D, D>) D] is computed as a vector from the center
    to the line (not as a difference of two large squares), factored as
    [(r - |l|)(r + |l|)]; and the root that is not the sum of like signs is
    taken as [c / q] rather than by subtracting nearly equal numbers.

    Accuracy (checked by the test suite in exact rational arithmetic on
    rays and spheres across 24 orders of magnitude): every root [t] puts
    the exact point [O + t D] within [16 u (|O - C| + r)] of the sphere's
    surface, [u = 2^-53], even for spheres 1e7 times smaller than their
    distance and for grazing rays; and a ray reported as a miss passes no
    closer to the center than [r - 16 u (|O - C| + r)]. The textbook
    formula's error on the same cases reaches the size of the sphere. *)

val normal : t -> Vec3.t -> Vec3.t
(** [normal s p] is the outward unit normal [(P - C) / |P - C|] at a point
    [p] of the surface of [s], computed as [(P - C) * (1 / |P - C|)] as in
    CGFS. *)
