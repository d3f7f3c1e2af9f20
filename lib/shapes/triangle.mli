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

type t = private { v0 : Vec3.t; v1 : Vec3.t; v2 : Vec3.t; material : Material.t }
(** The type for triangles, vertices in world units: read its fields,
    make one with {!v}. *)

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

val intersect : t -> origin:Vec3.t -> direction:Vec3.t -> float
(** [intersect tri ~origin ~direction] is the root of [roots], or [infinity]. *)

val crossing : t -> origin:Vec3.t -> direction:Vec3.t -> float
(** [crossing tri ~origin ~direction] is the crossing of [crosses], or [infinity]. *)

(**/**)

(* Internal: the kernel's side of this module, for the tracer and the tests, hidden from the documentation. Not for users: it changes without notice. *)

(** {1:kernel The kernel's routines}

    A triangle is stored in a float array at an offset [o]: [v0] at
    [o .. o + 2], [v1] at [o + 3 .. o + 5], [v2] at [o + 6 .. o + 8]. *)

val store : t -> float array -> int -> unit
(** [store tri g o] writes [tri] to [g] at offset [o] (9 floats). *)

val shear : Scratch.t -> int
(** [shear s] writes to [s.sx] .. [s.okz] the ray of [s] in the frame of
    the triangle test and is its axes, packed ([axis_x], [axis_y],
    [axis_z]): what [roots_at] reads, found once for all the triangles
    a ray is tested against. *)

val axis_x : int -> int
(** [axis_x a] is the axis (0 to 2) of the test's x in the axes [a] of [shear]. *)

val axis_y : int -> int
(** [axis_y a] is the axis of the test's y. *)

val axis_z : int -> int
(** [axis_z a] is the axis of the test's z: the largest coordinate of the ray's direction. *)

val hit : Scratch.t -> float array -> int -> int -> int -> int -> int -> int -> bool
(** [hit s g o0 o1 o2 kx ky kz] is [true] iff the line of the ray of [s]
    meets the triangle whose vertices [v0], [v1], [v2] are stored at [o0],
    [o1], [o2] in [g] (3 floats each), with its root then in [s.near]
    ([s] unchanged on a miss): the tracer's test, inlined into its loops
    with its axes as constants. The arithmetic is [roots]'s, operation
    for operation, and its bits are the same; a miss is decided from two
    edge functions of opposite signs before the third is computed.
    [s.sx] .. [s.okz] and [kx], [ky], [kz] must be [shear]'s for the ray
    of [s]. *)

val roots_at : Scratch.t -> float array -> int -> int -> int -> int -> int -> int -> bool
(** [roots_at s g o0 o1 o2 kx ky kz] is [hit], with its root in [s.near]
    and [s.far] ([infinity] in both for a miss): [roots] for a mesh's
    triangle, read where its vertices are, shared with the triangles
    around it. [roots] is [roots_at s g o (o + 3) (o + 6) kx ky kz] with
    [shear]'s axes. *)

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

(** {2:parity Crossings counted once: the parity of a closed mesh}

    [roots] is watertight for the closest hit: a ray through an edge
    shared by two triangles hits one of them {e or both}. Inside and
    outside of a closed mesh (CSG's leaves) is the parity of the number of
    crossings along the line, where "both" is one too many. [crosses]
    counts each crossing exactly once.

    {b The rule.} In the frame of the test (after [shear], the ray's
    origin at [(0, 0)] of the plane its direction is the normal of), the
    corners of every triangle are the same floats wherever they are read:
    a corner shared by triangles is moved into the frame once, by the same
    operations. The ray is taken to pass through the point [(e, e^2)] of
    that plane, [e > 0] infinitely small, rather than [(0, 0)] (a
    simulation of simplicity, Edelsbrunner and Mücke, 1990). The edge
    function of the edge [p -> q], [E = qx py - qy px] for the origin,
    becomes [E + e (qy - py) + e^2 (px - qx)]: its sign is that of [E]
    where [E <> 0], else that of [qy - py], else that of [px - qx], and it
    is 0 only if [p = q]. The triangle is crossed iff its three edge
    functions have one sign (either: triangles are seen from both sides),
    none 0. The sign of [E] is exact: where the computed [E] is not 0, its
    sign is the exact one (the two products are each rounded to nearest,
    a monotone rounding, so their computed difference can be 0 but never
    of the wrong sign); where it is 0, the two rounded products are equal
    and [E] is the difference of their rounding errors, each exact by
    [Float.fma] (while the products are not subnormal: corners more than
    about [1e-145] from the ray in the frame; nearer ones keep the rule's
    consistency below, not its exactness). The ties, [qy - py] and
    [px - qx], are differences of floats: their signs are exact.

    {b Why the count has the right parity.} The signs are exactly those of
    the point [(e, e^2)] against the exact triangles of the moved corners,
    a point on no edge's line (its edge functions are never 0). Over a
    closed mesh (every edge bordered by exactly two triangles, {!Csg.check_closed}),
    the number of triangles containing a point of the plane on no edge,
    modulo 2, changes across no edge (crossing one toggles its two
    triangles, or one of them twice where the other is seen edge on) and
    is 0 far away: it is even everywhere. So every line meets a closed
    mesh an even number of times: a ray through a shared edge or vertex
    counts one crossing there, where the surface goes on across it, and
    zero or two where it only touches the surface (a silhouette edge or
    vertex between faces seen from the front and from the back). Which
    triangle is counted depends only on the corners' floats, so the rule
    does not depend on the triangles' order or winding (reversing a
    triangle negates all three edge functions). Swapping an edge's ends
    negates each step of its sign, rounding included, so the two triangles
    of an edge take opposite sides of it even where products are
    subnormal. *)

val crosses : Scratch.t -> float array -> int -> bool
(** [crosses s g o] is [true] iff the line of the ray of [s] crosses the
    triangle stored at [o] in [g] under the rule above, with the crossing's
    [t] in [s.near] and [s.far] ([roots]'s formula; the mean depth of the
    corners for a triangle whose three edge functions are computed 0), and
    [infinity] in both otherwise. Where [roots] hits a triangle away
    from its edges, [crosses] does too, at the same [t]. *)

val crosses_at : Scratch.t -> float array -> int -> int -> int -> int -> int -> int -> bool
(** [crosses_at s g o0 o1 o2 kx ky kz] is [crosses] for the triangle
    with vertices at [o0], [o1], [o2] in [g], with [shear]'s axes (see
    [roots_at]). *)

val normal : Scratch.t -> float array -> int -> unit
(** [normal s g o] sets [s.nx], [s.ny], [s.nz] to the unit normal
    [(v1 - v0) x (v2 - v0) / |(v1 - v0) x (v2 - v0)|] of the triangle. *)

val normal_at : Scratch.t -> float array -> int -> int -> int -> unit
(** [normal_at s g o0 o1 o2] is [normal] for the triangle with vertices
    at [o0], [o1], [o2] in [g] (see [roots_at]). *)

val smooth_normal : Scratch.t -> float array -> int -> float array -> int -> int -> int -> bool
(** [smooth_normal s g o vn k0 k1 k2] is [true] after setting [s.nx], [s.ny],
    [s.nz] to the unit normal at the point [s.px], [s.py], [s.pz] of the
    triangle stored at [o] in [g], interpolated from the unit normals of
    its corners stored in [vn] at [k0 .. k0 + 2], [k1 .. k1 + 2] and
    [k2 .. k2 + 2] (in the order of the vertices) with the point's
    barycentric coordinates (corners may share a normal); [false], and [s]
    unchanged, if the interpolated normal is zero or not finite. *)

val smooth_normal_at : Scratch.t -> float array -> int -> int -> int -> float array -> int -> int -> int -> bool
(** [smooth_normal_at s g o0 o1 o2 vn k0 k1 k2] is [smooth_normal] for
    the triangle with vertices at [o0], [o1], [o2] in [g] (see
    [roots_at]). *)

val texcoords_at : Scratch.t -> float array -> int -> int -> int -> float array -> int -> unit
(** [texcoords_at s v o0 o1 o2 uv j] sets [s.tu], [s.tv] to the texture
    coordinates of the point [O + t D] of the ray of [s] on the triangle with
    vertices at [o0], [o1], [o2] in [v]: its barycentric weights [b1],
    [b2] on the corners ({!Texture_map.barycentric}'s formula; [0, 0] for
    a degenerate triangle) blending the corners' [u v], stored in that
    order at [uv.(j .. j + 5)] ({!Texture_map.interpolate}). The arrays
    are read without bounds checks: the caller keeps the offsets in them. *)

