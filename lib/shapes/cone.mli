(** Cones: the points whose distance from the segment [base]-[top] of the
    axis is at most the radius at their height, which runs linearly from
    [radius] at the base to [top_radius] at the top (either 0 for a
    point; equal radii make a cylinder). A capped cone is the solid,
    closed by its two disks (a CSG operand, a glass medium); an open one
    is its side alone, seen from both sides.

    Scene text (docs/scene-format.md):
    [(cone (base 0 0 5) (top 0 2 5) (radius 0.5) (top-radius 0) (capped true) (color 200 50 50))],
    [capped] [true] unless written.

    {b The kernel's roots and their bound.} {!roots} works relative to the
    base [B] with the axis [a = T - B] as stored ([|a|^2 = hh]): it first
    moves the ray's origin along the ray to its closest approach to [B]
    (the parameter [tc]), so that everything after has the cone's scale
    and not the ray's length; then finds the slab [0 <= w.a <= hh]
    between the caps' planes, and the side's quadratic
    [|p + tau q|^2 = (rho0 + tau rhod)^2] in the parts [p], [q] of the
    moved origin and the direction across the axis, by the stable
    formula ([q = -(B + sign(B) sqrt disc)], roots [C / q] and [q / A]).
    Near a double root (a line by the apex, or grazing the side) the
    roots move by the square root of the coefficients' error, which has
    the scale of the point they were found at: the quadratic is solved
    again from the middle of the chord (when that is near the slab),
    where [C] is small and exact to that point's rounding; where [A > 0]
    and the discriminant found there is negative, the line misses (the
    first one's sign was noise: a tangent point [-B / A] by the apex can
    lie off the surface by far more than the bound), unless it is within
    [A] times the rounding of [C] there of 0: a tangent line, whose
    double root's point is then within [16 u (|w| + |r0| + |dr|)] of the
    side (a line in a tangent plane of the side touches it, as
    [literal] decides exactly). Where [A > 0] and the first discriminant
    is negative within a bound of its rounding, the roots are found again
    from [-B / A], the line's closest approach to the side, as a tangent
    line's first discriminant is noise of either sign. A double root is
    [-B / A], not [C / q]. For a capped cone the entry and exit are the slab's part of the
    line's part inside the cone (between the roots where [A > 0]; where
    [A < 0] the line crosses both nappes of the double cone and the part
    is the half-line on the nappe of positive radius, the only one in
    the slab); an open cone's crossings are the side's roots inside the
    slab. Each coefficient has an absolute error of a few [u] times the
    square of the cone's and the moved origin's scale, and the moved
    origin lies within a few [u (|O| + |P| + extent)] of the line: the
    exact point [O + t D] of each root returned lies within
    [32 u (|O| + |P| + extent)] of the surface it was found on, at any
    scale and any angle ([extent] the largest stored float's magnitude,
    as the kernel's surfaces ([Surface]) offset the robust mode's
    secondary rays by twice that: they never see the surface they leave).
    test/test_cone.ml checks the bound in exact rational arithmetic, at
    scales 1e-6..1e6, translated by 1e6, for grazing rays and for rays
    through rims and the apex (docs/numerics.md, "Cones", says what it
    measured).

    {b Apex.} At the point of a pointed cone the side's normal is
    undefined: {!normal} gives the axis's direction out of the point.

    @canonical Raytrace.Private.Cone *)

type t = private {
  base : Vec3.t;  (** The centre of the base's disk. *)
  top : Vec3.t;  (** The centre of the top's disk; never [base]. *)
  radius : float;  (** The radius at the base, [>= 0]. *)
  top_radius : float;  (** The radius at the top, [>= 0]; not both 0. *)
  capped : bool;  (** Whether the two disks close the cone into a solid. *)
  material : Material.t;  (** The cone's material. *)
}
(** The type for cones. *)

val v : ?capped:bool -> base:Vec3.t -> top:Vec3.t -> radius:float -> top_radius:float -> Material.t -> t
(** [v ~capped ~base ~top ~radius ~top_radius m] is the cone of axis
    [base]-[top], of radius [radius] at the base and [top_radius] at the
    top, closed by its disks iff [capped] (default [true]); not
    validated ({!validate}). *)

val validate : t -> (t, [ `Msg of string ]) result
(** [validate c] is [Ok c] if its points are within {!Limits}, each
    radius is 0 or a size {!Limits.check_size} accepts, not both are 0,
    [base] and [top] are at least {!Limits.min_size} apart and its
    material is valid; otherwise [Error] with the message. *)

val equal : t -> t -> bool
(** [equal a b] is exact equality (floats by [=]). *)

val pp : Format.formatter -> t -> unit
(** [pp] prints a cone as its scene-text form, every field written. *)

val store : t -> float array -> int -> unit
(** [store c g o] writes [c]'s 9 floats of geometry at [g.(o)]: base,
    top, radius, top radius, [1.] if capped ([0.] if open). *)

val roots : Scratch.t -> float array -> int -> bool
(** [roots s g o] is the kernel's test of the ray in [s] against the cone
    stored at [g.(o)]: [true] with its crossings [s.near <= s.far] (a
    capped cone's entry and exit; an open cone's first and last crossing
    of its side, equal if there is one), or [false] with both
    [infinity]. Allocates nothing. *)

val normal : Scratch.t -> float array -> int -> unit
(** [normal s g o] is the outward unit normal, in [s.nx, s.ny, s.nz], at
    the point [s.px, s.py, s.pz] of the root [s.near] of the ray in [s]
    (the root kept: the traversal's [s.t], a CSG crossing), of the
    surface that {!roots} found that root on, found again for the same
    ray: the side or, if capped, a cap. A ray through a rim thus takes
    the normal of the surface it crosses there: a ray in a cap's plane
    crosses the side (never the cap, whose plane it runs in), as in
    [literal]. On a line tangent to the side the normal is turned off
    the ray where rounding leans it along it (the outside is seen). A
    root {!roots} does not give again takes the surface nearest the
    point. At the apex, the axis out of the point. [s.near] and [s.far]
    are kept. Allocates nothing. *)

val intersect : t -> origin:Vec3.t -> direction:Vec3.t -> float * float
(** [intersect c ~origin ~direction] is {!roots} on [c] alone:
    [(near, far)], or [(infinity, infinity)] for a miss (cold path). *)

val desc : t Shape_desc.t
(** [desc] is the cone's description: its scene-text form [cone], and
    [Literal]'s crossings from the definition ({!Shape_desc.t.literal}). *)
