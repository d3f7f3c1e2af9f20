(** Parts of an image rendered separately, and their assembly.

    A part is a rectangle ({!Raytrace.Render.Region.t}) of a canvas, rendered by one
    process on one machine, together with every setting that changes its
    pixels: a digest of the scene, the recursion depth, the samples per
    pixel, the renderer, the frame. Parts are stored as binary PPM files
    whose header comments record all of this, so that any PPM reader shows
    them and {!merge} can refuse parts that do not belong together:
{v
P6
# raytrace-part 1
# canvas 600 600
# region 0 86 600 172
# depth 3
# samples 1
# renderer fast
# scene 9e107d9d372bb6826bd81d3542a419d6
600 86
255
v}
    Every pixel is traced alone, by the same code, so parts merge into
    exactly the bytes of the whole image rendered at once. *)

type t = {
  canvas_width : int;  (** Width of the whole image, in pixels. *)
  canvas_height : int;  (** Height of the whole image, in pixels. *)
  region : Render.Region.t;  (** Where the part lies in the whole image. *)
  settings : (string * string) list;
      (** The settings that change pixels, in order, as [(key, value)]:
          keys are non-empty words without spaces, values one line. *)
  image : Image.t;  (** The pixels of [region]. *)
}
(** The type for parts. *)

val v :
  canvas_width:int -> canvas_height:int -> region:Render.Region.t -> settings:(string * string) list ->
  Image.t -> t
(** [v ~canvas_width ~canvas_height ~region ~settings img] is a part.
    @raise Invalid_argument if [region] is not inside the canvas, [img] is
    not of [region]'s size, a key is empty or holds a space or line break, a
    value holds a line break, a key is repeated or is one of [raytrace-part],
    [canvas] and [region]. *)

val settings :
  ?frame:int ->
  ?samples:int ->
  ?adaptive:int ->
  ?subsample:bool ->
  ?renderer:string ->
  ?files:string ->
  Scene.t ->
  (string * string) list
(** [settings ~frame ~samples ~adaptive ~subsample ~renderer ~files scene]
    is the settings of a part of [scene]: [depth], [samples] (default
    [1]), [adaptive] (the threshold) when given, [subsample] when [true]
    ({!Raytrace.Render.Sampling.v}), [renderer] (default ["fast"]), [frame] when
    given, and last [scene], the MD5 digest of
    {!Raytrace.Scene_file.to_string}[ scene] (which covers every field of
    the scene, the canvas and the camera of the frame included, but of a
    mesh only its file's name) and of [files], the digest of the contents
    of the files the scene read ({!Files.inputs_digest}; default [""],
    for none: then the digest of the text alone). Parts of a scene whose
    mesh file changed between them thus have different digests. *)

val to_string : t -> string
(** [to_string p] is [p] as a binary PPM file of the part's pixels whose
    header comments record the canvas, the region and the settings. *)

val of_string : ?limits:Limits.t -> ?file:string -> string -> (t, [> `Msg of string ]) result
(** [of_string ~limits ~file s] is the part stored in the PPM file
    contents [s], within [limits] (default {!Raytrace.Limits.default}).
    [Error], with a message that starts with [file] (default
    ["<string>"]), if [s] is not a PPM file, has no [raytrace-part 1]
    header, or its header is malformed or disagrees with its pixels. *)

val read_file : ?limits:Limits.t -> string -> (t, [> `Msg of string ]) result
(** [read_file ~limits path] reads the part stored in file [path]; a file
    too large for an image within [limits] is refused before it is read
    ({!Raytrace.Image.Ppm.check_file_size}). *)

val write_file : string -> t -> (unit, [> `Msg of string ]) result
(** [write_file path p] writes [to_string p] to [path] atomically
    ({!File_io.write_atomic}). *)

val merge : (string * t) list -> (Image.t, [> `Msg of string ]) result
(** [merge parts] is the whole image assembled from [parts], each named
    (for messages) by its file. [Error] names the parts at fault if there
    are none, if two parts differ in canvas size or in a setting (the first
    one that differs, the scene digest last), if two parts overlap, or if
    some pixel is in no part. *)
