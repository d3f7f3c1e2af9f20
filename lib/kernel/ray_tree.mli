(** The ray tree of transparent scenes: per-level storage, media, Snell's law.

    With transparency, a hit may spawn two rays, a reflected and a
    refracted one, and the tracer ({!Raytrace.Private.Trace}) follows the
    tree depth first, by recursion over levels. Level [l] is a hit [l]
    bounces below the camera: {b one depth for both kinds of ray}, counted
    along a path as the document's [recursion_depth] counts reflections
    (a ray that crosses a surface unbent and unweighted, an object of
    transparency 1 between equal indices, is the same ray and no bounce).
    Nothing here allocates per ray: each level has its slots in flat
    arrays made once per tracer, sized by the scene's depth.

    A ray's {e medium stack} lists the objects it is inside, innermost
    last, by material number (a mesh's triangles share one, so a ray
    entering through one triangle leaves through another). The index on
    the near side of a surface is the innermost medium's ([1], air, when
    the stack is empty), so nested and touching media refract by the
    ratio of their own indices. At most {!media_cap} media are kept; a
    ray entering more is treated as staying in the innermost kept one.

    @canonical Raytrace.Private.Ray_tree *)

type t = private {
  levels : int;  (** Levels of storage, [depth + 2]. *)
  pending : float array;
      (** Per level, {!pending_stride} floats: the origin and direction of
          the refracted ray waiting while the reflected one is traced. *)
  pending_leaving : int array;  (** Per level: the sphere slot the pending ray leaves, or [-1]. *)
  media : int array;  (** Per level, {!media_cap} ids: the medium stack of the level's ray. *)
  n_media : int array;  (** Per level: the size of its medium stack. *)
  pending_media : int array;  (** Per level: the pending ray's medium stack. *)
  pending_n_media : int array;
  node : float array;
      (** Per level, {!node_stride} floats: the hit's weighted local colour
          (3), the reflected and refracted weights, and the reflected
          colour once traced (3); one unused. *)
  weight : float array;  (** Per level: the product of the weights from the camera to it. *)
  tracing : int array;  (** Per level: [0] while its reflected child is traced, [1] its refracted one. *)
  attenuation : float array;  (** One float: the light a shadow ray lets through. *)
  optics : float array;  (** {!optics_size} floats: the arguments and results of {!indices} and {!split}. *)
}
(** The type for the storage of a tracer's ray tree. *)

val media_cap : int
(** [media_cap] is [16], the most media a ray's stack holds. *)

val pending_stride : int
(** [pending_stride] is [6]. *)

val node_stride : int
(** [node_stride] is [9]. *)

val optics_size : int
(** [optics_size] is [12]. *)

val create : depth:int -> t
(** [create ~depth] is the storage for trees of [depth] bounces. *)

val empty : t
(** [empty] has no level: the storage of a tracer of opaque scenes. *)

(** {1:media Media} *)

val find : int array -> int -> int -> int -> int
(** [find media base n id] is the position [k] (from [0]) of [id] in the
    stack [media.(base) .. media.(base + n - 1)], the innermost if it is
    there several times, or [-1]. *)

val top_index : float array -> int array -> int -> int -> float
(** [top_index index media base n] is [index.(id)] of the innermost medium
    of the stack, or [1.] for an empty stack: the index the ray is in. *)

val indices : float array -> int array -> int -> int -> int -> float array -> unit
(** [indices index media base n id io] sets [io.(0)] to the index on the
    near side of a surface of [id] ({!top_index}) and [io.(1)] to the index
    on its far side: [index.(id)] when the ray enters [id] ([id] is not in
    the stack); when it leaves it, the index of the medium under it if
    [id] was the innermost, else the innermost's (leaving an object one is
    not innermost in changes no index). (Floats pass through [io]: a float
    argument or result of a call that is not inlined is boxed.) *)

val cross : int array -> int -> int -> int -> int
(** [cross media base n id] updates the stack for crossing a surface of
    [id]: pushes [id] if absent (unless the stack is full), else removes
    it; the new size. *)

val copy_media : int array -> int -> int -> int array -> int -> unit
(** [copy_media src sbase n dst dbase] copies [n] ids. *)

(** {1:optics Optics} *)

val split : float array -> fresnel:bool -> unit
(** [split io ~fresnel] reads [n1 = io.(0)], [n2 = io.(1)], a direction
    [d = io.(2..4)] (any length > 0) and the unit normal [n = io.(5..7)]
    turned toward the ray ([<d, n> <= 0]) of a surface the ray crosses
    from index [n1] to [n2]; it writes the reflectance [R] to [io.(11)]
    and, unless [R = 1], the transmitted direction to [io.(8..10)] (unit
    length by Snell's law, or [d] itself when [n1 = n2]).

    [R] is [1.] for total internal reflection ([sin t >= 1], the critical
    angle included), Schlick's [R0 + (1 - R0)(1 - cos)^5] when [fresnel]
    (the cosine on the side of the lower index, so [R] is continuous at
    the critical angle), else [0.]; [0.] when [n1 = n2] (no interface: the
    ray goes straight on, unchanged; Schlick would reflect at grazing
    angles). Finite for every finite input with [|d| > 0]: the cosine is
    clamped to [\[0, 1\]], so grazing incidence gives no NaN. *)
