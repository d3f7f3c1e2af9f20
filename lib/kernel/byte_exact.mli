(** Exact byte output and the exact early stop: what turns a ray's colour
    into a pixel's bytes, and the proof-carrying tests that let a chain of
    mirror rays, or a ray tree, stop once what is left to trace cannot
    change those bytes.

    The early stop rests on one argument. A pixel's colour is a
    non-decreasing function of each colour still to be traced: each blend
    is [local (1 - r) + rc r] with [r >= 0] (in the tree, [local + wr
    reflected + wt refracted] with [wr, wt >= 0]), and rounding is
    monotonic. Each unknown colour lies in [\[0, max_channel\]] (the
    brightest a channel can be, {!Prepared.t}'s [max_channel]). So if the
    blend gives the same bytes with every unknown at [0] and at
    [max_channel], it gives them for the true colours too, and tracing can
    stop. When samples are averaged, a pixel is the mean of the samples'
    clamped floats, not of their bytes: then the two extremes must clamp
    to the same float (both [>= 255], both [<= 0], or equal). Tested by
    the [sampling] and [optics] suites, with the stop on and off. *)

val to_byte : float -> int
(** [to_byte x] is {!Color.to_byte}[ x]: [x] clamped to [\[0, 255\]] and
    rounded half to even, [0] for NaN. A copy, so that no float crosses a
    module boundary on the per-ray path; a test checks the two agree. *)

val store : Tracer.t -> Image.buffer -> int -> unit
(** [store tr buffer k] writes the bytes of the colour in [tr]'s per-ray
    record at [k], [k + 1], [k + 2] of [buffer]. *)

val store_average : Tracer.t -> Image.buffer -> int -> count:int -> unit
(** [store_average tr buffer k ~count] writes the bytes of the mean of the
    [count] samples summed in [tr]'s per-ray record: {!Trace.store_average}. *)

val settled : Tracer.t -> int -> bool
(** [settled tr levels] is [true] iff the chain of mirror rays whose
    [levels] local colours and reflectivities are on [tr.stack] gives the
    same bytes (the same clamped floats when [tr] averages) whatever the
    colour still to be traced. *)

val settled_tree : Tracer.t -> int -> bool
(** [settled_tree tr l] is [true] iff the ray tree, before level [l]
    traces the child [tr.tree.tracing.(l)] names, gives the same bytes
    (the same clamped floats when [tr] averages) whatever that child and
    the refracted children still pending on the way up turn out to be,
    evaluated with the operations of the tree's blend ({!Glass}). *)
