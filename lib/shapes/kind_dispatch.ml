(* Spheres, triangles and CSG solids have their own paths in the kernel
   (the traversal's sphere and triangle tests, the CSG table): asked here,
   they are the caller's error. *)
let own_path k = invalid_arg ("Kind_dispatch: a " ^ Kind.to_string k ^ " has its own path in the kernel")

(* Not inlined: the traversal's, the surface's and the CSG table's
   matches call these for the described kinds alone, and a call keeps their
   arm small, so that the callers stay as the compiler inlined them before
   a described kind existed (docs/performance.md, "Described kinds cost
   the others nothing"). *)
let[@inline never] roots k (s : Scratch.t) g o =
  match (k : Kind.t) with
  | Plane -> Plane.roots s g o
  | Box -> Box.roots s g o
  | Cylinder -> Cylinder.roots s g o
  | Disk -> Disk.roots s g o
  | Cone -> Cone.roots s g o
  | Torus -> Torus.roots s g o
  | Sphere | Triangle | Smooth_triangle | Csg | Instance -> own_path k

let[@inline never] normal k (s : Scratch.t) g o =
  match (k : Kind.t) with
  | Plane -> Plane.normal s g o
  | Box -> Box.hit_normal s g o
  | Cylinder -> Cylinder.normal s g o
  | Disk -> Disk.normal s g o
  | Cone -> Cone.normal s g o
  | Torus -> Torus.normal s g o
  | Sphere | Triangle | Smooth_triangle | Csg | Instance -> own_path k
