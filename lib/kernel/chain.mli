(** The general loop (section 7.8 of the document as a loop): each level
    traces one ray; a reflective hit pushes its local colour and
    reflectivity on {!Tracer.t}'s [stack] and continues with the mirror
    ray; then the stack is folded back from the deepest colour, blend by
    blend, in the order of the document's recursion. It stops early, with
    the skips, once the colour still to be traced cannot change a byte
    ({!Byte_exact.settled}). For every opaque scene but the document's
    kind with the skips on ({!Textbook}). *)

val trace_spheres : Tracer.t -> unit
(** [trace_spheres tr] traces the ray in [tr]'s per-ray record through a
    scene of spheres alone ({!Prepared.t}'s [all_spheres]), and leaves its
    colour in [s.r], [s.g], [s.b]; no object's kind or pattern is asked. *)

val trace_objects : Tracer.t -> unit
(** [trace_objects tr] is {!trace_spheres} for a scene of any objects. *)
