(** A faithful, fast and numerically sound basic ray tracer.

    [Raytrace] renders the scenes of the document "Very Basic Raytracer"
    (after Gabriel Gambetta's {e Computer Graphics from Scratch}):
    spheres; ambient, point and directional lights; diffuse and specular
    shading; shadows; recursive mirror reflection. It is pure OCaml: no
    files, processes, signals or environment (it builds for JavaScript).

    {1:start What to call first}

    The common case is one call from scene text to an image:
{[
let ppm_of_scene_text text =
  match Raytrace.render_string text with
  | Ok image -> Ok (Raytrace.Ppm.to_string image)
  | Error (`Msg m) -> Error m
]}
    Scenes are also built in code ({!Scene.v}) and validated
    ({!Scene.validate}); a single pixel's colour is {!Pixel.color}.

    {1:flow The data flow}

{v
scene text --Scene_file.of_string--> Scene.valid --Render.image--> Image.t --Ppm.to_string--> bytes
Scene.t (built in code) --Scene.validate--^        \--Pixel.color--> Color.t (one pixel)
v}
    A {!Scene.t} is its settings, one list of objects and its lights; a {!Scene.valid} is a scene that passed
    validation, the only kind the renderers take, so an invalid scene
    never reaches them and no scene is validated twice.

    {1:errors The error convention}

    Everything a user supplies (scene text, image bytes, sampling settings,
    a scene built in code) is checked, and failures are
    [Error (`Msg message)] in [(_, [> `Msg of string]) result]; scene-text
    messages start with [file:line:column]. [Invalid_argument] is raised
    only for programmer errors that a function documents (a region outside
    the canvas, a pixel outside the image), with a message that names the
    public function. Resource bounds (pixels, depth, samples, scene size,
    work) are a {!Limits.t} passed explicitly; the default is
    {!Limits.default}.

    {1:document The document's sections}

    - Section 1, the coordinate system and [plotc]: {!Image} (rows
      top-down; the window's [plotc] is in the program [raytrace]).
    - Section 2, colours and clamping: {!Color}.
    - Section 3, the scene, the camera and the viewport: {!Scene},
      {!Camera}, {!Viewport}, {!Scene_file} (scene text).
    - Sections 4-6, rays, the sphere and their intersection (6.1):
      {!Sphere}, {!Sphere.roots}.
    - Section 7, lights, diffuse and specular shading (7.1-7.6), shadows
      (7.7) and mirror reflection (7.8): {!Light}, and {!Literal}, the
      document's algorithm transcribed literally (the executable
      specification the fast tracer is tested against).
    - Section 8, rendering: {!Render}, {!Pixel}.
    - Beyond the document's spheres (its chapter "Extending the
      Raytracer"): {!Plane}, {!Triangle} (watertight), {!Box}, {!Mesh}
      (from Wavefront OBJ files, {!Obj_file}, or generated, {!Mesh_gen}),
      one type for them, {!Shape}, each with a {!Material}, which may
      carry a {!Pattern} (a checkerboard); constructive solid geometry of
      the closed ones, {!Csg}.
    - Beyond the document: {!Sampling} (antialiasing), {!Camera_path}
      (animation), {!Region} (tiles), {!Image_diff}, {!Ppm}.

    {1:system Beside this library}

    - [raytrace.unix] ([Raytrace_unix]): scene and image files, rendering
      in several processes, signals, the {!Limits} read from the
      environment, tiles and parts for farms.
    - [raytrace.view] ([Raytrace_view]): the window model and the
      coarse-first progressive renderer, for any front end.
    - [raytrace-png] ([Raytrace_png]): PNG files, through camlimages. *)

(** {1:modules Modules} *)

module Vec3 = Vec3
module Color = Color
module Viewport = Viewport
module Camera = Camera
module Camera_path = Camera_path
module Sphere = Sphere
module Pattern = Pattern
module Material = Material
module Plane = Plane
module Triangle = Triangle
module Box = Box
module Mesh = Mesh
module Csg = Csg
module Shape = Shape
module Obj_file = Obj_file
module Mesh_gen = Mesh_gen
module Spheres = Spheres
module Light = Light
module Scene = Scene
module Scene_file = Scene_file
module Limits = Limits
module Sampling = Sampling
module Region = Region
module Image = Image
module Stats = Stats
module Render = Render
module Pixel = Pixel
module Ppm = Ppm
module Image_diff = Image_diff
module Literal = Literal

(** {1:one_call One call} *)

val render_string :
  ?limits:Limits.t -> ?file:string -> string -> (Image.t, [> `Msg of string ]) result
(** [render_string ~limits ~file text] is the image of the scene text
    [text] ({!Scene_file.of_string}, then {!Render.image}), one ray per
    pixel, within [limits] (default {!Limits.default}). *)

val version : string
(** [version] is the version of raytrace, e.g. ["0.2.0"]. *)

(** {1:private Internals}

    {b Unstable}: the kernel of the fast tracer, exposed for the system
    libraries of this project ([raytrace.unix], [raytrace.view]), its
    tests and its benchmarks. It changes without notice; do not use it. *)

module Private : sig
  module Float_text = Float_text
  module Canvas = Canvas
  module Shading = Shading
  module Bvh = Bvh
  module Prepared = Prepared
  module Trace = Trace
  module Scratch = Scratch
  module Ray_tree = Ray_tree
  module Float_scan = Float_scan
  module Sexp_scan = Sexp_scan
  module Sphere_scan = Sphere_scan
  module Antialias = Antialias
  module Render_work = Render_work
  module Exact_float = Exact_float
  module Literal_geometry = Literal_geometry
end
