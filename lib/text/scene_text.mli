(** The reader of scene text ({!Raytrace.Scene_file} is its public face):
    the sequential read, its fast path for plain forms, and the part of a
    text read beside it in another process.

    {b Internal}: reached through [Raytrace.Private.Scene_text] by the
    system libraries ([Raytrace_unix.Files]) and the tests. *)

type error = { file : string; line : int; column : int; message : string }
(** The type for errors with their location ({!Raytrace.Scene_file.error}). *)

val error_message : error -> string
(** [error_message e] is {!Raytrace.Scene_file.error_message}. *)

val located :
  ?limits:Limits.t ->
  ?load_mesh:(string -> (Obj_file.t, [ `Msg of string ]) result) ->
  ?load_texture:(string -> (Texture.t, [ `Msg of string ]) result) ->
  ?file:string ->
  ?reader:[ `Fast | `Parsexp ] ->
  string ->
  (Scene.valid, error) result
(** [located] is {!Raytrace.Scene_file.located}. *)

val of_string :
  ?limits:Limits.t ->
  ?load_mesh:(string -> (Obj_file.t, [ `Msg of string ]) result) ->
  ?load_texture:(string -> (Texture.t, [ `Msg of string ]) result) ->
  ?file:string ->
  ?reader:[ `Fast | `Parsexp ] ->
  string ->
  (Scene.valid, [> `Msg of string ]) result
(** [of_string] is {!Raytrace.Scene_file.of_string}. *)

(** {1:streams Reading a text a window at a time} *)

type reader = { read : Bytes.t -> int -> int -> int; close : unit -> unit }
(** The type for texts being read: [read buf pos len] puts at most [len]
    bytes of the text, the next ones, in [buf] from [pos] and is how many,
    [0] at the end only (as [input] does); [close ()] is called once
    reading is done, or has failed. *)

type source = unit -> reader
(** The type for texts that can be read again: each call reads the text
    from its start (a failed load reads it a second time, to locate its
    error). *)

val string_source : string -> source
(** [string_source s] reads [s]. *)

(** {1:parts Reading the second half beside}

    A big scene of plain spheres is read on two cores: another process
    reads the spheres from a line start near the middle of the text
    ({!read_part}) while {!of_source} reads up to there, then uses that
    part instead of reading it, if it is exactly what it would have read.
    The core library forks nothing: [Raytrace_unix.Files.read_scene] does. *)

type part
(** The type for the spheres read from a point of a text on: a sequence of
    plain sphere forms that the sequential read would read on its fast
    path, with where it starts and stops. It holds no function (it can be
    sent between processes with [Marshal]). *)

val read_part : ?limits:Limits.t -> ?window_bytes:int -> reader -> from:int -> part
(** [read_part ~limits ~window_bytes r ~from] is the part of the text that
    [r] reads, which must be the text from absolute offset [from] on, read
    [window_bytes] (default 1 MiB) at a time: its plain sphere forms
    (parentheses, plain atoms, blanks, line comments, the fields of a
    sphere once each, finite numbers, values that pass the checks of
    {!of_string}) from the first form at or after [from] up to the first
    thing that is not one, or a form bound ([`Form_bytes] of [limits],
    default {!Limits.default}) that would be crossed. It makes no error:
    what it does not read is left to {!of_source}. Exceptions of [r.read]
    end the part where it got to; [r.close] is not called. *)

val part_length : part -> int
(** [part_length p] is the number of spheres of [p]. *)

val part_spheres : part -> Spheres.t
(** [part_spheres p] is the spheres of [p], in order, their material
    table {!part_materials}; {!Raytrace.Private.Spheres.empty} for a {!part_header}. *)

val part_materials : part -> Material.t array
(** [part_materials p] is the table of the materials of [p]'s spheres, in
    the order of first use. *)

val part_header : part -> part
(** [part_header p] is [p] without its spheres' fields ({!part_spheres} is
    empty), its length and materials kept: what a process that sends the
    fields another way sends by [Marshal]. *)

val append_part : Spheres.builder -> part -> unit
(** [append_part b p] is {!Raytrace.Private.Spheres.append}[ b (part_spheres p)]. *)

type beside = {
  split : int;  (** The absolute offset, a line start, of the part's [from]. *)
  wait : unit -> part option;
      (** Waits for the part ([None] if it could not be read), once. *)
  append : Spheres.builder -> part -> unit;
      (** [append b p] appends the spheres of the part [p] that [wait] gave
          to [b], materials first, as {!append_part} does: [wait] may give a
          {!part_header} whose fields [append] reads from elsewhere. *)
  seek : int -> unit;
      (** [seek o] makes the next read of the source's first reader start at
          absolute offset [o]. *)
}
(** The type for a part being read beside a read of the whole text. *)

val of_source :
  ?limits:Limits.t ->
  ?load_mesh:(string -> (Obj_file.t, [ `Msg of string ]) result) ->
  ?load_texture:(string -> (Texture.t, [ `Msg of string ]) result) ->
  ?file:string ->
  ?reader:[ `Fast | `Parsexp ] ->
  ?window_bytes:int ->
  ?beside:beside ->
  source ->
  (Scene.valid, [> `Msg of string ]) result
(** [of_source ~limits ~load_mesh ~file ~reader ~window_bytes ~beside src] is
    {!of_string} on the text of [src], read [window_bytes] (default 1 MiB;
    tests use a few) at a time: a big scene is never held whole as text,
    only its current window (more for a form longer than one). The same
    scenes, the same errors, positions included. The text's size is
    checked against its [`Scene_bytes] bound as it is read; a caller that
    knows it (a file's) checks it first. Exceptions of [src]'s functions
    ([Sys_error]) are not caught.

    With [beside], the read waits for the part when it gets to
    [beside.split] (or at its end, if it ends before), and if it is then
    between two forms, outside any comment, with the part's first sphere
    next, and the part's spheres keep within the [`Spheres] bound, it
    appends them, their materials in order of first use, seeks past them
    and reads on from there: the same scene and errors as without
    [beside]. Otherwise the part is not used. [beside] is not used with
    [~reader:`Parsexp]. *)

val to_string : Scene.t -> string
(** [to_string] is {!Raytrace.Scene_file.to_string}. *)
