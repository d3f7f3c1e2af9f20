(** Antialiasing: each pixel the mean of a regular grid of samples.

    The window's [a] key renders with this. A pixel is the mean of the
    [n x n] samples of {!Raytrace.Private.Trace.sample}, each channel clamped to [\[0, 255\]]
    before averaging (so that one overexposed sample cannot outweigh the
    others) and rounded once, by the rule of {!Color.to_byte}: the pixels
    of {!Render.image} [~samples:n], computed by {!Raytrace.Private.Trace.average}. With
    [n = 1] it is exactly {!Raytrace.Private.Trace.pixel} and {!Raytrace.Private.Trace.store}.

    @canonical Raytrace.Private.Antialias *)

val store : Trace.t -> Image.buffer -> int -> int -> n:int -> int -> unit
(** [store tr buf gx gy ~n k] traces the [n x n] samples of canvas pixel
    [(gx, gy)] and writes their clamped, averaged and rounded channels to
    bytes [k], [k + 1] and [k + 2] of [buf] (not bounds-checked, as
    {!Raytrace.Private.Trace.store}). For [n > 1], [tr] must have been created with
    [Trace.create ~averaging:true], whose reflection early stop is exact
    for averaged samples.
    @raise Invalid_argument if [n < 1], or [n > 1] and [tr] does not
    average. *)

val image : ?n:int -> Scene.valid -> Image.t
(** [image ~n scene] is [scene] rendered with {!store} at every pixel
    ([n] default 3), in one process.
    @raise Invalid_argument if [n < 1].
    @raise Limits.Work_exceeded when the tests done pass the budget of
    the tracer ({!Raytrace.Private.Trace.check_budget}, checked after each
    row). *)
