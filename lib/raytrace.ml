module Vec3 = Vec3
module Color = Color
module Viewport = Viewport

module Camera = struct
  include Camera
  module Path = Camera_path
end

module Light = Light
module Pattern = Pattern
module Material = struct
  include Material
  module Texture = Texture_map
end

module Sphere = Sphere
module Plane = Plane
module Triangle = Triangle
module Box = Box

module Mesh = struct
  include Mesh
  module Obj = Obj_file
  module Gen = Mesh_gen
end

module Csg = Csg

module Shape = struct
  include Shape
  module Transform = Transform
end
module Scene = Scene
module Scene_file = Scene_file
module Limits = Limits

module Render = struct
  include Render
  module Sampling = Sampling
  module Region = Region
  module Stats = Stats
  module Pixel = Pixel
end

module Image = struct
  include Image
  module Ppm = Ppm
  module Diff = Image_diff
  module Texture = Texture
end

let render_string ?limits ?file text =
  match Scene_file.of_string ?limits ?file text with
  | Error _ as e -> e
  | Ok scene -> ( match Render.image ?limits scene with Ok (img, _) -> Ok img | Error _ as e -> e)

let version = Version.v

module Private = struct
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
