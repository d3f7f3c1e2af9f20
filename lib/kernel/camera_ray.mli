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

(** {1:lens The thin lens} *)

val set_lens_pixel : Tracer.t -> int -> int -> unit
(** [set_lens_pixel tr col row] is {!set_pixel}, then, if the camera has
    a lens ([aperture > 0]), the ray moved to the lens point of the camera
    sample whose key is [tr.key] (see {!Camera}): from
    [O + L], [L = M (l_x, l_y, 0)] with [(l_x, l_y)] uniform over the disc
    of diameter [aperture] (by rejection from [Sample_key] numbers keyed by
    [Sample_key.key tr.key (-1)]), in direction [D - (d / f) L], so that it
    meets the pinhole ray [O + t D] at [t = f / d], on the plane of focus.
    The same bytes native and in JavaScript: no sine or cosine. For a
    pinhole, the ray of {!set_pixel}: for scenes that sample ([tr.p.sampled])
    for another reason. *)

val set_lens_point : Tracer.t -> unit
(** [set_lens_point tr] is {!set_point}, then the lens as in
    {!set_lens_pixel}. *)
