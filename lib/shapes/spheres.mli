(** Sequences of spheres, stored compactly.

    A scene's spheres (inside a {!Scene.t}): their centers and radii in
    float arrays, their materials as indices into a table of distinct
    materials: five words a sphere, against a block per field of a
    list of {!Sphere.t}, each scanned by the garbage collector. The order is the scene's: sphere [i] is
    the [i]-th sphere given. *)

(** {1:spheres Spheres} *)

type t
(** The type for sequences of spheres.

    @canonical Raytrace.Private.Spheres.t *)

val empty : t
(** [empty] holds no sphere. *)

val of_list : Sphere.t list -> t
(** [of_list l] holds the spheres of [l], in order. *)

val to_list : t -> Sphere.t list
(** [to_list s] is the spheres of [s], in order. *)

val length : t -> int
(** [length s] is the number of spheres of [s]. *)

val get : t -> int -> Sphere.t
(** [get s i] is sphere [i] of [s] (a new value at each call).
    @raise Invalid_argument if [i] is not in [\[0, length s - 1\]]. *)

val iter : (Sphere.t -> unit) -> t -> unit
(** [iter f s] applies [f] to the spheres of [s] in order. *)

val iteri : (int -> Sphere.t -> unit) -> t -> unit
(** [iteri f s] applies [f i] to each sphere [i] of [s] in order. *)

val fold : ('a -> Sphere.t -> 'a) -> 'a -> t -> 'a
(** [fold f acc s] is [f (... (f acc s0) ...) sn], the spheres in order. *)

val exists : (Sphere.t -> bool) -> t -> bool
(** [exists p s] is [true] iff some sphere of [s] satisfies [p]. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] have the same length and equal
    spheres ({!Sphere.equal}) at each index, however their materials are
    numbered. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf s] prints the spheres of [s] with {!Sphere.pp}, one a line. *)

(** {1:fields Fields without a sphere value}

    What loading and preparing a big scene read, allocating nothing. *)

val center_x : t -> int -> float
(** [center_x s i] is the x coordinate of the center of sphere [i].
    @raise Invalid_argument if [i] is out of bounds, as do the next ones. *)

val center_y : t -> int -> float
(** [center_y s i] is the y coordinate of the center of sphere [i]. *)

val center_z : t -> int -> float
(** [center_z s i] is the z coordinate of the center of sphere [i]. *)

val radius : t -> int -> float
(** [radius s i] is the radius of sphere [i]. *)

val material_index : t -> int -> int
(** [material_index s i] is the index in [materials s] of the material of
    sphere [i]. *)

val blit_fields :
  t -> x:float array -> y:float array -> z:float array -> radius:float array -> material:int array -> unit
(** [blit_fields s ~x ~y ~z ~radius ~material] writes the center, radius
    and {!material_index} of each sphere [i] of [s] at index [i] of the
    arrays, a block at a time.
    @raise Invalid_argument if an array is shorter than [length s]. *)

val materials : t -> Material.t array
(** [materials s] is the table of the materials of [s] (a copy): distinct
    bit for bit, but for patterned materials, which are kept as given. *)

(** {1:building Building} *)

type builder
(** The type for sequences being built, for readers that do not know how
    many spheres will come. It grows by blocks: no array is copied to a
    larger one, so the peak memory is the spheres' own.

    @canonical Raytrace.Private.Spheres.builder *)

val builder : unit -> builder
(** [builder ()] is an empty builder. *)

val builder_length : builder -> int
(** [builder_length b] is the number of spheres added to [b]. *)

val material : builder -> Material.t -> int
(** [material b m] is the index of [m] in [b]'s table: that of a material
    equal to [m] bit for bit if there is one and [m] has no pattern,
    otherwise a new one. *)

val add : builder -> Sphere.t -> unit
(** [add b s] appends [s] to [b]. *)

val add_fields : builder -> x:float -> y:float -> z:float -> radius:float -> int -> unit
(** [add_fields b ~x ~y ~z ~radius m] appends the sphere of center
    [(x, y, z)], radius [radius] and material [m], an index that
    {!material} returned for [b].
    @raise Invalid_argument if [m] is not such an index. *)

val append : builder -> t -> unit
(** [append b s] appends the spheres of [s] to [b], in order, after
    adding the materials of [s]'s table to [b]'s ({!material}) in the
    order of that table: spheres read in two halves and appended give the
    sequence and the table that one sequential read gives, when [s]'s
    table is in the order of first use (as {!build} makes it). *)

val append_fields :
  builder -> x:float array -> y:float array -> z:float array -> radius:float array -> material:int array -> int -> unit
(** [append_fields b ~x ~y ~z ~radius ~material n] appends to [b] the [n]
    spheres [i] of center [(x.(i), y.(i), z.(i))], radius [radius.(i)] and
    material [material.(i)], an index that {!material} returned for [b],
    in order, a block at a time.
    @raise Invalid_argument if an array is shorter than [n] or a material
    is not such an index (then nothing is appended). *)

val build : builder -> t
(** [build b] is the spheres added to [b], in order. [b] must not be
    used afterwards. *)
