(** Patterns: a second colour laid over an object's own.

    The one pattern is the checker, a 3-D checkerboard of cubic cells of
    side [size]: a point lies in the cell [(floor (x / size), floor (y /
    size), floor (z / size))], and the cells whose three indices sum to an
    odd number take the pattern's colour, the others the object's. The
    coordinates are world coordinates for spheres, planes and triangles,
    and object coordinates for boxes (relative to the box's [min] corner)
    and meshes (the file's coordinates, before the mesh's [scale] and
    [translate]). On a transformed object they are the object's own, in
    its frame before the transform (the cells move, turn and scale with
    it); a transform's or use's own material lays its pattern where the
    object's own would lie.

    Which cell a hit point belongs to, on a cell boundary: the point
    looked up is not the hit point [P] as computed but [Q = P + e N],
    moved off the surface toward the side the ray comes from ([N] the
    unit normal the shading uses, turned to face the ray) by twice the
    bound on [P]'s rounding error, [e = 64 u (|O|_1 + |P|_1 + extent)]
    ([u = 2^-53], [O] the ray's origin, [extent] the largest coordinate
    of the object: the tracer's bound for secondary rays).
    So a plane that lies exactly on a boundary, such as [y = -1] with
    [size 1], shows one cell's colour everywhere on the side the camera
    sees (seen from above, the cell above the plane: index [-1]), where
    the rounded hit points would otherwise fall on either side at random.
    Boundaries across a surface are real edges of the picture: the
    renderer's samples ([--samples]) anti-alias them.

    @canonical Raytrace.Pattern *)

(** {1:patterns Patterns} *)

type t = private Checker of { color : Color.t; size : float }
(** The type for patterns, made by {!checker}: [Checker {color; size}] alternates [color]
    (channels in [\[0, 255\]]) with the object's colour in cells of side
    [size > 0] (in the object's coordinates). *)

val checker : size:float -> Color.t -> t
(** [checker ~size color] is [Checker {color; size}]. *)

val color : t -> Color.t
(** [color p] is the second colour of [p]. *)

val size : t -> float
(** [size p] is the side of [p]'s cells. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] are equal field by field, floats
    compared with [=]. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf p] prints [p] as the field of an object's form in the
    scene-file syntax: [(pattern checker (color r g b) (size s))]. *)

val pp_optional : Format.formatter -> t option -> unit
(** [pp_optional ppf p] prints nothing for [None], and a space then {!pp}
    for [Some p]: the last field of an object's form. *)

(** {1:validation Validation} *)

val check_size : form:string -> float -> (float, [> `Msg of string ]) result
(** [check_size ~form s] checks {!Limits.check_size}, its message naming
    [form] (["sphere pattern size must be > 0, got 0"]). *)

val validate : form:string -> t -> (t, [> `Msg of string ]) result
(** [validate ~form p] is [Ok p] if its colour is in gamut and its size
    passes {!check_size}, and otherwise the first error, naming [form]. *)

(**/**)

(* Internal: the kernel's side of this module, for the tracer and the tests, hidden from the documentation. Not for users: it changes without notice. *)

(** {1:kernel For the tracers} *)

val stride : int
(** [stride] is [6], the floats per pattern in a table written by
    [store]. *)

val store : t -> origin:Vec3.t -> scale:float -> extent:float -> float array -> int -> unit
(** [store p ~origin ~scale ~extent table o] writes, at offset [o] of
    [table], what [odd] needs to look [p] up on one object: the object's
    coordinates of a world point [W] are [(W - origin) / scale], and
    [extent] is the largest magnitude of a coordinate of the object (in
    world units, for the error bound). *)

val store_frame : origin:Vec3.t -> scale:float -> extent:float -> float array -> int -> unit
(** [store_frame ~origin ~scale ~extent table o] writes the object's frame
    as [store] does, and not the pattern's size: the frame of a material
    with no pattern of its own, in a bottom level of instances, whose
    instances may give it one. *)

val frame : float array -> int -> Vec3.t * float * float
(** [frame table o] is the [(origin, scale, extent)] that [store] or
    [store_frame] wrote at offset [o] of [table]. *)

val odd : Scratch.t -> float array -> int -> bool
(** [odd s table o] is [true] iff the pattern stored at offset [o] of
    [table] gives the hit point in [s] its second colour: [s]'s fields
    [px, py, pz] hold the hit point [P] as computed, [nx, ny, nz] the unit
    normal (either side), [ox, oy, oz] and [dx, dy, dz] the ray. The cell
    is that of the point [Q] of the module's introduction. It reads [s]
    and writes nothing, and allocates nothing. *)
