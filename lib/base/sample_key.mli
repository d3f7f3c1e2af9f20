(** Deterministic sample numbers for the integrals of round 3 (area lights,
    lenses): every number is a function of integers that name the sample
    (the pixel, the antialiasing sample, the light, the cell), never of a
    generator's state, so an image is the same bytes for every [--jobs],
    every tile, every order of the pixels and on the web page.

    The same bits on the web: js_of_ocaml's [int] is 32 bits wide and its
    [*] keeps the low 32 bits of the product, as native code does below
    bit 63. Every value here is kept in [\[0, 2{^31})] and every constant
    below [2{^31}], so the low 31 bits that survive each step are the same
    on both (the test "sample keys are pinned" holds both to the same
    numbers). *)

(** {1:keys Keys} *)

val mix : int -> int
(** [mix h] is a well-mixed hash of the low 31 bits of [h], in
    [\[0, 2{^31})]: each input bit changes about half the output bits. *)

val key : int -> int -> int
(** [key h v] is the key [h] extended by the integer [v] (any sign; its low
    31 bits count), in [\[0, 2{^31})]. Keys are built by chains:
    [key (key (key 0 col) row) sample]. *)

val pixel : col:int -> row:int -> sample:int -> int
(** [pixel ~col ~row ~sample] is [key (key (key 0 col) row) sample]. *)

val camera : gx:int -> gy:int -> di:int -> dj:int -> int
(** [camera ~gx ~gy ~di ~dj] is [key (key (pixel ~col:gx ~row:gy ~sample:0)
    di) dj]: the key of the camera sample of the pixel at canvas point
    [(gx, gy)] (section 1's coordinates, the origin in the middle) whose
    offset from the pixel's centre is [(di / 2n, dj / 2n)] in an [n x n]
    grid ([di = 2 i + 1 - n], {!Raytrace.Render.Sampling}). The centre is
    [di = dj = 0] whatever [n]: the centre ray that adaptive sampling
    traces first and reuses as the middle sample of an odd grid has one
    key, so a refined pixel stays exactly the pixel of full sampling. *)

(** {1:numbers Numbers} *)

val unit : int -> float
(** [unit h] is [mix h] scaled into [\[0, 1)]: a multiple of [2{^-31}],
    exact in a float. *)

val stratum : int -> n:int -> int -> float
(** [stratum h ~n i] is [(i + unit (key h i)) / n], a point jittered in
    stratum [i] of [\[0, 1)] cut in [n] equal strata: in
    [\[i/n, (i+1)/n)] up to the division's rounding, and in [\[0, 1)].
    [n] sample points [stratum h ~n 0 .. stratum h ~n (n-1)] cover [\[0, 1)]
    evenly (stratified sampling). *)

val permute : int -> n:int -> int -> int
(** [permute h ~n k] is the image of [k] under a permutation of
    [\[0, n)] chosen by the key [h] (a hash-based permutation walked in
    cycles, Kensler 2013): for a fixed [h] and [n], [k] to [permute h ~n k]
    is a bijection of [\[0, n)], and different keys give unrelated
    permutations. Integer operations on at most 31 bits: the same on the
    web. Takes a few steps (twice the bits of [n] on average at worst),
    allocates nothing.
    @raise Invalid_argument if [k] is outside [\[0, n)] ([n >= 1]). *)

val mask : int -> int
(** [mask n] is [2{^b} - 1] for the least [b >= 0] with [2{^b} >= n]: the
    bits {!permute} walks on for a domain of [n]. *)

val walk : p:int -> w:int -> n:int -> int -> int
(** [walk ~p:(mix h) ~w:(mask n) ~n k] is [permute h ~n k], its key mixed
    and its mask computed by the caller, who may keep them from call to
    call (the kernel does, per pixel); not checked. *)

val fill : int array -> at:int -> shift:int -> p:int -> n:int -> unit
(** [fill t ~at ~shift ~p:(mix h) ~n] writes [shift + permute h ~n k]
    into [t.(at + k)] for every [k] in [\[0, n)]: a whole permutation
    tabulated, its mask computed once ([n] walks). The lens's sub-cells and
    an area light's cells take theirs so, once per pixel or lit point;
    [p] is not checked.
    @raise Invalid_argument if [t] holds fewer than [at + n] ints. *)
