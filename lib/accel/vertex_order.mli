(** The triangles' vertices in the order the hierarchy's leaves read them.

    A mesh's vertices come in the order of its file: for a generated tube,
    ring after ring. A leaf of the hierarchy holds up to 16 triangles that
    lie close together in space, and so names vertices from two or three
    rings: its tests read as many scattered runs of the vertex array, each
    behind a cache miss on a big mesh. Copied in the order in which the
    slots (leaf after leaf) first name them, a leaf's vertices lie
    together, a few cache lines in a row.

    The copy moves coordinates, never computes them: every test reads the
    same floats as before, and every image is the same. *)

val gather : ?sources:bool -> kind:Kind.t array -> vertex:float array -> int array -> int array -> int array -> float array * int array
(** [gather ~kind ~vertex at0 at1 at2] is [(vertex', source)]: the
    vertices (3 floats each) that the triangles name, in the order in
    which the slots [i] whose [kind.(i)] is {!Kind.Triangle} or
    {!Kind.Smooth_triangle} first name them (slot [0]'s three corners,
    then slot [1]'s new ones, ...), each copied once however many
    triangles share it; and per vertex of [vertex'] (its offset [o'], at
    [o' / 3]) its offset in [vertex]. It rewrites those slots' offsets
    [at0.(i)], [at1.(i)], [at2.(i)] (corners in [vertex], multiples of 3)
    to the same vertices' offsets in [vertex']; other slots are left as
    they are. [vertex'] holds only the vertices some triangle names: it is
    [vertex]'s length or shorter. With [~sources:false] (default [true]),
    [source] is empty: a flat mesh's shading reads no vertex's normal.
    @raise Invalid_argument if [at0], [at1], [at2] and [kind] differ in
    length, or if a triangle's corner lies outside [vertex]. *)
