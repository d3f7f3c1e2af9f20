(** The bounds that inputs must respect.

    Beyond these, a render would lose all precision, exhaust memory or run
    for years; scenes, images and command lines outside them are refused up
    front, before any large allocation, with a message that names the bound
    and how to raise it.

    Two kinds of bounds:
    - fixed ones, which protect precision or a file format:
      {!max_coordinate}, {!max_dimension};
    - resource ones, which protect memory and time: a value of type {!t},
      passed explicitly to what checks them. Each has a default
      ({!max_pixels}, ...) and a name, the environment variable by which
      the command line replaces it: [RAYTRACE_MAX_PIXELS],
      [RAYTRACE_MAX_DEPTH], [RAYTRACE_MAX_SAMPLES], [RAYTRACE_MAX_SPHERES],
      [RAYTRACE_MAX_TRIANGLES], [RAYTRACE_MAX_LIGHTS], [RAYTRACE_MAX_SCENE_BYTES],
      [RAYTRACE_MAX_FORM_BYTES], [RAYTRACE_MAX_MESH_BYTES], [RAYTRACE_MAX_WORK]. This library reads no environment:
      {!of_lookup} turns the variables into a {!t} given a lookup function
      (the system library [raytrace.unix] calls it once, with
      [Sys.getenv_opt]). *)

(** {1:fixed Fixed bounds} *)

val max_triangles : int
(** [max_triangles] is [4_000_000]: the most triangles (and vertices) of a
    mesh file, about 290 MB of mesh once read, 580 MB while it is read. *)

val max_coordinate : float
(** [max_coordinate] is [1e12]: the largest magnitude of a coordinate, a
    radius or a viewport dimension. Squares of larger values approach the
    range where sums of squares lose every digit of a unit-sized sphere. *)

val min_size : float
(** [min_size] is [1e-30]: the smallest radius, viewport dimension or
    directional-light vector length. Squares and products of smaller values
    underflow and would turn into division by zero. *)

val max_intensity : float
(** [max_intensity] is [1e6]: the largest light intensity, so that sums of
    intensities times colours can never overflow to infinity. *)

val max_dimension : int
(** [max_dimension] is [65536]: the largest canvas width or height. *)

val max_grid : int
(** [max_grid] is [64]: the largest side of a pixel's grid of samples
    ({!Raytrace.Render.Sampling.max_samples}), a fixed bound. *)

(** {1:defaults Defaults of the resource bounds} *)

val max_pixels : int
(** [max_pixels] is [268435456] ([2^28], 768 MiB of RGB): the default
    largest canvas area, and the largest PPM image read. *)

val max_depth : int
(** [max_depth] is [64]: the default largest recursion depth. Each level
    multiplies the weight of the reflected colour by at most 1, but deeper
    recursion only costs time. *)

val max_samples : int
(** [max_samples] is [max_grid * max_grid = 4096]: the default largest
    number of rays per pixel; the variable can only lower it. *)

val max_spheres : int
(** [max_spheres] is [1_000_000]: the default largest number of spheres of
    a scene. Measured: [grid:1000000] (an 88 MB file) loads, prepares and
    renders in 590 MB of memory. *)

val max_scene_triangles : int
(** [max_scene_triangles] is [4_000_000]: the default largest number of
    triangles over all the mesh forms of a scene (a file named twice
    counts twice: each form places its own copy), counted before each
    copy is made. As many as the largest mesh file ({!max_triangles}), so
    that a scene that names one big file once is accepted, and one that
    names it sixty times is refused before its memory runs out. *)

