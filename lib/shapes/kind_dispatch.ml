(* Spheres, triangles and CSG solids have their own paths in the kernel
   (the traversal's sphere and triangle tests, the CSG table): asked here,
   they are the caller's error. *)
let own_path k = invalid_arg ("Kind_dispatch: a " ^ Kind.to_string k ^ " has its own path in the kernel")

(* Not inlined: the traversal's and surfaces' own matches send here only
   the kinds they have no arm for (the described ones), and this match
   inlined in their catch-all arm, live once a described kind exists,
   grew the traversal's shape test past the compiler's inlining
   threshold (-inline 200): every box and plane test of every scene then
   paid a call, where a described kind pays one here. *)
let[@inline never] roots k (s : Scratch.t) g o =
  match (k : Kind.t) with
  | Plane -> Plane.roots s g o
  | Box -> Box.roots s g o
  | Cone -> Cone.roots s g o
  | Sphere | Triangle | Smooth_triangle | Csg -> own_path k

let[@inline never] normal k (s : Scratch.t) g o =
  match (k : Kind.t) with
  | Plane -> Plane.normal s g o
  | Box -> Box.hit_normal s g o
  | Cone -> Cone.normal s g o
  | Sphere | Triangle | Smooth_triangle | Csg -> own_path k
