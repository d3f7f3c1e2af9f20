(** PPM image files (Netpbm's portable pixmap).

    Images are written as binary P6 with maxval 255. The reader accepts P6
    and plain P3, with [#] comments in the header, and maxval from 1 to 255
    (values are rescaled to 0-255).

    @canonical Raytrace.Image.Ppm *)

val to_string : ?comments:string list -> Image.t -> string
(** [to_string ~comments img] is [img] as a binary P6 file: the header
    ["P6\n<w> <h>\n255\n"] then the pixels, rows top-down. Each of
    [comments] (default none) is a header line ["# <comment>\n"] after
    ["P6\n"], which every PPM reader skips.
    @raise Invalid_argument if a comment contains a line break. *)

val output : ?comments:string list -> out_channel -> Image.t -> unit
(** [output ~comments oc img] writes [to_string ~comments img] to [oc],
    through a 64 KiB buffer rather than a copy of the image. *)

val header : ?comments:string list -> Image.t -> string
(** [header ~comments img] is the start of [to_string ~comments img], up to
    its first pixel.
    @raise Invalid_argument if a comment contains a line break. *)

val output_rows : out_channel -> Image.t -> first:int -> stop:int -> unit
(** [output_rows oc img ~first ~stop] writes the bytes of rows [first] to
    [stop - 1] of [img] to [oc], as {!output} writes them after the
    {!header}: an image can be written in parts while it is being made.
    @raise Invalid_argument if [0 <= first <= stop <= Image.height img]
    does not hold. *)

val of_string : ?limits:Limits.t -> string -> (Image.t, [> `Msg of string ]) result
(** [of_string ~limits s] is the image in the PPM file contents [s]. [Error] says
    what is wrong and where (byte offset): not a PPM, a bad or missing
    header field, a maxval outside [\[1, 255\]], missing or extra pixel
    data, a P3 sample above maxval, an image of more pixels than
    {!Limits.check_image_size} allows with [limits] (default
    {!Limits.default}; checked before any allocation). It never raises. *)

val texture_of_channel : ?limits:Limits.t -> in_channel -> length:int -> (Texture.t, [> `Msg of string ]) result
(** [texture_of_channel ~limits ic ~length] is the texture of the PPM
    file of [length] bytes read from [ic] (at its start), as
    [Texture.of_image] of {!of_string} of the file's contents: the same
    pixels, the same errors. A P6 file's pixels are read straight into
    the texture's channels, so that reading it holds little more than the
    texture (a P3 file's text, or a P6 header longer than 1 MiB, is read
    whole and decoded by {!of_string}). [Error] too if [ic] ends before
    [length] bytes. Never raises but [Sys_error] from [ic]. *)

val check_file_size : ?limits:Limits.t -> int -> (int, [> `Msg of string ]) result
(** [check_file_size ~limits n] is [Ok n] if [n] bytes can hold an image
    within the pixel bound of [limits] (default {!Limits.default}): at most
    [3] bytes a pixel plus 1 MiB of header (a PNG compresses, so it fits
    too); [Error] says so and names the variable that raises the bound.
    For readers of files, which check a file's size before they read it. *)

val header_comments : string -> string list
(** [header_comments s] is the text of the [#] comments in the header of
    the PPM file contents [s] (between the magic number and the maxval), in
    order, each without its [#], one following space, and the line end.
    It is [\[\]] if [s] does not start with [P6] or [P3]; it does not
    check the rest of the file ({!of_string} does). *)