val max_levels : int
(** [max_levels] is [2^20]: the largest recursion depth whatever the
    [`Depth] bound says, a fixed bound: a tracer keeps a few floats per
    level, made when it is created. *)

val max_tree_levels : int
(** [max_tree_levels] is [4096]: the largest recursion depth of a scene
    with transparent objects, a fixed bound: the tracer follows their ray
    tree by recursion, a few hundred bytes of the system stack a level (8
    MiB, the usual stack, overflowed at about 20000 levels). *)

val max_lights : int
(** [max_lights] is [1000]: the default largest number of lights of a
    scene. *)

val max_scene_bytes : int
(** [max_scene_bytes] is [134_217_728] (128 MiB): the default largest
    scene file. Loading streams form by form, and so does the second pass
    that locates an error: measured on [grid:1000000] (88 MB), 590 MB to
    load and render it, 380 MB to locate an error at its end. *)

val max_form_bytes : int
(** [max_form_bytes] is [16_777_216] (16 MiB): the default largest
    top-level form of a scene file (a camera path of about 250000 keys).
    The parser holds a form whole before it is converted, in 30 to 50
    bytes of memory per byte of text (measured on a form of numbers: 1 GB
    for 20 MB; refused at this bound, 500 MB), so this bounds the memory
    of loading whatever the file's size. *)

val max_mesh_bytes : int
(** [max_mesh_bytes] is [1_073_741_824] (1 GiB): the default largest mesh
    (OBJ) file. A mesh is read 64 KiB at a time, so its text costs no
    memory; the bound stops a read that would never end (a file that
    grows as it is read) or that could not give a mesh within
    {!max_triangles} in a sensible time: an OBJ file of 4M triangles with
    normals is some 300 to 600 MB. *)

val max_work : float
(** [max_work] is [1e12]: the default largest number of
    intersection tests that a render may need by the estimate of
    {!work}, about four hours of one core at the 7e7 tests per second
    measured on the reference scene. *)

(** {1:current Resource bounds} *)

type t
(** The type for resource bounds. *)

type name = [ `Pixels | `Depth | `Samples | `Spheres | `Triangles | `Lights | `Scene_bytes | `Form_bytes | `Mesh_bytes | `Work ]
(** The type for the names of the resource bounds. *)

val default : t
(** [default] is every bound at its default ({!max_pixels}, ...). *)

val bound : t -> name -> float
(** [bound l n] is the bound [n] of [l], an integer. *)

val with_bound : t -> name -> float -> t
(** [with_bound l n x] is [l] with bound [n] set to [x]. *)

val variable : name -> string
(** [variable n] is the environment variable that sets the bound [n], e.g.
    ["RAYTRACE_MAX_PIXELS"]. *)

val of_lookup : (string -> string option) -> (t, [> `Msg of string ]) result
(** [of_lookup lookup] is {!default} with each bound [n] replaced by the
    value of [lookup (variable n)] when that is [Some] non-empty text: a
    positive integer, optionally written with [_] separators or in exponent
    notation ([1e13]). [Error] names the first variable whose value is
    something else. *)

