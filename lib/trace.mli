(** The fast tracer: the document's algorithm on a {!Prepared.t} scene,
    allocating nothing per ray.

    It computes the same floating-point operations in the same order as
    {!Literal}, so it produces the same bytes; it only skips work whose
    result provably cannot change them (see {!Prepared.prepare}). Rays,
    hit points and colours live in a mutable all-float record (stored
    unboxed), hits are returned as sphere indices ([-1] for none), and
    reflection is a loop over a small stack instead of recursion, because
    in OCaml 4.13 without flambda a float crossing a function call that is
    not inlined is boxed. *)

type counters = {
  mutable primary : int;  (** Primary rays cast. *)
  mutable shadow : int;  (** Shadow rays cast. *)
  mutable reflection : int;  (** Mirror rays cast. *)
  mutable tests : int;  (** Ray-sphere intersection tests. *)
  mutable box_tests : int;  (** Ray-box tests in the sphere hierarchy. *)
  mutable early_stops : int;  (** Reflections stopped by the weight bound. *)
}
(** The type for work counters. *)

type t
(** The type for tracers: a prepared scene and the scratch space of one
    process. A tracer is not reentrant. *)

val create : Prepared.t -> t
(** [create p] is a tracer for [p] with zeroed counters. *)

val prepared : t -> Prepared.t
(** [prepared tr] is the scene [tr] traces. *)

val counters : t -> counters
(** [counters tr] are the work counters of [tr], updated by every call. *)

val pixel : t -> int -> int -> unit
(** [pixel tr gx gy] traces the primary ray through canvas pixel
    [(gx, gy)] (centered coordinates, {!Canvas}) from the camera, [t > 1],
    with the scene's recursion depth (section 8). The unclamped colour is
    then in {!red}, {!green} and {!blue}, and {!store} writes it. *)

val sample : t -> int -> int -> i:int -> j:int -> n:int -> unit
(** [sample tr gx gy ~i ~j ~n] is {!pixel} for the point
    [(gx + (i + 1/2) / n - 1/2, gy + (j + 1/2) / n - 1/2)], sample [(i, j)]
    of a regular [n x n] grid centered on the pixel ([i] to the right, [j]
    up, both in [\[0, n)]). [sample tr gx gy ~i:0 ~j:0 ~n:1] is exactly
    [pixel tr gx gy]. *)

val store : t -> Image.buffer -> int -> unit
(** [store tr buf k] writes the colour of the last {!pixel}, each channel
    clamped and rounded by the rule of {!Color.to_byte}, to bytes [k],
    [k + 1] and [k + 2] of [buf]. [k] is not bounds-checked: callers pass
    [k = 3 * (y * width + x)] of a pixel inside the image. *)

val to_byte : float -> int
(** [to_byte] is {!Color.to_byte}: a copy kept in this module so that the
    per-ray path passes no float across modules. *)

val cast : t -> from:int -> Vec3.t -> Vec3.t -> int
(** [cast tr ~from origin direction] is the sphere that the secondary ray
    [origin + t direction] leaving sphere [from] ([-1]: none) meets first
    with [t > epsilon] (the scene's epsilon, or [0] in the robust mode, where
    [from] is handled exactly: the ray can meet it only by going into it),
    or [-1] if it meets none: the test behind shadow and mirror rays. *)

val red : t -> float
(** [red tr] is the red channel of the last {!pixel}, unclamped. *)

val green : t -> float
(** [green tr] is the green channel of the last {!pixel}, unclamped. *)

val blue : t -> float
(** [blue tr] is the blue channel of the last {!pixel}, unclamped. *)

val hit_sphere : t -> int
(** [hit_sphere tr] is the index of the sphere the primary ray of the last
    {!pixel} hit, or [-1] if it hit nothing. *)
