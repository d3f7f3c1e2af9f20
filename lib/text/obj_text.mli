(** The reader and writer of Wavefront OBJ text, whole: {!Raytrace.Mesh.Obj}
    shows users its meshes, reading and writing, and
    {!Raytrace.Private.Obj_parts} the reading of a text in two parts on two
    cores. One module, because the two readers share the parser's state and
    its loop; each function is documented in the module that shows it,
    under the same name.

    {b Internal}: it changes without notice. *)

(** {1:mesh Meshes} *)

type t = private {
  positions : float array;
  normals : float array;
  triangles : int array;
  triangle_normals : int array;
  texcoords : float array;
  triangle_texcoords : int array;
  skipped : (string * int) list;
}
(** The type for triangle meshes: {!Raytrace.Mesh.Obj.t}.

    @canonical Raytrace.Mesh.Obj.t *)

val v : positions:float array -> normals:float array -> triangles:int array -> triangle_normals:int array -> t
(** {!Raytrace.Mesh.Obj.v}. *)

val with_texcoords : texcoords:float array -> triangle_texcoords:int array -> t -> t
(** {!Raytrace.Mesh.Obj.with_texcoords}. *)

val texcoord_count : t -> int
(** {!Raytrace.Mesh.Obj.texcoord_count}. *)

val vertex_count : t -> int
(** {!Raytrace.Mesh.Obj.vertex_count}. *)

val triangle_count : t -> int
(** {!Raytrace.Mesh.Obj.triangle_count}. *)

val skipped_total : t -> int
(** {!Raytrace.Mesh.Obj.skipped_total}. *)

val equal : t -> t -> bool
(** {!Raytrace.Mesh.Obj.equal}. *)

(** {1:reading Reading} *)

val max_line_bytes : int
(** {!Raytrace.Mesh.Obj.max_line_bytes}. *)

type parser
(** The type for readers of one OBJ text fed in chunks.

    @canonical Raytrace.Mesh.Obj.parser *)

val create : name:string -> max_vertices:int -> max_triangles:int -> parser
(** {!Raytrace.Mesh.Obj.create}. *)

val feed : parser -> string -> int -> int -> (unit, [> `Msg of string ]) result
(** {!Raytrace.Mesh.Obj.feed}. *)

val feed_bytes : parser -> Bytes.t -> int -> int -> (unit, [> `Msg of string ]) result
(** {!Raytrace.Mesh.Obj.feed_bytes}. *)

val finish : parser -> (t, [> `Msg of string ]) result
(** {!Raytrace.Mesh.Obj.finish}. *)

val of_string : name:string -> max_vertices:int -> max_triangles:int -> string -> (t, [> `Msg of string ]) result
(** {!Raytrace.Mesh.Obj.of_string}. *)

(** {1:writing Writing} *)

val to_buffer : ?digits:int -> Buffer.t -> t -> unit
(** {!Raytrace.Mesh.Obj.to_buffer}. *)

val to_string : ?digits:int -> t -> string
(** {!Raytrace.Mesh.Obj.to_string}. *)

(** {1:parts Reading on two cores} *)

type part
(** The type for parts: {!Raytrace.Private.Obj_parts.part}.

    @canonical Raytrace.Private.Obj_parts.part *)

val create_part :
  output:(Bytes.t -> int -> int -> unit) -> name:string -> max_vertices:int -> max_triangles:int -> parser
(** {!Raytrace.Private.Obj_parts.create_part}. *)

val finish_part : parser -> (part, [> `Msg of string ]) result
(** {!Raytrace.Private.Obj_parts.finish_part}. *)

val part_triangle_count : part -> int
(** {!Raytrace.Private.Obj_parts.part_triangle_count}. *)

val part_bytes : part -> int
(** {!Raytrace.Private.Obj_parts.part_bytes}. *)

val join : parser -> part -> input:(Bytes.t -> int -> int -> unit) -> t option
(** {!Raytrace.Private.Obj_parts.join}. *)
