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

let render_string ?limits ?file text =
  match Scene_file.of_string ?limits ?file text with
  | Error _ as e -> e
  | Ok scene -> ( match Render.image ?limits scene with Ok (img, _) -> Ok img | Error _ as e -> e)

let version = Version.v

module Private = struct
  module Float_text = Float_text
  module Canvas = Canvas
  module Shading = Shading
  module Bvh = Bvh
  module Kind = Kind
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
