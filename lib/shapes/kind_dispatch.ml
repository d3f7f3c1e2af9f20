(* Spheres, triangles and CSG solids have their own paths in the kernel
   (the traversal's sphere and triangle tests, the CSG table): asked here,
   they are the caller's error. *)
let own_path k = invalid_arg ("Kind_dispatch: a " ^ Kind.to_string k ^ " has its own path in the kernel")

let[@inline] roots k (s : Scratch.t) g o =
  match (k : Kind.t) with
  | Plane -> Plane.roots s g o
  | Box -> Box.roots s g o
  | Sphere | Triangle | Smooth_triangle | Csg | Instance -> own_path k

let[@inline] normal k (s : Scratch.t) g o =
  match (k : Kind.t) with
  | Plane -> Plane.normal s g o
  | Box -> Box.hit_normal s g o
  | Sphere | Triangle | Smooth_triangle | Csg | Instance -> own_path k
