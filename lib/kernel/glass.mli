(** The ray tree, for scenes with transparency ({!Ray_tree} describes its
    storage). A hit's colour is [local (1 - r - t) + reflected wr +
    refracted wt], with [wr = r + t R] and [wt = t (1 - R)], [R] the
    reflectance ([0] without Fresnel, [1] on total internal reflection,
    so that it folds into the reflected part). Opaque hits ([t = 0]) take
    the floating-point operations of {!Chain}, so a transparent object
    changes nothing where it is not seen. Surfaces that change nothing
    (transparency 1, the same index on both sides) are crossed on the
    same ray. With the skips, a child whose colour cannot change a byte is
    not traced ({!Byte_exact.settled_tree}). *)

val trace_tree : Tracer.t -> unit
(** [trace_tree tr] traces the camera ray in [tr]'s per-ray record and
    leaves its colour in [s.r], [s.g], [s.b].
    @raise Limits.Work_exceeded when the work budget runs out: checked
    at every hit, since without the early stop a tree of depth 64 may have
    2{^64} rays. *)
