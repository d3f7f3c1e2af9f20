(** Triangles, watertight.

    A triangle has vertices [v0], [v1], [v2]; its normal is
    [(v1 - v0) x (v2 - v0)], normalised. It is seen from both sides:
    shading uses the normal turned toward the incoming ray.

    The intersection is the watertight test of Woop, Benthin and Wald
    ("Watertight Ray/Triangle Intersection", JCGT 2013): the vertices are
    moved into the ray's frame (origin at [O], the ray along the third
    axis after a shear), where the test is a 2-D point-in-triangle test
    of the origin by three edge functions. An edge shared by two
    triangles gives them edge functions that are exact negations (or
    equal) of each other, rounding included, since both are computed from
    the same transformed vertices: a ray through a shared edge or vertex
    hits at least one of the triangles, never slips between them. *)

(** {1:triangles Triangles} *)

type t = { v0 : Vec3.t; v1 : Vec3.t; v2 : Vec3.t; material : Material.t }
(** The type for triangles, vertices in world units. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf x] prints [x] as its form in the scene-file syntax,
    [(triangle (vertices (x y z) (x y z) (x y z)) ...)], the material's fields as {!Material.pp} prints them. *)

val show : t -> string
(** [show x] is [x] formatted by {!pp}. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] are equal field by field, floats
    compared with [=]. *)

val v : Vec3.t -> Vec3.t -> Vec3.t -> Material.t -> t
(** [v v0 v1 v2 m] is a triangle, not validated. *)

val validate : t -> (t, [> `Msg of string ]) result
(** [validate tri] checks each vertex ({!Limits.check_point}), that the
    triangle is not degenerate (its normal can be normalised: the vertices
    are not on a line) and the material. *)

(** {1:kernel The kernel's routines}

    A triangle is stored in a float array at an offset [o]: [v0] at
    [o .. o + 2], [v1] at [o + 3 .. o + 5], [v2] at [o + 6 .. o + 8]. *)

val store : t -> float array -> int -> unit
(** [store tri g o] writes [tri] to [g] at offset [o] (9 floats). *)

val shear : Scratch.t -> int
(** [shear s] writes to [s.sx] .. [s.okz] the ray of [s] in the frame of
    the triangle test and is its axes, packed ({!axis_x}, {!axis_y},
    {!axis_z}): what {!roots_at} reads, found once for all the triangles
    a ray is tested against. *)

val axis_x : int -> int
(** [axis_x a] is the axis (0 to 2) of the test's x in the axes [a] of {!shear}. *)

val axis_y : int -> int
(** [axis_y a] is the axis of the test's y. *)

val axis_z : int -> int
(** [axis_z a] is the axis of the test's z: the largest coordinate of the ray's direction. *)

val hit : Scratch.t -> float array -> int -> int -> int -> int -> int -> int -> bool
(** [hit s g o0 o1 o2 kx ky kz] is [true] iff the line of the ray of [s]
    meets the triangle whose vertices [v0], [v1], [v2] are stored at [o0],
    [o1], [o2] in [g] (3 floats each), with its root then in [s.near]
    ([s] unchanged on a miss): the tracer's test, inlined into its loops
    with its axes as constants. The arithmetic is {!roots}'s, operation
    for operation, and its bits are the same; a miss is decided from two
    edge functions of opposite signs before the third is computed.
    [s.sx] .. [s.okz] and [kx], [ky], [kz] must be {!shear}'s for the ray
    of [s]. *)

val roots_at : Scratch.t -> float array -> int -> int -> int -> int -> int -> int -> bool
(** [roots_at s g o0 o1 o2 kx ky kz] is {!hit}, with its root in [s.near]
    and [s.far] ([infinity] in both for a miss): {!roots} for a mesh's
    triangle, read where its vertices are, shared with the triangles
    around it. {!roots} is [roots_at s g o (o + 3) (o + 6) kx ky kz] with
    {!shear}'s axes. *)

val roots : Scratch.t -> float array -> int -> bool
(** [roots s g o] is [true] iff the line of the ray of [s] meets the
    triangle stored at [o] in [g] (edges and vertices included), with its
    root in [s.near] and [s.far]; [false] when it misses it or lies in its
    plane.

    Accuracy (checked by the test suite in exact rational arithmetic): with
    the exact edge functions [e(a, b) = <D, (a - O) x (b - O)>] of the
    three edges, a ray whose exact line passes inside the triangle (all
    three of one sign) is reported as a hit, and one that passes outside
    (two of opposite signs) as a miss, whenever each [e(a, b)] involved
    exceeds [64 u (|a - O| |(b - O) x D| + |b - O| |(a - O) x D|)] in
    magnitude, the rounding of the vertices moved into the ray's frame;
    and the exact point
    [O + t D] of a hit lies within [32 u (|v0 - O| + |v1 - O| + |v2 - O|)]
    of the triangle's plane ([u = 2^-53]). *)

val normal : Scratch.t -> float array -> int -> unit
(** [normal s g o] sets [s.nx], [s.ny], [s.nz] to the unit normal
    [(v1 - v0) x (v2 - v0) / |(v1 - v0) x (v2 - v0)|] of the triangle. *)

val normal_at : Scratch.t -> float array -> int -> int -> int -> unit
(** [normal_at s g o0 o1 o2] is {!normal} for the triangle with vertices
    at [o0], [o1], [o2] in [g] (see {!roots_at}). *)

val smooth_normal : Scratch.t -> float array -> int -> float array -> int -> int -> int -> bool
(** [smooth_normal s g o vn k0 k1 k2] is [true] after setting [s.nx], [s.ny],
    [s.nz] to the unit normal at the point [s.px], [s.py], [s.pz] of the
    triangle stored at [o] in [g], interpolated from the unit normals of
    its corners stored in [vn] at [k0 .. k0 + 2], [k1 .. k1 + 2] and
    [k2 .. k2 + 2] (in the order of the vertices) with the point's
    barycentric coordinates (corners may share a normal); [false], and [s]
    unchanged, if the interpolated normal is zero or not finite. *)

val smooth_normal_at : Scratch.t -> float array -> int -> int -> int -> float array -> int -> int -> int -> bool
(** [smooth_normal_at s g o0 o1 o2 vn k0 k1 k2] is {!smooth_normal} for
    the triangle with vertices at [o0], [o1], [o2] in [g] (see
    {!roots_at}). *)

val intersect : t -> origin:Vec3.t -> direction:Vec3.t -> float
(** [intersect tri ~origin ~direction] is the root of {!roots}, or [infinity]. *)
