(** Testables and helpers shared by the test suites. *)

val vec3 : Raytrace.Vec3.t Alcotest.testable
(** Vectors compared exactly. *)

val vec3_near : float -> Raytrace.Vec3.t Alcotest.testable
(** [vec3_near eps] compares coordinates within absolute [eps]. *)

val color : Raytrace.Color.t Alcotest.testable
(** Colours compared exactly. *)

val float_near : float -> float Alcotest.testable
(** [float_near eps] compares within absolute [eps]. *)

val check_images : ?max_abs:int -> ?min_share:float -> string -> expected:Raytrace.Image.t -> Raytrace.Image.t -> unit
(** [check_images ~max_abs ~min_share what ~expected actual] fails, saying
    how many pixels differ and by how much, unless the sizes agree and
    either every channel differs by at most [max_abs] (default 0) or, with
    [min_share], at least that share of pixels is within 1 per channel. *)

val scene_path : string -> string
(** [scene_path name] is the path of [scenes/name] seen from the test
    directory. *)

val scene_names : unit -> string list
(** [scene_names ()] is the sorted list of files in [scenes/] ending in
    [.scene]. *)

val load_scene : string -> Raytrace.Scene.t
(** [load_scene name] parses [scenes/name], failing the test on error. *)

val qcheck : ?count:int -> string -> 'a QCheck.arbitrary -> ('a -> bool) -> unit Alcotest.test_case
(** [qcheck name arb prop] is an Alcotest case that checks the QCheck
    property [prop] on [count] (default 200) values of [arb], with a fixed
    seed so failures reproduce. *)

