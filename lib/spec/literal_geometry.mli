(** The oracle's geometry: every shape's roots, normals, inside tests,
    CSG membership and mesh parity, the refraction of glass and the cells
    of patterns, computed from the definitions for {!Literal}.

    Nothing here calls a routine of the kernel: it reads the scene types'
    data (vertices, centers, corners, materials), and uses {!Vec3} and
    {!Exact_float}. Where a comparison decides a pixel (which side of a
    triangle's edge a line passes, whether a line meets a box or is
    parallel to a plane, the order of two crossings of a CSG solid's boxes
    and meshes, the order of two objects' hits) it is exact:
    a float filter with a proven error bound, and exact arithmetic where
    the filter cannot decide. Boxed vectors, lists and options: slow on
    purpose. *)

(** {1:exact Crossing parameters} *)

type key = {
  t : float;  (** The parameter, rounded. *)
  lo : float;  (** The exact parameter is at least [lo]. *)
  hi : float;  (** and at most [hi]. *)
  num : Exact_float.t Lazy.t;  (** Its numerator, exact. *)
  den : Exact_float.t Lazy.t;  (** Its denominator, exact, not zero. *)
}
(** The type for parameters [t] along a ray, known exactly as a fraction
    of exact values (a box's and a triangle's are rational functions of
    the float inputs; a sphere's is its rounded float). *)

val key_of_float : float -> key
(** [key_of_float x] is the parameter [x], exactly. *)

val in_range : continued:bool -> t_min:float -> t_max:float -> key -> bool
(** [in_range ~continued ~t_min ~t_max k] is [t_min < k], exactly (the
    document's range is strict: a surface met at exactly [t = 1] is not
    seen by the camera), and [k.t < t_max] on [k]'s rounded parameter
    (a shadow ray's [t_max] is its light's [t = 1], which the rounded
    direction [L - P] reaches only within its rounding); with
    [continued] (a ray continued from a hit whose rounded parameter is
    [t_min]), also [t_min < k.t], so that the ray does not meet that
    surface there again, as it would where the exact parameter lies above
    its rounding. *)

val from_origin : computed:bool -> Vec3.t -> (unit -> 'a) -> 'a
(** [from_origin ~computed o f] is [f ()], with the searches it makes
    from the origin [o] counted in {!undecided}'s [near] also where the
    line passes a triangle's edge within [64u max |o_i|] of [o] (per
    coordinate) of it, if [computed]: the origin of a ray from a hit point,
    which the kernel computes from its own rounded parameter, may lie that
    far from the oracle's, on the edge's other side. A camera ray's origin
    is the camera's own value ([computed] false). *)

val undecided : unit -> int * int
(** [undecided ()] is [(near, ties)], counts so far of decisions the
    float filter could not make: [near], those exact arithmetic made
    non-zero (a line within rounding of a triangle's edge or vertex, two
    parameters within rounding of each other, off them), and [ties], a
    line exactly through a triangle's edge (not parallel to it, its
    origin off the triangle's plane). Exact ties of two parameters (CSG
    operands sharing a face, a line through a box's edge) are not
    counted: they hold wherever the line's origin is. {!odd} counts in
    [near] a point within rounding of a checker cell's boundary. The
    kernel's float tests decide near cases only up to their rounding, and
    ties of a ray from a rounded point ({!Literal.rounding_dependent}). *)

val compare_keys : key -> key -> int
(** [compare_keys a b] is the sign of [a - b], exact: by the enclosures
    where they do not overlap, else by {!Exact_float.compare_fractions}. *)

(** {1:spheres Spheres} *)

val sphere_textbook_roots : Sphere.t -> origin:Vec3.t -> direction:Vec3.t -> float * float
(** [sphere_textbook_roots s ~origin ~direction] is section 6.1's
    [((-b + sqrt disc) / 2a, (-b - sqrt disc) / 2a)] with [a = <D, D>],
    [b = 2 <CO, D>], [c = <CO, CO> - r^2], [disc = b^2 - 4ac], in the
    CGFS demos' order of operations; [(infinity, infinity)] if
    [disc < 0]. *)

val sphere_roots : Sphere.t -> origin:Vec3.t -> direction:Vec3.t -> (float * float) option
(** [sphere_roots s ~origin ~direction] is [Some (t0, t1)], [t0 <= t1],
    where the line meets [s], by Ray Tracing Gems' cancellation-free
    formula (chapter 7): the discriminant from the distance [|l|] of the
    center to the line as [a (r - |l|) (r + |l|)], the root of like signs
    [q / a] and the other [c / q]; [None] if [|l| > r]. *)

val sphere_normal : Sphere.t -> Vec3.t -> Vec3.t
(** [sphere_normal s p] is [(p - c) * (1 / |p - c|)], outward, as CGFS. *)

(** {1:planes Planes and triangles} *)

val plane_key : Plane.t -> origin:Vec3.t -> direction:Vec3.t -> key option
(** [plane_key p ~origin ~direction] is where the line meets the plane:
    exactly [<P0 - O, n> / <D, n>] for [p]'s normal [n] as given, in floats
    with the unit normal; [None] if [<D, n> = 0] exactly or the float
    quotient is not finite. *)

val plane_normal : Plane.t -> Vec3.t
(** [plane_normal p] is [p]'s normal divided by its length. *)

val triangle_key : origin:Vec3.t -> direction:Vec3.t -> Vec3.t -> Vec3.t -> Vec3.t -> key
(** [triangle_key ~origin ~direction a b c] is the parameter where the
    line meets the plane of [a b c]: [<A - O, n> / <D, n>],
    [n = (B - A) x (C - A)], its enclosure from the rounding bounds of
    each step. *)

val triangle_hit : origin:Vec3.t -> direction:Vec3.t -> Vec3.t -> Vec3.t -> Vec3.t -> key option
(** [triangle_hit ~origin ~direction a b c] is {!triangle_key} if the line
    meets the closed triangle (as {!triangle_root} decides) and its float
    is finite, [None] otherwise. *)

val triangle_root : origin:Vec3.t -> direction:Vec3.t -> Vec3.t -> Vec3.t -> Vec3.t -> float
(** [triangle_root ~origin ~direction a b c] is the [t] of {!triangle_key}
    if the line meets the closed triangle [a b c] (its edges and corners
    included), [infinity] if not or if the line is parallel to its plane:
    each edge function [det\[P - O, Q - O, D\]] of the edges [b c], [c a],
    [a b] has, exactly, the sign of [det\[B - A, C - A, D\]] or is zero. *)

val triangle_crossing : origin:Vec3.t -> direction:Vec3.t -> Vec3.t -> Vec3.t -> Vec3.t -> bool
(** [triangle_crossing ~origin ~direction a b c] is [true] iff the line,
    moved off every edge and vertex by an infinitesimal [e d1 + e^2 d2]
    ([d1], [d2] the two coordinate axes after the largest of [D], fixed for
    the ray), crosses the triangle: the edge functions' signs, taken from
    their first nonzero term in [e], all equal the triangle's. Of the
    triangles of a closed mesh that share an edge or a vertex a line passes
    through, exactly one counts it where the surface crosses the line
    (two or none where it folds back): the mesh's parity is watertight. *)

val triangle_normal : Vec3.t -> Vec3.t -> Vec3.t -> Vec3.t
(** [triangle_normal a b c] is the unit vector along [(b - a) x (c - a)]. *)

val smooth_normal : Vec3.t -> Vec3.t -> Vec3.t -> Vec3.t * Vec3.t * Vec3.t -> Vec3.t -> Vec3.t option
(** [smooth_normal a b c (na, nb, nc) p] is the corners' unit normals
    weighted by [p]'s barycentric coordinates (signed areas of the
    sub-triangles over the triangle's), divided by its length; [None] if
    that length is [0] or not finite. *)

(** {1:boxes Boxes} *)

type box_hit = {
  enter : key;  (** Where the line enters the box. *)
  enter_normal : Vec3.t;  (** The outward normal of the face entered. *)
  exit : key;  (** Where it leaves it, [>= enter]. *)
  exit_normal : Vec3.t;  (** The outward normal of the face left. *)
}
(** The type for a line's meeting with a box. *)

val box_hit : Box.t -> origin:Vec3.t -> direction:Vec3.t -> box_hit option
(** [box_hit b ~origin ~direction] is where the line meets the closed box
    [b] (a line touching an edge or a corner meets it, [enter = exit]):
    the largest of the slabs' entries and the smallest of their exits,
    compared exactly; the face of the axis that decides, the first axis
    of equals. [None] if the line misses it. *)

(** {1:csg CSG solids} *)

val leaves : Csg.t -> Csg.solid list
(** [leaves c] is the leaves of [c], left to right; one that a
    transformed operand's material covers wrapped in an identity
    placement with that material. *)

type csg_hit = {
  key : key;  (** The parameter of the hit. *)
  leaf : Csg.solid;  (** The leaf whose surface is hit. *)
  normal : Vec3.t;  (** The solid's outward unit normal there. *)
  entering : bool;  (** [true] iff the ray enters the solid there. *)
}
(** The type for hits on CSG solids. *)

val csg_hit :
  ?continued:bool ->
  tested:(int -> unit) ->
  into:(Transform.t -> Vec3.t -> Vec3.t -> Vec3.t * Vec3.t) ->
  out:(Transform.t -> Vec3.t -> Vec3.t) ->
  Csg.t ->
  origin:Vec3.t ->
  direction:Vec3.t ->
  t_min:float ->
  t_max:float ->
  csg_hit option
(** [csg_hit ~continued ~tested c ~origin ~direction ~t_min ~t_max] is the
    first crossing of [c]'s surface beyond [t_min], if it is before
    [t_max] ({!in_range}'s comparisons), if any: every crossing of every leaf along the whole line (a sphere's
    or a box's interval of positive length, a closed mesh's crossings by
    {!triangle_crossing}), in exact order (a sphere's ends as their
    floats), classified by [c]'s boolean expression on the leaves just
    before and just after it; of crossings at the same parameter, the
    leftmost leaf's. [tested n] is called for every [n] tests done (one
    per sphere or box leaf, one per mesh triangle) before they are done;
    an exception it raises stops the search and passes through. A leaf
    inside transformed operands is crossed by the line [into tr o d]
    carries into its frame through each, outermost first (the caller's
    own matrices; [t] is the same number in every frame), and its normal
    is brought back by [out tr n] through each, innermost first. *)

(** {1:patterns Patterns} *)

val odd :
  Pattern.t -> frame:Vec3.t * float * float -> origin:Vec3.t -> direction:Vec3.t -> point:Vec3.t -> normal:Vec3.t -> bool
(** [odd p ~frame:(o, scale, extent) ~origin ~direction ~point ~normal] is
    [true] iff the point [Q = P + e N], moved toward the side the ray comes
    from by [e = 64 u (|O|_1 + |P|_1 + extent)], lies in a cell of
    [p]'s checkerboard whose indices [floor ((Q - o) / scale / size)] sum
    to an odd number (docs/scene-format.md, Patterns). *)

(** {1:glass Refraction} *)

type split = {
  refracted : Vec3.t option;  (** The refracted direction, [None] on total internal reflection. *)
  reflectance : float;  (** [R], the share of the transparent part reflected. *)
}
(** The type for the split of a ray at a transparent surface. *)

val split : n1:float -> n2:float -> fresnel:bool -> direction:Vec3.t -> normal:Vec3.t -> split
(** [split ~n1 ~n2 ~fresnel ~direction ~normal] is the split of a ray along
    [direction] from index [n1] into [n2] at a surface of unit [normal]
    facing the ray: between equal indices the ray goes on unchanged and
    [R = 0]; otherwise, with [d] the unit direction, [c = -<d, n>]
    (clamped to [\[0, 1\]]), [eta = n1 / n2] and
    [sin^2 t = eta^2 (1 - c) (1 + c)]: total internal reflection
    ([R = 1]) when [sin^2 t >= 1], else the direction
    [eta d + (eta c - cos t) n] and [R] Schlick's
    [R0 + (1 - R0) (1 - x)^5], [R0 = ((n1 - n2) / (n1 + n2))^2], [x] the
    cosine on the side of the lower index, when [fresnel], [0] if not. *)
