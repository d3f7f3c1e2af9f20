(** PNG image files, through libpng (read) and camlimages (written).

    Images are written as 8-bit RGB PNG. The reader accepts what libpng
    reads (grey, palette, RGB, 16-bit samples, interlacing) as 8-bit RGB,
    decoded straight into the image's buffer, with the bytes camlimages'
    readers gave: alpha channels are dropped (not blended), 16-bit samples
    keep their high byte, an RGB file's transparent colour is ignored, and
    a palette file with one is refused. Errors are values whose message starts with
    the path, on one line: libpng's own messages to stderr are silenced. *)

val signature : string
(** [signature] is the 8 bytes every PNG file starts with. *)

val is_png : string -> bool
(** [is_png s] is [true] iff the file contents [s] start with {!signature}. *)

val read_file : ?limits:Raytrace.Limits.t -> string -> (Raytrace.Image.t, [> `Msg of string ]) result
(** [read_file ~limits path] reads and decodes the PNG file [path]. Its header's
    width and height are checked first, before libpng allocates anything:
    [Error] if they are beyond {!Raytrace.Limits.check_image_size} (the
    pixel bound of [limits], default {!Raytrace.Limits.default}) or if decoding would need more memory than is
    available (4 bytes a pixel); [Error] saying so if the decoding process
    runs out of memory or is killed by SIGKILL. *)

val to_string : Raytrace.Image.t -> (string, [> `Msg of string ]) result
(** [to_string img] is [img] encoded as an 8-bit RGB PNG file. [Error] if
    the temporary file that libpng writes through cannot be written. *)

val write_file : string -> Raytrace.Image.t -> (unit, [> `Msg of string ]) result
(** [write_file path img] writes [to_string img] to [path] atomically
    ({!Raytrace_unix.File_io.write_atomic}). *)