val run : ?env:string array -> string -> string list -> int * string * string
(** [run ~env exe args] runs [exe] with [args] (and environment [env],
    default the test's) and is its exit status, stdout and stderr. *)

val raytrace : unit -> string
(** [raytrace ()] is the path of the [raytrace] executable under test. *)

val temp_dir : unit -> string
(** [temp_dir ()] is a fresh empty directory. *)

(** {1:valid Validated scenes for the tests} *)

val valid : Raytrace.Scene.t -> Raytrace.Scene.valid
(** [valid s] is [s] validated, failing the test if it is invalid. *)

val render :
  ?limits:Raytrace.Limits.t ->
  ?jobs:int ->
  ?split:Raytrace_unix.Render_jobs.split ->
  ?skips:bool ->
  ?samples:int ->
  ?adaptive:int ->
  ?subsample:bool ->
  ?progress:(rows:int -> total:int -> rays:int -> unit) ->
  Raytrace.Scene.t ->
  (Raytrace.Image.t * Raytrace.Render.Stats.t, [> `Msg of string ]) result
(** [render ... s] is {!Raytrace_unix.Render_jobs.image} on [s]
    validated (with the same [limits]), its workers forked whatever the
    image and the host unless [split] (default [`Always]) says otherwise;
    [Error] if [s] is invalid. *)

val render_region :
  ?limits:Raytrace.Limits.t ->
  ?jobs:int ->
  ?split:Raytrace_unix.Render_jobs.split ->
  ?skips:bool ->
  ?samples:int ->
  ?adaptive:int ->
  ?subsample:bool ->
  ?progress:(rows:int -> total:int -> rays:int -> unit) ->
  Raytrace.Scene.t ->
  Raytrace.Render.Region.t ->
  (Raytrace.Image.t * Raytrace.Render.Stats.t, [> `Msg of string ]) result
(** [render_region ... s r] is {!Raytrace_unix.Render_jobs.region_image}
    on [s] validated, [split] as for {!render}; [Error] if [s] is invalid. *)

val image_exn :
  ?jobs:int -> ?skips:bool -> ?samples:int -> ?adaptive:int -> ?subsample:bool -> Raytrace.Scene.t -> Raytrace.Image.t
(** [image_exn ~jobs ~skips ~samples ~adaptive ~subsample s] is the image of {!render}, failing
    the test on [Error]. *)

val prepare : ?skips:bool -> Raytrace.Scene.t -> Raytrace.Private.Prepared.t
(** [prepare ~skips s] is [s] validated and prepared. *)

val oracle_floats : Raytrace.Scene.t -> bool
(** [oracle_floats s] is [true] iff every pixel's colour floats of the fast
    tracer (skips off: the early stop changes floats, never bytes) are
    within [1e-9] (relative, absolute below 1) of
    {!Raytrace.Private.Literal.pixel}'s; the first difference is printed. The
    oracle computes its geometry its own way ({!Raytrace.Literal}): the
    two agree to rounding, and a pixel where they decide differently (a
    hit, a shadow, a cell) differs by far more. *)

val read_scene : string -> (Raytrace.Scene.t, [> `Msg of string ]) result
(** [read_scene path] is the scene of the file [path], as a plain scene. *)

val of_string : ?limits:Raytrace.Limits.t -> ?file:string -> string -> (Raytrace.Scene.t, [> `Msg of string ]) result
(** [of_string ~limits ~file text] is {!Raytrace.Scene_file.of_string} as a plain
    scene. *)

val parse_ok : string -> Raytrace.Scene.t
(** [parse_ok text] is the scene of [text], read as the file [t.scene];
    the test fails on an error. *)

val parse_error : string -> string
(** [parse_error text] is the message of [text]'s error, read as the file
    [t.scene]; the test fails if it reads. *)

(** {1:skips Skips}

    A check that cannot run here (a tool missing, no root) is skipped
    through {!skip}, never silently: the skip is on the console, in the
    summary at the end of the run, and under [CI=true] a failure. *)

val skip : string -> why:string -> unit
(** [skip what ~why] records that the check [what] did not run because of
    [why] and prints [SKIPPED what: why] on the console (the stderr the
    test program started with: Alcotest captures the tests' own). Under
    the environment variable [CI=true] it then fails the test.
    @raise Alcotest's failure under [CI=true]. *)

val skips : unit -> (string * string) list
(** [skips ()] is the list of [(what, why)] skipped so far, in order. *)

val report_skips : unit -> int
(** [report_skips ()] prints on the console a summary of the skips, if
    any, and is the exit status they call for: 1 if anything was skipped
    under [CI=true], 0 otherwise. *)

val on_path : string -> bool
(** [on_path prog] is [true] iff a file [prog] is in a directory of [PATH]. *)

val missing : string list -> string list
(** [missing progs] is the programs of [progs] that are not on [PATH]. *)

val mask_errors : bool array array -> [ `In | `Out | `Edge ] array array -> int * int
(** [mask_errors mask exact] is [(wrong, inside)]: the pixels whose hit in
    [mask] (row by row) disagrees with the exact classification [exact]
    ([`Edge] pixels, within the error bound of an edge, are not counted),
    and the pixels classified [`In]. *)

(** {1:obj Meshes read in two parts} *)

val obj_part_joined :
  Raytrace.Mesh.Obj.parser -> name:string -> max_vertices:int -> max_triangles:int -> string -> int -> int ->
  Raytrace.Mesh.Obj.t option
(** [obj_part_joined p ~name ~max_vertices ~max_triangles s off len] is
    the bytes [s.[off] .. s.[off+len-1]] read as a part
    ({!Raytrace.Private.Obj_parts.create_part}, its output kept in a buffer) and
    joined to [p] ({!Raytrace.Private.Obj_parts.join}, its input that buffer), as
    [Files.read_mesh] does without the fork; [None] where the part is an
    error or the join declines. *)

(** {1:slow Scenes slow to render} *)

val csg_spiral : int -> string
(** [csg_spiral n] is the text of a scene of 16 x 16 pixels: a CSG union of
    [n] small spheres along a spiral, as a balanced tree (CSG nests at most
    32 deep), lit by an ambient and a point light. *)

val glass_planes : width:int -> height:int -> depth:int -> string
(** [glass_planes ~width ~height ~depth] is the text of a scene of four
    parallel planes, each half mirror, half glass, one behind the other,
    seen face on: every hit spawns two rays, so a pixel's ray tree grows
    about as [2^(depth/2)] rays (tens of thousands at depth 20, millions at
    28), the front ends' slowest pixels. *)

val sphere :
  ?specular:float ->
  ?reflective:float ->
  ?transparency:float ->
  ?refractive_index:float ->
  ?fresnel:bool ->
  ?pattern:Raytrace.Pattern.t ->
  center:Raytrace.Vec3.t ->
  radius:float ->
  Raytrace.Color.t ->
  Raytrace.Sphere.t
(** [sphere ~specular ... ~center ~radius color] is the sphere made of
    [Material.v ~specular ... color]: the tests' short way. *)

val scene :
  ?width:int ->
  ?height:int ->
  ?viewport:Raytrace.Viewport.t ->
  ?camera:Raytrace.Camera.t ->
  ?background:Raytrace.Color.t ->
  ?depth:int ->
  ?epsilon:float ->
  ?camera_path:Raytrace.Camera.Path.t ->
  ?shapes:Raytrace.Shape.t list ->
  spheres:Raytrace.Sphere.t list ->
  lights:Raytrace.Light.t list ->
  unit ->
  Raytrace.Scene.t
(** [scene ~spheres ~shapes ~lights ()] is {!Raytrace.Scene.v} of the
    objects [spheres] then [shapes]. *)

val with_sphere_material : Raytrace.Sphere.t -> (Raytrace.Material.t -> Raytrace.Material.t) -> Raytrace.Sphere.t
(** [with_sphere_material s f] is [s] made of [f] of its material. *)

val scene_spheres : Raytrace.Scene.t -> Raytrace.Sphere.t list
(** [scene_spheres s] is the spheres of [s], in order. *)

val with_objects : ?spheres:Raytrace.Sphere.t list -> ?shapes:Raytrace.Shape.t list -> Raytrace.Scene.t -> Raytrace.Scene.t
(** [with_objects ~spheres ~shapes s] is [s] with the objects [spheres]
    then [shapes], each list by default [s]'s own. *)

val by_pixels : Raytrace.Private.Trace.t -> Raytrace.Image.t
(** [by_pixels tr] is the image [tr] traces a pixel at a time, column by
    column ({!Raytrace.Private.Trace.pixel}). *)
