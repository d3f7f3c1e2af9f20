(** Every object's shape, as one type: a sphere is a shape like the others.

    The kernel stores every shape in a table: a kind, and its geometry in
    a float array (a fixed number of floats per shape, written by the
    shape module's [store]; a triangle's three corners in
    an array of vertices, a mesh's shared by its triangles). This module
    ties the kinds to the shape modules, for the kernel and for
    {!Raytrace.Private.Literal}. *)

type t =
  | Sphere of Sphere.t
  | Plane of Plane.t
  | Triangle of Triangle.t
  | Box of Box.t
  | Mesh of Mesh.t
  | Csg of Csg.t
  | Primitive of Shape_desc.primitive
      (** A shape of a kind its module describes ({!Raytrace.Private.Shape_desc}, listed in
          {!Raytrace.Private.Primitives}): every function here takes it from the description. *)
  | Instance of instance
      (** An object placed by a transform ({!instance}): scene text's
          [transform] and [use] forms. *)
(** The type for shapes. *)

and instance = {
  transform : Transform.t;  (** Object frame to world. *)
  shape : t;
      (** The object in its own frame: shared, the same value, by every
          instance of one definition, and then prepared once (the
          hierarchy's bottom level). *)
  own_material : Material.t option;
      (** The instance's material for every surface of [shape], or [None]
          for [shape]'s own (a CSG solid's leaves keep theirs). *)
  name : string option;  (** The name of its definition ([define]), printed as [use]; [None] for [transform]. *)
}
(** The type for a transformed object. *)

val instance : ?material:Material.t -> ?name:string -> Transform.t -> t -> t
(** [instance ~material ~name tr s] is [s] placed by [tr]: an
    {!constructor-Instance}, except that a plane is mapped to a plane
    (its point by [tr], its normal by the inverse transpose) and an
    instance of an instance is one instance, the inner transform
    first. *)

val box_bounds : t -> Vec3.t * Vec3.t
(** [box_bounds s] is a box (lower and upper corners) that holds [s],
    rounded outward; a mesh's from its placed positions.
    @raise Invalid_argument on a plane. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] are the same kind of shape with
    equal fields ({!Sphere.equal}, {!Plane.equal}, {!Triangle.equal}, {!Box.equal},
    {!Mesh.equal}, {!Csg.equal}, {!Transform.equal}). *)

val equal_instance : instance -> instance -> bool
(** [equal_instance a b] is {!equal} on instances. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf s] prints [s] as its form in the scene-file syntax ([sphere], [plane],
    [triangle], [box], [mesh] or [csg]; a mesh as the form that reads its
    file again), [specular] and [reflective] only when they are not the
    defaults. *)

val show : t -> string
(** [show s] is [s] formatted by {!pp}. *)

val material : t -> Material.t
(** [material s] is the material of [s]; of a CSG solid, its first leaf's
    (each of its leaves has its own: {!materials}). *)

val materials : t -> Material.t list
(** [materials s] is [[material s]], or the materials of a CSG solid's
    leaves ({!Csg.materials}). *)

val validate : t -> (t, [> `Msg of string ]) result
(** [validate s] is the shape module's [validate]; an instance's object
    is validated, and an instance is refused if it is of a plane (see
    {!instance}). A texture ({!Texture_map}) must take the mapping of its
    object's kind ({!Texture_map.mapping_for}; a mesh's [uv] needs its
    texture coordinates). An instance's own material's texture lies on
    every surface of its object, in the object's frame (the frame before
    the transform: a globe turned by a transform turns its map with it),
    so each of them must take its mapping (a mesh's [uv] needs its
    texture coordinates); a CSG solid's operands are checked by
    {!Csg.check_textures}. *)

val name : t -> string
(** [name s] is the scene-file form of [s]: ["sphere"], ["plane"], ["triangle"], ["box"], ["mesh"] or ["csg"]. *)

val store : t -> float array -> int -> unit
(** [store s g o] writes the geometry of [s] to [g] at offset [o]. *)

val bounded : t -> bool
(** [bounded s] is [false] for planes, [true] otherwise (an instance too:
    a plane is never one). *)

val bounds : t -> Vec3.t * float
(** [bounds s] is [(c, h)]: the cube of center [c] and half-side [h] holds
    [s] (for the bounding volume hierarchy).
    @raise Invalid_argument on a plane. *)

val pattern_frame : t -> Vec3.t * float * float
(** [pattern_frame s] is [(origin, scale, extent)] for [Pattern.store]:
    the world origin and scale of the coordinates a pattern on [s] uses
    (world coordinates for planes and triangles; the [min] corner for
    boxes; the mesh's [translate] and [scale] for meshes), and the
    largest magnitude of a coordinate of [s]'s geometry. A CSG solid's
    patterns are its leaves' ({!leaf_pattern_frame}).
    @raise Invalid_argument if [s] is a [Csg]. *)

val leaf_pattern_frame : Csg.solid -> Vec3.t * float * float
(** [leaf_pattern_frame l] is {!pattern_frame} of the CSG leaf [l] as an
    object of its own (a sphere's pattern uses world coordinates).
    @raise Invalid_argument if [l] is a [Csg] node. *)

(** {1:readable For the literal tracer} *)

val roots : t -> origin:Vec3.t -> direction:Vec3.t -> float * float
(** [roots s ~origin ~direction] is [(near, far)], [near <= far], the
    roots of the ray [origin + t direction] on [s], by the kernel's
    routine, or [(infinity, infinity)] if it misses. *)

val normal : t -> Vec3.t -> Vec3.t
(** [normal s p] is the unit normal of [s] at its point [p], by the
    kernel's routine (outward for boxes; for planes and triangles the side
    they were given with). *)

(**/**)

(* The kernel's side, hidden from the documentation: which kind of the
   kernel's table a shape is. *)

val kind : t -> Kind.t
(** [kind s] is the kind of [s] in the kernel's table.
    @raise Invalid_argument on a mesh, which is many objects of kind
    {!Raytrace.Private.Kind.Triangle} or {!Raytrace.Private.Kind.Smooth_triangle} (so are {!store}, {!bounds},
    {!roots} and {!normal}); {!store}, {!roots} and {!normal} raise it
    on a CSG solid too, which the kernel traces from its own table. *)
