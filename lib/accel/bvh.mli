(** Bounding volume hierarchies over a scene's bounded objects.

    A binary tree of axis-aligned boxes, each leaf holding a few objects
    (spheres, triangles, boxes, CSG solids; the planes, unbounded, stay
    outside), so that a ray is tested only against the objects whose boxes
    it meets: about [log n] boxes per ray instead of [n] objects. Built top-down
    ({!build_boxes}): each node's objects binned by their centers along the
    longest axis of the centers' bounds and split where the surface area
    heuristic is lowest (at the median when the centers coincide), in one
    pass over the node's objects (the partition that moves each object to
    its side bins it for its child), so building is [O(n log n)].

    Nodes are stored depth-first, 8 floats each in one array, so that the
    tracer reads a node from one cache line: the left child of inner node
    [k] is [k + 1], the right child is its [link]. Objects are referred
    to by slot: leaf [k] holds [tag] slots from its [link], and
    [order.(slot)] is the object's index in the input.

    @canonical Raytrace.Private.Bvh *)

type t = private {
  order : int array;  (** Input index of the object in each slot. *)
  n_nodes : int;  (** The number of nodes. *)
  nodes : float array;
      (** Node [k] at offset [root + 8 k] ({!offset}), [node_floats]
          floats: the lower corner of its box (x, y, z), the upper corner,
          its link, its tag. Link and tag are integers held as floats
          (exactly: they are below [2^53]). Link: of an inner node, the
          offset of its right child; of a leaf, its first slot. Tag: of a
          leaf, its number of slots, [>= 1]; of an inner node, [-1 - a],
          [a] the axis 0 to 2 its children are split along. The array
          holds [8 n_nodes + 7] floats: the [root] unused ones before the
          nodes, the others after ({!split_leaves}' may hold more after). *)
  root : int;
      (** The offset of node 0 in [nodes], from 0 to 7: where the nodes
          start on a 64-byte boundary in memory, so that each node is one
          cache line (if the collector has not moved the array since). *)
  depth : int;  (** Largest number of nodes on a path from the root. *)
}
(** The type for hierarchies. *)

(** {1:nodes Nodes}

    The tracer reads [nodes] directly, with the array's primitives (a
    float returned by a function of another module may be boxed); these
    read a node of the layout of {!t}, checked. *)

val node_floats : int
(** [node_floats] is 8, the number of floats a node takes in [nodes]. *)

val offset : t -> int -> int
(** [offset t k] is [t.root + 8 k], the offset of node [k] in [t.nodes]. *)

val lo : t -> int -> int -> float
(** [lo t k a] is the lower bound along axis [a] of node [k]'s box.
    @raise Invalid_argument if [k] is not a node or [a] not in 0 to 2. *)

val hi : t -> int -> int -> float
(** [hi t k a] is the upper bound along axis [a] of node [k]'s box.
    @raise Invalid_argument if [k] is not a node or [a] not in 0 to 2. *)

val link : t -> int -> int
(** [link t k] is node [k]'s link as an index: of an inner node, the index
    of its right child (not its offset, as in {!t}); of a leaf, its first
    slot.
    @raise Invalid_argument if [k] is not a node. *)

val tag : t -> int -> int
(** [tag t k] is node [k]'s tag (see {!t}).
    @raise Invalid_argument if [k] is not a node. *)

(** {1:build Building} *)

val build : ?leaf_size:int -> cx:float array -> cy:float array -> cz:float array -> float array -> t
(** [build ~leaf_size ~cx ~cy ~cz extent] is a hierarchy over the spheres
    with centers [(cx.(i), cy.(i), cz.(i))], each boxed by the cube of
    half-side [extent.(i)] around its center (the radius, plus any margin the
    caller needs). Leaves hold at most [leaf_size] (default 4) spheres.
    @raise Invalid_argument if the arrays are empty or of different
    lengths. *)

type floats = (float, Bigarray.float64_elt, Bigarray.c_layout) Bigarray.Array1.t
(** The type for floats that a process shares with its copies. *)

type beside = {
  beside : 'a. (unit -> 'a) -> unit -> 'a option;
      (** [beside f] starts computing [f ()] on another core (in a copy
          of this process) and is [wait]: [wait ()], called once, is
          [Some (f ())], or [None] if it could not be had (the caller then
          computes it). Where no process can be started, [wait] may
          compute [f ()] itself, in this process; never [beside]. [f ()]
          holds no functions. *)
  min_objects : int;  (** The fewest objects of a subtree built beside. *)
  floats : int -> floats * (int -> unit);
      (** [floats n] is [(a, reserve)]: [a], at least [n] floats that a
          computation started by a later [beside] writes and this process
          reads (memory shared with the copy; in this process's own
          memory where [beside] computes here), of which the computation
          writes the first [k] only after [reserve k], which gives them
          memory (it may raise [Failure]: the computation then fails, and
          the subtree is built here). The subtree built beside leaves its
          objects' numbers and its leaves' boxes there (at most 56 bytes
          an object), for this process to read in order. [floats] may
          raise [Failure] or [Out_of_memory]: the subtree is then built
          here. *)
  idle : unit -> bool;
      (** [idle ()] is [true] where a computation that [beside] started
          now would likely have a core of its own. It is asked once
          before the one [beside] of a build, and once before a
          caller's other use ([Prepared]'s twins); where it is [false],
          neither [floats] nor [beside] is called, and the work is done
          here in the order it has without [beside]. *)
}
(** The type for ways to build a part of a hierarchy on another core. The
    core library forks nothing: a caller that can gives {!build_boxes} a
    [beside]. *)

