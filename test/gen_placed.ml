(* Scenes placed where the kernel's boundaries are: objects on every side
   of every light, surfaces that touch or coincide, the camera inside
   solids and glass, pixel rays exactly through edges and vertices. The
   coordinates that decide a boundary are multiples of 1/4 (positions) or
   of k/W (pixel rays at depth k): sums and products of such numbers are
   exact in floats, so the boundary is really met, not merely nearly. *)
open Raytrace
open QCheck.Gen

let quarter lo hi = map (fun k -> Float.of_int k /. 4.) (int_range (4 * lo) (4 * hi))
let qvec lo hi = map3 Vec3.v (quarter lo hi) (quarter lo hi) (quarter lo hi)
let channel = oneof [ return 0.; return 255.; map Float.of_int (int_range 0 255) ]
let color = map3 Color.v channel channel channel

(* Glass, mirrors and matte as Gen_scene draws them; with [plain], none
   of glass and patterns (the spheres-only scenes keep the kernel's
   fastest loops, which take neither). *)
let material ~plain =
  let* m = Gen_scene.material in
  if plain then return (Material.update ~transparency:0. ~refractive_index:1. ~pattern:None m)
  else
    let* checker = frequencyl [ (3, false); (1, true) ] in
    if not checker then return m
    else
      let* size = oneof [ return 0.5; float_range 0.1 1.5 ] and* c = color in
      return (Material.update ~pattern:(Some (Pattern.checker ~size c)) m)

let glass =
  let* m = material ~plain:false in
  let m = Material.update ~reflective:(Float.min m.reflective 0.5) m in
  let* transparency = oneof [ return (1. -. m.reflective); float_range 0.1 (1. -. m.reflective) ] in
  let* refractive_index = oneof [ return 1.; return 1.5; float_range 0.5 2.5 ] in
  (* [r + (1 - r)] may round above 1. *)
  let transparency = if m.reflective +. transparency > 1. then Float.pred transparency else transparency in
  return (Material.update ~transparency:(Float.max transparency 0.) ~refractive_index m)

let sphere_of (m : Material.t) ~center ~radius =
  Helpers.sphere ~specular:m.specular ~reflective:m.reflective ~transparency:m.transparency
    ~refractive_index:m.refractive_index ~fresnel:m.fresnel ?pattern:m.pattern ~center ~radius m.color

(* {1 Meshes}

   Each mesh is named after its OBJ text (its positions are the file's:
   scale 1, no translation), so that a printed scene reads it back from
   the file that {!obj_files} prints beside it. *)

let obj_text positions triangles =
  let b = Buffer.create 256 in
  for v = 0 to (Array.length positions / 3) - 1 do
    Printf.bprintf b "v %s %s %s\n" (Float_text.to_string positions.(3 * v))
      (Float_text.to_string positions.((3 * v) + 1))
      (Float_text.to_string positions.((3 * v) + 2))
  done;
  for t = 0 to (Array.length triangles / 3) - 1 do
    Printf.bprintf b "f %d %d %d\n" (triangles.(3 * t) + 1) (triangles.((3 * t) + 1) + 1) (triangles.((3 * t) + 2) + 1)
  done;
  Buffer.contents b

