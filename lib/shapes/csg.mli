(** Constructive solid geometry: union, intersection and difference of
    closed solids.

    A CSG solid combines two closed solids (spheres, boxes, closed meshes,
    the closed described kinds, CSG solids themselves, or any of these
    placed by a transform) by a boolean operation on their insides.
    Each point of its surface lies on the surface of one of its leaves and
    shows that leaf's material; its outward normal is the leaf's outward
    normal, reversed where the leaf is subtracted (the inside of a cavity
    faces into the cavity).

    The kernel traces it by the interval method: along a ray, each leaf
    is a list of [entry, exit] intervals of the line; an operation merges
    its children's lists into its own (one sweep over both lists' ends in
    order); the first end of the solid's list beyond [t_min] is the hit.
    Every list has room reserved once per tracer ([work]), so that a ray
    allocates nothing. {!literal_hit} is the oracle: it classifies every
    crossing of every leaf by evaluating the boolean expression just before
    and just after it. *)

(** {1:solids Solids} *)

type op = Union | Intersection | Difference  (** The type for operations. *)

type t = private { op : op; a : solid; b : solid }
(** The type for CSG solids: [a op b]; read its fields, make one with {!v}. *)

and solid =
  | Sphere of Sphere.t
  | Box of Box.t
  | Mesh of Mesh.t
  | Csg of t
  | Primitive of Shape_desc.primitive
  | Transformed of placed  (** A closed solid placed by a transform: scene text's [transform] and [use] as operands. *)
(** The type for the operands. A mesh must be closed ({!check_closed}). *)

and placed = {
  transform : Transform.t;  (** The operand's frame to the frame around it. *)
  solid : solid;  (** The operand in its own frame. *)
  own_material : Material.t option;
      (** The material of every surface of [solid], or [None] for their
          own; an outer operand's covers an inner one's, as an instance's
          does. *)
  name : string option;  (** The name of its definition ([define]), printed as [use]; [None] for [transform]. *)
}
(** The type for transformed operands. The kernel carries the ray into
    the operand's frame inside the CSG table ([t] unchanged: the direction
    is not renormalised) and brings its normals back by the inverse
    transpose. *)

val v : op -> solid -> solid -> t
(** [v op a b] is [a op b], not validated. *)

val placed : ?material:Material.t -> ?name:string -> Transform.t -> solid -> solid
(** [placed ~material ~name tr s] is [s] placed by [tr] ({!constructor-Transformed}). *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] are the same operation on equal
    operands ({!Sphere.equal}, {!Box.equal}, {!Mesh.equal}). *)

val equal_solid : solid -> solid -> bool
(** [equal_solid a b] is {!equal} for operands. *)

val op_name : op -> string
(** [op_name op] is ["union"], ["intersection"] or ["difference"]. *)

val op_of_string : string -> op option
(** [op_of_string s] is the operation that {!op_name} names [s], if any. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf c] prints [c] as its form in the scene-file syntax,
    [(csg union A B)], each operand as its own form. *)

val pp_solid : Format.formatter -> solid -> unit
(** [pp_solid ppf s] prints the operand [s] as its form: a named
    transformed operand as [(use NAME (transform OPS) ...)], whose
    definition {!Raytrace.Scene.pp} prints first. *)

val show : t -> string
(** [show c] is [c] formatted by {!pp}. *)

val max_depth : int
(** [max_depth] is [32], the most CSG forms nested in one another. *)

val check_closed : Mesh.t -> (unit, [> `Msg of string ]) result
(** [check_closed m] is [Ok ()] iff every edge of [m]'s non-degenerate
    triangles borders exactly two of them; edges are compared by their
    endpoints' coordinates, so that a vertex repeated in the file is one
    vertex. The error names one edge that does not. *)

val validate : t -> (t, [> `Msg of string ]) result
(** [validate c] checks every operand as its module's [validate] does,
    that every mesh is closed ({!check_closed}), that no transformed
    operand's material has a pattern (patterns are not carried into an
    object's frame), and that [c] nests at most {!max_depth} levels deep
    (CSG forms and transformed operands each count one). *)

