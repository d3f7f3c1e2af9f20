(** Triangle meshes, as flat arrays.

    A mesh is many triangles that share vertices, with one material, an
    optional normal per triangle corner for smooth shading, and the
    placement of its file in the scene ([scale], then [translate]). Each
    of its triangles is an object of the kernel of its own, so that meshes
    share the watertight test ([Triangle.roots_at]), the hierarchy and
    everything else with the other shapes; the kernel reads its corners
    in [positions], where neighbouring triangles read them too: a shared
    edge is computed from the same floats in both triangles, and leaks no
    ray. *)

type found
(** The type for what a mesh finds of its triangles when it is made
    (which are degenerate, how many are not), for the tracer. *)

type t = private {
  positions : float array;  (** [x y z] per vertex, already scaled and translated. *)
  triangles : int array;  (** Three 0-based vertex numbers per triangle. *)
  normals : float array;  (** [x y z] per normal, as given (any length). *)
  triangle_normals : int array;
      (** Three 0-based normal numbers per triangle, parallel to
          [triangles]; [-1] where a corner has none. *)
  texcoords : float array;  (** [u v] per texture coordinate (the file's [vt]), as given. *)
  triangle_texcoords : int array;
      (** Three 0-based texture numbers per triangle, parallel to
          [triangles], [-1] where a corner has none; or [\[||\]] when no
          triangle has any. *)
  smooth : bool;
      (** Shade with the normals interpolated across each triangle (where
          all three corners have a usable one), not the flat normal. *)
  material : Material.t;
  source : string;  (** The file it was read from, as the scene names it; [""] if none. *)
  scale : float;  (** The scale applied to the file's positions. *)
  translate : Vec3.t;  (** The translation applied after the scale. *)
  skipped : int;  (** Statements of the file that were skipped (not v, vn or f). *)
  found : found;  (** What the mesh found of its triangles: {!degenerate}, {!val-objects}. *)
}
(** The type for meshes. *)

val v :
  ?smooth:bool ->
  ?scale:float ->
  ?translate:Vec3.t ->
  ?source:string ->
  ?skipped:int ->
  ?texcoords:float array ->
  ?triangle_texcoords:int array ->
  positions:float array ->
  triangles:int array ->
  normals:float array ->
  triangle_normals:int array ->
  Material.t ->
  (t, [> `Msg of string ]) result
(** [v ~positions ~triangles ~normals ~triangle_normals m] is the mesh of
    these arrays (positions as in the file), each position [p] placed at
    [scale * p + translate] ([scale] defaults to [1], [translate] to zero,
    [smooth] to [false], [source] to [""], [skipped] to [0]). It is an
    error if the arrays are inconsistent (lengths not multiples of 3, an
    index outside its array), if [scale] is not finite and [> 0], if a
    placed coordinate is beyond {!Limits.max_coordinate}, or if there is
    no triangle; [texcoords] and [triangle_texcoords] (default none) are
    checked likewise. Degenerate triangles (their vertices on a line) are kept
    here and dropped by the kernel, which can never hit them. *)

val of_obj :
  ?smooth:bool ->
  ?scale:float ->
  ?translate:Vec3.t ->
  ?source:string ->
  Obj_file.t ->
  Material.t ->
  (t, [> `Msg of string ]) result
(** [of_obj ~smooth ~scale ~translate ~source obj m] is the mesh of
    [obj]'s arrays placed as {!v} places them, with [skipped] set to
    {!Raytrace.Mesh.Obj.skipped_total}[ obj]: the mesh the scene form
    [(mesh (file source) (scale ...) (translate ...) (smooth ...))]
    makes of its file, its texture coordinates included, and the errors
    of {!v}. The placed positions are
    a new array; the index and normal arrays are [obj]'s, shared. *)

val triangle_count : t -> int
(** [triangle_count m] is the number of triangles of [m]. *)

val vertex : t -> int -> int -> Vec3.t
(** [vertex m k c] is corner [c] (0 to 2) of triangle [k], placed. *)

val triangle : t -> int -> Triangle.t
(** [triangle m k] is triangle [k] of [m], with [m]'s material. *)

val has_texcoords : t -> bool
(** [has_texcoords m] is [true] iff some triangle of [m] has texture
    numbers ([m.triangle_texcoords] is not empty). *)

val store_texcoords : t -> int -> float array -> int -> unit
(** [store_texcoords m t uv j] writes the [u v] of triangle [t]'s three
    corners, in their order, into [uv.(j .. j + 5)]; a corner without a
    [vt] leaves its two floats as they are (the kernel's tables start
    them at [0 0]). Needs {!has_texcoords}[ m]. Both the table of a
    plain mesh's [vt] and a CSG mesh operand's ({!Csg}) are filled by it. *)

val texcoord : t -> int -> b1:float -> b2:float -> (float * float) option
(** [texcoord m k ~b1 ~b2] is the texture coordinates [(u, v)] of the
    point of triangle [k] of barycentric weights [(1 - b1 - b2, b1, b2)]
    (those of {!Texture_map.barycentric} on its placed corners, corner 0
    first): {!Texture_map.interpolate} of its corners' [vt]; [None] if a
    corner has none.
    @raise Invalid_argument if [k] is not a triangle of [m]. *)

val degenerate : t -> int -> bool
(** [degenerate m k] is [true] iff triangle [k] has no normal: its
    vertices lie on a line, as {!Triangle.validate} refuses. *)

val objects : t -> int
(** [objects m] is the number of [m]'s triangles that are not
    {!degenerate}: the objects it gives the kernel (no ray can hit the
    others). *)

val unit_normal : t -> int -> float array -> int -> bool
(** [unit_normal m j g o] writes normal [j] of [m], divided by its length,
    to [g] at [o .. o + 2] and is [true], if its length can be normalised
    (it is [> 0], finite, and so is its inverse); otherwise it is [false]
    and [g] is unchanged. *)

val corner_normals : t -> int -> float array -> int -> bool
(** [corner_normals m k g o] writes the unit normals of the three corners
    of triangle [k] to [g] at [o .. o + 8] and is [true], if [m] is
    [smooth] and every corner has a normal of a length that can be
    normalised; otherwise it is [false] (and may have written some of
    them). *)

val box : t -> int -> float array -> unit
(** [box m k b] writes the box of triangle [k] to [b]: its lower corner
    [x y z] at [0 .. 2], its upper corner at [3 .. 5]. *)

val flat_view : t -> t
(** [flat_view m] is [m] if it is [smooth]; otherwise [m] without its
    normals ([normals] empty, every other field [m]'s, shared): all that a
    flat mesh's shading reads, none of its normals. [Prepared] holds it in
    place of [m], so that the normals go with a scene let go (12 MB for a
    million of them). Its [triangle_normals] are [m]'s: they may name
    normals it no longer has, as no mesh of {!v} does. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff every field of [a] equals [b]'s, floats
    compared with [Float.equal]. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf m] prints a summary of [m]: its source (quoted, or
    [built in code] if it has none), triangle count and placement. *)

val pp_form : Format.formatter -> t -> unit
(** [pp_form ppf m] prints [m] as its form in the scene-file syntax: the
    form that reads its file again ([file], [scale], [translate],
    [smooth] when true, the material's fields). A mesh with no [source]
    (built in code) has no file to read again and the syntax has no
    inline mesh: it prints as [(mesh (file "") ...)] after a [;] comment
    line that says so and gives its triangle count, which a scene file
    refuses ("expected a file name") rather than reading a wrong mesh. *)
