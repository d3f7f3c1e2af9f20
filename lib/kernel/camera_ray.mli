(** Camera rays: the ray from the camera through a point of the viewport
    (section 3 of the document), turned by the camera's rotation, written
    to the tracer's per-ray record ({!Scratch}) with the range [(1, inf)].
    No float is an argument: a point is a pixel's numbers or the record's
    canvas point. (The document's kernel sets up its rows' camera rays
    itself, with the same operations: {!Textbook}.) *)

val set_pixel : Tracer.t -> int -> int -> unit
(** [set_pixel tr col row] sets the camera ray through the centre of the
    pixel in column [col] and row [row] of the canvas (from the top left,
    [0 <= col < width], [0 <= row < height]: not checked), from the
    frame's per-column and per-row viewport coordinates. *)

val set_point : Tracer.t -> unit
(** [set_point tr] sets the camera ray through the canvas point
    [(s.gx, s.gy)] of the per-ray record (from the canvas centre, [y] up):
    any point, a sample's as well as a pixel's; for a pixel centre, the
    same ray as {!set_pixel}'s. *)
