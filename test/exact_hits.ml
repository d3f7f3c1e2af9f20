open Raytrace

type v = { x : Q.t; y : Q.t; z : Q.t }

let v (p : Vec3.t) = { x = Q.of_float p.x; y = Q.of_float p.y; z = Q.of_float p.z }
let sub a b = { x = Q.sub a.x b.x; y = Q.sub a.y b.y; z = Q.sub a.z b.z }
let dot a b = Q.(add (add (mul a.x b.x) (mul a.y b.y)) (mul a.z b.z))

let cross a b =
  { x = Q.(sub (mul a.y b.z) (mul a.z b.y)); y = Q.(sub (mul a.z b.x) (mul a.x b.z)); z = Q.(sub (mul a.x b.y) (mul a.y b.x)) }

let beyond t_min t = if Q.gt t t_min then Some t else None

(* The plane's equation <P - point, n> = 0 along the ray. *)
let plane (p : Plane.t) ~origin ~direction ~t_min =
  let n = v p.normal in
  let den = dot direction n in
  if Q.equal den Q.zero then None else beyond t_min (Q.div (dot (sub (v p.point) origin) n) den)

(* The point of the triangle's plane, inside when it lies on the inner
   side of every edge or on it. *)
let triangle a b c ~origin ~direction ~t_min =
  let n = cross (sub b a) (sub c a) in
  let den = dot direction n in
  if Q.equal den Q.zero then None
  else
    let t = Q.div (dot (sub a origin) n) den in
    let p = { x = Q.(add origin.x (mul t direction.x)); y = Q.(add origin.y (mul t direction.y)); z = Q.(add origin.z (mul t direction.z)) } in
    let inside u w = Q.sign (dot (cross (sub w u) (sub p u)) n) >= 0 in
    if Q.gt t t_min && inside a b && inside b c && inside c a then Some t else None

(* The intersection of the three slabs, [near, far], closed. *)
let box (b : Box.t) ~origin ~direction ~t_min =
  let lo = v b.min and hi = v b.max in
  let slab (near, far) (l, h, o, d) =
    if Q.equal d Q.zero then if Q.leq l o && Q.leq o h then (near, far) else (Q.inf, Q.minus_inf)
    else
      let t0 = Q.div (Q.sub l o) d and t1 = Q.div (Q.sub h o) d in
      (Q.max near (Q.min t0 t1), Q.min far (Q.max t0 t1))
  in
  let near, far =
    List.fold_left slab (Q.minus_inf, Q.inf)
      [ (lo.x, hi.x, origin.x, direction.x); (lo.y, hi.y, origin.y, direction.y); (lo.z, hi.z, origin.z, direction.z) ]
  in
  if Q.gt near far then None else match beyond t_min near with Some t -> Some t | None -> beyond t_min far

(* Exact arithmetic is slow: a line that misses, in floats, a box grown
   well beyond any rounding around a bounded object is not tried. *)
let may_meet (lo : Vec3.t) (hi : Vec3.t) =
  let m = 1e-6 *. (1. +. List.fold_left (fun m x -> Float.max m (Float.abs x)) 0. [ lo.x; lo.y; lo.z; hi.x; hi.y; hi.z ]) in
  fun (o : Vec3.t) (d : Vec3.t) ->
    let slab (near, far) (l, h, o, d) =
      let l = l -. m and h = h +. m in
      if d = 0. then if l <= o && o <= h then (near, far) else (infinity, neg_infinity)
      else
        let t0 = (l -. o) /. d and t1 = (h -. o) /. d in
        (Float.max near (Float.min t0 t1), Float.min far (Float.max t0 t1))
    in
    let near, far = List.fold_left slab (neg_infinity, infinity) [ (lo.x, hi.x, o.x, d.x); (lo.y, hi.y, o.y, d.y); (lo.z, hi.z, o.z, d.z) ] in
    near <= far +. (1e-9 *. (Float.abs near +. Float.abs far))

let bounded lo hi exact =
  let meets = may_meet lo hi in
  fun ~(origin : Vec3.t) ~(direction : Vec3.t) ~t_min ->
    if meets origin direction then exact ~origin:(v origin) ~direction:(v direction) ~t_min else None

let roots (s : Scene.t) =
  if Private.Spheres.length (Scene.spheres s) > 0 then invalid_arg "Exact_hits.roots: a sphere";
  let triangle_of (t : Triangle.t) =
    let corner f = Vec3.v (f t.v0.x (f t.v1.x t.v2.x)) (f t.v0.y (f t.v1.y t.v2.y)) (f t.v0.z (f t.v1.z t.v2.z)) in
    bounded (corner Float.min) (corner Float.max) (triangle (v t.v0) (v t.v1) (v t.v2))
  in
  Array.of_list
    (List.concat_map
       (function
         | Shape.Sphere _ -> invalid_arg "Exact_hits.roots: a sphere"
         | Shape.Plane p -> [ (fun ~origin ~direction -> plane p ~origin:(v origin) ~direction:(v direction)) ]
         | Triangle t -> [ triangle_of t ]
         | Box b -> [ bounded b.min b.max (box b) ]
         | Mesh m ->
             List.filter_map
               (fun k -> if Mesh.degenerate m k then None else Some (triangle_of (Mesh.triangle m k)))
               (List.init (Mesh.triangle_count m) Fun.id)
         | Csg _ -> invalid_arg "Exact_hits.roots: a CSG solid"
         | Primitive _ -> invalid_arg "Exact_hits.roots: a described kind has its own exact tests"
         | Instance _ -> invalid_arg "Exact_hits.roots: an instance")
       (Scene.shapes s))

(* Each object of [roots]' order: the mesh (its number among the shapes)
   and the triangle, for a mesh's triangles. *)
let facets (s : Scene.t) =
  Array.of_list
    (List.concat
       (List.mapi
          (fun i -> function
            | Shape.Mesh m ->
                List.filter_map
                  (fun k -> if Mesh.degenerate m k then None else Some (Some (i, m, k)))
                  (List.init (Mesh.triangle_count m) Fun.id)
            | _ -> [ None ])
          (Scene.shapes s)))

let neighbours s i j =
  let f = facets s in
  i >= 0 && j >= 0 && i < Array.length f && j < Array.length f
  &&
  match (f.(i), f.(j)) with
  | Some (mi, m, ki), Some (mj, _, kj) when mi = mj && Array.length m.Mesh.normals = 0 ->
      let a = Mesh.triangle m ki and b = Mesh.triangle m kj in
      let corners (t : Triangle.t) = [ t.v0; t.v1; t.v2 ] in
      let shared = List.filter (fun p -> List.exists (Vec3.equal p) (corners b)) (corners a) in
      let n = cross (sub (v a.v1) (v a.v0)) (sub (v a.v2) (v a.v0)) in
      List.length shared >= 2
      && List.for_all (fun p -> Q.equal (dot (sub (v p) (v a.v0)) n) Q.zero) (corners b)
  | _ -> false
