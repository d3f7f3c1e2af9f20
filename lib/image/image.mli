(** Images: rectangles of 8-bit RGB pixels.

    Pixels are addressed by column [x] (left to right) and row [y] (top to
    bottom), the order of PPM files; {!Raytrace.Private.Canvas} converts from the document's
    centered, upward coordinates. The bytes live in a [Bigarray], so that
    worker processes can fill one image through shared memory. *)

type buffer = (int, Bigarray.int8_unsigned_elt, Bigarray.c_layout) Bigarray.Array1.t
(** The type for pixel storage: [3 * width * height] bytes, row by row,
    [r g b] per pixel. *)

type t
(** The type for images. *)

val create : int -> int -> t
(** [create w h] is a black image of [w x h] pixels.
    @raise Invalid_argument if [w < 1] or [h < 1]. *)

val of_buffer : int -> int -> buffer -> t
(** [of_buffer w h buf] is the image of [w x h] pixels stored in [buf]
    (shared, not copied).
    @raise Invalid_argument if [buf] does not hold [3 * w * h] bytes. *)

val width : t -> int
(** [width img] is the width of [img] in pixels. *)

val height : t -> int
(** [height img] is the height of [img] in pixels. *)

val buffer : t -> buffer
(** [buffer img] is the storage of [img] (shared, not copied). *)

val get : t -> int -> int -> int * int * int
(** [get img x y] is the [(r, g, b)] of pixel [(x, y)].
    @raise Invalid_argument if the pixel is outside [img]. *)

val set : t -> int -> int -> int -> int -> int -> unit
(** [set img x y r g b] sets pixel [(x, y)] to [(r, g, b)], each in
    [\[0, 255\]].
    @raise Invalid_argument if the pixel is outside [img] or a channel is
    out of range. *)

val channel : t -> int -> int
(** [channel img k] is byte [k] of the storage, [k] in
    [\[0, 3 * width * height)]: pixel [k / 3], channel [k mod 3]. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] have the same size and bytes. *)

val copy : t -> t
(** [copy img] is a fresh image equal to [img]. *)

val blit : src:t -> dst:t -> x:int -> y:int -> unit
(** [blit ~src ~dst ~x ~y] copies all of [src] into [dst] with its top-left
    pixel at [(x, y)].
    @raise Invalid_argument if [src] does not fit. *)

val sub : t -> x:int -> y:int -> w:int -> h:int -> t
(** [sub img ~x ~y ~w ~h] is a copy of the [w x h] rectangle of [img] whose
    top-left pixel is [(x, y)].
    @raise Invalid_argument if the rectangle does not lie inside [img]. *)
