(** The document's kernel: the fast path of the reference scene.

    {1 When it runs}

    {!Trace} hands a ray or a row of camera rays to this module when the
    prepared scene is the document's kind ({!Prepared.t}'s [textbook_all]:
    spheres alone, the scene's epsilon, no hierarchy) and the skips are on
    ([skips]); a row only when no primary sphere is assumed
    ({!Trace.pixel_assuming}). Every other scene, and this one with
    [~skips:false], takes the general loop ({!Chain}).

    {1 What it promises}

    Its bytes are the general path's. The whole ray tree of a pixel is one
    loop over local variables (rays, hit points, normals and light vectors
    stay in registers or on the stack, never in memory that the shadow test
    must read back; nothing is called per ray but [pow] and, rarely,
    {!Byte_exact.settled}), and every value that reaches a pixel is
    computed with the operands and the order of operations of the general
    loop, which computes those of {!Literal}. The skips below only leave
    out work whose result cannot change a byte; each is exact on its own,
    each has a switch that turns it off ({!Prepared.without}), and the
    [kernel] suite renders the reference scenes with each one off and
    finds the same bytes ("the reference scenes, each skip on or off, at
    160 x 160"), and fewer tests or shadow rays with it on ("each skip
    saves work on the reference scene").

    {1 The skips and their proofs}

    {2 Spheres behind the ray ([Behind], [behind])}

    A sphere is rejected without the square root and the two divisions
    when [k2 > 0] and [k3 > 0]. Then [disc = fl(fl(k2^2) - fl(4 k1 k3)) <=
    fl(k2^2)], since [fl(4 k1 k3) >= 0] and rounding is monotonic, and
    [sqrt (fl (k2^2)) = k2] exactly (a theorem of binary floating point;
    an overflow gives infinity either way), so [-k2 + sq <= 0] and both
    roots, divided by [2 k1 >= 0], are [<= 0] or NaN: never in
    [(t_min, t_max)] with [t_min >= 0] (1 for the camera, the scene's
    epsilon, validated [>= 0], for the others). Tested with it off by the
    [kernel] suite and by [fast_oracle] (the sphere's shadow test).

    {2 Culling by tile ([Culling], [cull])}

    The camera rays of a tile of {!Tracer.tile} pixels a side test only the
    spheres that may meet them. Their directions are affine in the
    pixel's [(gx, gy)] (to within the rounding of the viewport mapping,
    about an ulp), so they lie in the convex hull of the four corner rays,
    hence in the cone around the corners' mean direction whose half-angle
    [theta] is the largest corner angle (cones of half-angle below [pi /
    2] are convex). A sphere of radius [r] at distance [dist] from the
    camera is seen within the angle [alpha = asin (re / dist)] of its
    centre's direction, with [re = r (1 + 1e-6) + 1e-6 dist]; if that
    direction is more than [theta + alpha + 1e-6] from the axis, every ray
    of the tile passes the centre at a distance over [re + 1e-6 dist cos
    alpha]: the true discriminant is negative by at least
    [4 k1 1e-12 dist^2], some thousand times the rounding of the
    textbook's [k2^2 - 4 k1 k3] (a few ulps of [4 k1 dist^2]) and of these
    angles ([acos] near 1 loses at most [sqrt u], [1e-8] rad). So the
    textbook test of a culled sphere gives [disc < 0] for every ray of the
    tile: a culled sphere is one the ray would have missed. Spheres near
    or around the camera ([dist <= 2 re]), wide tiles ([theta > 1] rad)
    and anything NaN keep every sphere. The kept spheres stay in scene
    order, so equal roots keep the first sphere, as the full loop does.
    Tested with it off by the [kernel] suite.

    {2 Shadow rays for lights that add nothing ([Shadow_rays], [shadow_skip])}

    A light's diffuse and specular terms are decided before its shadow
    ray; a light that would add neither casts none: lit or not, it leaves
    the sum as it is. (A point light on the lit point, [L = 0], adds
    nothing: [<N, L> = 0] and [R = 0]; without the skip it is left out, as
    {!Literal} does.) Tested with it off by the [kernel] suite, here and on
    the general path ("the general path's skips of shadow rays, on or off,
    give the same bytes").

    {2 Negligible specular terms ([Negligible_terms], [specular_cut])}

    At or below the cut of a material and a light, [li cos^s] is 0 or
    below half an ulp of the intensity it joins (at least the ambient
    lights listed before it), so the sum is what it would be with it, and
    [pow] is not called ({!Prepared.t}'s [specular_cut]). Matte spheres
    have an infinite cut, so the cosine is computed for them too rather
    than the material asked at every light. Tested with it off by the
    [kernel] suite ("a negligible specular term changes no sum, at its
    cut").

    {2 Any blocker, the last one first}

    A shadow ray asks whether some sphere blocks it, not which is nearest:
    it stops at the first blocker, trying the spheres in this light's
    order of {!Tracer.t}'s [blockers], where the last blocker found was
    swapped to the front. The answer is the same as the document's
    closest-hit search; with the skips off ({!Prepared.prepare}
    [~skips:false]) the general path searches the closest hit, and the
    [fast_oracle] suite compares the two.

    {2 The early stop of reflections}

    As on the general path: once the colour still to be traced cannot
    change a byte ({!Byte_exact.settled}, whose [.mli] gives the
    argument), the chain stops. Off when the skips are off ([early_stop]);
    tested by the [sampling] and [optics] suites.

    {2 Ambient lights first}

    The ambient lights listed before the first other light add up to the
    same sum in any case: the intensity starts from their total
    ({!Prepared.t}'s [ambient_lead], summed from [0.] in order). *)

val use_tile : Tracer.t -> int -> int -> unit
(** [use_tile tr col row] makes the camera rays of the tile of pixel
    [(col, row)] (canvas coordinates from the top left) test only that
    tile's candidate spheres, found when the tile's row changes. Only
    with [cull] on. *)

val untiled : Tracer.t -> unit
(** [untiled tr] makes the next camera ray test every sphere: a ray of no
    tile (a sample, a point off the canvas). *)

val trace : Tracer.t -> unit
(** [trace tr] traces the ray in [tr]'s per-ray record and leaves its
    colour there ([r], [g], [b], unclamped floats), with and without the
    rejection of spheres behind as [behind] says. *)

val row : Tracer.t -> Image.buffer -> int -> int -> int -> int -> unit
(** [row tr buffer k col0 count r] traces the camera rays of columns
    [col0] to [col0 + count - 1] of canvas row [r] (from the top left, in
    the canvas: not checked) and stores pixel [col] at [k + 3 (col -
    col0)] of [buffer], in blocks of 256 pixels with the work budget
    checked before each. *)
