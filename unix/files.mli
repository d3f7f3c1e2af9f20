(** Scene and PPM files: {!Raytrace.Scene_file} and {!Raytrace.Image.Ppm} on files, read whole
    with a size bound and written atomically ({!File_io}). Errors start
    with the path. *)

(** {1:scenes Scenes and the files they read} *)

type input = {
  what : string;  (** What it is to the scene, for messages: ["mesh"] or ["texture"]. *)
  path : string;  (** The path it was read from (joined to the scene file's directory). *)
  stats : Unix.stats;  (** Its identity and version when it was opened. *)
}
(** The type for files that a scene reads. *)

type loaded = {
  scene : Scene.valid;
  inputs : input list;
      (** Every file the scene read (its meshes and textures), once each, in the order
          first read; not the scene file itself. No output may replace one
          ({!Io_plan.check}), and a part's digest covers their contents
          ({!inputs_digest}). *)
}
(** The type for scenes read from files. *)

val load_scene :
  ?limits:Limits.t ->
  ?jobs:int ->
  ?split_bytes:int ->
  ?on_part:(int -> unit) ->
  ?read_image:(string -> (Image.t, [ `Msg of string ]) result) ->
  ?read_texture:(string -> (Image.Texture.t, [ `Msg of string ]) result) ->
  string ->
  (loaded, [> `Msg of string ]) result
(** [load_scene ~limits ~jobs ~split_bytes ~on_part ~read_image ~read_texture path]
    is {!read_scene} with the files the scene read. *)

val inputs_digest : input list -> (string, [> `Msg of string ]) result
(** [inputs_digest inputs] is [""] if [inputs] is empty, and otherwise the
    hex MD5 digest of what each input is and of its contents, read again,
    in order. [Error], naming the file, if one is no longer the version
    that was read (another file, or the same one written to since: its
    device, inode, size, modification or change time differ), before or
    while it is digested. *)

val read_scene :
  ?limits:Limits.t ->
  ?jobs:int ->
  ?split_bytes:int ->
  ?on_part:(int -> unit) ->
  ?read_image:(string -> (Image.t, [ `Msg of string ]) result) ->
  ?read_texture:(string -> (Image.Texture.t, [ `Msg of string ]) result) ->
  string ->
  (Scene.valid, [> `Msg of string ]) result
(** [read_scene ~limits ~jobs ~split_bytes ~on_part ~read_image ~read_texture path]
    is the scene in file [path] ({!Raytrace.Scene_file.of_string} with
    [~file:path]), its meshes read by {!read_mesh} with
    [jobs] and [split_bytes], its textures by [read_texture], else as
    images by [read_image], else by {!read_ppm_texture} (PPM files only,
    within [limits]; pass [Raytrace_png.Image_file.read_texture] for PNG
    too), a texture file's
    error prefixed by ["cannot read texture file: "]; a file larger than the [`Scene_bytes]
    bound of [limits] (default {!Raytrace.Limits.default}) is refused
    before it is read. A regular file is read a window at a time
    ({!Raytrace.Private.Scene_text.of_source}, the file opened again to locate an
    error), never held whole; others (pipes) are read whole, from the one
    descriptor {!File_io.open_read} opened: a FIFO that no program writes
    is an error, not a wait without end.

    With [jobs > 1] (default [1]), a regular file of [split_bytes] bytes
    or more (default {!split_bytes}; tests use less) is read on two cores:
    a child process ({!Parallel.beside}) reads the spheres of its second
    half ({!Raytrace.Private.Scene_text.read_part}), from a line start near the
    middle, while this one reads the first half. The scene and the errors
    are those of a read on one core, whatever the file holds; the child's
    spheres are simply not used when they are not exactly what that read
    would read. [on_part k] is called with the number [k] of spheres the
    child read, once it sent them. *)

val split_bytes : int
(** [split_bytes] is 4 MiB: the smallest file {!read_scene} and
    {!read_mesh} read on two cores by default. *)

val read_mesh :
  ?limits:Limits.t ->
  ?jobs:int ->
  ?split_bytes:int ->
  ?on_part:(pid:int -> int -> unit) ->
  string ->
  (Mesh.Obj.t, [ `Msg of string ]) result
(** [read_mesh ~limits ~jobs ~split_bytes ~on_part path] is the Wavefront
    OBJ mesh in file [path], read 64 KiB at a time by
    {!Raytrace.Mesh.Obj.feed_bytes}, with at most
    {!Raytrace.Limits.max_triangles} vertices and triangles. {!read_scene}
    reads a scene's meshes with it, with its [limits], [jobs] and
    [split_bytes]. [path] must be a regular file (opened without waiting:
    a FIFO, a directory or a device is an error that names it) within the
    [`Mesh_bytes] bound of [limits] (default {!Raytrace.Limits.default}),
    checked before it is read and as it is read. Errors start with
    ["cannot read mesh file: "] and [path], or name it.

    With [jobs > 1] (default [1]), a regular file of [split_bytes] bytes
    or more (default {!split_bytes}) is read on two cores: a child process
    ({!Parallel.beside}) reads from the first line start after the middle
    to the end ([Raytrace.Private.Obj_parts.create_part]) while this one reads the
    first half, then joins the two ([Raytrace.Private.Obj_parts.join]). The mesh
    and the errors are those of a read on one core, whatever the file
    holds: where the child failed or its part cannot be joined, this
    process reads the second half itself. [on_part ~pid k] is called when
    the child's part is joined, with the number [k] of its triangles and
    the id [pid] of the process that read it (this one's where no process
    could be forked). *)

val read_ppm_texture : ?limits:Limits.t -> string -> (Image.Texture.t, [> `Msg of string ]) result
(** [read_ppm_texture ~limits path] is the texture of the PPM file
    [path], a regular file, as [Texture.of_image] of {!read_ppm}'s image,
    with its errors, but read by {!Raytrace.Image.Ppm.texture_of_channel}:
    a P6 file's pixels go straight into the texture, so its reading holds
    about the texture's size, not three times it. *)

val read_ppm : ?limits:Limits.t -> string -> (Image.t, [> `Msg of string ]) result
(** [read_ppm ~limits path] reads and decodes the PPM file [path]. A file
    larger than a binary image of the pixel bound of [limits] (default
    {!Raytrace.Limits.default}) is refused before it is read
    ({!Raytrace.Image.Ppm.check_file_size}). *)

val write_ppm : ?comments:string list -> string -> Image.t -> (unit, [> `Msg of string ]) result
(** [write_ppm ~comments path img] writes [Image.Ppm.to_string ~comments img] to
    [path] atomically ({!File_io.write_atomic}): [path] either keeps its
    old contents or gets the whole image. *)

val render_file :
  ?limits:Limits.t -> ?jobs:int -> string -> (Image.t, [> `Msg of string ]) result
(** [render_file ~limits ~jobs path] is the image of the scene in file
    [path] ({!read_scene}), one ray per pixel, rendered by [jobs] (default
    1) processes ({!Render_jobs.image}). *)
