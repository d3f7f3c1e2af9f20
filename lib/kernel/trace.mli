(** The fast tracer: the document's algorithm on a {!Raytrace.Private.Prepared.t} scene,
    allocating nothing per ray.

    It computes the same floating-point operations in the same order as
    {!Literal}, so it produces the same bytes; it only skips work whose
    result provably cannot change them (see {!Raytrace.Private.Prepared.prepare}). Rays,
    hit points and colours live in a mutable all-float record (stored
    unboxed), hits are returned as object indices ([-1] for none), and
    reflection is a loop over a small stack instead of recursion, because
    in OCaml 4.13 without flambda a float crossing a function call that is
    not inlined is boxed.

    Scenes with transparency (some material with [transparency > 0]) are
    traced by the ray tree instead, chosen once by {!create}: each hit may
    spawn a reflected and a refracted ray, followed by a recursion over
    levels whose arguments are ints only, the floats in the per-level
    arrays of {!Raytrace.Private.Ray_tree}; shadow rays pass through
    transparent objects. Scenes without transparency keep the reflection
    loop, instruction for instruction.

    This module is the kernel's front: the work is done by the kernel's
    modules under it, one job each (the tracer's state, exact bytes and
    the early stop, camera rays, traversal, surfaces, lighting, the
    general loop, the ray tree, the document's kernel), listed in
    docs/architecture.md, "The kernel's modules".

    @canonical Raytrace.Private.Trace *)

type counters = {
  mutable primary : int;  (** Primary rays cast. *)
  mutable shadow : int;  (** Shadow rays cast. *)
  mutable reflection : int;  (** Mirror rays cast, and refracted rays. *)
  mutable tests : int;  (** Ray-object intersection tests. *)
  mutable box_tests : int;  (** Ray-box tests in the object hierarchy. *)
  mutable early_stops : int;  (** Reflections (and refractions) stopped by the weight bound. *)
  mutable decided : int;  (** Points an adaptive area light's corners decided. *)
  mutable penumbra : int;  (** Points an adaptive area light's corners left in doubt. *)
  mutable umbra : int;  (** Area light samples in an exact umbra: no shadow ray. *)
  mutable whole : int;  (** Points that see an area or sphere light whole: no shadow ray to it (exact). *)
}
(** The type for work counters. *)

type t
(** The type for tracers: a prepared scene and the scratch space of one
    process. A tracer is not reentrant. *)

val create : ?averaging:bool -> Prepared.t -> t
(** [create ~averaging p] is a tracer for [p] with zeroed counters and
    the budget of {!Limits.default} ({!Limits.work_budget}, {!set_budget}).
    [averaging] (default [false]) says how the colours it computes will be
    combined, which decides when the reflection early stop of
    {!Raytrace.Private.Prepared.prepare}'s skips is exact. Without it, each ray is one
    pixel, rounded to bytes on its own: a reflection stops once its
    remaining weight cannot change a byte of the pixel. With it, rays are
    samples whose clamped floats are averaged ({!accumulate}): a reflection
    stops only when it cannot change the clamped float of the sample
    (every channel already saturated, or the bound is exact), since the
    mean of several samples can round differently from any one of them.
    Either way the skips change no output byte. *)

val prepared : t -> Prepared.t
(** [prepared tr] is the scene [tr] traces. *)

val counters : t -> counters
(** [counters tr] are the work counters of [tr], updated by every call.
    The leaf tests of CSG solids (each sphere, box, mesh triangle and box
    of a mesh's hierarchy) are counted apart, at no cost per ray, and
    added to [tests] and [box_tests] when [counters] or {!work} is called:
    read the counters through them. *)

(** {1:budget The work budget}

    The estimate of {!Limits.check_work} can be beaten by a scene that
    defeats the bounding volume hierarchy (many coincident spheres). The
    renderers therefore count the work as it is done, from the counters,
    and check it before each pixel ({!pixel}, {!average},
    {!average_reusing}; {!row} before each pixel, or each block of 64
    pixels in the document's kernel), at every hit of a ray tree and
    every surface a ray crosses in a scene with transparency: a sum and a
    comparison, nothing per ray of an opaque scene, and no allocation. A
    render passes its budget by at most the work of one pixel (of one
    block, in the document's kernel), or of one hit of a tree. *)

val work : t -> int
(** [work tr] is the intersection tests [tr] has done: [tests + box_tests]
    of {!val-counters}. *)

val set_budget : ?refill:(int -> int) -> t -> int -> unit
(** [set_budget ~refill tr n] lets {!check_budget} accept up to [n] tests
    of [tr]. Past them, it calls [refill w] with the work [w] done so far:
    that is the next budget (a renderer whose workers share one budget
    takes its next slice of it there), or it raises
    [Limits.Work_exceeded]; the default [refill] raises
    [Limits.Work_exceeded w]. {!create} sets the budget of
    {!Limits.default}. *)

val check_budget : t -> unit
(** [check_budget tr] does nothing while {!work}[ tr] is within the budget
    of [tr], and otherwise calls its [refill] ({!set_budget}), which may
    raise [Limits.Work_exceeded]. It allocates nothing (unless [refill]
    does). The front ends give a [refill] that looks at their keys or
    their clock while a pixel is traced (a pixel of a deep glass tree can take
    seconds) and may raise to pause: an exception from [refill] ends the pixel
    being traced; the tracer can trace other pixels after it. *)

val pixel : t -> int -> int -> unit
(** [pixel tr gx gy] traces the primary ray through canvas pixel
    [(gx, gy)] (centered coordinates, {!Raytrace.Private.Canvas}) from the camera, [t > 1],
    with the scene's recursion depth (section 8). With a lens
    ({!Camera.has_lens}), the ray leaves the lens point of the pixel's
    centre sample, key [Sample_key.camera ~gx ~gy ~di:0 ~dj:0]
    ({!Raytrace.Private.Camera_ray.set_lens_pixel}). The unclamped colour is
    then in {!red}, {!green} and {!blue}, and {!store} writes it.
    @raise Limits.Work_exceeded once the work counted ({!work}) has
    passed the budget ({!set_budget}) before the pixel; in a scene with
    transparency, also during the pixel: a ray tree may have [2^depth]
    rays, so the tree checks at every hit (so do {!sample}, {!average}
    and {!average_reusing}, which trace rays alike). *)

val row : t -> Image.buffer -> int -> int -> int -> int -> unit
(** [row tr buf k gx gy n] is {!pixel} then {!store} for the [n] pixels
    [(gx, gy)] to [(gx + n - 1, gy)], stored from byte [k] of [buf] on,
    three bytes apart.
    @raise Limits.Work_exceeded as {!pixel} does, before a pixel (or a
    block of 64 in the document's kernel). *)

val sample : t -> int -> int -> i:int -> j:int -> n:int -> unit
(** [sample tr gx gy ~i ~j ~n] is {!pixel} for the point
    [(gx + (i + 1/2) / n - 1/2, gy + (j + 1/2) / n - 1/2)], sample [(i, j)]
    of a regular [n x n] grid centered on the pixel ([i] to the right, [j]
    up, both in [\[0, n)]). [sample tr gx gy ~i:0 ~j:0 ~n:1] is exactly
    [pixel tr gx gy]. With a lens, each sample has its own lens point,
    keyed by [Sample_key.camera ~gx ~gy ~di:(2i+1-n) ~dj:(2j+1-n)] and,
    stratified (the default), one cell each of the lens's [n x n] cut
    (multi-jittered: one each of its [n^2] columns and rows too),
    the centre of an odd grid taking {!pixel}'s point: the grid's samples
    average over the lens as over the pixel. *)

val store : t -> Image.buffer -> int -> unit
(** [store tr buf k] writes the colour of the last {!pixel}, each channel
    clamped and rounded by the rule of {!Color.to_byte}, to bytes [k],
    [k + 1] and [k + 2] of [buf]. [k] is not bounds-checked: callers pass
    [k = 3 * (y * width + x)] of a pixel inside the image. *)

val to_byte : float -> int
(** [to_byte] is {!Color.to_byte}: a copy kept in this module so that the
    per-ray path passes no float across modules. *)

val cast : t -> from:int -> Vec3.t -> Vec3.t -> int
(** [cast tr ~from origin direction] is the object (counted as
    {!hit_object} counts them) that the secondary ray
    [origin + t direction] leaving object [from] ([-1]: none) meets first
    with [t > epsilon] (the scene's epsilon, or [0] in the robust mode, where
    [from] is handled exactly: the ray can meet it only by going into it),
    or [-1] if it meets none: the test behind shadow and mirror rays. *)

val camera_hit : t -> int -> int -> int
(** [camera_hit tr gx gy] is the object (counted as {!hit_object} counts
    them) that the camera ray through the centre of canvas pixel
    [(gx, gy)] (centered coordinates, as {!pixel}) meets first with
    [t > 1], or [-1]: {!pixel}'s search for the first hit, the
    hierarchy's traversal and the intersection tests, without the
    pixel's shading. The ray is the pinhole's (a lens is ignored), and it
    counts as a primary ray. For the benchmark against Embree
    ([bench/embree/]); it allocates nothing.
    @raise Invalid_argument if the pixel is outside the canvas. *)

val shadow_blocked : t -> float array -> int -> bool
(** [shadow_blocked tr rays k] is [true] iff some object meets the ray
    [o + t d] with [epsilon < t < 1] (the scene's epsilon, [0] in the
    robust mode), where [o] and [d] are the six floats of [rays] from
    [6 k] on (origin, then direction): the test of a shadow ray toward a
    point at [o + d] ({!pixel}'s shadow rays' test, stopping at the first
    blocker, light [0]'s last blocker tried first), counted as a shadow
    ray. For the benchmark against Embree; it allocates nothing.
    @raise Invalid_argument if [rays] has no ray [k]. *)

val roots : t -> int -> Vec3.t -> Vec3.t -> float * float
(** [roots tr k origin direction] is [(near, far)], the roots that the
    tracer's own intersection test computes for object [k] (objects
    counted in the order of {!Scene.objects}, a mesh one object per
    triangle) and the secondary ray
    [origin + t direction]: the cancellation-free roots of a sphere in the
    robust mode, the textbook roots in the document's mode, the shape
    module's routine for the others (for a CSG solid, its first crossing
    of its surface as both, [Csg.roots]); [(infinity, infinity)] for a miss. It
    runs the code the renderer runs, for the tests of its accuracy.
    @raise Invalid_argument if [k] is not an object of the scene. *)

val probe : t -> int -> int -> int -> unit
(** [probe tr gx gy k] traces, as {!pixel} does, the ray of pixel
    [(gx, gy)] of the canvas from the fixed point [k] ([0] to [3]) of the
    lens's rim ({!Raytrace.Private.Camera_ray.set_probe}; for a pinhole,
    the pixel's ray), counted as a primary ray: adaptive sampling's test
    of whether a blurred pixel's cone of rays sees more than its first
    ray. {!hit_object}, {!red}, {!green}, {!blue} and {!store} then
    describe it. Not a sample: nothing averages it.
    @raise Invalid_argument if the pixel is outside the canvas or [k] is
    outside [\[0, 3\]].
    @raise Limits.Work_exceeded as {!pixel}. *)

val red : t -> float
(** [red tr] is the red channel of the last {!pixel}, unclamped. *)

val green : t -> float
(** [green tr] is the green channel of the last {!pixel}, unclamped. *)

val blue : t -> float
(** [blue tr] is the blue channel of the last {!pixel}, unclamped. *)

val hit_object : t -> int
(** [hit_object tr] is the index of the object the primary ray of the last
    {!pixel} hit (objects counted in the order of {!Scene.objects}, a
    mesh one object per triangle), or [-1] if it hit nothing. *)

(** {1:sampling Several rays per pixel}

    Supersampling averages the colours of an [n x n] grid of {!sample}s.
    Each sample is clamped to [\[0, 255\]] first (as a float, not
    rounded), the clamped colours are summed in the tracer, and the mean is
    rounded once by {!store_average}. Clamping before averaging makes a
    pixel the mean of what the document would display at its sample
    points, so the image converges to the area average of the document's
    picture; averaging unclamped colours would let one overexposed sample
    (a highlight of 2000) brighten a whole pixel. The sums live in the
    tracer so that no float crosses a module boundary per sample. The
    functions below that sum raise [Invalid_argument] on a tracer created
    without [~averaging:true]. *)

type samples = (float, Bigarray.float64_elt, Bigarray.c_layout) Bigarray.Array1.t
(** The type for saved sample colours: three floats per pixel, clamped to
    [\[0, 255\]], at indices [k], [k + 1], [k + 2]. *)

val averaging : t -> bool
(** [averaging tr] is the [averaging] argument [tr] was created with. *)

val clear : t -> unit
(** [clear tr] sets the sum of sample colours of [tr] to zero. *)

val accumulate : t -> unit
(** [accumulate tr] adds the colour of the last {!pixel} or {!sample},
    each channel clamped to [\[0, 255\]], to the sum.
    @raise Invalid_argument if [tr] is not {!averaging}. *)

val average : t -> int -> int -> n:int -> unit
(** [average tr gx gy ~n] is {!clear}, then {!sample} and {!accumulate}
    for every sample of the [n x n] grid of pixel [(gx, gy)], rows [j]
    then columns [i]. {!store_average} [~count:(n * n)] then writes the
    pixel; for [n = 1] that is exactly the byte {!store} writes after
    {!pixel}.
    @raise Invalid_argument if [tr] is not {!averaging} or [n < 1]. *)

val save : t -> samples -> int -> unit
(** [save tr saved k] writes the colour of the last {!pixel} or {!sample}, each
    channel clamped to [\[0, 255\]], to [saved] at [k], [k + 1], [k + 2].
    @raise Invalid_argument if [k + 2] is outside [saved]. *)

val save_blur : t -> samples -> int -> unit
(** [save_blur tr blur k] writes to [blur] at [k] the diameter, in pixels,
    of the circle of confusion of the last {!pixel}'s first hit: a point at
    depth [z] (along the view axis) spreads, through a lens of diameter
    [A] focused at [f], over a circle of diameter [A |z - f| / z] on the
    plane of focus, here divided by a pixel's width on that plane. [0.] if
    the ray hit nothing (the background is one colour) or the camera is a
    pinhole. An estimate: [z] is the ray's parameter times the viewport
    distance, exact for an orthonormal camera matrix; reflections and
    refractions of blurred objects are not counted.
    @raise Invalid_argument if [k] is outside [blur]. *)

val average_reusing : t -> samples -> int -> int -> int -> n:int -> unit
(** [average_reusing tr saved k gx gy ~n] is {!average} [tr gx gy ~n] for
    an odd [n], whose grid has the pixel's centre as its middle sample
    [(n / 2, n / 2)], exactly the ray of {!pixel}: that sample is not
    traced again, its clamped colour is read from [saved] at [k] (where
    {!save} wrote it after {!pixel} [tr gx gy]). The sum, and so the pixel,
    is exactly that of {!average}, for [n * n - 1] rays.
    @raise Invalid_argument if [tr] is not {!averaging}, [n] is not odd
    and positive, or [k + 2] is outside [saved]. *)

val store_average : t -> Image.buffer -> int -> count:int -> unit
(** [store_average tr buf k ~count] writes the sum divided by [count],
    each channel rounded by the rule of {!Color.to_byte}, to bytes [k],
    [k + 1] and [k + 2] of [buf] ([k] unchecked, as for {!store}). *)

val pixel_assuming : t -> int -> int -> int -> unit
(** [pixel_assuming tr gx gy k] is {!pixel} [tr gx gy] for CGFS's
    subsampling: the primary ray is assumed to hit object [k] (counted as
    {!hit_object} counts them; nothing if [k = -1]), as the rays of two
    neighbouring pixels did, and is intersected with that object alone; if
    it misses it, all objects are searched as usual. Shading, shadows and
    reflections are traced as usual. Approximate: an object in front of object [k], or an object
    where both neighbours saw nothing, is missed. With a lens (whose rays
    do not start at the camera's position) no object is assumed: {!pixel}.
    @raise Invalid_argument if [k < -1] or [k] is not an object of the
    scene. *)
