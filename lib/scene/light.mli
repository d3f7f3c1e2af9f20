(** Lights (document sections 7.1 to 7.4).

    Lights are white; an intensity is a plain, non-negative float that does
    not fall off with distance. The document's advice is that the
    intensities of a scene sum to 1, else some points are overexposed. *)

(** {1:lights Lights} *)

(** Where an area light's samples lie on its rectangle (see
    {!section-samples_def}). *)
type sampling =
  | Stratified  (** One jittered point in each of the [u x v] cells (the default). *)
  | Uniform
      (** [u v] points drawn independently and uniformly over the whole
          rectangle: the plain Monte Carlo estimate, kept to measure what
          stratifying gains (docs/run-time-against-error.md). *)

type t = private
  | Ambient of { intensity : float }
      (** Lights every point of every object equally (7.3). *)
  | Point of { intensity : float; position : Vec3.t }
      (** Shines from [position] in every direction (7.1). *)
  | Directional of { intensity : float; direction : Vec3.t }
      (** Shines from infinitely far away: [direction] points from the
          scene {e toward} the light, and is the same vector [L] at every
          point (7.2). It need not be unit length but must not be zero. *)
  | Area of {
      intensity : float;
      corner : Vec3.t;
      edge1 : Vec3.t;
      edge2 : Vec3.t;
      samples_u : int;
      samples_v : int;
      adaptive : bool;
      sampling : sampling;
    }
      (** A rectangle [corner + a edge1 + b edge2], [a, b] in [\[0, 1\]],
          that shines from each of its points: the light at a point [P] is
          that of [samples_u x samples_v] point lights, each of intensity
          [intensity / (samples_u samples_v)], one in each cell of the
          rectangle cut in [samples_u] strips along [edge1] and [samples_v]
          along [edge2], at a point jittered in its cell by {!Raytrace.Private.Sample_key}
          (see {!section-samples_def}); with [sampling = Uniform], at
          [samples_u x samples_v] points drawn independently over the whole
          rectangle instead. Its shadows are soft. With
          [adaptive], the penumbra alone is sampled (see
          {!section-adaptive}). *)
  | Sphere of { intensity : float; position : Vec3.t; radius : float; samples : int }
      (** A ball of light: seen from [P], the disc of radius [radius]
          through [position] facing [P], sampled by [samples] point lights
          of intensity [intensity / samples] (see {!section-samples_def}).
          The ball is not an object: it blocks nothing and is not seen. *)
  | Spot of { intensity : float; position : Vec3.t; direction : Vec3.t; angle : float; falloff : float }
      (** A point light at [position] that shines into the cone of half
          angle [angle] degrees about [direction] (from the light, not
          necessarily unit length): at [P], whose direction from the light
          makes the angle [theta] with [direction], its intensity is
          [intensity cos{^falloff} theta] for [theta <= angle] and [0]
          beyond. Its shadows are hard. *)
(** The type for lights. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf l] prints [l] as its [light] form in the scene-file syntax,
    e.g. [(light point (intensity 0.6) (position 2 1 0))]. *)

val show : t -> string
(** [show x] is [x] formatted by {!pp}. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] are equal field by field, floats
    compared with [=]. *)

val ambient : float -> t
(** [ambient i] is [Ambient {intensity = i}]. *)

val point : float -> Vec3.t -> t
(** [point i q] is the point light of intensity [i] at [q]. *)

val directional : float -> Vec3.t -> t
(** [directional i l] is the directional light of intensity [i] toward
    [l]. *)

val area :
  ?adaptive:bool -> ?sampling:sampling -> float -> corner:Vec3.t -> edge1:Vec3.t -> edge2:Vec3.t -> samples:int * int -> t
(** [area ~adaptive ~sampling i ~corner ~edge1 ~edge2 ~samples:(u, v)] is
    the rectangle light of intensity [i] with [u x v] samples; [adaptive]
    (default [false]) samples only the points its corners leave in
    doubt; [sampling] (default [Stratified]) places the samples. *)

val sphere : float -> position:Vec3.t -> radius:float -> samples:int -> t
(** [sphere i ~position ~radius ~samples] is the sphere light of intensity
    [i] centred on [position]. *)

val spot : float -> position:Vec3.t -> direction:Vec3.t -> angle:float -> falloff:float -> t
(** [spot i ~position ~direction ~angle ~falloff] is the spotlight of
    intensity [i]; [angle] in degrees. *)

val intensity : t -> float
(** [intensity l] is the intensity of [l]. *)

val corners_first : t -> bool
(** [corners_first l] is [true] iff [l] is an adaptive area light of at
    least four samples, whose corners are traced first ({!adaptive}). *)