let mesh m positions triangles =
  let source = "gen-" ^ String.sub (Digest.to_hex (Digest.string (obj_text positions triangles))) 0 8 ^ ".obj" in
  match
    Mesh.v ~source ~positions ~triangles ~normals:[||] ~triangle_normals:(Array.make (Array.length triangles) (-1)) m
  with
  | Ok mesh -> mesh
  | Error (`Msg e) -> invalid_arg ("Gen_placed.mesh: " ^ e)

let corners (ps : Vec3.t list) = Array.concat (List.map (fun (p : Vec3.t) -> [| p.x; p.y; p.z |]) ps)

(* Closed: an octahedron of half-diagonal [r] (its six vertices at
   [c +- r] on each axis), a tetrahedron, a cube with 12 triangles. *)
let octahedron m (c : Vec3.t) r =
  let at x y z = Vec3.v (c.x +. (r *. x)) (c.y +. (r *. y)) (c.z +. (r *. z)) in
  mesh m
    (corners [ at 1. 0. 0.; at (-1.) 0. 0.; at 0. 1. 0.; at 0. (-1.) 0.; at 0. 0. 1.; at 0. 0. (-1.) ])
    [| 0; 2; 4; 2; 1; 4; 1; 3; 4; 3; 0; 4; 2; 0; 5; 1; 2; 5; 3; 1; 5; 0; 3; 5 |]

let tetrahedron m (c : Vec3.t) r =
  let at x y z = Vec3.v (c.x +. (r *. x)) (c.y +. (r *. y)) (c.z +. (r *. z)) in
  mesh m
    (corners [ at 1. 1. 1.; at 1. (-1.) (-1.); at (-1.) 1. (-1.); at (-1.) (-1.) 1. ])
    [| 0; 1; 2; 0; 3; 1; 0; 2; 3; 1; 3; 2 |]

(* Corner [i] has x from bit 0, y from bit 1, z from bit 2. *)
let cube m (lo : Vec3.t) (hi : Vec3.t) =
  let at i = Vec3.v (if i land 1 = 0 then lo.x else hi.x) (if i land 2 = 0 then lo.y else hi.y) (if i land 4 = 0 then lo.z else hi.z) in
  mesh m
    (corners (List.init 8 at))
    [| 0; 4; 6; 0; 6; 2; 1; 3; 7; 1; 7; 5; 0; 1; 5; 0; 5; 4; 2; 6; 7; 2; 7; 3; 0; 2; 3; 0; 3; 1; 4; 5; 7; 4; 7; 6 |]

(* Open: two triangles of a square that share its diagonal. *)
let quad m (p : Vec3.t) (u : Vec3.t) (v : Vec3.t) =
  mesh m (corners [ p; Vec3.add p u; Vec3.add (Vec3.add p u) v; Vec3.add p v ]) [| 0; 1; 2; 0; 2; 3 |]

let rec solid_meshes = function
  | Csg.Mesh m -> [ m ]
  | Csg.Csg c -> solid_meshes c.a @ solid_meshes c.b
  | Csg.Transformed p -> solid_meshes p.solid
  | Csg.Sphere _ | Csg.Box _ | Csg.Primitive _ -> []

let obj_files (s : Scene.t) =
  let meshes =
    List.concat_map (function Shape.Mesh m -> [ m ] | Shape.Csg c -> solid_meshes (Csg.Csg c) | _ -> []) (Scene.shapes s)
  in
  String.concat ""
    (List.map
       (fun (m : Mesh.t) ->
         let lines = String.split_on_char '\n' (String.trim (obj_text m.positions m.triangles)) in
         Printf.sprintf "\n;; %s (each line after \"; \"):\n%s\n" m.source (String.concat "\n" (List.map (( ^ ) "; ") lines)))
       (List.sort_uniq (fun (a : Mesh.t) b -> String.compare a.source b.source) meshes))

let print s = Scene_file.to_string s ^ obj_files s

(* {1 Objects} *)

type obj = Ball of Sphere.t | Other of Shape.t

let box_around m (p : Vec3.t) (h : Vec3.t) = Box.v ~min:(Vec3.sub p h) ~max:(Vec3.add p h) m

let half_sizes r =
  let* a = float_range 0.5 1. and* b = float_range 0.5 1. and* c = float_range 0.5 1. in
  return (Vec3.v (r *. a) (r *. b) (r *. c))

let vec3 r = map3 Vec3.v (float_range (-.r) r) (float_range (-.r) r) (float_range (-.r) r)

(* A CSG operand around [p], of size about [r]. *)
let rec solid ~plain ~depth m (p : Vec3.t) r =
  let* m = oneof [ return m; material ~plain ] in
  let leaf =
    [
      (3, return (Csg.Sphere (sphere_of m ~center:p ~radius:r)));
      (3, map (fun h -> Csg.Box (box_around m p h)) (half_sizes r));
      (1, return (Csg.Mesh (octahedron m p r)));
      (1, return (Csg.Mesh (cube m (Vec3.sub p (Vec3.v r r r)) (Vec3.add p (Vec3.v r r r)))));
    ]
  in
  frequency (if depth > 0 then (2, map (fun c -> Csg.Csg c) (csg ~plain ~depth:(depth - 1) m p r)) :: leaf else leaf)

(* Two operands around [p]: overlapping, or touching exactly (boxes that
   share a face or a part of one, spheres tangent at [p], a box face
   tangent to a sphere, a box inside another sharing a face). *)
and csg ~plain ~depth m (p : Vec3.t) r =
  let* op = oneofl [ Csg.Union; Csg.Intersection; Csg.Difference ] in
  let* m2 = oneof [ return m; material ~plain ] in
  let* r = map (fun k -> Float.of_int k /. 8.) (int_range 2 (max 2 (truncate (8. *. r)))) in
  let* a, b =
    frequency
      [
        ( 3,
          let* off = vec3 r in
          pair (solid ~plain ~depth m p r) (solid ~plain ~depth m2 (Vec3.add p off) (r *. 0.8)) );
        ( 2,
          (* Boxes side by side along x, sharing the plane x = p.x: the
             same faces, or the second shifted by r / 2 in y. *)
          let* shift = oneofl [ 0.; r /. 2. ] in
          let lo = Vec3.v (p.x -. r) (p.y -. r) (p.z -. r) in
          return
            ( Csg.Box (Box.v ~min:lo ~max:(Vec3.v p.x (p.y +. r) (p.z +. r)) m),
              Csg.Box (Box.v ~min:(Vec3.v p.x (p.y -. r +. shift) (p.z -. r)) ~max:(Vec3.v (p.x +. r) (p.y +. r +. shift) (p.z +. r)) m2) ) );
        ( 1,
          return
            ( Csg.Sphere (sphere_of m ~center:(Vec3.v (p.x -. (r /. 2.)) p.y p.z) ~radius:(r /. 2.)),
              Csg.Sphere (sphere_of m2 ~center:(Vec3.v (p.x +. (r /. 2.)) p.y p.z) ~radius:(r /. 2.)) ) );
        ( 1,
          return
            ( Csg.Sphere (sphere_of m ~center:p ~radius:r),
              Csg.Box (Box.v ~min:(Vec3.v (p.x +. r) (p.y -. r) (p.z -. r)) ~max:(Vec3.v (p.x +. (2. *. r)) (p.y +. r) (p.z +. r)) m2) ) );
        ( 1,
          (* A box inside another, on its floor: a difference leaves a
             cavity open at the face they share. *)
          let lo = Vec3.sub p (Vec3.v r r r) in
          return
            ( Csg.Box (Box.v ~min:lo ~max:(Vec3.add p (Vec3.v r r r)) m),
              Csg.Box
                (Box.v
                   ~min:(Vec3.v (p.x -. (r /. 2.)) lo.y (p.z -. (r /. 2.)))
                   ~max:(Vec3.add p (Vec3.v (r /. 2.) (r /. 2.) (r /. 2.)))
                   m2) ) );
      ]
  in
  return (Csg.v op a b)

let nonzero (v : Vec3.t) = if Vec3.norm2 v = 0. then Vec3.oy else v

(* An object of a kind drawn from [kinds], around [p], of size about
   [r]; a plane through [p] faces [toward] (a light) or any way. *)
let object_at ~kinds ~plain ?(toward = Vec3.oy) (p : Vec3.t) r =
  let* m = material ~plain in
  let* kind = oneofl kinds in
  match kind with
  | `Sphere -> return (Ball (sphere_of m ~center:p ~radius:r))
  | `Plane ->
      let* normal = oneof [ return toward; map nonzero (qvec (-1) 1); return Vec3.oy ] in
      return (Other (Shape.Plane (Plane.v ~point:p ~normal m)))
  | `Triangle ->
      let* e1 = vec3 r and* e2 = vec3 r in
      let v0 = Vec3.sub p (Vec3.smul (1. /. 3.) (Vec3.add e1 e2)) in
      let t = Triangle.v v0 (Vec3.add v0 e1) (Vec3.add v0 e2) m in
      let t =
        match Triangle.validate t with
        | Ok t -> t
        | Error _ -> Triangle.v (Vec3.v (p.x -. r) p.y p.z) (Vec3.v (p.x +. r) p.y p.z) (Vec3.v p.x (p.y +. r) p.z) m
      in
      return (Other (Shape.Triangle t))
  | `Box -> map (fun h -> Other (Shape.Box (box_around m p h))) (half_sizes r)
  | `Mesh ->
      let* u = vec3 r and* v = vec3 r in
      let open_quad = quad m (Vec3.sub p (Vec3.smul 0.5 (Vec3.add u v))) u v in
      oneofl
        [
          Other (Shape.Mesh (octahedron m p r));
          Other (Shape.Mesh (tetrahedron m p r));
          Other (Shape.Mesh (cube m (Vec3.sub p (Vec3.v r r r)) (Vec3.add p (Vec3.v r r r))));
          Other (Shape.Mesh (if Vec3.norm2 (Vec3.cross u v) > 1e-6 then open_quad else octahedron m p r));
        ]
  | `Csg -> map (fun c -> Other (Shape.Csg c)) (csg ~plain ~depth:1 m p r)

(* {1 Lights and what is around them} *)

(* A light and one or two objects placed on one side of it, as seen from
   [receiver], a point of the floor: a point light's objects in front of
   it (between it and the receiver: a shadow), beyond it (on the line
   from the receiver past the light: no shadow) or around it (the light
   inside or on the object); a directional light's objects where it
   comes from (a shadow) or on the other side. *)
let placed_light ~kinds ~plain (receiver : Vec3.t) =
  let* intensity = oneof [ return 0.5; float_range 0.1 0.8 ] in
  let* point = bool in
  if point then
    let* at = map3 Vec3.v (quarter (-2) 2) (quarter 0 3) (quarter 1 6) in
    let d = Vec3.sub at receiver in
    let len = Vec3.norm d in
    let* p, size =
      oneof
        [
          (let* s = oneof [ return 0.5; float_range 0.2 0.8 ] in
           return (Vec3.add receiver (Vec3.smul s d), Float.max 0.05 (0.3 *. Float.min s (1. -. s) *. len)));
          (let* s = oneof [ return 2.; float_range 1.3 3. ] in
           return (Vec3.add receiver (Vec3.smul s d), Float.max 0.05 (Float.min 0.8 (0.3 *. (s -. 1.) *. len))));
          (let* off = vec3 0.1 and* size = float_range 0.3 0.8 in
           return (Vec3.add at off, size));
        ]
    in
    let* objects = list_size (int_range 1 2) (object_at ~kinds ~plain ~toward:d p size) in
    (* Or, for some places, a light of issue 27 there: a small panel
       around it, a ball of light on it, a spot aimed at the receiver.
       Chosen from the place, not drawn: the other scenes stay the ones
       the generator made before. *)
    let light =
      match abs (Float.to_int (at.x *. 4.) + (3 * Float.to_int (at.z *. 4.))) mod 6 with
      | 0 ->
          Light.area intensity ~corner:(Vec3.sub at (Vec3.v 0.25 0. 0.25)) ~edge1:(Vec3.v 0.5 0. 0.)
            ~edge2:(Vec3.v 0. 0.1 0.5) ~samples:(3, 2)
      | 1 -> Light.sphere intensity ~position:at ~radius:0.2 ~samples:5
      | 2 -> Light.spot intensity ~position:at ~direction:(Vec3.sub receiver at) ~angle:35. ~falloff:2.
      | _ -> Light.point intensity at
    in
    return (light, objects)
  else
    let* direction = oneof [ return Vec3.oy; return (Vec3.v 1. 4. 4.); map nonzero (qvec (-1) 1) ] in
    let* toward = bool and* s = float_range 1. 4. and* size = float_range 0.2 0.8 in
    let u = Vec3.unit direction in
    let p = if toward then Vec3.add receiver (Vec3.smul s u) else Vec3.sub receiver (Vec3.smul s u) in
    let* objects = list_size (int_range 1 2) (object_at ~kinds ~plain ~toward:direction p size) in
    return (Light.directional intensity direction, objects)

(* {1 Touching and coinciding} *)

(* Objects resting on the floor [y = -1] or on each other, exactly: a box
   on the floor, two boxes sharing a face, the same box twice in two
   materials, a sphere on the floor, two tangent spheres, a triangle in
   the floor's plane, a plane through a box's face, a cube mesh on a box,
   a CSG solid standing on the floor. *)
let touching ~kinds ~plain =
  let* m = material ~plain and* m2 = material ~plain in
  let* x = quarter (-2) 2 and* z = quarter 3 7 and* r = map (fun k -> Float.of_int k /. 4.) (int_range 1 4) in
  let bottom = -1. in
  let box = Box.v ~min:(Vec3.v (x -. r) bottom (z -. r)) ~max:(Vec3.v (x +. r) (bottom +. r) (z +. r)) in
  let choices =
    List.concat_map
      (function
        | `Box ->
            [
              [ Other (Shape.Box (box m)) ];
              [
                Other (Shape.Box (box m));
                Other (Shape.Box (Box.v ~min:(Vec3.v (x +. r) bottom (z -. r)) ~max:(Vec3.v (x +. (2. *. r)) (bottom +. (2. *. r)) (z +. r)) m2));
              ];
              [ Other (Shape.Box (box m)); Other (Shape.Box (box m2)) ];
            ]
        | `Sphere ->
            [
              [ Ball (sphere_of m ~center:(Vec3.v x (bottom +. r) z) ~radius:r) ];
              [
                Ball (sphere_of m ~center:(Vec3.v (x -. r) (bottom +. r) z) ~radius:r);
                Ball (sphere_of m2 ~center:(Vec3.v (x +. r) (bottom +. r) z) ~radius:r);
              ];
              [ Ball (sphere_of m ~center:(Vec3.v x (bottom +. r) z) ~radius:r); Ball (sphere_of m2 ~center:(Vec3.v x (bottom +. r) z) ~radius:r) ];
            ]
        | `Triangle ->
            [
              [ Other (Shape.Triangle (Triangle.v (Vec3.v (x -. r) bottom z) (Vec3.v (x +. r) bottom z) (Vec3.v x bottom (z -. r)) m)) ];
              [
                Other (Shape.Box (box m));
                Other
                  (Shape.Triangle
                     (Triangle.v
                        (Vec3.v (x -. r) (bottom +. r) (z -. r))
                        (Vec3.v (x +. r) (bottom +. r) (z -. r))
                        (Vec3.v x (bottom +. r) (z +. r))
                        m2));
              ];
            ]
        | `Plane -> [ [ Other (Shape.Box (box m)); Other (Shape.Plane (Plane.v ~point:(Vec3.v (x +. r) 0. 0.) ~normal:Vec3.ox m2)) ] ]
        | `Mesh ->
            [
              [
                Other (Shape.Box (box m));
                Other (Shape.Mesh (cube m2 (Vec3.v (x -. r) bottom (z -. r)) (Vec3.v (x +. r) (bottom +. r) (z +. r))));
              ];
            ]
        | `Csg -> [ [ Other (Shape.Csg (Csg.v Csg.Union (Csg.Box (box m)) (Csg.Box (box m2)))) ] ])
      kinds
  in
  let* csg =
    if List.mem `Csg kinds then map (fun c -> [ [ Other (Shape.Csg c) ] ]) (csg ~plain ~depth:1 m (Vec3.v x (bottom +. r) z) r)
    else return []
  in
  oneofl (choices @ csg)

(* {1 Grazing} *)

(* Objects whose edges and vertices lie exactly on the camera rays of a
   [w] x [h] canvas ([w] and [h] powers of 2) from [c]: the ray of pixel
   [(a, b)] is at [q a b k] when [t = k]. A triangle with an edge along a
   row of pixels, two triangles whose shared diagonal the rays meet, a box
   with a corner on a ray and edges along rows and columns, an octahedron
   with its vertices on rays, two boxes sharing a face in a CSG union or
   difference, a plane that holds a row or a column of rays. *)
let grazing ~kinds ~plain ~w ~h (c : Vec3.t) =
  let q a b k = Vec3.v (c.x +. (k *. (Float.of_int a /. Float.of_int w))) (c.y +. (k *. (Float.of_int b /. Float.of_int h))) (c.z +. k) in
  let* m = material ~plain and* m2 = material ~plain in
  let* a = int_range (-w / 2) ((w / 2) - 1) and* b = int_range (-h / 2) ((h / 2) - 1) in
  let* k = map Float.of_int (int_range 2 6) and* n = int_range 1 4 and* k2 = map Float.of_int (int_range 2 6) in
  let* a2 = int_range (-w / 2) (w / 2) and* b2 = int_range (-h / 2) (h / 2) in
  let* sx = bool and* sy = bool and* sz = bool and* depth = quarter 0 2 in
  let triangle v0 v1 v2 m = match Triangle.validate (Triangle.v v0 v1 v2 m) with Ok t -> [ Other (Shape.Triangle t) ] | Error _ -> [] in
  let corner = q a b k in
  let far = Vec3.add (q (a + n) (b + n) k) (Vec3.v 0. 0. (depth +. 0.25)) in
  let lo =
    Vec3.v
      (if sx then corner.x else (2. *. corner.x) -. far.x)
      (if sy then corner.y else (2. *. corner.y) -. far.y)
      (if sz then corner.z else corner.z -. depth -. 0.25)
  in
  let hi = Vec3.v (if sx then far.x else corner.x) (if sy then far.y else corner.y) (if sz then far.z else corner.z) in
  let slab = Box.v ~min:(q a b k) ~max:far in
  let beside = Box.v ~min:(Vec3.v far.x (q a b k).y (q a b k).z) ~max:(Vec3.add far (Vec3.v (far.x -. (q a b k).x) 0. 0.)) in
  let choices =
    List.concat_map
      (function
        | `Triangle ->
            [
              triangle (q a b k) (q (a + n) b k) (q a2 b2 k2) m;
              triangle (q a b k) (q (a + n) b k) (q (a + n) (b + n) k) m
              @ triangle (q a b k) (q (a + n) (b + n) k) (q a (b + n) k) m2;
              (* Edge-on: in the plane of the rays of row [b]. *)
              triangle (q a b k) (q (a + n) b k) (q a2 b k2) m;
            ]
        | `Box -> [ [ Other (Shape.Box (Box.v ~min:lo ~max:hi m)) ] ]
        | `Mesh ->
            [
              [ Other (Shape.Mesh (octahedron m (q a b k) (k *. Float.of_int n /. Float.of_int w))) ];
              [ Other (Shape.Mesh (cube m lo hi)) ];
            ]
        | `Csg ->
            [
              [ Other (Shape.Csg (Csg.v Csg.Union (Csg.Box (slab m)) (Csg.Box (beside m2)))) ];
              [ Other (Shape.Csg (Csg.v Csg.Difference (Csg.Box (Box.v ~min:lo ~max:hi m)) (Csg.Box (slab m2)))) ];
            ]
        | `Plane ->
            [
              [ Other (Shape.Plane (Plane.v ~point:c ~normal:Vec3.oy m)) ];
              [ Other (Shape.Plane (Plane.v ~point:c ~normal:Vec3.ox m)) ];
              [ Other (Shape.Plane (Plane.v ~point:(q a b k) ~normal:(Vec3.v 0. 1. (-.Float.of_int b /. Float.of_int h)) m)) ];
            ]
        | `Sphere -> [])
      kinds
  in
  match List.filter (( <> ) []) choices with [] -> return [] | l -> oneofl l

(* {1 Scenes} *)

(* An object around the camera at [c], opaque or glass: seen from inside
   (when larger than the viewport's distance), or only its shadows and
   media. *)
let around_camera ~kinds ~plain (c : Vec3.t) =
  let* m = if plain then material ~plain else oneof [ material ~plain; glass ] in
  let* off = vec3 0.2 and* r = oneof [ return 2.; float_range 0.5 3. ] in
  let p = Vec3.add c off in
  (* The camera in the first of two boxes that share the face [z = c.z +
     k], which every camera ray crosses at [t = k]: joined by a union,
     the rays go on through it; the second box as wide, or shifted up. *)
  let touching_boxes =
    let* op = oneofl [ Csg.Union; Csg.Union; Csg.Difference; Csg.Intersection ] in
    let* m2 = oneof [ return m; material ~plain ] in
    let* k = oneofl [ 1.5; 2.; 3. ] and* shift = oneofl [ 0.; 0.; 1. ] in
    let a = Box.v ~min:(Vec3.sub c (Vec3.v 2. 2. 1.)) ~max:(Vec3.v (c.x +. 2.) (c.y +. 2.) (c.z +. k)) m in
    let b = Box.v ~min:(Vec3.v (c.x -. 2.) (c.y -. 2. +. shift) (c.z +. k)) ~max:(Vec3.v (c.x +. 2.) (c.y +. 2. +. shift) (c.z +. k +. 2.)) m2 in
    return (Other (Shape.Csg (Csg.v op (Csg.Box a) (Csg.Box b))))
  in
  let choices =
    List.concat_map
      (function
        | `Sphere -> [ return (Ball (sphere_of m ~center:p ~radius:r)) ]
        | `Box -> [ map (fun h -> Other (Shape.Box (box_around m p h))) (half_sizes r) ]
        | `Mesh -> [ return (Other (Shape.Mesh (cube m (Vec3.sub p (Vec3.v r r r)) (Vec3.add p (Vec3.v r r r))))) ]
        | `Csg -> [ map (fun c -> Other (Shape.Csg c)) (csg ~plain ~depth:1 m p r); touching_boxes ]
        | `Plane | `Triangle -> [])
      kinds
  in
  oneof choices

let floor ~kinds ~plain =
  let* m = material ~plain in
  oneofl
    ((if List.mem `Plane kinds then [ Other (Shape.Plane (Plane.v ~point:(Vec3.v 0. (-1.) 0.) ~normal:Vec3.oy m)) ] else [])
    @ (if List.mem `Box kinds then [ Other (Shape.Box (Box.v ~min:(Vec3.v (-8.) (-3.) (-2.)) ~max:(Vec3.v 8. (-1.) 20.) m)) ] else [])
    @ if List.mem `Sphere kinds then [ Ball (sphere_of m ~center:(Vec3.v 0. (-1001.) 0.) ~radius:1000.) ] else [])

(* With [grid], canvases of 8 or 16 pixels a side only, on which every
   grazing object's boundary is exact. *)
let scene ?(grid = false) ~kinds ~plain () =
  let* plain = if plain then return true else bool in
  let* w, h = frequencyl [ (3, (8, 8)); (3, (16, 16)); (1, (8, 16)); (1, (16, 8)) ] in
  let* w, h = if grid then return (w, h) else frequency [ (4, return (w, h)); (1, pair (int_range 3 12) (int_range 3 12)) ] in
  let* c = oneof [ return Vec3.zero; map3 Vec3.v (quarter (-1) 1) (quarter (-1) 1) (quarter (-1) 1) ] in
  let* receiver = map3 Vec3.v (quarter (-1) 1) (return (-1.)) (quarter 3 6) in
  let* floor = frequency [ (5, map Option.some (floor ~kinds ~plain)); (1, return None) ] in
  let* placed = list_size (int_range 1 3) (placed_light ~kinds ~plain receiver) in
  let* ambient = frequency [ (4, map (fun i -> [ Light.ambient i ]) (float_range 0.05 0.3)); (1, return []) ] in
  let* touching = frequency [ (2, touching ~kinds ~plain); (1, return []) ] in
  (* On other canvases the grazing objects' coordinates are rounded: their
     rays pass within an ulp of an edge, where a float test and the exact
     answer may differ (the kernel's stated accuracy), not exactly on it. *)
  let exact = List.mem w [ 8; 16 ] && List.mem h [ 8; 16 ] in
  let* grazing = if exact then frequency [ (2, grazing ~kinds ~plain ~w ~h c); (1, return []) ] else return [] in
  let* inside = frequency [ (1, map Option.some (around_camera ~kinds ~plain c)); (3, return None) ] in
  let* crowd =
    frequency
      [
        (2, return []);
        ( 1,
          list_size (int_range 1 10)
            (let* p = map3 Vec3.v (float_range (-3.) 3.) (float_range (-1.) 3.) (float_range 2. 9.) in
             let* r = float_range 0.1 0.6 in
             object_at ~kinds ~plain p r) );
      ]
  in
  let* depth = int_range 0 3 in
  let* epsilon = oneof [ return 0.001; return Scene.document_epsilon; float_range 0. 0.01 ] in
  let* background = color in
  let objects = Option.to_list floor @ List.concat_map snd placed @ touching @ grazing @ Option.to_list inside @ crowd in
  let* objects = shuffle_l objects in
  let spheres = List.filter_map (function Ball s -> Some s | Other _ -> None) objects in
  let shapes = List.filter_map (function Other s -> Some s | Ball _ -> None) objects in
  let* lights = shuffle_l (ambient @ List.map fst placed) in
  return
    (Helpers.scene ~width:w ~height:h ~camera:(Camera.v c) ~depth ~epsilon ~background ~spheres ~shapes ~lights ())

let all_kinds = [ `Sphere; `Plane; `Triangle; `Box; `Mesh; `Csg ]
let gen = scene ~kinds:all_kinds ~plain:false ()
let spheres = scene ~kinds:[ `Sphere ] ~plain:true ()
let flat = scene ~grid:true ~kinds:[ `Plane; `Triangle; `Box; `Mesh ] ~plain:true ()
let arbitrary = QCheck.make ~print ~shrink:Gen_scene.shrink gen
let arbitrary_spheres = QCheck.make ~print ~shrink:Gen_scene.shrink spheres
let arbitrary_flat = QCheck.make ~print ~shrink:Gen_scene.shrink flat
