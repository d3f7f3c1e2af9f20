(** Generated triangle meshes for tests and benchmarks.

    Scenes and benchmarks generate their meshes rather than ship large
    OBJ files; {!Raytrace.Mesh.Obj.to_buffer} writes them as OBJ text. Both
    generators are deterministic: the same arguments give the same floats
    on every 64-bit platform (only [+ - * /], [sqrt], [sin] and [cos] of
    the OCaml runtime's C library are used). Triangles are counter-clockwise
    seen from the front, the side the vertex normals point to.

    @canonical Raytrace.Mesh.Gen *)

val torus_knot : p:int -> q:int -> radius:float -> tube:float -> segments:int -> sides:int -> Obj_file.t
(** [torus_knot ~p ~q ~radius ~tube ~segments ~sides] is a tube of radius
    [tube] around the [(p, q)] torus knot, the curve
    [((2 + cos q t) cos p t, (2 + cos q t) sin p t, -sin q t)] scaled by [radius / 3]
    for [t] in \[0, 2π\] (it winds [p] times around the z axis and [q]
    times through the torus's hole; coprime [p] and [q] make a knot, others
    a link that crosses itself). The tube is cut into [segments] rings of
    [sides] vertices, each with its unit outward normal: [segments * sides]
    vertices and normals, [2 * segments * sides] triangles. The mesh is
    closed: every edge is shared by exactly two triangles, in opposite
    directions. The tube crosses itself if [tube] is too large for the
    knot's curvature.
    @raise Invalid_argument unless [p, q >= 1], [segments, sides >= 3] and
    [radius], [tube] are finite and [> 0]. *)

val terrain : seed:int -> nx:int -> nz:int -> size:float -> height:float -> Obj_file.t
(** [terrain ~seed ~nx ~nz ~size ~height] is a height field over the square
    [\[-size/2, size/2\]] in x and z, cut into [nx * nz] cells of two
    triangles each: [(nx + 1) * (nz + 1)] vertices at heights
    [y] in \[0, height\] of a value noise of four octaves drawn from
    [seed], each with the unit normal of the surface there (central
    differences), facing up: [2 * nx * nz] triangles.
    @raise Invalid_argument unless [nx, nz >= 1] and [size], [height] are
    finite with [size > 0] and [height >= 0]. *)