val samples : t -> int
(** [samples l] is the most shadow rays [l] casts at a point: [u v]
    for an area light ([u v + 4] if {!corners_first}: its corners' rays
    first), [samples] for a sphere light, [1] otherwise. *)

val sampled : t -> bool
(** [sampled l] is [true] iff [l] is an area or sphere light, whose light
    is an integral that draws numbers ({!Raytrace.Private.Sample_key}). *)

val max_samples : int
(** [max_samples] is [4096]: the most samples of a sphere light and along
    each edge of an area light. *)

val check_intensity : float -> (float, [> `Msg of string ]) result
(** [check_intensity i] checks [0 <= i <= Limits.max_intensity]. *)

val check_position : Vec3.t -> (Vec3.t, [> `Msg of string ]) result
(** [check_position q] checks a point light's position with
    {!Limits.check_point}. *)

val check_direction : Vec3.t -> (Vec3.t, [> `Msg of string ]) result
(** [check_direction l] checks a directional light's direction with
    {!Limits.check_point}, and that its length is at least
    {!Limits.min_size}. *)

val validate : t -> (t, [> `Msg of string ]) result
(** [validate l] is [Ok l] if the intensity, position and direction pass
    their checks, and otherwise the first error. An area light's corner
    and edges pass {!Limits.check_point}, its edges are not zero nor
    parallel; a sphere light's radius lies in [\[1e-30, 1e12\]]; a
    spotlight's direction is not zero, its angle lies in [(0, 180\]] and its
    falloff in [\[0, 1e6\]]; samples lie in [\[1, max_samples\]]. *)

(** {1:geometry Geometry} *)

val vector : t -> Vec3.t -> Vec3.t option
(** [vector l p] is the vector [L] from point [p] toward [l] (7.1, 7.2):
    [Q - P] for a point light at [Q], the light's direction for a
    directional light, [None] for an ambient light; for an area light the
    vector toward the rectangle's centre, for a sphere light and a
    spotlight toward its position (their shadow rays go to sample points:
    {!section-samples_def}). *)

val centre : t -> Vec3.t option
(** [centre l] is the point at the middle of [l]: a point, sphere or spot
    light's position, the centre of an area light's rectangle, [None] for
    an ambient or directional light. *)

val shadow_t_max : t -> float
(** [shadow_t_max l] is the end of the range of [t] in which an object on
    the shadow ray [P + t L] blocks [l] (7.7): [1.] for a point light (the
    light itself is at [t = 1]), and likewise for the shadow rays of area,
    sphere and spot lights, each aimed at its sample point; [infinity]
    otherwise. *)

