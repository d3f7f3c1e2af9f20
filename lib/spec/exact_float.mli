(** Exact arithmetic on floats, for the oracle's decisions.

    A value is a finite sum of floats, held exactly: sums and products of
    floats are formed without rounding by error-free transformations
    (Knuth's two-sum; the two-product [a * b = p + e] with
    [e = Float.fma a b (-p)]), and a sum is reduced to a nonoverlapping
    expansion (Shewchuk, "Adaptive Precision Floating-Point Arithmetic and
    Fast Robust Geometric Predicates", 1997), whose largest component
    carries the sign of the exact value. {!Literal} decides with it
    every comparison of its geometry that a pixel depends on (which side
    of a triangle's edge a ray passes, whether a ray meets a box, the
    order of crossings along a ray). It allocates lists: it is slow on
    purpose and used only where a float filter cannot decide.

    Exactness holds while no partial product underflows or overflows: for
    the oracle's polynomials (degree 6 at most) in coordinates of
    magnitude below [1e12] ({!Limits.max_coordinate}), and differences of
    coordinates either [0] or above about [1e-40] in magnitude.

    @canonical Raytrace.Private.Exact_float *)

type t
(** The type for exact values: sums of floats.

    @canonical Raytrace.Private.Exact_float.t *)

val of_float : float -> t
(** [of_float x] is [x], exactly. [x] must be finite. *)

val diff : float -> float -> t
(** [diff a b] is [a - b], exactly. *)

val add : t -> t -> t
(** [add a b] is [a + b], exactly. *)

val sub : t -> t -> t
(** [sub a b] is [a - b], exactly. *)

val mul : t -> t -> t
(** [mul a b] is [a * b], exactly. *)

val sign : t -> int
(** [sign a] is [-1], [0] or [1], the sign of [a]'s exact value. *)

val approx : t -> float
(** [approx a] is the largest component of [a]: the others, each below
    the next one's last bit, sum to less than two of its units in the last
    place, so [approx a] is within [2u |approx a|] of [a]'s value ([u] the
    unit roundoff), with its sign. *)

val compare_fractions : t -> t -> t -> t -> int
(** [compare_fractions n1 d1 n2 d2] is the sign of [n1 / d1 - n2 / d2],
    exactly. [d1] and [d2] must not be zero. *)
