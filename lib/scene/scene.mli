(** Scenes (document section 3): what to render and how.

    A scene is its settings (a canvas size, a viewport, a camera or a
    camera path, a background colour, a recursion depth, an optional
    epsilon), one list of objects ({!Shape.t}: spheres and every other
    shape, each with its {!Material.t}) in the order given, and its
    lights. Build one in code with {!v} or load it from text with
    {!Scene_file}. Where two objects give a ray equal roots, the earlier
    object in the list is the one seen. *)

(** {1:scenes Scenes} *)

type t
(** The type for scenes. *)

val v :
  ?width:int ->
  ?height:int ->
  ?viewport:Viewport.t ->
  ?camera:Camera.t ->
  ?background:Color.t ->
  ?depth:int ->
  ?epsilon:float ->
  ?camera_path:Camera_path.t ->
  objects:Shape.t list ->
  lights:Light.t list ->
  unit ->
  t
(** [v ~objects ~lights ()] is a scene with the given objects and lights,
    and otherwise the document's values: a 600 x 600 canvas,
    {!Viewport.default}, {!Camera.default}, a black background, depth 3,
    the robust mode (no epsilon) and no camera path. The result is not
    validated: see {!validate}. *)

val width : t -> int
(** [width s] is the canvas width [G_w] in pixels, [>= 1]. *)

val height : t -> int
(** [height s] is the canvas height [G_h] in pixels, [>= 1]. *)

val viewport : t -> Viewport.t
(** [viewport s] is the viewport of [s]. *)

val camera : t -> Camera.t
(** [camera s] is the camera of a still picture of [s]. *)

val camera_path : t -> Camera_path.t option
(** [camera_path s] is the camera of each frame of an animation
    ({!at_frame}), if any. *)

val background : t -> Color.t
(** [background s] is the colour of rays that hit nothing. *)

val depth : t -> int
(** [depth s] is the recursion depth, [>= 0]: how many times a ray may be
    followed after its first hit, reflected (7.8) or refracted through
    glass, one level for either. *)

val epsilon : t -> float option
(** [epsilon s] is [Some e] for the document's semantics (shadow and
    reflection rays see objects at [t > e] only), [None] for the robust
    mode, which needs no scene-dependent constant. *)

val objects : t -> Shape.t list
(** [objects s] is the objects of [s], in order (a new list at each
    call: a scene of a million spheres keeps them compactly). *)

val n_objects : t -> int
(** [n_objects s] is [List.length (objects s)], without the list. *)

val lights : t -> Light.t list
(** [lights s] is the lights of [s], in order. *)

val with_overrides :
  ?width:int ->
  ?height:int ->
  ?depth:int ->
  ?viewport:Viewport.t ->
  ?camera:Camera.t ->
  ?camera_path:Camera_path.t option ->
  ?background:Color.t ->
  ?epsilon:float option ->
  ?objects:Shape.t list ->
  ?lights:Light.t list ->
  t ->
  t
(** [with_overrides ~width ... s] is [s] with the given parts replaced,
    not validated. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf s] prints [s] in the scene-file syntax, one form a line, the
    objects in order, every number written so that it reads back as the
    same float: {!Scene_file.of_string} reads [show s] back as a scene
    equal to [s] (a mesh prints as its [mesh] form, which reads its file
    again). *)

val show : t -> string
(** [show x] is [x] formatted by {!pp}. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] have equal settings, equal
    objects in the same order and equal lights, floats compared with
    [=]. *)

val cgfs : t
(** [cgfs] is the reference scene of CGFS's demos (and of
    [scenes/cgfs.scene]): red, green, blue and a huge yellow ground sphere;
    ambient 0.2, point 0.6 at [(2, 1, 0)], directional 0.2 toward
    [(1, 4, 4)]; 600 x 600, depth 3, epsilon 0.001. It is the default
    scene of the [raytrace] command. *)

val cgfs_camera : t
(** [cgfs_camera] is {!cgfs} seen from [(3, 0, 1)], turned by the CGFS
    camera demo's matrix [(0.7071 0 -0.7071) (0 1 0) (0.7071 0 0.7071)]
    (and [scenes/cgfs-camera.scene]). *)

val grid : int -> t
(** [grid n] is the many-sphere scene [grid:n] of the C reference
    ([../shared/reference/]): [n] spheres of radius 0.4 in a wall facing
    the camera -- with [k] the smallest integer such that [k * k >= n],
    sphere [i] has center [(i mod k - (k - 1) / 2, i / k - 0.6, 2 k)],
    colour red, green, blue, yellow, cyan, magenta by [i mod 6], specular
    [-1, 10, 500, 1000] by [i mod 4] and reflective [0, 0.2, 0.4] by
    [i mod 3] -- then the ground sphere and the three lights of {!cgfs};
    800 x 800, depth 3, epsilon 0.001.
    @raise Invalid_argument if [n < 1]. *)

val document_epsilon : float
(** [document_epsilon] is [0.0001], the document's lower bound of [t] for
    shadow rays (7.7), used by {!Raytrace.Private.Literal} for scenes without an epsilon. *)

(** {1:validation Validation} *)

