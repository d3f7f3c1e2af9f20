(** What a primitive shape kind is, told once by its module: the cold-path
    description that parsing, validating, preparing and the executable
    specification ([Literal]) read, never the kernel per ray (the kernel
    reads the kind's stored floats through {!Kind_dispatch}).

    A new bounded closed kind (a cylinder, say) is its module, which
    defines its [t], its kernel routines (roots and normal on the per-ray
    record) and a [desc : t Shape_desc.t], plus a line in {!Kind}, two in
    {!Kind_dispatch} and one in {!Primitives}: {!Shape}, {!Csg}, the
    scene text and [Literal] take it from the description
    (docs/architecture.md, "Adding a shape kind"). *)

(** {1:witness Type witnesses} *)

type (_, _) eq = Equal : ('a, 'a) eq  (** A proof that two types are one. *)

type _ id = ..
(** The witnesses' constructors, one per {!val-witness}. *)

module type ID = sig
  type t

  type _ id += Id : t id
end

type 'a witness = (module ID with type t = 'a)
(** A witness of the type ['a], compared by {!same}. *)

val witness : unit -> 'a witness
(** [witness ()] is a new witness of ['a]: make one per kind. *)

val same : 'a witness -> 'b witness -> ('a, 'b) eq option
(** [same a b] is [Some Equal] iff [a] and [b] are one witness. *)

(** {1:desc Descriptions} *)

type field =
  | Point  (** Three numbers, a point or a vector within {!Limits}. *)
  | Number  (** One finite number. *)
  | Flag of bool  (** [true] or [false], with its default. *)
(** The type of a field of a kind's scene-text form. *)

type reader = { point : string -> Vec3.t; number : string -> float; flag : string -> bool }
(** The fields of one form as the scene text read them, by name: each
    raises the reader's own located error for a missing or bad field. *)

type 'a t = {
  name : string;  (** The form's name in scene text ([cylinder]), and in messages. *)
  kind : Kind.t;  (** The kernel's kind: its facts ({!Kind.facts}) and its routines ({!Kind_dispatch}). *)
  witness : 'a witness;  (** ['a]'s witness, for {!equal_primitive}. *)
  fields : (string * field) list;  (** The form's fields besides the material's. *)
  read : reader -> Material.t -> 'a;  (** [read r m] is the shape of the form's fields, not yet validated. *)
  validate : 'a -> ('a, [ `Msg of string ]) result;  (** Checks a shape, as the scene does before preparing it. *)
  material : 'a -> Material.t;  (** A shape's material. *)
  closed : 'a -> bool;
      (** [closed x] is [true] iff [x] bounds a volume, when its kind
          ({!Kind.closed}) may: a cylinder's kind is closed, an open one
          (without its caps) is not, and a CSG operand must be. *)
  bounds : 'a -> Vec3.t * Vec3.t;
      (** The lower and upper corners of a box that holds the shape, rounded outward (a bounded kind). *)
  store : 'a -> float array -> int -> unit;
      (** [store x g o] writes [x]'s {!Kind.floats} floats of geometry at [g.(o)], as its kernel routines read them. *)
  pp : Format.formatter -> 'a -> unit;  (** Prints a shape as its scene-text form. *)
  equal : 'a -> 'a -> bool;  (** Exact equality. *)
  literal : 'a -> origin:Vec3.t -> direction:Vec3.t -> (float * Vec3.t) list;
      (** [literal x ~origin ~direction] is the line's crossings of the
          surface, nearer first, each with the surface's unit normal there
          (outward for a closed kind: its entries and exits, alternating,
          two for a convex one), computed from the definition, never by
          the kernel's routines: the executable
          specification's answer, which the kernel is tested against. *)
}
(** The type for descriptions of a primitive kind of shape ['a].

    @canonical Raytrace.Private.Shape_desc.t *)

type primitive = Primitive : 'a t * 'a -> primitive  (** A shape of some described kind. *)

(** The type for a description of some kind, for lists of them ({!Primitives.all}).

    @canonical Raytrace.Private.Shape_desc.any *)
type any = Any : 'a t -> any

(** {1:prim Primitives} *)

val equal_primitive : primitive -> primitive -> bool
(** [equal_primitive p q] is [true] iff [p] and [q] are of one kind and equal by its [equal]. *)

val pp_primitive : Format.formatter -> primitive -> unit
(** [pp_primitive ppf p] prints [p] by its kind's [pp]. *)

val name : primitive -> string
(** [name p] is the name of [p]'s kind. *)

val kind : primitive -> Kind.t
(** [kind p] is [p]'s kernel kind. *)

val material : primitive -> Material.t
(** [material p] is [p]'s material. *)

val bounds : primitive -> Vec3.t * Vec3.t
(** [bounds p] is [p]'s bounds, as its kind's [bounds]. *)

val store : primitive -> float array -> int -> unit
(** [store p g o] writes [p]'s geometry at [g.(o)]. *)

val literal : primitive -> origin:Vec3.t -> direction:Vec3.t -> (float * Vec3.t) list
(** [literal p ~origin ~direction] is [p]'s crossings by its kind's [literal]. *)

val closed : primitive -> bool
(** [closed p] is [true] iff [p]'s kind is closed ({!Kind.closed}) and
    [p] itself is, by its kind's [closed]: a CSG operand must be. *)

val not_closed : primitive -> string
(** [not_closed p] names [p] in the message that refuses it as a CSG
    operand when it is not {!closed}: ["a disk"], or ["a cylinder without
    its caps (capped false)"] for a shape of a closed kind left open. *)

val validate : primitive -> (primitive, [> `Msg of string ]) result
(** [validate p] is [p] checked by its kind's [validate]. *)