val exceeded : t -> name -> string -> string
(** [exceeded l n what] is the message for a value beyond bound [n] of
    [l]: [what] (which says the value), then the bound and how to raise
    it, e.g. ["canvas 70000x70000 has 4900000000 pixels, more than the
    limit of 268435456 (set RAYTRACE_MAX_PIXELS to raise it)"]. *)

(** {1:checks Checks} *)

val max_jobs : int
(** [max_jobs] is [1024]: the most worker processes a render forks. *)

val check_jobs : int -> (int, [> `Msg of string ]) result
(** [check_jobs n] is [Ok n] if [1 <= n <= max_jobs]. *)

val coordinate_ok : float -> bool
(** [coordinate_ok x] is [true] iff {!check_coordinate} accepts [x]; it
    allocates nothing (a million spheres are checked with it). *)

val size_ok : float -> bool
(** [size_ok x] is [true] iff {!check_size} accepts [x]; it allocates
    nothing. *)

val check_coordinate : string -> float -> (float, [> `Msg of string ]) result
(** [check_coordinate what x] is [Ok x] if [x] is finite with
    [|x| <= max_coordinate], and otherwise [Error] naming [what]. *)

val check_size : string -> float -> (float, [> `Msg of string ]) result
(** [check_size what x] is [Ok x] if [min_size <= x <= max_coordinate],
    and otherwise [Error] naming [what] ("sphere radius", ...). *)

val check_point : string -> Vec3.t -> (Vec3.t, [> `Msg of string ]) result
(** [check_point what p] is {!check_coordinate} on each coordinate. *)

val check_dimension : string -> int -> (int, [> `Msg of string ]) result
(** [check_dimension what n] is [Ok n] if [1 <= n <= max_dimension], and
    otherwise [Error] naming the canvas's [what] ("width", "height"). *)

val check_canvas : t -> int -> int -> (unit, [> `Msg of string ]) result
(** [check_canvas l w h] is [Ok ()] if [1 <= w, h <= max_dimension] and
    [w * h] is within the [`Pixels] bound of [l]. *)

val check_image_size : t -> int -> int -> (unit, [> `Msg of string ]) result
(** [check_image_size l w h] is [Ok ()] if [w, h >= 1] and [w * h] is within
    the [`Pixels] bound of [l] (images read from files, which have no
    {!max_dimension}). Never overflows. *)

val check_depth : t -> int -> (int, [> `Msg of string ]) result
(** [check_depth l d] is [Ok d] if [0 <= d <= max_levels] and [d] is
    within the [`Depth] bound of [l]. *)

val check_samples : t -> int -> (int, [> `Msg of string ]) result
(** [check_samples l n] is [Ok n] if [1 <= n] and [n] rays per pixel are
    within the [`Samples] bound of [l] (the renderer checks
    [samples x samples]). *)

val check_triangles : t -> int -> (int, [> `Msg of string ]) result
(** [check_triangles l n] is [Ok n] if meshes of [n] triangles in all are
    within the [`Triangles] bound of [l]. *)

val check_count : t -> [ `Spheres | `Objects | `Lights ] -> int -> (int, [> `Msg of string ]) result
(** [check_count l kind n] is [Ok n] if a scene with [n] spheres (or lights)
    is within that bound of [l]. [`Objects] counts spheres and other shapes
    together against the [`Spheres] bound, and says "objects" where
    [`Spheres] says "spheres". *)

val check_scene_bytes : t -> int -> (int, [> `Msg of string ]) result
(** [check_scene_bytes l n] is [Ok n] if a scene text of [n] bytes is within
    the [`Scene_bytes] bound of [l]. *)

val check_form_bytes : t -> int -> (int, [> `Msg of string ]) result
(** [check_form_bytes l n] is [Ok n] if a top-level form of [n] bytes (or
    more, as far as it was read) is within the [`Form_bytes] bound of
    [l]. *)

val check_mesh_bytes : t -> string -> int -> (int, [> `Msg of string ]) result
(** [check_mesh_bytes l file n] is [Ok n] if a mesh file of [n] bytes (or
    more, as far as it was read) is within the [`Mesh_bytes] bound of [l];
    [Error] names [file]. *)

val rays_per_sample : depth:int -> split:bool -> float
(** [rays_per_sample ~depth ~split] is the most rays that one camera ray
    leads to, itself included: [depth + 1] along a chain of reflections
    (or of refractions), [2^(depth + 1) - 1] when a hit may spawn both a
    reflected and a refracted ray ([split]: a material that is transparent
    and reflective, or transparent with the Fresnel term), the size of a
    full binary tree of [depth] levels below its root. A float, [infinity]
    rather than an overflow for a large [depth]; a negative [depth] counts
    as [0]. *)

val work :
  ?split:bool -> ?leaves:int -> pixels:int -> samples:int -> depth:int -> spheres:int -> lights:int -> unit -> float
(** [work ~split ~leaves ~pixels ~samples ~depth ~spheres ~lights ()]
    bounds the intersection tests of a render:
    [pixels * samples * r * (m + leaves) * (1 + lights)], where [r] is
    {!rays_per_sample} [~depth ~split] ([split] defaults to [false]),
    [depth] counts the bounces a ray may make (0 without reflective or
    transparent objects), [lights] the lights that cast shadow rays (point
    and directional), [m] the objects a ray meets: all of them up to 8,
    beyond that (where the renderer uses a bounding volume hierarchy) at
    most [16 log2 spheres], rounded up; and [leaves] (default [0]) the
    leaves of CSG solids, each of which a ray that meets its solid tests.
    A float, computed in floats, so that no factor can overflow (it may be
    [infinity]). *)

exception Work_exceeded of int
(** [Work_exceeded n] is raised by a renderer that has counted [n]
    intersection tests (with objects, CSG leaves and the hierarchies' boxes) in a render, more than
    {!work_budget}: the estimate of {!check_work} can be beaten by a scene
    that defeats the bounding volume hierarchy (many coincident spheres),
    so the work done is also counted as it is done. *)

val work_budget : t -> int
(** [work_budget l] is the [`Work] bound of [l] as a count of tests,
    [max_int] if it is larger. *)

val work_exceeded : t -> int -> string
(** [work_exceeded l n] is the message for a render stopped after [n]
    intersection tests, naming the bound of [l] and how to raise it. *)

val check_work :
  ?split:bool ->
  ?leaves:int ->
  t ->
  pixels:int ->
  samples:int ->
  depth:int ->
  spheres:int ->
  lights:int ->
  unit ->
  (unit, [> `Msg of string ]) result
(** [check_work l ...] is [Ok ()] if {!work} is within the [`Work] bound of
    [l], and otherwise [Error] with the estimate and its factors, in one
    line. *)
