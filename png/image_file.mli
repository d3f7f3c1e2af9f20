(** Image files in the format their name or contents say: PPM or PNG.

    PPM ({!Raytrace.Image.Ppm}) is the default and needs no library; a name
    ending in [.png] (in any case) means PNG ({!Png_file}). *)

type format = Ppm | Png  (** The type for image file formats. *)

val format_of_path : string -> format
(** [format_of_path path] is [Png] if [path] ends in [.png], ignoring case,
    and [Ppm] otherwise. *)

val extension : format -> string
(** [extension f] is [".ppm"] or [".png"]. *)

val write_file : string -> Raytrace.Image.t -> (unit, [> `Msg of string ]) result
(** [write_file path img] writes [img] to [path] atomically, in
    [format_of_path path]. *)

val read_file : ?limits:Raytrace.Limits.t -> string -> (Raytrace.Image.t, [> `Msg of string ]) result
(** [read_file ~limits path] reads the image in [path]: a PNG file if its contents
    start with the PNG signature, whatever its name; [Error] if they do not
    and [path] ends in [.png]; and otherwise a PPM file. A file larger than
    a PPM image within [limits] (default {!Raytrace.Limits.default}) is
    refused before it is read. *)

val read_texture : ?limits:Raytrace.Limits.t -> string -> (Raytrace.Image.Texture.t, [> `Msg of string ]) result
(** [read_texture ~limits path] is the texture of the image in [path], as
    [Texture.of_image] of {!read_file}'s image, with its errors: a PNG
    file decoded by {!Png_file.read_file}, a PPM file read by
    [Raytrace_unix.Files.read_ppm_texture] (its pixels straight into the
    texture: the reading holds about the texture's size). Only the first
    8 bytes are read to tell the two apart. *)
