(** Scene and PPM files: {!Raytrace.Scene_file} and {!Raytrace.Ppm} on files, read whole
    with a size bound and written atomically ({!File_io}). Errors start
    with the path. *)

val read_scene :
  ?limits:Limits.t ->
  ?jobs:int ->
  ?split_bytes:int ->
  ?on_part:(int -> unit) ->
  string ->
  (Scene.valid, [> `Msg of string ]) result
(** [read_scene ~limits ~jobs ~split_bytes ~on_part path] is the scene in
    file [path] ({!Raytrace.Scene_file.of_string} with [~file:path], its
    meshes read by {!read_mesh} with [jobs] and [split_bytes]); a file larger than the [`Scene_bytes]
    bound of [limits] (default {!Raytrace.Limits.default}) is refused
    before it is read. A regular file is read a window at a time
    ({!Raytrace.Scene_file.of_source}, the file opened again to locate an
    error), never held whole; others (pipes) are read whole.

    With [jobs > 1] (default [1]), a regular file of [split_bytes] bytes
    or more (default {!split_bytes}; tests use less) is read on two cores:
    a child process ({!Parallel.beside}) reads the spheres of its second
    half ({!Raytrace.Scene_file.read_part}), from a line start near the
    middle, while this one reads the first half. The scene and the errors
    are those of a read on one core, whatever the file holds; the child's
    spheres are simply not used when they are not exactly what that read
    would read. [on_part k] is called with the number [k] of spheres the
    child read, once it sent them. *)

val split_bytes : int
(** [split_bytes] is 4 MiB: the smallest file {!read_scene} and
    {!read_mesh} read on two cores by default. *)

val read_mesh :
  ?jobs:int -> ?split_bytes:int -> ?on_part:(pid:int -> int -> unit) -> string -> (Obj_file.t, [ `Msg of string ]) result
(** [read_mesh ~jobs ~split_bytes ~on_part path] is the Wavefront OBJ mesh
    in file [path], read 64 KiB at a time by
    {!Raytrace.Obj_file.feed_bytes}, with at most
    {!Raytrace.Limits.max_triangles} vertices and triangles. {!read_scene}
    reads a scene's meshes with it, with its [jobs] and [split_bytes].

    With [jobs > 1] (default [1]), a regular file of [split_bytes] bytes
    or more (default {!split_bytes}) is read on two cores: a child process
    ({!Parallel.beside}) reads from the first line start after the middle
    to the end ({!Raytrace.Obj_file.create_part}) while this one reads the
    first half, then joins the two ({!Raytrace.Obj_file.join}). The mesh
    and the errors are those of a read on one core, whatever the file
    holds: where the child failed or its part cannot be joined, this
    process reads the second half itself. [on_part ~pid k] is called when
    the child's part is joined, with the number [k] of its triangles and
    the id [pid] of the process that read it (this one's where no process
    could be forked). *)

val read_ppm : ?limits:Limits.t -> string -> (Image.t, [> `Msg of string ]) result
(** [read_ppm ~limits path] reads and decodes the PPM file [path]. A file
    larger than a binary image of the pixel bound of [limits] (default
    {!Raytrace.Limits.default}) is refused before it is read
    ({!Raytrace.Ppm.check_file_size}). *)

val write_ppm : ?comments:string list -> string -> Image.t -> (unit, [> `Msg of string ]) result
(** [write_ppm ~comments path img] writes [Ppm.to_string ~comments img] to
    [path] atomically ({!File_io.write_atomic}): [path] either keeps its
    old contents or gets the whole image. *)

val render_file :
  ?limits:Limits.t -> ?jobs:int -> string -> (Image.t, [> `Msg of string ]) result
(** [render_file ~limits ~jobs path] is the image of the scene in file
    [path] ({!read_scene}), one ray per pixel, rendered by [jobs] (default
    1) processes ({!Render_jobs.image}). *)
