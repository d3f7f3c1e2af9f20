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
    sample whose key is [tr.key] (see {!Camera}): from [O + L],
    [L = M (l_x, l_y, 0)] with [(l_x, l_y)] on the disc of diameter
    [aperture], in direction [D - (d / f) L], so that it meets the pinhole
    ray [O + t D] at [t = f / d], on the plane of focus. With
    [(lens-sampling uniform)], [(l_x, l_y)] is uniform over the disc, by
    rejection from [Sample_key] numbers keyed by [Sample_key.key tr.key
    (-1)], independent from sample to sample. Stratified (the default):
    sample [tr.lens_k] of the [tr.lens_n x tr.lens_n] grid of pixel
    [(tr.lens_gx, tr.lens_gy)] takes a cell of the [n x n] cut of the unit
    square (permuted per pixel, the centre of an odd grid in cell 0), and
    in it the sub-cell that two more permutations of the pixel's give the
    cell's column and row (multi-jittered: the pixel's [n^2] points fall
    one in each of [n^2] columns and rows), a jittered point in that, plus the pixel's offset modulo 1 (the centre:
    the offset itself, the point of the pixel's one-sample ray), mapped
    onto the disc by the concentric map: {!Raytrace.Private.Literal.lens_point}
    states it exactly. The same bytes native and in JavaScript: no libm
    sine or cosine, but polynomials of sums and products. For a pinhole,
    the ray of {!set_pixel}: for scenes that sample ([tr.p.sampled]) for
    another reason. *)

val set_lens_point : Tracer.t -> unit
(** [set_lens_point tr] is {!set_point}, then the lens as in
    {!set_lens_pixel}. *)

val set_probe : Tracer.t -> int -> int -> int -> unit
(** [set_probe tr col row k] is {!set_pixel}, then, if the camera has a
    lens, the ray moved (as {!set_lens_pixel} moves it) to the fixed point
    [(1, 0)], [(-1, 0)], [(0, 1)] or [(0, -1)] ([k = 0, 1, 2], else) of
    the unit disc: the lens's rim, through the pixel centre's point on the
    plane of focus. Adaptive sampling's probes of a blurred pixel
    ({!Raytrace.Private.Trace.probe}); no key, so the same ray everywhere. *)
