(* In this order, a [match] of the kernel that sets spheres, triangles and
   the other shapes apart compiles to two comparisons, not a jump table. *)
type t = Sphere | Triangle | Smooth_triangle | Plane | Box | Csg | Cylinder | Disk | Cone | Torus | Instance

let all = [ Sphere; Triangle; Smooth_triangle; Plane; Box; Csg; Cylinder; Disk; Cone; Torus; Instance ]

(* Each kind's facts in one match: its name, whether it is bounded (in the
   hierarchy), closed (a CSG operand, a medium) and the floats of geometry
   its module stores. A new kind is one line here, and the compiler names
   it in the kernel's dispatch ([Kind_dispatch]). *)
let facts = function
  | Sphere -> ("sphere", true, true, 4)
  | Triangle -> ("triangle", true, false, 9)
  | Smooth_triangle -> ("smooth triangle", true, false, 9)
  | Plane -> ("plane", false, false, 9)
  | Box -> ("box", true, true, 6)
  | Csg -> ("csg", true, true, 1)
  | Cylinder -> ("cylinder", true, true, 7)
  | Disk -> ("disk", true, false, 7)
  | Cone -> ("cone", true, true, 9)
  | Torus -> ("torus", true, true, 8)
  | Instance -> ("instance", true, true, 1)

let to_string k =
  let name, _, _, _ = facts k in
  name

let bounded k =
  let _, b, _, _ = facts k in
  b

let closed k =
  let _, _, c, _ = facts k in
  c

let floats k =
  let _, _, _, n = facts k in
  n

(* How many intervals a line meets a closed kind's solid in, at most: a
   CSG leaf's room in the work arrays. *)
let spans = function Torus -> 2 | Sphere | Triangle | Smooth_triangle | Plane | Box | Csg | Cylinder | Disk | Cone | Instance -> 1

let stride = List.fold_left (fun m k -> max m (floats k)) 0 all
(* Every other kind, a new one too, is not a triangle. *)
let[@inline] is_triangle = function Triangle | Smooth_triangle -> true | _ -> false
