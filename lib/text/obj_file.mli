(** Wavefront OBJ meshes as flat arrays.

    A pure reader: the caller supplies the text, whole ({!of_string}) or
    in chunks of any size ({!create}, {!feed}, {!finish}), so that a large
    file is read 64 KiB at a time and never held whole. It keeps the
    statements that make a triangle mesh:
    - [v x y z [w]] a position (also [v x y z r g b], the common
      extension with a vertex colour; [w] and colours are ignored);
    - [vn x y z] a normal (kept as written, not normalised);
    - [vt u [v [w]]] a texture coordinate ([v] defaults to [0], [w] is
      ignored; they count against the bound of vertices);
    - [f] with 3 or more vertices, each [v], [v/vt], [v//vn] or
      [v/vt/vn], forms mixed freely, indices from 1 or negative (relative:
      [-1] is the last one defined); a polygon is fan-triangulated from
      its first vertex: [f 1 2 3 4] gives the triangles [1 2 3] and
      [1 3 4].

    Every other statement ([o], [g], [s], [usemtl], [mtllib], [l], [p],
    comments...) is skipped and counted ({!skipped}). Lines end
    with LF or CRLF; the last line needs no line end. A UTF-8 byte order
    mark (bytes [EF BB BF]) at the start of the text is skipped.

    Errors name [name:line:column] (both from 1, the column in bytes) and
    what was expected: a number that is malformed, NaN or infinite; an
    index that is zero or out of range; a face with fewer than 3
    vertices; more vertices or triangles than the caller's bounds; a line
    longer than {!max_line_bytes}.

    Memory: a mesh takes 24 bytes per vertex, 24 per normal and 48 per
    triangle (its vertex and normal numbers), so 72 bytes per triangle for
    a closed mesh with one normal per vertex (half as many vertices as
    triangles); where every corner's normal has its vertex's number, as
    most exporters write ([f 1//1 2//2 3//3]), the two numberings are one
    array ([triangle_normals == triangles]), 48 bytes per triangle.
    Loading builds the arrays in blocks, then concatenates them: its peak
    is about twice the mesh. Measured on a torus knot of 1M triangles
    (bench/obj_load.ml): 45.8 MB of mesh, a peak heap of 157 MB, a peak
    resident size of 121 MB.

    @canonical Raytrace.Mesh.Obj *)

(** {1:mesh Meshes} *)

type t = Obj_text.t = private {
  positions : float array;  (** [x y z] of each vertex, 3 floats per vertex. *)
  normals : float array;  (** [x y z] of each [vn], 3 floats per normal. *)
  triangles : int array;
      (** Three 0-based vertex numbers per triangle, in the face's order
          (counter-clockwise seen from the front, by OBJ's convention). *)
  triangle_normals : int array;
      (** Three 0-based normal numbers per triangle, parallel to
          [triangles]; [-1] where the face's vertex gives no normal. *)
  texcoords : float array;  (** [u v] of each [vt], 2 floats per texture coordinate. *)
  triangle_texcoords : int array;
      (** Three 0-based texture numbers per triangle, parallel to
          [triangles], [-1] where the face's vertex gives none; or [\[||\]]
          when no face of the file gives one (most meshes: no memory is
          spent on them). *)
  skipped : (string * int) list;
      (** How many statements of each skipped kind were read, in a fixed
          order of kinds, only those read at least once: ["#"] (comments),
          ["vp"], ["o"], ["g"], ["s"], ["usemtl"], ["mtllib"],
          ["l"], ["p"], then ["other"] for any other keyword. *)
}
(** The type for triangle meshes. Every index is within its array.

    @canonical Raytrace.Mesh.Obj.t *)

val v : positions:float array -> normals:float array -> triangles:int array -> triangle_normals:int array -> t
(** [v ~positions ~normals ~triangles ~triangle_normals] is the mesh of
    these arrays, with no skipped statements.
    @raise Invalid_argument if a length is not a multiple of 3, the two
    triangle arrays differ in length, a vertex number is outside the
    positions or a normal number (other than [-1]) outside the normals. *)

val with_texcoords : texcoords:float array -> triangle_texcoords:int array -> t -> t
(** [with_texcoords ~texcoords ~triangle_texcoords m] is [m] with these
    texture coordinates and numbers.
    @raise Invalid_argument if [texcoords]'s length is odd,
    [triangle_texcoords] is neither empty nor as long as [m.triangles], or
    a number (other than [-1]) is outside [texcoords]. *)

val texcoord_count : t -> int
(** [texcoord_count m] is [Array.length m.texcoords / 2]. *)

val vertex_count : t -> int
(** [vertex_count m] is [Array.length m.positions / 3]. *)

val triangle_count : t -> int
(** [triangle_count m] is [Array.length m.triangles / 3]. *)

val skipped_total : t -> int
(** [skipped_total m] is the sum of the counts of [m.skipped]. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff every array and count of [a] equals [b]'s
    (floats compared with [Float.equal]: bit for bit but for NaNs, which a
    mesh never holds). *)

(** {1:reading Reading} *)

val max_line_bytes : int
(** [max_line_bytes] is [1_048_576]: the longest line read (a face of
    about 100000 vertices), so that a chunked reader's line buffer stays
    bounded whatever the input. *)

type parser = Obj_text.parser
(** The type for readers of one OBJ text fed in chunks. *)

val create : name:string -> max_vertices:int -> max_triangles:int -> parser
(** [create ~name ~max_vertices ~max_triangles] is a reader that names
    [name] (a file name) in its errors, and refuses more than
    [max_vertices] positions (and as many normals) and more than
    [max_triangles] triangles (after triangulation). *)

val feed : parser -> string -> int -> int -> (unit, [> `Msg of string ]) result
(** [feed p s off len] reads the bytes [s.[off] .. s.[off+len-1]], which
    continue those fed before; chunk boundaries may fall anywhere, inside
    numbers and line ends included. After an error, every later [feed]
    and {!finish} return that error.
    @raise Invalid_argument if [off] and [len] do not designate a
    substring of [s], or after {!finish}. *)

val feed_bytes : parser -> Bytes.t -> int -> int -> (unit, [> `Msg of string ]) result
(** [feed_bytes] is {!feed} on bytes, e.g. the buffer of [input]; the
    bytes may be changed once it returns. *)

val finish : parser -> (t, [> `Msg of string ]) result
(** [finish p] reads the last line (if the text does not end with a line
    end) and is the mesh read.
    @raise Invalid_argument if called twice on [p]. *)

val of_string : name:string -> max_vertices:int -> max_triangles:int -> string -> (t, [> `Msg of string ]) result
(** [of_string ~name ~max_vertices ~max_triangles s] is the mesh of the
    OBJ text [s] (see {!create}). *)

(** {1:writing Writing} *)

val to_buffer : ?digits:int -> Buffer.t -> t -> unit
(** [to_buffer ~digits b m] appends the OBJ text of [m] to [b]: the [v]
    lines, the [vn] lines, then one [f] line per triangle ([a b c],
    [a//n b//n c//n] or a mix). Numbers have [digits] significant digits
    ([%g]), like the 6 to 9 of most exporters; without [digits] (or with
    [digits <= 0]) they read back as the same floats, so that
    {!of_string} of the text is {!equal} to [m] but for [skipped]. *)

val to_string : ?digits:int -> t -> string
(** [to_string ~digits m] is the text of {!to_buffer}. *)
