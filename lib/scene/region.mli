(** Rectangles of the canvas, and the tiles that split it.

    A region is a rectangle of image pixels: columns [x] to [x + w - 1] and
    rows [y] to [y + h - 1], rows counted from the top as in {!Image} and
    PPM files. Parts of an image rendered separately ([Raytrace_unix.Part]) are regions;
    since every pixel is traced alone, a region renders to exactly the
    bytes that the whole image has there.

    @canonical Raytrace.Render.Region *)

type t = private { x : int; y : int; w : int; h : int }
(** The type for regions: top-left pixel [(x, y)], [w x h] pixels, [w] and
    [h] positive.

    @canonical Raytrace.Render.Region.t *)

val pp : Format.formatter -> t -> unit
(** [pp ppf x] prints [x] as an OCaml record (derived). *)

val show : t -> string
(** [show x] is [x] formatted by {!pp}. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] are equal field by field. *)

val v : x:int -> y:int -> w:int -> h:int -> t
(** [v ~x ~y ~w ~h] is the region of [w x h] pixels whose top-left pixel
    is [(x, y)]. It checks nothing: the renderers check a region against
    their canvas ({!contains}) and raise [Invalid_argument] on one outside
    it. *)

val x : t -> int
(** [x r] is the column of [r]'s left edge. *)

val y : t -> int
(** [y r] is the row of [r]'s top edge, counted from the top. *)

val w : t -> int
(** [w r] is the width of [r], in pixels. *)

val h : t -> int
(** [h r] is the height of [r], in pixels. *)

val full : width:int -> height:int -> t
(** [full ~width ~height] is the whole canvas, [{x = 0; y = 0; w = width;
    h = height}]. *)

val of_corners :
  width:int -> height:int -> int -> int -> int -> int -> (t, [> `Msg of string ]) result
(** [of_corners ~width ~height x0 y0 x1 y1] is the region of columns
    [\[x0, x1)] and rows [\[y0, y1)] (the command line's [--region]).
    [Error] unless [0 <= x0 < x1 <= width] and [0 <= y0 < y1 <= height]. *)

val tile : width:int -> height:int -> index:int -> count:int -> (t, [> `Msg of string ]) result
(** [tile ~width ~height ~index ~count] is tile [index] of [count] (the
    command line's [--tile index/count]), [index] in [\[1, count\]]: the
    band of full-width rows [\[(index - 1) h / count, index h / count)]
    with [h = height] and integer division, so that the [count] tiles
    cover the canvas exactly, top to bottom, and their heights differ by
    at most one row. [Error] if [index] is outside [\[1, count\]] or
    [count > height] (a tile would be empty). *)

val parse_tile : string -> (int * int, [> `Msg of string ]) result
(** [parse_tile s] is [(i, n)] for [s = "I/N"] with decimal [I] and [N].
    It checks the syntax only; {!tile} checks the range. *)

val parse_corners : string -> (int * int * int * int, [> `Msg of string ]) result
(** [parse_corners s] is [(x0, y0, x1, y1)] for [s = "X0,Y0,X1,Y1"] (commas
    or spaces between the four integers). It checks the syntax only;
    {!of_corners} checks the range. *)

val contains : t -> width:int -> height:int -> bool
(** [contains r ~width ~height] is [true] iff [r] is non-empty and lies
    inside the [width x height] canvas. *)

val pixels : t -> int
(** [pixels r] is [r.w * r.h]. *)

val pp_corners : Format.formatter -> t -> unit
(** [pp_corners ppf r] prints [r] as the corners [x0 y0 x1 y1] that
    {!of_corners} takes, e.g. [0 86 600 172]. *)