(** {1:samples_def Sample points}

    The light of an area or sphere light at a point [P] is the sum, in the
    order below, of the terms (diffuse and specular, sections 7.4 to 7.6)
    of point lights of intensity [intensity / n] at sample points [Q]
    ([n] the number of samples), each with its own shadow ray from [P] to
    [Q] ([t] in [(epsilon, 1)]). The numbers come from {!Raytrace.Private.Sample_key},
    keyed by the camera sample [k] ({!Raytrace.Private.Sample_key.camera}; the centre ray
    of a pixel [(gx, gy)] has [camera ~gx ~gy ~di:0 ~dj:0]) and the
    light's place [l] in the scene's list of lights (from 0, every kind
    counted), so a pixel's image depends on nothing else:

    - area light, cells [(a, b)] for [a] from [0] to [u - 1], then [b]
      from [0] to [v - 1]: [h = key (key k l) (a v + b)],
      [sigma = permute (key (key k l) (-1)) ~n:v],
      [tau = permute (key (key k l) (-2)) ~n:u],
      [s = ((a v + sigma b) + unit h) / (u v)],
      [t = ((b u + tau a) + unit (mix h)) / (u v)] (either taken as the
      largest float below 1 where it rounds to 1),
      [Q = (corner + s edge1) + t edge2]: the point of cell [(a, b)] lies
      in the sub-cell [(sigma b, tau a)] of the cell's own [v x u] cut, so
      the [u v] values of [s] fall one in each of [u v] equal strata of
      [\[0, 1)], and so do those of [t] (Kensler's correlated
      multi-jittered sampling, 2013, as a lens's points); with
      [sampling = Uniform], [s = unit h] and [t = unit (mix h)] instead
      (the same keys, each point anywhere on the rectangle);
    - sphere light, samples [j] from [0] to [n - 1]: [h = key (key k l) j],
      [rho = radius sqrt (stratum (key h 0) ~n j)],
      [c = sectors n], [q = ceil (n / c)], [r = unit (key (key k l) (-1))],
      [b = permute (key (key k l) (-2)) ~n:q (j / c)],
      [phi = 2 pi (r + ((j mod c) + (b + unit (key h 1)) / q) / c)],
      [w = (position - P) / |position - P|],
      [e1 = (a x w) / |a x w|] with [a = (0, 1, 0)] if [|w.x| > 0.9] and
      [(1, 0, 0)] otherwise, [e2 = w x e1],
      [Q = position + (rho cos phi) e1 + (rho sin phi) e2]: stratified in
      area by rings of the disc facing [P], and in angle: the disc,
      turned by [r], is cut in [c] sectors of [2 pi / c], and the [c]
      rings of each block [j / c] (an annulus) hold one sample in each
      sector, at a place in it that the block's [b] sets: across the [q]
      blocks, a sector's samples lie one in each of [q] sub-sectors (the
      angle stratified in [c q] strata, as in Kensler's correlated
      multi-jittered sampling, 2013, on the disc by its polar map of
      equal areas). A point at the centre gets no light from it.

    The stratified points give each ring or cell one sample: the error of
    a soft shadow falls faster with [n] than independent samples'. *)

val sectors : int -> int
(** [sectors n] is the largest [m >= 1] with [m * m <= n] ([n >= 1]):
    the angular sectors of a sphere light of [n] samples ({!samples_def}). *)

(** {1:adaptive Penumbra-only sampling}

    An area light with [adaptive] and at least four samples
    ({!corners_first}) first sends a shadow ray from [P] to
    each of its four corners, [corner], [corner + edge1], [corner + edge2]
    and [corner + edge1 + edge2] (each [(corner + a edge1) + b edge2], [a],
    [b] in [{0, 1}], as the samples'). If all four pass freely (through
    glass: a factor of exactly 1), every sample's terms are added without
    its shadow ray; if all four are stopped (factor 0), the light adds
    nothing; otherwise (the penumbra) the samples are traced as above.
    With fewer than four samples the corners' four rays cost more than
    they save: [adaptive] is then full sampling, exactly.

    What is exact and what is an estimate: the samples' terms, and the
    samples of the points in doubt, are exactly those of full sampling. A
    point whose four corner rays agree is taken as fully lit or fully
    shadowed: an estimate, wrong where a blocker smaller than the light
    (as seen from [P]) hides part of it but none of its corners, or where
    a hole in a blocker lets part of it through; such a blocker's shadow
    is then missed or incomplete. The tests hold the kernel to this
    definition ({!Raytrace.Private.Literal} transcribes it), and
    docs/run-time-against-error.md measures the error and the rays
    saved.

    Without [adaptive], the kernel's exact umbra skip (with the skips on)
    changes no byte: where one convex object stops the shadow rays of the
    four corner cells' samples, the samples inside their hull cast none
    (the kernel's [Lighting] (lib/kernel/lighting.mli)).

    With the skips on, adaptive or not, a stratified area light of at
    least four samples and a sphere light of at least four first ask whether
    anything at all could hide them from [P]: where no plane and no
    blocker's bounding box meets the hull of [P] and the light's
    rectangle (for a sphere light, the square around its disc facing
    [P]), every sample is seen, and its terms are added without a shadow
    ray. That is what the rays would find: it changes no byte, adaptive
    or not. With [sampling = Uniform] (plain Monte Carlo, the baseline that
    docs/run-time-against-error.md measures the others against) an area
    light does not ask (it would change none of its bytes either; the kernel's
    [Lighting] states the margins; [--stats] counts the points, [soft
    light, whole]). *)

(** {1:document The document's light record}

    The document represents a light as a record with a [char] tag. These
    let code written against the document build lights of this library. *)

type point = float * float * float
(** The document's point: [(x, y, z)]. *)

type document = { k : char; i : float; v : point option }
(** The document's light: [k] is ['p'] (point), ['d'] (directional) or
    ['a'] (ambient); [i] is the intensity; [v] the position of a point
    light, the direction of a directional light, [None] for an ambient
    light. *)

val of_document : document -> (t, [> `Msg of string ]) result
(** [of_document d] is the light [d] describes, validated as by
    {!validate}. [Error] names what is wrong: an unknown tag, a missing or
    superfluous [v], an invalid number. *)

val of_document_exn : document -> t
(** [of_document_exn] is {!of_document}.
    @raise Invalid_argument with the error message on invalid records. *)

val to_document : t -> document
(** [to_document l] is [l] as the document's record;
    [of_document (to_document l) = Ok l].
    @raise Invalid_argument on an area, sphere or spot light. *)
