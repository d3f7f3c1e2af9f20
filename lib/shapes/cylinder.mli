(** Cylinders: the points within [radius] of the segment's axis line
    between the planes across it at [base] and [top]. Capped (the
    default), it is that solid, closed (a CSG operand, a medium); open
    ([capped] false), it is the tube alone, seen from both sides (its
    inside shows its inner wall).

    Scene text: [(cylinder (base x y z) (top x y z) (radius r) (capped
    true) ...)], the material's fields after. *)

type t = private { base : Vec3.t; top : Vec3.t; radius : float; capped : bool; material : Material.t }
(** The type for cylinders. Read its fields, make one with {!v}. *)

val v : ?capped:bool -> base:Vec3.t -> top:Vec3.t -> radius:float -> Material.t -> t
(** [v ~capped ~base ~top ~radius m] is the cylinder of axis [base]-[top]
    and radius [radius], with its caps iff [capped] (default [true]); not
    validated. *)

val validate : t -> (t, [> `Msg of string ]) result
(** [validate c] checks the ends ({!Limits.check_point}), the radius
    ({!Limits.check_size}), that the ends are at least
    {!Limits.min_size} apart, and the material. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] are equal field by field,
    floats compared with [=]. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf c] prints [c] as its scene-text form, [(capped false)] only
    when open; it reads back as [c]. *)

val show : t -> string
(** [show c] is [c] formatted by {!pp}. *)

val desc : t Shape_desc.t
(** [desc] is the cylinder's description: its form, bounds (the box of
    its caps' circles, {!Disk.rim_extent} either side of each end, rounded
    outward),
    its stored floats and its literal crossings. *)

(**/**)

(* Internal: the kernel's side of this module, hidden from the
   documentation. Not for users: it changes without notice. *)

val solid_ends : direction:Vec3.t -> (float * Vec3.t) list -> (float * Vec3.t) list
(** [solid_ends ~direction l] is the entry and the exit, in that order,
    of a convex solid whose surfaces a line of direction [direction]
    crosses at [l] (roots with their outward normals, sorted by root;
    [[]] for none): the first and the last, but at a tie of roots (a line
    through a rim) the first of those the line goes in by (against the
    normal) and the first of those it goes out by. The capped cylinder's
    and cone's [literal] (the oracle's, cold path). *)

val store : t -> float array -> int -> unit
(** [store c g o] writes [c] at [g.(o)] (7 floats): [base], [top], and
    the radius, negated for an open cylinder. *)

val roots : Scratch.t -> float array -> int -> bool
(** [roots s g o] is [true] iff the line of the ray of [s] meets the
    cylinder stored at [g.(o)]: capped, with its entry and exit in
    [s.near <= s.far]; open, with its crossings of the tube (both, or
    one as both). Allocates nothing.

    The side is the circle of radius [r] in the plane across the axis
    [A = top - base]: the ray's [O - B] and [D] are projected there
    ([p = w - (<w, A> / |A|^2) A], [q] likewise) and the quadratic is
    solved as {!Sphere.roots} solves it: the closest approach
    [l = p - (<p, q> / <q, q>) q], the discriminant [(r - |l|)(r + |l|)],
    the root of like signs [m = -(<p, q> + sign sqrt (<q, q> (r - |l|)(r + |l|)))]
    and the other [(|p|^2 - r^2) / m]. The caps are the slab
    [0 <= <P - B, A> <= |A|^2], as a box's slab.

    Accuracy (checked by the test suite in exact rational arithmetic,
    test/test_cylinder.ml, with [u = 2^-53] and
    [S = |O - B| + |A| + r]): every root [t] puts the exact point
    [O + t D] within [16 u S] of the cylinder's surface (the side, or a
    cap's plane); and a ray is reported as a hit or a miss as the exact
    line says, unless the line passes within [16 u S] of the radius from
    the axis, or crosses a cap's plane at the side's edge: so the
    silhouette of a cylinder [1e7] times thinner than its distance is
    exact beyond that band. No constant of the scene's scale enters. *)

val normal : Scratch.t -> float array -> int -> unit
(** [normal s g o] sets [s.nx], [s.ny], [s.nz] to the outward unit normal
    at the hit point [s.px], [s.py], [s.pz] of the surface that the root
    [s.near] of the ray of [s] is on, as {!roots} finds it for the same
    ray (the side's, away from the axis, or a cap's, along it): a ray
    through the rim gets the normal of the surface its root is on. For a
    root that {!roots} does not give (a point alone, {!Shape.normal}), the
    surface nearest the point. Leaves [s.near] and [s.far] as they were.
    Allocates nothing. *)
