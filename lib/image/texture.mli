(** Image textures: decoded pixels looked up with bilinear filtering.

    A texture is a rectangle of 8-bit RGB pixels, decoded by whoever read
    its file (PPM by {!Ppm.of_string}, PNG by [Raytrace_png]): the core
    never names a file format's library. It is looked up at texture
    coordinates [(u, v)]: [u] runs left to right across the image and [v]
    bottom to top (OBJ's [vt] convention), one copy of the image over the
    unit square [\[0, 1\] x \[0, 1\]].

    {b Filtering.} Pixel [(x, y)] (column [x], row [y] from the top, as
    in {!Image}) is a sample at its centre, [u = (x + 0.5) / width],
    [v = 1 - (y + 0.5) / height]. A lookup at [(u, v)] is the bilinear
    blend of the four pixels around it: with [fx = u * width - 0.5] and
    [fy = (1 - v) * height - 0.5], the columns [x0 = floor fx] and
    [x0 + 1] weigh [1 - tx] and [tx] ([tx = fx - x0]), and likewise the
    rows. A column or row outside the image is brought back in by the
    axis's {!wrap}: [Repeat] tiles the plane with copies of the image
    (a column [-1] is the last one), [Clamp] takes the nearest edge pixel.
    Each blend is computed as [a + t (b - a)]: where the neighbours are
    equal (a flat region, or a pixel's centre when [u * width - 0.5] is
    computed exactly, as for widths that are powers of two) the lookup is
    that colour exactly, and every channel stays between its neighbours',
    so within [\[0, 255\]].

    @canonical Raytrace.Image.Texture *)

type t
(** The type for textures: at least one pixel, 8-bit RGB. *)

type wrap =
  | Repeat  (** The image tiles the plane: coordinates are taken modulo 1. *)
  | Clamp  (** Coordinates outside [\[0, 1\]] take the nearest edge. *)
(** The type for what a lookup does beyond the image's edge, per axis. *)

(** {1:make Constructors} *)

val of_image : Image.t -> t
(** [of_image img] is the texture of [img]'s pixels: its buffer
    ({!Image.buffer}) shared, not copied, so that a decoder's image
    becomes the texture without a second copy of its pixels; [img] must
    not be changed after. *)

val v : width:int -> height:int -> string -> t
(** [v ~width ~height bytes] is the texture of [width x height] pixels
    whose channels are [bytes], [r g b] per pixel, rows top-down (the
    layout of a P6 file's pixels), copied into the texture's channels
    ({!channels}).
    @raise Invalid_argument if [width < 1], [height < 1] or
    [String.length bytes <> 3 * width * height]. *)

(** {1:access Accessors} *)

val width : t -> int
(** [width t] is [t]'s width in pixels, [>= 1]. *)

val height : t -> int
(** [height t] is [t]'s height in pixels, [>= 1]. *)

val channels : t -> Image.buffer
(** [channels t] is [t]'s channels in {!v}'s layout: [r g b] per pixel,
    rows top-down, [3 * width t * height t] bytes. The buffer itself, not
    a copy: the renderer reads its lookups there. *)

val pixel : t -> int -> int -> Color.t
(** [pixel t x y] is the colour of pixel [(x, y)], channels in
    [\[0, 255\]].
    @raise Invalid_argument if the pixel is outside [t]. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] have the same size and bytes. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf t] prints a summary of [t]: ["<texture WxH>"]. *)

(** {1:lookup Lookups} *)

val color : ?wrap_u:wrap -> ?wrap_v:wrap -> t -> float -> float -> Color.t
(** [color ~wrap_u ~wrap_v t u v] is the bilinear lookup of [t] at
    [(u, v)] (see the module's introduction); [wrap_u] and [wrap_v]
    default to [Repeat]. A NaN or infinite coordinate looks up [0].
    It allocates its result. *)

val lookup : wrap_u:wrap -> wrap_v:wrap -> t -> float array -> int -> float array -> int -> unit
(** [lookup ~wrap_u ~wrap_v t uv i dst j] writes the lookup {!color}
    would give at [(uv.(i), uv.(i + 1))] to [dst.(j)], [dst.(j + 1)],
    [dst.(j + 2)] (red, green, blue): the form for the renderer, whose
    floats cannot cross a module's boundary unboxed. It allocates
    nothing.
    @raise Invalid_argument if an index is outside its array. *)