val check_epsilon : float -> (float, [> `Msg of string ]) result
(** [check_epsilon e] checks that [e] is finite and [>= 0]. *)

val check_background : Color.t -> (Color.t, [> `Msg of string ]) result
(** [check_background c] checks {!Color.in_gamut}. *)

type valid
(** The type for validated scenes: only {!validate} makes them, so a value
    of this type renders without NaN or infinity, within the bounds it was
    validated against. The renderers take only validated scenes. *)

val validate : ?limits:Limits.t -> t -> (valid, [> `Msg of string ]) result
(** [validate ~limits s] is [Ok s] if every part of [s] passes its check
    (canvas, depth and the numbers of objects, lights and triangles of
    meshes within [limits], default {!Limits.default};
    {!Viewport.validate}, {!Camera.validate}, {!Shape.validate},
    {!Light.validate}), and otherwise [Error (`Msg m)] with the first
    failure. A failure of one object or light names it before the part's
    own message, e.g. [object 3 (sphere): sphere radius must be > 0, got -1]
    or [light 2 (point): ...]: objects are numbered from [1] in the order
    of {!objects} (the first failing one is reported), a mesh or a CSG
    solid counting as one object; lights from [1] in the order of
    {!val-lights}; the kind in parentheses is the scene-file form
    ({!Shape.name}, or [ambient], [point], [directional]). A scene read by
    {!Scene_file} has each object checked where it is read, so its
    messages name [file:line:column] instead. A sphere's texture must be [spherical]. *)

val of_valid : valid -> t
(** [of_valid v] is the scene [v]. *)

val bottom : valid -> Shape.t -> valid
(** [bottom v s] is the scene of [v]'s settings with [s] its one object
    and no lights: the bottom level of an instance of [s] (a part of
    [v], validated with it), which [Prepared] prepares once per object.
    [bottom v] holds none of [v]'s objects. *)

val override :
  ?limits:Limits.t ->
  ?width:int ->
  ?height:int ->
  ?depth:int ->
  ?viewport:Viewport.t ->
  ?camera:Camera.t ->
  valid ->
  (valid, [> `Msg of string ]) result
(** [override ~limits ~width ~height ~depth ~viewport ~camera v] is [v]
    with the given parts replaced, checking only those (the canvas against
    [limits] if [width] or [height] is given, the depth, the viewport, the
    camera): the rest was validated. *)

val check_work : ?limits:Limits.t -> ?samples:int -> ?pixels:int -> valid -> (unit, [> `Msg of string ]) result
(** [check_work ~limits ~samples ~pixels s] is [Ok ()] if rendering
    [pixels] (default the whole canvas; fewer for a region) of [s] with
    [samples] (default 1) samples per pixel needs at most [limits]' bound
    on intersection tests ({!Limits.check_work}: the recursion
    depth counts only when some object is reflective or transparent, as a
    tree where some transparent object also reflects or has the Fresnel
    term; only point and directional lights cast shadow rays; a mesh's
    triangles are objects of the hierarchy, a CSG solid's leaves are
    tested by every ray that meets it), and otherwise [Error] saying the
    estimate, the bound and how to raise it; a scene with transparent
    objects deeper than {!Limits.max_tree_levels} is an [Error] too.
    {!Render.image} checks it before it allocates anything. *)

(** {1:animation Animation} *)

val at_frame : valid -> int -> (valid, [> `Msg of string ]) result
(** [at_frame s f] is the still scene of frame [f] of [s]'s camera path:
    [s] with the path's camera of frame [f] ({!Raytrace.Camera.Path.camera}) and no
    camera path; the lens of [s]'s camera (its aperture and focal
    distance), if it has one, goes on the path's camera. [Error] if [s]
    has no camera path or [f] lies outside it. *)

(**/**)

(* For the library's own readers and its preparation: the spheres kept
   compactly, and each other object with the number of spheres before it
   in the list. Not for users: it changes without notice. *)

type view = {
  width : int;
  height : int;
  viewport : Viewport.t;
  camera : Camera.t;
  background : Color.t;
  depth : int;
  epsilon : float option;
  spheres : Spheres.t;
  shapes : Shape.t list;  (** The objects but the spheres, in order. *)
  placed : (int * Shape.t) list;  (** Each with the number of spheres before it. *)
  lights : Light.t list;
  camera_path : Camera_path.t option;
}

val view : t -> view
(** [view s] is [s]'s parts as a record (no copy). *)

val spheres : t -> Spheres.t
(** [spheres s] is the spheres of [s], in order. *)

val placed : t -> (int * Shape.t) list
(** [placed s] is the other objects of [s], in order, each with the
    number of spheres before it in the list. *)

val shapes : t -> Shape.t list
(** [shapes s] is the other objects of [s], in order. *)

val with_objects : t -> spheres:Spheres.t -> placed:(int * Shape.t) list -> t
(** [with_objects s ~spheres ~placed] is [s] with these objects (as a
    reader builds them, without a list of the spheres). *)

val iter_objects : t -> sphere:(int -> unit) -> shape:(Shape.t -> unit) -> unit
(** [iter_objects s ~sphere ~shape] walks the objects of [s] in order:
    [sphere i] for sphere [i] of {!spheres}, [shape sh] for the others. *)
