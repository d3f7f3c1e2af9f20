(* Spheres, triangles and CSG solids have their own paths in the kernel
   (the traversal's sphere and triangle tests, the CSG table): asked here,
   they are the caller's error. *)
let own_path k = invalid_arg ("Kind_dispatch: a " ^ Kind.to_string k ^ " has its own path in the kernel")

(* Not inlined: a described kind's routine is long anyway, and the
   callers' catch-alls (the traversal's, the surfaces', the CSG table's)
   stay small enough for OCaml to inline them into the loops. *)
let[@inline never] roots k (s : Scratch.t) g o =
  match (k : Kind.t) with
  | Plane -> Plane.roots s g o
  | Box -> Box.roots s g o
  | Torus -> Torus.roots s g o
  | Sphere | Triangle | Smooth_triangle | Csg -> own_path k

let[@inline never] normal k (s : Scratch.t) g o =
  match (k : Kind.t) with
  | Plane -> Plane.normal s g o
  | Box -> Box.hit_normal s g o
  | Torus -> Torus.normal s g o
  | Sphere | Triangle | Smooth_triangle | Csg -> own_path k
