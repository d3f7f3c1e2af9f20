(** The kinds of object the kernel traces: one constant constructor per
    kind, as cheap as an integer (immediate, compared in a register), so
    that every [match] on a kind is one the compiler checks: a new kind
    makes it name each match that misses it.

    The kernel's matches on a kind: {!Kind_dispatch} (the roots and the
    normal of every kind stored in a geometry table), and the paths of
    the kinds that have their own (spheres and triangles in [Traversal]
    and [Surface], CSG solids in {!module-Csg}), which send every other
    kind to {!Kind_dispatch}. Everything else here is a cold fact
    ({!facts}), read when a scene is prepared, never per ray.

    @canonical Raytrace.Private.Kind *)

type t =
  | Sphere  (** A sphere: the kernel's own arrays of centres and radii. *)
  | Triangle  (** A triangle, alone or a mesh's, shaded with its flat normal. *)
  | Smooth_triangle
      (** A mesh's triangle shaded with normals interpolated from its
          corners ([Triangle.smooth_normal]). *)
  | Plane  (** A plane: unbounded, outside the hierarchy. *)
  | Box  (** An axis-aligned box. *)
  | Csg
      (** A CSG solid, whose geometry is the number of its root node in
          the kernel's {!module-Csg.type-table}. *)
  | Cylinder  (** A cylinder, capped (closed) or open ({!module-Cylinder}). *)
  | Disk  (** A flat disk, seen from both sides ({!module-Disk}). *)
  | Cone  (** A cone, capped or open ({!module-Cone}). *)
  | Torus  (** A torus ({!module-Torus}). *)
  | Instance
      (** A transformed object, whose geometry is its number in the
          prepared scene's table of instances: the kernel traces it in its
          own prepared scene (the bottom level), the ray carried into the
          object's frame. Closed for the media of glass: an instance of an
          open surface is seen as a sheet. *)
(** The type for kinds. The order of the constructors is the kernel's:
    spheres, then triangles, then the rest, so that the traversal's
    three-way [match] compiles to two comparisons. *)

val all : t list
(** [all] is every kind, in the order of the type's constructors. *)

val facts : t -> string * bool * bool * int
(** [facts k] is [k]'s name, whether it is {!bounded}, whether it is
    {!closed}, and its {!floats}: one line per kind. *)

val to_string : t -> string
(** [to_string k] is [k]'s name in lower case (["sphere"], ["plane"],
    ["triangle"], ["smooth triangle"], ["box"], ["csg"], ["cylinder"],
    ["disk"]). *)

val bounded : t -> bool
(** [bounded k] is [true] iff an object of kind [k] fits in a box: it is
    then in the bounding volume hierarchy; the others (planes) are
    tested before each walk of it. *)

val closed : t -> bool
(** [closed k] is [true] iff an object of kind [k] bounds a volume (a
    sphere, a box, a CSG solid, a cylinder): it may be a CSG operand, and
    a ray that enters it leaves it. A described kind may leave one shape
    open (a cylinder without its caps): {!Shape_desc.closed} tells. *)

val floats : t -> int
(** [floats k] is how many floats of geometry the shape module's [store]
    writes for an object of kind [k], at most {!stride}. *)

val spans : t -> int
(** [spans k] is the most intervals in which a line meets a solid of the
    closed kind [k] (2 for a torus, 1 for the convex kinds): the room a
    CSG leaf of kind [k] takes in the work arrays, and how many times
    the CSG table asks its roots. *)

val stride : int
(** [stride] is the largest {!floats} of any kind ([9]): the floats of
    geometry per shape in the kernel's tables ([Prepared]'s [geom], the
    CSG table's). *)

val is_triangle : t -> bool
(** [is_triangle k] is [true] iff [k] is {!constructor-Triangle} or {!constructor-Smooth_triangle}:
    the kinds whose corners are offsets into the table of vertices. *)
