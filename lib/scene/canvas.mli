(** The centered canvas (document sections 1 and 8).

    The document draws through [plotc], which puts the origin of the canvas
    in the middle of the window with [y] pointing up. A canvas of [w x h]
    pixels has canvas coordinates [G_x] in [\[-w/2, w - w/2)] and [G_y] in
    [\[-h/2, h - h/2)] ([/] is integer division, so for even sizes these are
    the document's [\[-G_w/2, G_w/2)]). The document's own loop
    [for x = -gw/2 to gw/2] would visit one column and one row too many; this
    module visits exactly [w x h] pixels.

    Images ({!Image}) store rows top-down, as PPM files do. This module is
    the one place where the upward canvas [y] is flipped into a downward
    image row.

    @canonical Raytrace.Private.Canvas *)

val min_x : int -> int
(** [min_x w] is [-(w / 2)], the leftmost canvas [G_x] of a canvas [w]
    pixels wide. *)

val max_x : int -> int
(** [max_x w] is [w - w / 2 - 1], the rightmost canvas [G_x]. *)

val min_y : int -> int
(** [min_y h] is [-(h / 2)], the bottom canvas [G_y]. *)

val max_y : int -> int
(** [max_y h] is [h - h / 2 - 1], the top canvas [G_y]. *)

val column : width:int -> int -> int
(** [column ~width gx] is the image column [gx + width / 2] of canvas
    coordinate [gx]: [plotc]'s translation of [x]. *)

val row : height:int -> int -> int
(** [row ~height gy] is the image row, counted from the top, of canvas
    coordinate [gy]: [height - 1 - (gy + height / 2)]. *)

val x_of_column : width:int -> int -> int
(** [x_of_column ~width col] is the canvas [G_x] of image column [col];
    the inverse of {!column}. *)

val y_of_row : height:int -> int -> int
(** [y_of_row ~height row] is the canvas [G_y] of image row [row]; the
    inverse of {!row}. *)

val screen : width:int -> height:int -> int -> int -> int * int
(** [screen ~width ~height gx gy] is [(gx + width / 2, gy + height / 2)],
    the position that the document's [plotc] plots in a Graphics window
    whose origin is its bottom-left corner. *)
