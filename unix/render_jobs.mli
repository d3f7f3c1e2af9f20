(** Rendering in several processes: {!Raytrace.Render} with [jobs] worker
    processes that trace bands of rows into shared memory
    ({!Parallel}), taking them from a queue as they go. The image is the same, byte for byte, whatever the
    number of jobs: each pixel is traced alone, by the same code. *)

type split = [ `Auto | `Always ]
(** The type for when a render with several jobs forks its workers:
    [`Always], or [`Auto], only where it may pay ({!split_work}). *)

val split_work : Scene.valid -> Render.Region.t -> samples:int -> float
(** [split_work scene r ~samples] is the guess of a trace's length that
    decides whether to fork workers, made before anything is prepared:
    [r]'s pixels times [samples]{^2}, times [1 + log2 (1 + n)] for the
    [n] objects of the scene's hierarchy (each mesh triangle one), the
    levels that a ray's walk descends. *)

val least_split_work : int
(** [least_split_work] is [2^20]: with [~split:`Auto], a render with several
    jobs traces in this process (its hierarchy's build still shared with
    a child of {!bvh_beside} where a core is idle), where {!split_work} is
    less (the workers' fork and shared memory would cost more than half
    the trace saves: the reference scene's four spheres split from about
    316,000 primary rays, 560 x 560, a million triangles from 50,000), or
    where {!Parallel.idle_core} is [false] (the workers would share one
    core). [`Always] forks the hierarchy's child of {!bvh_beside} too,
    whatever the host. The image is the same bytes either way; the
    {!Raytrace.Render.Stats.t}'s [jobs] says how many processes traced. *)

val image :
  ?limits:Limits.t ->
  ?jobs:int ->
  ?split:split ->
  ?skips:bool ->
  ?samples:int ->
  ?adaptive:int ->
  ?subsample:bool ->
  ?progress:(rows:int -> total:int -> rays:int -> unit) ->
  ?rows_done:(Image.t -> int -> unit) ->
  Scene.valid ->
  (Image.t * Render.Stats.t, [> `Msg of string ]) result
(** [image ~limits ~jobs ~split ~skips ~samples ~adaptive ~subsample ~progress ~rows_done scene] is
    {!Raytrace.Render.image} traced by [jobs] processes (default 1: this one), timed
    by the wall clock, where [split] (default [`Auto]) says to fork them
    ({!split_work}; otherwise by this one alone, as with one job). With workers, [progress] is called about ten
    times a second by this process (the workers count their rows in shared
    memory), with the meaning it has for {!Raytrace.Render.image}.
    [rows_done img r] is called by this process whenever the first [r]
    rows of [img], the image being rendered, are final, with [r]
    increasing and last the image's height, before [image] returns [Ok img]:
    with workers and a single pass ([Raytrace.Private.Sampling_rows.passes]), while the
    workers trace the rest (to write the image as it is made); otherwise
    once, at the end. It must not raise. Besides {!Raytrace.Render.image}'s errors, [Error] before
    anything is allocated if the image needs more memory than the system
    has available, and [Error] if no shared memory can be had or a worker
    process dies.
    @raise Invalid_argument if [jobs < 1]. *)

val region_image :
  ?limits:Limits.t ->
  ?jobs:int ->
  ?split:split ->
  ?skips:bool ->
  ?samples:int ->
  ?adaptive:int ->
  ?subsample:bool ->
  ?progress:(rows:int -> total:int -> rays:int -> unit) ->
  ?rows_done:(Image.t -> int -> unit) ->
  Scene.valid ->
  Render.Region.t ->
  (Image.t * Render.Stats.t, [> `Msg of string ]) result
(** [region_image ~limits ~jobs ~split ~skips ~samples ~adaptive ~subsample ~progress ~rows_done scene r]
    is {!Raytrace.Render.region_image} traced by [jobs] processes, with the errors
    of {!image}.
    @raise Invalid_argument if [jobs < 1] or [r] is not inside the
    canvas. *)

val bvh_beside : ?min_objects:int -> ?idle:(unit -> bool) -> ?take_over:bool -> unit -> Bvh.beside
(** [bvh_beside ~min_objects ~idle ~take_over ()] builds the right subtree of a hierarchy's
    node of at least [min_objects] (default [2^16]) objects in a child
    process ({!Parallel.beside}) while this one builds the rest; the
    child's leaves' boxes come back in memory shared with it, which the
    child reserves as it writes ({!Parallel.shared_floats_later}). A child
    that fails (killed, out of memory) costs the time it took: its part
    is built here; so is the part of a child that is late when this
    process has built the rest ({!Parallel.beside}'s [take_over], default
    [true]; a test that counts the parts built beside turns it off): it is
    killed. It forks only where [idle ()] (default
    {!Parallel.idle_core}; {!Bvh.beside}'s [idle]), asked before each fork,
    says a core is idle; otherwise the part is built here at once, as
    with one job: on a machine whose other core is busy the child comes
    late and its copy-on-write faults cost more than it saves, on a quiet
    one it saves time (docs/performance.md, issue 31). {!image} and
    {!region_image} use it with more than one job; [bench/load.exe --jobs
    2] measures it. *)

val bands : jobs:int -> int -> int array
(** [bands ~jobs n] is how a pass of [n] rows is cut for [jobs] workers:
    band [b] is the rows [s.(b)] to [s.(b + 1) - 1] of [s = bands ~jobs n],
    [s.(0) = 0], the last element is [n]. Band [b] has
    [max 1 (left / (8 * jobs))] rows, where [left] is the number of rows in
    no earlier band (guided scheduling): large bands first, single rows
    last. Where that would make more than {!Parallel.max_tasks} bands, the
    least band is 2, 4, ... rows instead of 1. *)
