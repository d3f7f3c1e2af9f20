(** PPM image files (Netpbm's portable pixmap).

    Images are written as binary P6 with maxval 255. The reader accepts P6
    and plain P3, with [#] comments in the header, and maxval from 1 to 255
    (values are rescaled to 0-255). *)

val to_string : Image.t -> string
(** [to_string img] is [img] as a binary P6 file: the header
    ["P6\n<w> <h>\n255\n"] then the pixels, rows top-down. *)

val output : out_channel -> Image.t -> unit
(** [output oc img] writes [to_string img] to [oc], through a 64 KiB
    buffer rather than a copy of the image. *)

val of_string : string -> (Image.t, [> `Msg of string ]) result
(** [of_string s] is the image in the PPM file contents [s]. [Error] says
    what is wrong and where (byte offset): not a PPM, a bad or missing
    header field, a maxval outside [\[1, 255\]], missing or extra pixel
    data, a P3 sample above maxval, an image of more pixels than
    {!Limits.check_image_size} allows (checked before any allocation). It
    never raises. *)

val read_file : string -> (Image.t, [> `Msg of string ]) result
(** [read_file path] reads and decodes the PPM file [path]. [Error]
    messages start with [path]. A file larger than a binary image of the
    {!Limits} pixel bound ([3] bytes a pixel, plus 1 MiB of header) is
    refused before it is read. *)

val write_file : string -> Image.t -> (unit, [> `Msg of string ]) result
(** [write_file path img] writes [img] to [path] atomically
    ({!File_io.write_atomic}): [path] either keeps its old contents or gets the
    whole image. *)