val build_boxes :
  ?leaf_size:int ->
  ?beside:beside ->
  x0:float array ->
  y0:float array ->
  z0:float array ->
  x1:float array ->
  y1:float array ->
  z1:float array ->
  unit ->
  t
(** [build_boxes ~leaf_size ~beside ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 ()] is a hierarchy over
    the objects whose boxes have lower corners [(x0.(i), y0.(i), z0.(i))]
    and upper corners [(x1.(i), y1.(i), z1.(i))], split by the surface area
    heuristic over 16 bins of their centers along the longest axis (at the
    median when their centers coincide). Leaves hold at most [leaf_size]
    (default 4, at most 32767: a larger one is taken as 32767) objects. The six arrays are reordered in place (the
    boxes move with the objects, so that each pass over a node reads
    memory in order): afterwards, without [beside], [x0.(slot)] is the
    box of object [order.(slot)]; with [beside], they are the build's
    scratch (its leaves' boxes are gathered there for the last pass) and
    hold other boxes.

    With [beside], the right subtree of the first node (depth first) whose
    children each hold at least a quarter of all the objects, the right
    one at least [beside.min_objects], is built beside (if [leaf_size <=
    127]) while this process builds the rest:
    the same tree, node for node and bit for bit, as without.
    @raise Invalid_argument if the arrays are empty or of different
    lengths, or hold more than [2^31 - 1] objects. *)

val ray_box_margin :
  ?among:int array -> cx:float array -> cy:float array -> cz:float array -> radius:float array -> Vec3.t -> float array
(** [ray_box_margin ~among ~cx ~cy ~cz ~radius camera] is, for each sphere
    [among.(j)] (default: all of them, in order), at [j], how much
    to grow its box beyond its radius so that no intersection test of the
    tracer can report a hit outside the box through rounding: rays start at
    [camera] or on a sphere, so with [D] the diameter and [M] the largest
    coordinate of everything, the textbook quadratic's hit points stay
    within about [3 u D^2 / r] of the sphere and the slab test errs by a few
    [u M]; the margin is [64 u (D^2 / r + M)] ([u = 2^-53]), a safety
    factor of 20 over the worst error measured on the hard cases of the
    test suite. For the reference scene it is about 2e-6. *)

type margin = private { d2 : float; m : float }
(** The type for the terms of {!ray_box_margin} common to all the
    spheres: [D^2] and [M]. *)

val margin_terms :
  ?among:int array ->
  ?reach:float ->
  cx:float array ->
  cy:float array ->
  cz:float array ->
  radius:float array ->
  Vec3.t ->
  margin
(** [margin_terms ~among ~reach ~cx ~cy ~cz ~radius camera] is [D^2] and
    [M] of {!ray_box_margin} for the same arguments, with camera rays
    starting anywhere in the cube of half side [reach] (default [0.], the
    point [camera]) around [camera]: a lens's disc inside it. *)

val margin_of_bounds : float array -> margin
(** [margin_of_bounds b] is [D^2] and [M] of {!ray_box_margin} for the
    spheres and camera whose bounds have lower corner [(b.(0), b.(1),
    b.(2))] and upper corner [(b.(3), b.(4), b.(5))]: a caller that finds
    the bounds as it makes the boxes needs no arrays of centers and radii
    for {!margin_terms}.
    @raise Invalid_argument if [b] has fewer than 6 elements. *)

val margin : margin -> float -> float
(** [margin t r] is the margin of {!ray_box_margin} of a sphere of radius
    [r] among those of [t], bit for bit: with {!margin_terms}, a million
    boxes are padded with no array of margins. *)

(** {1:cut Leaves cut by planes} *)

val split_leaves :
  ?cost:float ->
  ?cuts:int ->
  t ->
  triangle:(int -> bool) ->
  vertex:float array ->
  at0:int array ->
  at1:int array ->
  at2:int array ->
  margin:margin ->
  t
(** [split_leaves ~cost ~cuts t ~triangle ~vertex ~at0 ~at1 ~at2 ~margin]
    is [t] with each leaf of triangles cut in two where the surface area
    heuristic finds it pays, and so on [cuts] (default 1) times down: the
    plane halves the leaf's box across its longest side, and the leaf
    becomes an inner node (tagged with that axis) over two leaves, each
    over the range of the leaf's slots that have a part on its side,
    boxed by those parts. The slots are shared, not copied ([order] is
    [t]'s): a ray that meets both sides' boxes tests the triangles of both
    ranges, some twice. A cut is made where [cost A + A_l n_l + A_r n_r <
    n A] ([A] the leaf's box's area, [n] its slots; [A_l], [n_l] and
    [A_r], [n_r] its sides'): [cost] (default 3.) is the price of the
    inner node's two box tests in triangle tests. It pays on long thin
    triangles, whose boxes are far bigger than they are (a fine mesh's:
    the 1M-triangle knot's are 150 times longer than wide); never on
    leaves of [cost] slots or fewer, which are not tried. Leaves of more
    than 64 slots or with a slot that is not a triangle are left as they
    are. Inner nodes' boxes are their children's union again; [depth] is
    the new tree's. The cut leaf's nodes follow each other: the inner
    node, then its sides.

    [triangle s] is whether slot [s] is a triangle; its corners are then
    at [vertex.(at0.(s))], [vertex.(at1.(s))], [vertex.(at2.(s))] (x, y,
    z at each). A part of a triangle (its corners on one side of the
    plane and the points where its edges cross it, rounded) is boxed
    padded by twice {!margin}[ margin h] on every side, [h] the largest
    half side of the triangle's box ([Prepared]'s boxes pad by one: a
    part's rounding is a few units in the last place), so that a ray that
    hits the triangle in that part meets the box. If no leaf is cut, the
    result is [t] itself. The new nodes are written once, into an array
    with room for two more nodes a leaf tried: its [nodes] may hold more
    than [8 n_nodes + 7] floats (at most an eighth more nodes than
    [n_nodes]; an exact copy is made where more room than that went
    unused).
    @raise Invalid_argument if [cuts < 0] or [cost] is negative or NaN,
    or a triangle's corners are not in [vertex]. *)
