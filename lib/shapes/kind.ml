(* In this order, a [match] of the kernel that sets spheres, triangles and
   the other shapes apart compiles to two comparisons, not a jump table. *)
type t = Sphere | Triangle | Smooth_triangle | Plane | Box | Csg

let all = [ Sphere; Triangle; Smooth_triangle; Plane; Box; Csg ]

let to_string = function
  | Sphere -> "sphere"
  | Plane -> "plane"
  | Triangle -> "triangle"
  | Smooth_triangle -> "smooth triangle"
  | Box -> "box"
  | Csg -> "csg"

(* Each kind's facts in one match: a new kind is one line here, and the
   compiler names it in every other match of the kernel. *)
let bounded = function Plane -> false | Sphere | Triangle | Smooth_triangle | Box | Csg -> true
let closed = function Sphere | Box | Csg -> true | Plane | Triangle | Smooth_triangle -> false

let floats = function
  | Sphere -> 4
  | Plane -> 9
  | Triangle | Smooth_triangle -> 9
  | Box -> 6
  | Csg -> 1

let stride = List.fold_left (fun m k -> max m (floats k)) 0 all
let[@inline] is_triangle = function Triangle | Smooth_triangle -> true | Sphere | Plane | Box | Csg -> false
