(** Scene files: S-expressions, read with parsexp.

    A scene file is a sequence of top-level forms in any order, with [;]
    line comments, [#| |#] block comments and [#;] sexp comments:
{v
(canvas (width 600) (height 600))
(viewport (width 1) (height 1) (distance 1))
(camera (position 3 0 1) (rotation (0.7071 0 -0.7071) (0 1 0) (0.7071 0 0.7071)))
(background 0 0 0)
(recursion-depth 3)
(epsilon 0.001)
(sphere (center 0 -1 3) (radius 1) (color 255 0 0) (specular 500) (reflective 0.2))
(light ambient (intensity 0.2))
(light point (intensity 0.6) (position 2 1 0))
(light directional (intensity 0.2) (direction 1 4 4))
v}
    Every form but [sphere] and [light] may appear at most once and has a
    default ({!Scene.v}). A [camera] gives [position] (default the origin)
    and either [rotation] (three rows) or [look-at] with an optional [up].
    A [camera-path] animates the camera ({!Raytrace.Camera.Path}):
{v
(camera-path
 (key (frame 0) (position 0 0 -1) (look-at 0 0 3))
 (key (frame 48) (position 3 1 1) (look-at 0 0 3) (up 0 1 0)))
v}
    Each [key] gives [frame] (an integer in [\[0, Camera_path.max_frame\]]),
    [position] and [look-at], and optionally [up] (default [0 1 0]); keys
    come in increasing frame order. Without a [camera] form, a still
    picture of such a scene is the path's first frame.
    In a [sphere], [center], [radius] and [color] are required; [specular]
    defaults to [-1] (matte) and [reflective] to [0]. A material may be
    named once, [(material glass (color 230 230 255) (transparency 0.9))],
    and used by any later object as [(material glass)] in place of
    [color]; fields written on the object override the named material's. Numbers are OCaml
    floats ([1], [-0.5], [1e-3]), finite; sizes and depths are integers.

    An object's material may take an image texture (DESIGN.md, "Round 3:
    soft light, lenses, textures"):
    [(texture (file "earth.png") (mapping spherical))], the file (PPM or
    PNG) named relative to the scene file as a mesh's is and read by
    [load_texture], the mapping the one that fits the object
    ({!Texture_map.mapping_for}: [spherical] on a sphere, [planar] on a
    plane, which also takes [(size s)], [box] on a box, [uv] on a mesh).
    A transformed or instanced object shows its own texture in its own
    frame; a [transform] or [use] takes none of its own (an error at the
    field), and a CSG solid's operand none (an error at the form): the
    renderer does not draw them there yet.

    A UTF-8 byte order mark (bytes [EF BB BF], which some editors write)
    at the start of the text is read as blanks: columns still count its
    bytes.

    Errors are one line, [file:line:column: message], with 1-based lines
    and columns pointing at the offending text, e.g.
    [scenes/x.scene:4:17: sphere radius must be > 0, got -1]. Unknown forms
    and fields, duplicates, missing fields, wrong arities and values out of
    their domain ({!Sphere.validate}, {!Light.validate}, ...) are all
    errors. *)

type error = {
  file : string;  (** The source's name, the [file] argument. *)
  line : int;  (** 1-based; [0] for an error of the whole text (too long). *)
  column : int;  (** 1-based, in bytes; [0] with [line]. *)
  message : string;  (** What is wrong, without the location. *)
}
(** The type for errors with their location, beside their message. *)

val error_message : error -> string
(** [error_message e] is the one line [file:line:column: message] (or
    [file: message] without a line) that {!of_string} gives. *)

val pp_error : Format.formatter -> error -> unit
(** [pp_error ppf e] prints {!error_message}[ e]. *)

val located :
  ?limits:Limits.t ->
  ?load_mesh:(string -> (Obj_file.t, [ `Msg of string ]) result) ->
  ?load_texture:(string -> (Texture.t, [ `Msg of string ]) result) ->
  ?file:string ->
  ?reader:[ `Fast | `Parsexp ] ->
  string ->
  (Scene.valid, error) result
(** [located] is {!of_string} with the error's location as numbers: an
    editor can put its cursor there. *)

val of_string :
  ?limits:Limits.t ->
  ?load_mesh:(string -> (Obj_file.t, [ `Msg of string ]) result) ->
  ?load_texture:(string -> (Texture.t, [ `Msg of string ]) result) ->
  ?file:string ->
  ?reader:[ `Fast | `Parsexp ] ->
  string ->
  (Scene.valid, [> `Msg of string ]) result
(** [of_string ~limits ~load_mesh ~file ~reader text] is the scene described by
    [text], validated against [limits] (default {!Limits.default}). [Error]
    if [text] is longer than its [`Scene_bytes] bound (refused before it is
    parsed), or one of its top-level forms longer than its [`Form_bytes]
    bound (found as the text is parsed, 64 KiB at a time, before the form
    is held whole). [file] (default ["<string>"]) names the source in error
    messages. A [(mesh (file p) ...)] form is read by [load_mesh], given
    [p] joined to the directory of [file] when [p] is relative, once per
    path; its error becomes the form's (the default refuses every mesh:
    text alone names no file it can read;
    [Raytrace_unix.Files.read_scene] reads scene files and their meshes).
    A texture's file is read by [load_texture] likewise, once per path,
    its error told at the file's name (the default refuses every file;
    a loader's message is made one line, its control characters, which a
    file name may hold, escaped as [\n], [\r], [\t] or [\xNN]);
    the textures' pixels count together against [limits]' [`Pixels]
    bound (a path read twice counts once), refused at the file that
    passes it.
    Plain forms (parentheses, plain atoms, blanks and line comments) are
    read without parsexp, spheres straight into their values, unless
    [reader] (default [`Fast]) is [`Parsexp], which reads every form with
    parsexp: the same scenes and the same errors, slower (the tests
    compare the two). Never raises. *)

val to_string : Scene.t -> string
(** [to_string s] is {!Scene.show}[ s]: [s] in the scene-file syntax, every number written so
    that it reads back as the same float: [of_string (to_string s)] is
    [Ok v] with [Scene.of_valid v = s] for every [s] that passes
    {!Scene.validate}. *)
