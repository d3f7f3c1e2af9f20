(** Reading one OBJ text on two cores.

    A text cut at a line start reads as its two parts read apart, then
    joined: the part after the cut by a reader that knows nothing of the
    text before ([create_part], [finish_part]), which sends its arrays
    as bytes while it reads, the part before by a reader of the whole text
    ({!Raytrace.Mesh.Obj.create}), which then [join]s the first's result, reading those
    bytes. Where the join cannot tell the mesh, the whole text's reader
    reads the second part itself: the mesh and the errors are always those
    of one reader. The core forks nothing: [Raytrace_unix.Files.read_mesh]
    reads the second part in a child process, which sends its bytes
    through a temporary file.

    {b Internal}: for [raytrace.unix] and the tests; it changes without
    notice.

    @canonical Raytrace.Private.Obj_parts *)

type part
(** The type for meshes read from a line start of a text on, without the
    text before: their counts, what their indices need of the text before,
    and how many bytes their reader sent. A part holds no function: a
    child process can send it back with [Marshal].

    @canonical Raytrace.Private.Obj_parts.part *)

val create_part :
  output:(Bytes.t -> int -> int -> unit) -> name:string -> max_vertices:int -> max_triangles:int -> Obj_file.parser
(** [create_part ~output ~name ~max_vertices ~max_triangles] is a reader,
    fed with {!Raytrace.Mesh.Obj.feed} and ended with [finish_part], of the text that
    starts at a line start of a larger text. It reads as {!Raytrace.Mesh.Obj.create}'s would
    but leaves the indices to check and resolve to [join], which knows
    how many vertices, normals and texture coordinates the text before
    defined: a negative index is never out of range here, nor a positive
    one. Its errors (a bad number, an index 0, a bound crossed by the
    part alone...) count lines from the part's start: a caller reads the
    part again with the whole text's reader to report them.

    Its arrays are not kept: they are sent by calls [output b off len],
    each of which must take all of [b.[off] .. b.[off+len-1]] (e.g. write
    it to a file) before it returns, 512 KiB at most at a time (a block of
    65536 numbers, 8 bytes each, in the machine's byte order), during
    {!Raytrace.Mesh.Obj.feed} and [finish_part], which raise what [output] raises. The
    reader then holds a few blocks, whatever the size of the text.
    @raise Invalid_argument where integers have fewer than 63 bits
    (JavaScript). *)

val finish_part : Obj_file.parser -> (part, [> `Msg of string ]) result
(** [finish_part p] reads the last line of [p]'s text (if it does not end
    with a line end), sends the rest of its arrays and is the part read.
    @raise Invalid_argument if [p] is not from {!create_part}, or if
    called twice on [p]. *)

val part_triangle_count : part -> int
(** [part_triangle_count part] is the number of triangles of [part]. *)

val part_bytes : part -> int
(** [part_bytes part] is the number of bytes that the reader of [part]
    sent to its output. *)

val join : Obj_file.parser -> part -> input:(Bytes.t -> int -> int -> unit) -> Obj_file.t option
(** [join p part ~input] is [Some m] where [p] (from {!Raytrace.Mesh.Obj.create}) was fed a
    text [a] that is empty or ends with a line end and [part] is the part
    read from a text [b]: [m] is then what {!Raytrace.Mesh.Obj.finish} of [p] fed [a] then
    [b] would be, every array and count the same. The bytes that the
    part's reader sent are read by calls [input b off len], each of which
    must fill [b.[off] .. b.[off+len-1]] or raise; they must be those
    bytes, from the same program on the same machine: like [Marshal],
    this is not a reader of untrusted input.

    It is [None] where that read would be an error or would differ (an
    index of [b] out of range given [a]'s counts, a bound crossed by [a]
    and [b] together), and where [p] is finished, holds an error or was
    fed a text that does not end with a line end, before any [input]:
    then [p] is unchanged, and feeding it [b] and finishing it is that
    read, mesh or error.
    @raise Failure if the bytes are not a part's, and what [input]
    raises; [p] is then unchanged too. *)