val check_textures : ?texture:Texture_map.t -> t -> (unit, [> `Msg of string ]) result
(** [check_textures ~texture c] is [Ok ()] iff every leaf's texture (its
    material's as {!leaves} gives it, or [texture] on every leaf where
    given: an instance's own material's) fits the leaf: a sphere takes
    the [spherical] mapping, a box the [box] one, a described kind none
    ({!Texture_map.mapping_for}), a mesh the [uv] one if it has [vt]
    ({!Mesh.has_texcoords}). The texture maps in the leaf's
    frame: the solid's, or inside transformed operands the frame before
    their transforms, as the leaf's own surface would as an object.
    {!Shape.validate} calls it. *)

val leaf_material : solid -> Material.t
(** [leaf_material l] is the material of the leaf [l] (a sphere's own
    fields as a material, pattern included).
    @raise Invalid_argument if [l] is a [Csg] or [Transformed] node. *)

val leaves : t -> (solid * Material.t * Transform.t list) list
(** [leaves c] is [c]'s leaves, left to right, each with the material
    it shows (that of the outermost transformed operand around it that
    has its own, else {!leaf_material}) and the transforms around it,
    innermost first. *)

val materials : t -> Material.t list
(** [materials c] is the materials of [c]'s leaves as {!leaves} gives
    them, left to right. *)

val bounds : t -> Vec3.t * Vec3.t
(** [bounds c] is [(lo, hi)], a box that holds [c]: for a union the box
    around both operands' boxes, for an intersection their common part (a
    point if they are disjoint), for a difference the first operand's. *)

val triangles : t -> int
(** [triangles c] is the number of triangles of [c]'s mesh leaves that the
    kernel keeps ({!Mesh.val-objects}). *)

val extent : t -> float
(** [extent c] is the largest magnitude of a coordinate of the boxes of
    [c]'s leaves, the scale of its geometry for the error-bound offsets of
    secondary rays. *)

(** {1:literal The literal algorithm} *)

val literal_hit :
  t -> origin:Vec3.t -> direction:Vec3.t -> t_min:float -> t_max:float -> (float * solid * Vec3.t) option
(** [literal_hit c ~origin ~direction ~t_min ~t_max] is [Some (t, l, n)]
    for the first crossing [t] of the surface of [c] with
    [t_min < t < t_max], the leaf [l] whose surface is crossed (its
    material is {!leaf_material}[ l]) and [c]'s outward normal [n] there; [None] if there is none.
    The straightforward algorithm: every crossing of every leaf's surface,
    in order, each classified by evaluating [c]'s boolean expression on
    its leaves just before and just after it (a leaf is inside between
    its entry and exit; a mesh after an odd number of crossings). *)

type table
(** The type for tables of CSG solids. *)

type builder
(** The type for tables being built. *)

type work
(** The type for the per-tracer room of the interval lists, and the
    surface of the last hit found by [roots]. *)

(**/**)

(* Internal: the kernel's side of this module, for the tracer and the tests, hidden from the documentation. Not for users: it changes without notice. *)

(** {1:kernel The kernel's table}

    The CSG solids of a prepared scene are stored in one table of nodes
    (operations and leaves) and surfaces (a sphere, a box or a mesh, each
    with its material's number). A mesh leaf keeps the mesh's own
    positions (no copy), its kept triangles' corners (3 ints a triangle)
    and a bounding volume hierarchy ({!Raytrace.Private.Bvh}) over them, which a ray
    descends along its whole line: its crossings anywhere are the parity
    of the points along it, and a triangle's box is grown so that no
    crossing the triangle test reports is missed (see [csg.ml]). A
    transformed operand is a leaf of a surface of kind [Instance] (no
    solid's kind), whose geometry is its frame's number (the world-to-object
    matrix of its transforms and those around it, composed) and whose
    child is the operand's node: the ray is carried into that frame for
    the child and put back after. *)

val builder : unit -> builder
(** [builder ()] is an empty table being built. *)

val add : builder -> material:(solid -> Material.t -> int) -> t -> int
(** [add b ~material c] adds [c] to [b], numbering its leaves' materials
    by [material] (called once per leaf, given the leaf and the material
    it shows, as {!leaves} gives them, left to right); the number of its
    root node, for [roots]. A transformed operand is a node of the table
    that carries the ray into its frame (its transforms composed with
    those around it, so that each level carries the world's ray) for its
    child and puts it back after. *)

val table : builder -> table
(** [table b] is the table built by [b].
    @raise Invalid_argument if its leaves, numbered with room for the
    triangles of its largest mesh operand, do not fit the platform's
    integers: never with 63-bit integers within {!Limits}; in JavaScript
    (32-bit), past [2^31] leaves without a mesh operand, fewer beside one. *)

val empty : table
(** [empty] is the table of no solid. *)

val work : table -> work
(** [work tb] is room for tracing the solids of [tb], allocated once. *)

val roots : table -> work -> Scratch.t -> int -> bool
(** [roots tb w s root] is [true] iff the ray of [s] crosses the surface
    of the solid of root node [root] at some [t > s.t_min]; then the first
    such [t] is in both [s.near] and [s.far], and [w] remembers the
    surface crossed there and whether the ray enters or leaves the solid
    ([entering]). Otherwise [s.near] and [s.far] are [infinity]. Leaves'
    roots are their modules' kernel routines ([Box.roots],
    [Triangle.crosses], {!Sphere.roots}'s arithmetic), so a CSG silhouette
    is exactly its leaves' silhouettes, combined; a mesh's crossings are
    counted once each ([Triangle.crosses]), so that its inside is right
    along rays through its shared edges and corners. Allocates nothing. *)

val normal : table -> work -> Scratch.t -> unit
(** [normal tb w s] sets [s.nx], [s.ny], [s.nz] to the outward unit
    normal of the solid at the hit point [s.px], [s.py], [s.pz] found by
    the last [roots] with [w] for the ray still in [s]: against the ray
    where it enters the solid, along it where it leaves. *)

val geometry : table -> float array
(** [geometry tb] is the leaves' geometry: a surface's numbers as its
    kind's [store] writes them (a sphere's centre and radius, a box's
    corners), {!Kind.stride} floats each. *)

val surface_offset : table -> work -> int
(** [surface_offset tb w] is the offset in [geometry tb] of the surface of
    the last hit found by [roots] with [w]: the kernel's texture
    mappings read a textured leaf's sphere or box there. *)

val texcoords : table -> work -> Scratch.t -> unit
(** [texcoords tb w s] sets [s.tu], [s.tv] to the texture coordinates, by
    its [vt] ({!Triangle.texcoords_at}), of the point [O + t D] of the
    ray of [s] (carried into the leaf's frame: {!enter_surface_frame}) on the mesh
    triangle whose surface the last hit found by [roots] with [w] is; [0,
    0] for a mesh without [vt] (which {!check_textures} refuses a uv
    texture on). The surface must be a mesh leaf's; else what it reads is
    unspecified. *)

val enter_surface_frame : table -> work -> Scratch.t -> unit
(** [enter_surface_frame tb w s] carries the ray of [s] into the frame of
    the surface of the last hit found by [roots] with [w] (its transformed
    operands' frame, as [normal] carries it: [t] the same number), if it
    has one; the ray is kept in [w] for {!leave_surface_frame}. *)

val leave_surface_frame : table -> work -> Scratch.t -> unit
(** [leave_surface_frame tb w s] puts back the ray that
    {!enter_surface_frame}[ tb w s] carried. *)

val material : table -> work -> int
(** [material tb w] is the material's number of the surface of the last
    hit found by [roots] with [w]. *)

val take_tests : work -> int
(** [take_tests w] is the number of leaf tests (a sphere, a box, a mesh's
    triangle) the calls of [roots] with [w] made since the last
    [take_tests w], and restarts that count: the kernel adds them to its
    count of intersection tests whenever it reads it (the statistics, the
    work bound), at no cost per ray. *)

val take_boxes : work -> int
(** [take_boxes w] is [take_tests] for the boxes of the mesh leaves'
    hierarchies, counted as the kernel's box tests. *)

val pending : work -> int
(** [pending w] is the leaf and box tests that [take_tests] and
    [take_boxes] would take now, without taking them: the kernel's check
    of its work bound reads it. *)

val entering : work -> bool
(** [entering w] is [true] iff the last hit found by [roots] with [w] is
    where the ray enters the solid, [false] where it leaves it. *)
