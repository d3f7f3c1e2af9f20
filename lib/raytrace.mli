(** A faithful, fast and numerically sound basic ray tracer.

    [Raytrace] renders the scenes of the document "Very Basic Raytracer"
    (after Gabriel Gambetta's {e Computer Graphics from Scratch}):
    spheres; ambient, point and directional lights; diffuse and specular
    shading; shadows; recursive mirror reflection -- and beyond it planes,
    triangles, boxes, meshes, constructive solid geometry, glass,
    patterns, antialiasing and animation. It is pure OCaml: no
    files, processes, signals or environment (it builds for JavaScript).

    {1:start What to call first}

    The common case is one call from scene text to an image:
{[
let ppm_of_scene_text text =
  match Raytrace.render_string text with
  | Ok image -> Ok (Raytrace.Image.Ppm.to_string image)
  | Error (`Msg m) -> Error m
]}
    Scenes are also built in code ({!Scene.v}: settings, one list of
    objects, lights) and validated ({!Scene.validate}); a single pixel's
    colour, with samples, is {!Render.Pixel.color}.

    {1:flow The data flow}

{v
scene text --Scene_file.of_string--> Scene.valid --Render.image--> Image.t --Image.Ppm.to_string--> bytes
Scene.v ~objects ~lights --Scene.validate--^     \--Render.Pixel.color--> Color.t (one pixel)
v}
    An object is a shape ({!Shape.t}: {!Sphere}, {!Plane}, {!Triangle},
    {!Box}, {!Mesh}, {!Csg}) made of a {!Material.t}, one value that any
    number of objects may share; scene text may name a material once and
    use it by name. A {!Scene.t} is its settings, one list of objects in
    the order given (of equal roots, the earlier object is seen) and its
    lights; a {!Scene.valid} is a scene that passed validation, the only
    kind the renderers take, so an invalid scene never reaches them and no
    scene is validated twice. The types a user builds are abstract or
    private, made by their [v] constructors.

    {1:errors The error convention}

    Everything a user supplies (scene text, image bytes, sampling settings,
    a scene built in code) is checked, and failures are
    [Error (`Msg message)] in [(_, [> `Msg of string]) result]; scene-text
    messages start with [file:line:column] ({!Scene_file.located} gives
    them as numbers too), and a scene built in code names the failing
    object, [object 3 (sphere): ...]. [Invalid_argument] is raised only
    for programmer errors that a function documents (a region outside the
    canvas, a pixel outside the image), with a message that names the
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
      (7.7), mirror reflection (7.8): {!Light}, {!Material}; the
      document's algorithm transcribed literally, the executable
      specification the fast tracer is tested against, is
      {!Private.Literal}.
    - Section 8, rendering: {!Render}, {!Render.Pixel}.
    - Beyond the document's spheres (its chapter "Extending the
      Raytracer"): {!Plane}, {!Triangle} (watertight), {!Box}, {!Mesh}
      (from Wavefront OBJ files, {!Mesh.Obj}, or generated, {!Mesh.Gen}),
      one type for every object, {!Shape}; a {!Material} may carry a
      {!Pattern} (a checkerboard) and the optics of glass; constructive
      solid geometry of the closed shapes, {!Csg}.
    - Beyond the document: {!Render.Sampling} (antialiasing),
      {!Camera.Path} (animation), {!Render.Region} (tiles),
      {!Image.Diff}, {!Image.Ppm}.

    {1:system Beside this library}

    - [raytrace.unix] ([Raytrace_unix]): scene and image files, rendering
      in several processes, signals, the {!Limits} read from the
      environment, tiles and parts for farms.
    - [raytrace.view] ([Raytrace_view]): the window model and the
      coarse-first progressive renderer, for any front end.
    - [raytrace-png] ([Raytrace_png]): PNG files, through camlimages. *)

(** {1:modules Modules}

    Nineteen modules and {!Private}. The few that belong to another are
    inside it: the camera's path in {!Camera}, mesh files and generated
    meshes in {!Mesh}, sampling, regions, statistics and single pixels in
    {!Render}, PPM files and image differences in {!Image}. *)

(** {2:numbers Numbers and colours} *)

module Vec3 = Vec3
module Color = Color

(** {2:scene The scene: settings, objects, lights} *)

module Viewport = Viewport

module Camera : sig
  include module type of struct
    include Camera
  end

  module Path = Camera_path
  (** Animations: the camera of each frame, from keyframes. *)
end

module Light = Light
module Pattern = Pattern
module Material : sig
  include module type of struct
    include Material
  end

  module Texture = Texture_map
  (** Image textures on objects: the mappings, a material's texture. *)
end

module Sphere = Sphere
module Plane = Plane
module Triangle = Triangle
module Box = Box

module Mesh : sig
  include module type of struct
    include Mesh
  end

  module Obj = Obj_file
  (** Wavefront OBJ files, read into the arrays of {!Mesh.of_obj}. *)

  module Gen = Mesh_gen
  (** Generated meshes (a torus knot, a terrain). *)
end

module Csg = Csg

module Shape : sig
  include module type of struct
    include Shape
  end

  module Transform = Transform
  (** Scales, rotations and translations of objects ({!Shape.instance}). *)
end
module Scene = Scene
module Scene_file = Scene_file
module Limits = Limits

(** {2:render Rendering and images} *)

module Render : sig
  include module type of struct
    include Render
  end

  module Sampling = Sampling
  (** Rays per pixel: antialiasing, adaptive and subsampled. *)

  module Region = Region
  (** Rectangles of the canvas and the tiles that split it. *)

  module Stats = Stats
  (** What a render cost. *)

  module Pixel = Pixel
  (** One pixel at a time, with the renderer's own code and samples. *)
end

module Image : sig
  include module type of struct
    include Image
  end

  module Ppm = Ppm
  (** PPM files. *)

  module Diff = Image_diff
  (** Differences between two images. *)

  module Texture = Texture
  (** Decoded images looked up with bilinear filtering, for textures. *)
end

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
  module Spheres = Spheres
  module Literal = Literal
  module Scene_text = Scene_text
  module Float_text = Float_text
  module Canvas = Canvas
  module Shading = Shading
  module Bvh = Bvh
  module Kind = Kind
  module Kind_dispatch = Kind_dispatch
  module Torus = Torus
  module Shape_desc = Shape_desc
  module Primitives = Primitives
  module Cylinder = Cylinder
  module Disk = Disk
  module Cone = Cone
  module Prepared = Prepared
  module Trace = Trace
  module Scratch = Scratch
  module Ray_tree = Ray_tree
  module Float_scan = Float_scan
  module Sexp_scan = Sexp_scan
  module Sphere_scan = Sphere_scan
  module Antialias = Antialias
  module Render_work = Render_work
  module Render_region = Render_region
  module Sampling_rows = Sampling_rows
  module Obj_parts = Obj_parts
  module Exact_float = Exact_float
  module Literal_geometry = Literal_geometry
  module Sample_key = Sample_key
end
