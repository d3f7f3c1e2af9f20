(* What the public interfaces (and the rules the kernel's comments state)
   promise at their boundaries, one test per promise that no other suite
   asserted: the tracer's tangent rays, a plane's parallel ray, a box's
   outward normals and the rays that touch its faces, edges and corners
   exactly, a triangle's edges, vertices and plane, the bounds the
   hierarchy is built from, a mesh's and a box's validation, shadows that
   end at a point light and are the same with the skips on and off, and
   CSG solids' touching, coincident and tied surfaces. Most were found by
   the mutation test of docs/testing.md ("Mutants"): each catches a
   mutant no other suite caught. The cases are exact in floats (small
   integers and halves), so that each expected value is the promise
   itself, with no rounding to allow for. *)
open Raytrace

let white = Material.v Color.white
let infinite = Alcotest.(pair (float 0.) (float 0.))
let roots shape origin direction = Shape.roots shape ~origin ~direction

(* [Plane.intersect] and [Shape.roots] of a plane, which must agree. *)
let plane_root p origin direction =
  let t = Plane.intersect p ~origin ~direction in
  let near, far = roots (Shape.Plane p) origin direction in
  if not (Float.equal near t && Float.equal far t) then
    Alcotest.failf "Plane.intersect %h, Shape.roots (%h, %h)" t near far;
  t

(* The unit cube [0, 1]^3, and the box [1, 3] x [2, 5] x [-1, 0]. *)
let cube = Box.v ~min:Vec3.zero ~max:(Vec3.v 1. 1. 1.) white
let slab = Box.v ~min:(Vec3.v 1. 2. (-1.)) ~max:(Vec3.v 3. 5. 0.) white
let box_normal b p = Shape.normal (Shape.Box b) p
let cone c = Shape.Primitive (Private.Shape_desc.Primitive (Private.Cone.desc, c))
let v = Vec3.v

(* The triangle (0, 0, 0), (1, 0, 0), (0, 1, 0) in the plane z = 0. *)
let tri = Triangle.v Vec3.zero Vec3.ox Vec3.oy white

(* Exact containment of [lo, hi] in the cube [(c, h)], in rationals. *)
let cube_holds (c, h) (lo : Vec3.t) (hi : Vec3.t) =
  let q = Q.of_float in
  let inside x lo hi = Q.(leq (sub (q x) (q h)) (q lo) && geq (add (q x) (q h)) (q hi)) in
  inside c.Vec3.x lo.x hi.x && inside c.y lo.y hi.y && inside c.z lo.z hi.z

let tests =
  [
    Alcotest.test_case "a ray tangent to a sphere: the tracer's own test gives the double root, in both modes" `Quick
      (fun () ->
        (* Sphere.roots promises a double root for a tangent ray; the
           tracer's inlined copy (Trace.roots runs it) must agree. Exact in
           floats: the line's distance to the center is the radius, and the
           textbook discriminant is 0. *)
        List.iter
          (fun (center, radius, origin, direction, t) ->
            let sphere = Helpers.sphere ~center ~radius Color.white in
            Alcotest.check infinite "Sphere.roots" (t, t) (Sphere.roots sphere ~origin ~direction);
            List.iter
              (fun epsilon ->
                let tr = Trace.create (Helpers.prepare (Helpers.scene ?epsilon ~spheres:[ sphere ] ~lights:[] ())) in
                Alcotest.check infinite (Printf.sprintf "Trace.roots, epsilon %b" (epsilon <> None)) (t, t) (Trace.roots tr 0 origin direction))
              [ None; Some 0.001 ])
          [ (v 0. 0. 5., 1., v 1. 0. 0., v 0. 0. 1., 5.); (Vec3.zero, 2., v 2. (-3.) 0., v 0. 1. 0., 3.);
            (v 0. 0. 5., 1., v 0. (-1.) 0., v 0. 0. 0.5, 10.) ]);
    Alcotest.test_case "a ray parallel to a plane: Plane.intersect is infinity, never -infinity or nan" `Quick (fun () ->
        (* <D, N> = 0 exactly: above, below and in the plane y = 0, with
           -0. components; and a tilted plane whose unit normal (1, 1, 0) /
           sqrt 2 has two equal coordinates, so that <(1, -1, 0), N> is 0. *)
        let floor = Plane.v ~point:Vec3.zero ~normal:(v 0. 2. 0.) white in
        List.iter
          (fun (what, o, d) -> Alcotest.(check (float 0.)) what infinity (plane_root floor o d))
          [ ("above", v 0. 1. 0., v 1. 0. 0.); ("below", v 3. (-2.) 1., v 0. 0. (-1.)); ("in the plane", v 1. 0. 1., v 1. 0. 1.);
            ("-0. components", v 0. 1. 0., v (-0.) (-0.) 1.) ];
        let tilted = Plane.v ~point:(v 1. 0. 0.) ~normal:(v 1. 1. 0.) white in
        Alcotest.(check (float 0.)) "tilted" infinity (plane_root tilted (v 5. 5. 5.) (v 1. (-1.) 0.));
        Alcotest.check infinite "Shape.roots: (infinity, infinity)" (infinity, infinity) (roots (Shape.Plane floor) (v 0. 1. 0.) (v 1. 0. 0.)));
    Alcotest.test_case "a plane's root is <P0 - O, N> / <D, N>, behind the origin too" `Quick (fun () ->
        (* The plane y = 0 from (0, 5, 0): t = -5 / -2 = 2.5 down, -5 / 1 = -5 up. *)
        let floor = Plane.v ~point:(v 7. 0. (-3.)) ~normal:(v 0. 4. 0.) white in
        Alcotest.(check (float 0.)) "toward it" 2.5 (plane_root floor (v 0. 5. 0.) (v 1. (-2.) 0.));
        Alcotest.(check (float 0.)) "away from it: negative" (-5.) (plane_root floor (v 0. 5. 0.) (v 0. 1. 0.)));
    Alcotest.test_case "a plane's normal is its unit normal on the side it was given with, from either side" `Quick
      (fun () ->
        let p = Plane.v ~point:Vec3.zero ~normal:(v 0. (-3.) 0.) white in
        Alcotest.check Helpers.vec3 "below" (v 0. (-1.) 0.) (Shape.normal (Shape.Plane p) (v 2. 0. 1.));
        let p = Plane.v ~point:Vec3.zero ~normal:(v 0. 0. 0.5) white in
        Alcotest.check Helpers.vec3 "above" (v 0. 0. 1.) (Shape.normal (Shape.Plane p) (v 2. 1. 0.)));
    Alcotest.test_case "a box's normal is the outward unit normal of the nearest face, at points outside and inside"
      `Quick (fun () ->
        (* The slab [1, 3] x [2, 5] x [-1, 0]: each face's center, a point
           just inside it and one just outside it. *)
        List.iter
          (fun (p, n) ->
            List.iter
              (fun k ->
                let q = Vec3.add p (Vec3.smul k n) in
                Alcotest.check Helpers.vec3 (Format.asprintf "at %a" Vec3.pp q) n (box_normal slab q))
              [ 0.; -0.25; 0.25 ])
          [ (v 1. 3.5 (-0.5), v (-1.) 0. 0.); (v 3. 3.5 (-0.5), v 1. 0. 0.); (v 2. 2. (-0.5), v 0. (-1.) 0.);
            (v 2. 5. (-0.5), v 0. 1. 0.); (v 2. 3.5 (-1.), v 0. 0. (-1.)); (v 2. 3.5 0., v 0. 0. 1.) ];
        (* From inside, the ray meets the far wall; the normal there still
           points out, along the ray. *)
        let near, far = roots (Shape.Box slab) (v 2. 3.5 (-0.5)) (v 0. 0. 2.) in
        Alcotest.check infinite "from inside: one root behind, one ahead" (-0.25, 0.25) (near, far);
        Alcotest.check Helpers.vec3 "the far wall's normal, along the ray" (v 0. 0. 1.) (box_normal slab (v 2. 3.5 0.)));
    Alcotest.test_case
      "at a box's edges and corners, and inside where faces are equally near, the first of the faces -x, +x, -y, +y, \
       -z, +z gives the normal"
      `Quick (fun () ->
        List.iter
          (fun (p, n) -> Alcotest.check Helpers.vec3 (Format.asprintf "at %a" Vec3.pp p) n (box_normal cube p))
          [ (v 1. 1. 1., v 1. 0. 0.); (v 0. 0. 0., v (-1.) 0. 0.); (v 0. 1. 1., v (-1.) 0. 0.); (v 0.5 1. 1., v 0. 1. 0.);
            (v 0.5 0. 1., v 0. (-1.) 0.); (v 0.5 1. 0., v 0. 1. 0.); (v 1. 0.5 0., v 1. 0. 0.); (v 0.5 0.5 1., v 0. 0. 1.);
            (* Inside, as near to two opposite faces as to any: the first. *)
            (v 0.5 0.5 0.5, v (-1.) 0. 0.); (v 0.25 0.5 0.5, v (-1.) 0. 0.); (v 0.5 0.5 0.75, v 0. 0. 1.); (v 0.75 0.5 0.5, v 1. 0. 0.) ]);
    Alcotest.test_case "a ray along a box's face, edge or axis: that axis bounds nothing when the origin is between its \
                        planes, planes included; beside them it misses"
      `Quick (fun () ->
        (* Along x, on the face y = 1 of the unit cube, on its edge
           y = 0, z = 0, and through the middle: it enters at x = 0, t = 1,
           leaves at x = 1, t = 2. A hair beside the face: a miss. *)
        List.iter
          (fun (what, o) -> Alcotest.check infinite what (1., 2.) (roots (Shape.Box cube) o (v 1. 0. 0.)))
          [ ("on the face y = 1", v (-1.) 1. 0.5); ("on the edge y = 0, z = 0", v (-1.) 0. 0.); ("through the middle", v (-1.) 0.5 0.5);
            ("on the edge y = 1, z = 1", v (-1.) 1. 1.) ];
        List.iter
          (fun (what, o) -> Alcotest.check infinite what (infinity, infinity) (roots (Shape.Box cube) o (v 1. 0. 0.)))
          [ ("above the face y = 1", v (-1.) (Float.succ 1.) 0.5); ("below the face z = 0, on y = -0.", v (-1.) (-0.) (Float.pred 0.)) ];
        Alcotest.check infinite "Box.intersect of a miss" (infinity, infinity) (Box.intersect cube ~origin:(v 2. 2. 2.) ~direction:(v 1. 0. 0.)));
    Alcotest.test_case "a ray that touches only a box's edge, or only a corner, meets it there once: near = far" `Quick
      (fun () ->
        (* Along the line x - y = 1 in the plane z = 0.5, from (0, -1):
           the x slab is t in [0, 1], the y slab [1, 2]: they share t = 1,
           the point (1, 0, 0.5) of the edge x = 1, y = 0. Through the
           corner (1, 1, 1) from (0, 0, 2) along (1, 1, -1): slabs [0, 1],
           [0, 1], [1, 2]. All exact in floats: the box is closed, the
           exact line meets it, and so must the test. *)
        Alcotest.check infinite "edge" (1., 1.) (roots (Shape.Box cube) (v 0. (-1.) 0.5) (v 1. 1. 0.));
        Alcotest.check infinite "corner" (1., 1.) (roots (Shape.Box cube) (v 0. 0. 2.) (v 1. 1. (-1.)));
        (* The parallel line half a unit away misses. *)
        Alcotest.check infinite "beside the edge" (infinity, infinity) (roots (Shape.Box cube) (v 0. (-1.5) 0.5) (v 1. 1. 0.)));
    Alcotest.test_case "a triangle's edges and vertices are part of it: rays exactly through them hit" `Quick (fun () ->
        List.iter
          (fun (what, x, y) ->
            List.iter
              (fun dz ->
                let origin = v x y (-.dz) in
                Alcotest.(check (float 0.)) (Printf.sprintf "%s, from z = %g" what (-.dz)) 1.
                  (Triangle.intersect tri ~origin ~direction:(v 0. 0. dz)))
              [ 1.; -1. ])
          [ ("vertex v0", 0., 0.); ("vertex v1", 1., 0.); ("vertex v2", 0., 1.); ("edge v0 v1", 0.5, 0.); ("edge v1 v2", 0.5, 0.5);
            ("edge v2 v0", 0., 0.25); ("inside", 0.25, 0.25) ];
        Alcotest.(check (float 0.)) "outside, beside the long edge" infinity
          (Triangle.intersect tri ~origin:(v 0.5 (Float.succ 0.5) (-1.)) ~direction:(v 0. 0. 1.)));
    Alcotest.test_case "a ray in a triangle's plane misses it, even through its inside" `Quick (fun () ->
        List.iter
          (fun (o, d) ->
            Alcotest.(check (float 0.)) (Format.asprintf "from %a" Vec3.pp o) infinity (Triangle.intersect tri ~origin:o ~direction:d);
            Alcotest.check infinite "Shape.roots" (infinity, infinity) (roots (Shape.Triangle tri) o d))
          [ (v (-1.) 0.25 0., v 1. 0. 0.); (v 0.25 0.25 0., v 0. 1. 0.); (v (-1.) (-1.) 0., v 1. 1. 0.) ]);
    Alcotest.test_case "a triangle's normal is (v1 - v0) x (v2 - v0), unit: the order of the vertices picks the side"
      `Quick (fun () ->
        let n t = Shape.normal (Shape.Triangle t) (v 0.25 0.25 0.) in
        Alcotest.check Helpers.vec3 "counter-clockwise seen from +z" (v 0. 0. 1.) (n tri);
        Alcotest.check Helpers.vec3 "two vertices swapped" (v 0. 0. (-1.)) (n (Triangle.v Vec3.zero Vec3.oy Vec3.ox white));
        Alcotest.check Helpers.vec3 "large: still unit" (v 0. 0. 1.) (n (Triangle.v Vec3.zero (v 1e6 0. 0.) (v 0. 1e6 0.) white)));
    Alcotest.test_case "a shape's bounding cube holds it, exactly (rationals), for boxes, triangles and CSG solids" `Quick
      (fun () ->
        (* Corners that are not sums of halves: the center and half-side
           are rounded, and the cube must still hold every corner. *)
        let rand = Random.State.make [| 30 |] in
        let coord () = (Random.State.float rand 2. -. 1.) *. (10. ** float (Random.State.int rand 7 - 3)) in
        (* Half the shapes small and far: 1e-6 across, 1e6 from the origin,
           where an ulp of the center is 1e12 ulps of the half side. *)
        let near k = Vec3.add k (v (1e-6 *. coord ()) (1e-6 *. coord ()) (1e-6 *. coord ())) in
        for i = 1 to 2000 do
          let a = v (coord ()) (coord ()) (coord ()) and b = v (coord ()) (coord ()) (coord ()) and c = v (coord ()) (coord ()) (coord ()) in
          let a, b, c = if i mod 2 = 0 then (a, b, c) else let k = Vec3.smul 1e6 (v 1. (-0.7) 0.3) in (near k, near k, near k) in
          let lo = v (Float.min a.x b.x) (Float.min a.y b.y) (Float.min a.z b.z)
          and hi = v (Float.max a.x b.x) (Float.max a.y b.y) (Float.max a.z b.z) in
          let box = Box.v ~min:lo ~max:hi white in
          if not (cube_holds (Shape.bounds (Shape.Box box)) lo hi) then
            Alcotest.failf "the cube of the box %a .. %a does not hold it" Vec3.pp lo Vec3.pp hi;
          let t = Triangle.v a b c white in
          if not (cube_holds (Shape.bounds (Shape.Triangle t)) lo hi && cube_holds (Shape.bounds (Shape.Triangle t)) c c) then
            Alcotest.failf "the cube of the triangle %a %a %a does not hold it" Vec3.pp a Vec3.pp b Vec3.pp c
        done);
    Alcotest.test_case "a CSG solid's box: around both for a union, the common part for an intersection (a point when \
                        disjoint), the first operand's for a difference"
      `Quick (fun () ->
        let a = Csg.Box (Box.v ~min:(v 0. 0. 0.) ~max:(v 2. 2. 2.) white)
        and b = Csg.Sphere (Helpers.sphere ~center:(v 2. 1. 1.) ~radius:1. Color.white)
        and far = Csg.Box (Box.v ~min:(v 5. 5. 5.) ~max:(v 6. 6. 6.) white) in
        let bounds op x y = Csg.bounds (Csg.v op x y) in
        let pair = Alcotest.pair Helpers.vec3 Helpers.vec3 in
        Alcotest.check pair "union" (v 0. 0. 0., v 3. 2. 2.) (bounds Csg.Union a b);
        Alcotest.check pair "intersection" (v 1. 0. 0., v 2. 2. 2.) (bounds Csg.Intersection a b);
        Alcotest.check pair "difference" (v 0. 0. 0., v 2. 2. 2.) (bounds Csg.Difference a b);
        Alcotest.check pair "difference, the other way" (v 1. 0. 0., v 3. 2. 2.) (bounds Csg.Difference b a);
        let lo, hi = bounds Csg.Intersection a far in
        Alcotest.check Helpers.vec3 "disjoint: a point" lo hi);
    Alcotest.test_case "a plane has no bounds, a mesh is many objects: Shape.bounds and Shape.kind raise Invalid_argument"
      `Quick (fun () ->
        let raises what f = match f () with _ -> Alcotest.failf "%s: no exception" what | exception Invalid_argument _ -> () in
        let plane = Shape.Plane (Plane.v ~point:Vec3.zero ~normal:Vec3.oy white) in
        raises "bounds of a plane" (fun () -> Shape.bounds plane);
        let mesh =
          match Mesh.v ~positions:[| 0.; 0.; 0.; 1.; 0.; 0.; 0.; 1.; 0. |] ~triangles:[| 0; 1; 2 |] ~normals:[||] ~triangle_normals:[| -1; -1; -1 |] white with
          | Ok m -> Shape.Mesh m
          | Error (`Msg m) -> Alcotest.fail m
        in
        raises "kind of a mesh" (fun () -> Shape.kind mesh);
        raises "bounds of a mesh" (fun () -> Shape.bounds mesh);
        Alcotest.(check bool) "a plane is unbounded" false (Shape.bounded plane));
    Alcotest.test_case
      "an object beyond a point light casts no shadow (Light.shadow_t_max = 1), for every kind, skips on and off, in \
       both modes"
      `Quick (fun () ->
        (* A floor lit by a point light at (0, 2, 2) (and an ambient one),
           seen from (0, 2.5, -1) looking down at (0, 0, 2): every camera
           ray goes down, so nothing above y = 2.5 is seen. Above the light,
           at y = 3 to 4, each object lies on the continuation of the floor's
           shadow rays past the light (t > 1): the floor must not change.
           The same object below the light must shadow it (else the scene
           would prove nothing). *)
        let camera = match Camera.look_at ~position:(v 0. 2.5 (-1.)) (v 0. 0. 2.) with Ok c -> c | Error (`Msg m) -> Alcotest.fail m in
        let floor = Shape.Plane (Plane.v ~point:Vec3.zero ~normal:Vec3.oy (Material.v (Color.v 200. 200. 200.))) in
        (* Or a ground sphere, for scenes of spheres alone: the document's
           own kernel and its shadow loop. *)
        let ground = Helpers.sphere ~center:(v 0. (-1000.) 0.) ~radius:1000. (Color.v 200. 200. 200.) in
        let scene ~on_sphere ?(spheres = []) shapes =
          let spheres, shapes = if on_sphere then (ground :: spheres, shapes) else (spheres, floor :: shapes) in
          Helpers.scene ~width:32 ~height:32 ~camera ~spheres ~shapes ~lights:[ Light.ambient 0.2; Light.point 0.8 (v 0. 2. 2.) ] ()
        in
        let grey = Material.v (Color.v 90. 90. 90.) in
        let terrain y =
          let o = Mesh.Gen.terrain ~seed:1 ~nx:4 ~nz:4 ~size:30. ~height:0. in
          match Mesh.v ~translate:(v 0. y 2.) ~positions:o.positions ~triangles:o.triangles ~normals:o.normals ~triangle_normals:o.triangle_normals grey with
          | Ok m -> Shape.Mesh m
          | Error (`Msg m) -> Alcotest.fail m
        in
        let many_spheres y = List.init 40 (fun k -> Helpers.sphere ~center:(v (float (k mod 8) -. 3.5) y (float (k / 8) -. 0.5)) ~radius:0.4 Color.white) in
        (* Each kind at height [y] (the middle of it), wide enough to cover
           every shadow ray's continuation. *)
        let kinds y =
          [ ("triangle", false, [], [ Shape.Triangle (Triangle.v (v (-20.) y (-20.)) (v 20. y (-20.)) (v 0. y 30.) grey) ]);
            ("box", false, [], [ Shape.Box (Box.v ~min:(v (-20.) (y -. 0.5) (-20.)) ~max:(v 20. (y +. 0.5) 30.) grey) ]);
            ("plane", false, [], [ Shape.Plane (Plane.v ~point:(v 0. y 0.) ~normal:Vec3.oy grey) ]);
            ("cone", false, [], [ cone (Private.Cone.v ~base:(v 0. (y -. 0.5) 2.) ~top:(v 0. (y +. 0.5) 2.) ~radius:40. ~top_radius:30. grey) ]);
            ("sphere", false, [ Helpers.sphere ~center:(v 0. y 2.) ~radius:0.5 Color.white ], []);
            ("sphere, on a ground sphere", true, [ Helpers.sphere ~center:(v 0. y 2.) ~radius:0.5 Color.white ], []);
            ("mesh", false, [], [ terrain y ]);
            (* Many spheres: the hierarchy's shadow traversal. *)
            ("spheres", false, many_spheres y, []); ("spheres, on a ground sphere", true, many_spheres y, []) ]
        in
        List.iter
          (fun epsilon ->
            List.iter
              (fun skips ->
                let render s = Helpers.image_exn ~skips (Scene.with_overrides ~epsilon s) in
                List.iter2
                  (fun (name, on_sphere, spheres, shapes) (_, _, spheres_below, shapes_below) ->
                    let bare = render (scene ~on_sphere []) in
                    let what = Printf.sprintf "%s beyond the light, skips %b, epsilon %b" name skips (epsilon <> None) in
                    Helpers.check_images ~max_abs:0 what ~expected:bare (render (scene ~on_sphere ~spheres shapes));
                    if Image.equal bare (render (scene ~on_sphere ~spheres:spheres_below shapes_below)) then
                      Alcotest.failf "%s below the light casts no shadow: the scene proves nothing" name)
                  (kinds 3.5) (kinds 1.))
              [ true; false ])
          [ None; Some 0.001 ]);
    Alcotest.test_case
      "every kind of blocker casts the same shadow with the skips on and off, with and without a hierarchy, in both \
       modes"
      `Quick (fun () ->
        (* The floor and light of the test above; between them one blocker
           of each kind: the plane z = 1.5 (the floor before it, toward the
           camera, is in its shadow), a box, a triangle, a sphere, a small
           mesh, each over (0, 0, 2). With twelve spheres behind the camera
           (seen by no ray) the scene has a hierarchy, and the skips' shadow
           rays take its traversal, planes first. *)
        let camera = match Camera.look_at ~position:(v 0. 2.5 (-1.)) (v 0. 0. 2.) with Ok c -> c | Error (`Msg m) -> Alcotest.fail m in
        let floor = Shape.Plane (Plane.v ~point:Vec3.zero ~normal:Vec3.oy (Material.v (Color.v 200. 200. 200.))) in
        let grey = Material.v (Color.v 90. 90. 90.) in
        let far = List.init 12 (fun k -> Helpers.sphere ~center:(v (float k) 10. (-10.)) ~radius:0.3 Color.white) in
        let small_mesh =
          let o = Mesh.Gen.terrain ~seed:2 ~nx:3 ~nz:3 ~size:0.8 ~height:0.1 in
          match Mesh.v ~translate:(v 0. 1. 2.) ~positions:o.positions ~triangles:o.triangles ~normals:o.normals ~triangle_normals:o.triangle_normals grey with
          | Ok m -> Shape.Mesh m
          | Error (`Msg m) -> Alcotest.fail m
        in
        let blockers =
          [ ("plane", [], [ Shape.Plane (Plane.v ~point:(v 0. 0. 1.5) ~normal:Vec3.oz grey) ]);
            ("box", [], [ Shape.Box (Box.v ~min:(v (-0.3) 0.8 1.7) ~max:(v 0.3 1.2 2.3) grey) ]);
            ("triangle", [], [ Shape.Triangle (Triangle.v (v (-0.4) 1. 1.6) (v 0.4 1. 1.6) (v 0. 1. 2.4) grey) ]);
            ("sphere", [ Helpers.sphere ~center:(v 0. 1. 2.) ~radius:0.3 Color.white ], []); ("mesh", [], [ small_mesh ]);
            ("cone", [], [ cone (Private.Cone.v ~base:(v 0. 0.8 2.) ~top:(v 0. 1.2 2.) ~radius:0.3 ~top_radius:0. grey) ]) ]
        in
        List.iter
          (fun (name, spheres, shapes) ->
            List.iter
              (fun (crowd, extra) ->
                List.iter
                  (fun epsilon ->
                    let scene spheres shapes =
                      Helpers.scene ~width:32 ~height:32 ?epsilon ~camera ~spheres:(spheres @ extra) ~shapes:(floor :: shapes)
                        ~lights:[ Light.ambient 0.2; Light.point 0.8 (v 0. 2. 2.) ] ()
                    in
                    let s = scene spheres shapes in
                    let what = Printf.sprintf "%s%s, epsilon %b" name crowd (epsilon <> None) in
                    let off = Helpers.image_exn ~skips:false s in
                    Helpers.check_images ~max_abs:0 (what ^ ": skips on and off") ~expected:off (Helpers.image_exn s);
                    if Image.equal off (Helpers.image_exn ~skips:false (scene [] [])) then Alcotest.failf "%s: no shadow, no blocker seen" what)
                  [ None; Some 0.001 ])
              [ ("", []); (", in a hierarchy", far) ])
          blockers);
    Alcotest.test_case
      "a union of two touching boxes is one solid: from inside and outside it looks as the one box they make" `Quick
      (fun () ->
        (* The boxes [0, 3] x [0, 2] x [1, 4] and [3, 6] x [0, 2] x [1, 4]
           share the face x = 3, inside their union: an interval that opens
           where the last one closed extends it (Csg.merge), so no ray sees
           that face. Lit from inside and outside, from cameras looking
           across it (from inside, from 2.5 before it: camera rays start at
           t = 1), the union renders as the box [0, 6] x [0, 2] x [1, 4]
           (the same material, so the same colour everywhere). *)
        let m = Material.v ~specular:50. (Color.v 200. 120. 40.) in
        let a = Csg.Box (Box.v ~min:(v 0. 0. 1.) ~max:(v 3. 2. 4.) m) and b = Csg.Box (Box.v ~min:(v 3. 0. 1.) ~max:(v 6. 2. 4.) m) in
        let one = Shape.Box (Box.v ~min:(v 0. 0. 1.) ~max:(v 6. 2. 4.) m) in
        List.iter
          (fun (where, position, target) ->
            let camera = match Camera.look_at ~position target with Ok c -> c | Error (`Msg e) -> Alcotest.fail e in
            List.iter
              (fun epsilon ->
                let scene shapes =
                  Helpers.scene ~width:24 ~height:24 ?epsilon ~camera ~spheres:[] ~shapes
                    ~lights:[ Light.ambient 0.3; Light.point 0.7 (v 5. 1.5 2.5); Light.directional 0.2 (v (-1.) 1. (-1.)) ] ()
                in
                List.iter
                  (fun (name, c) ->
                    Helpers.check_images ~max_abs:0 (Printf.sprintf "%s, %s, epsilon %b" name where (epsilon <> None))
                      ~expected:(Helpers.image_exn (scene [ one ])) (Helpers.image_exn (scene [ Shape.Csg c ])))
                  [ ("a union b", Csg.v Csg.Union a b); ("b union a", Csg.v Csg.Union b a) ])
              [ None; Some 0.001 ])
          [ ("from inside", v 0.5 1. 2.5, v 6. 1. 2.5); ("from outside", v (-3.) 4. (-1.), v 3. 1. 2.5) ]);
    Alcotest.test_case
      "a hole cut through a box by a box whose face lies in the first one's face is a hole: no face drawn across it"
      `Quick (fun () ->
        (* A = [0, 2] x [0, 2] x [1, 3] minus B = [0.5, 1.5] x [0.5, 1.5] x
           [1, 5]: B's front face lies in A's, so a ray through the hole
           enters A and B at the same t, where the difference opens and
           closes at once: that empty interval is dropped (Csg.merge). The
           picture is that of the same hole cut by B reaching out to z =
           0.5 (the same solid, no coincident faces): the background through
           the hole, from in front, at an angle, in both modes. *)
        let m = Material.v (Color.v 60. 160. 220.) in
        let a = Csg.Box (Box.v ~min:(v 0. 0. 1.) ~max:(v 2. 2. 3.) m) in
        let hole z0 = Csg.v Csg.Difference a (Csg.Box (Box.v ~min:(v 0.5 0.5 z0) ~max:(v 1.5 1.5 5.) m)) in
        List.iter
          (fun (position, epsilon) ->
            let camera = match Camera.look_at ~position (v 1. 1. 2.) with Ok c -> c | Error (`Msg e) -> Alcotest.fail e in
            let scene c =
              Helpers.scene ~width:24 ~height:24 ?epsilon ~camera ~spheres:[] ~shapes:[ Shape.Csg c ]
                ~lights:[ Light.ambient 0.4; Light.directional 0.6 (v 0.3 0.5 (-1.)) ] ()
            in
            Helpers.check_images ~max_abs:0
              (Format.asprintf "from %a, epsilon %b" Vec3.pp position (epsilon <> None))
              ~expected:(Helpers.image_exn (scene (hole 0.5))) (Helpers.image_exn (scene (hole 1.))))
          [ (v 1. 1. (-3.), None); (v 1. 1. (-3.), Some 0.001); (v 1.3 0.8 (-4.), None) ]);
    Alcotest.test_case
      "where two leaves' surfaces coincide, a CSG solid shows the leaf further left: the intersection's front face is \
       the first box's"
      `Quick (fun () ->
        (* A = [0, 2] x [0, 2] x [1, 3], red, and B = [0.5, 1.5] x [0.5, 1.5]
           x [1, 5], blue, enter at the same t on the face z = 1, where it is
           B's end that makes the ray enter A and B: the point belongs to the
           surface of the lower number, A's (Csg.merge). So A and B's
           intersection looks as A and B' where B' = [0.5, 1.5] x [0.5, 1.5]
           x [0.5, 5] starts before A (a red front face, A's alone), and B
           and A's as B and A' with A' = [0, 2] x [0, 2] x [0.5, 3] (a blue
           one). (Not as a lone box: its edges are hit by the rays that only
           touch them, which a CSG solid drops; here the pixels' rays run
           exactly along the front face's edges.) *)
        let red = Material.v (Color.v 220. 30. 30.) and blue = Material.v (Color.v 30. 30. 220.) in
        let box z0 lo hi m = Csg.Box (Box.v ~min:(v lo lo z0) ~max:(v hi hi (if hi = 2. then 3. else 5.)) m) in
        let a = box 1. 0. 2. red and a' = box 0.5 0. 2. red and b = box 1. 0.5 1.5 blue and b' = box 0.5 0.5 1.5 blue in
        let camera = match Camera.look_at ~position:(v 1. 1. (-3.)) (v 1. 1. 2.) with Ok c -> c | Error (`Msg e) -> Alcotest.fail e in
        let image x y =
          Helpers.image_exn
            (Helpers.scene ~width:24 ~height:24 ~camera ~spheres:[] ~shapes:[ Shape.Csg (Csg.v Csg.Intersection x y) ]
               ~lights:[ Light.ambient 0.4; Light.directional 0.6 (v 0.3 0.5 (-1.)) ] ())
        in
        let front_red = image a b' and front_blue = image b a' in
        if Image.equal front_red front_blue then Alcotest.fail "the two colours give one picture: the scene proves nothing";
        Helpers.check_images ~max_abs:0 "A and B: A's red" ~expected:front_red (image a b);
        Helpers.check_images ~max_abs:0 "B and A: B's blue" ~expected:front_blue (image b a));
    Alcotest.test_case "Box.validate refuses a box flat or inverted on any axis, and takes one of any thinness" `Quick
      (fun () ->
        let check what ~min ~max ok =
          match (Box.validate (Box.v ~min ~max white), ok) with
          | Ok _, true | Error (`Msg _), false -> ()
          | Ok _, false -> Alcotest.failf "%s: accepted" what
          | Error (`Msg m), true -> Alcotest.failf "%s: refused (%s)" what m
        in
        List.iteri
          (fun axis name ->
            let at k x = if axis = k then x else 1. in
            let max x = v (at 0 x) (at 1 x) (at 2 x) in
            check (name ^ ": min = max") ~min:Vec3.zero ~max:(max 0.) false;
            check (name ^ ": min > max") ~min:Vec3.zero ~max:(max (-1.)) false;
            check (name ^ ": one float thick") ~min:Vec3.zero ~max:(max (Float.succ 0.)) true)
          [ "x"; "y"; "z" ]);
    Alcotest.test_case
      "with samples averaged, a mirror's reflection is traced until the clamped float is known: samples just below \
       255"
      `Quick (fun () ->
        (* Two white balls of reflectivity 0.0035 on a white background,
           under an ambient light of 1: a sample is 255 * 0.9965 = 254.1075
           before its reflection, which adds 0.0035 * 255 = 0.8925 more
           where it sees the background: 255 in all, its byte 255, 254 if
           the reflection were skipped. With samples averaged, the early
           stop may stop only when both extremes clamp alike (lo >= 255,
           hi <= 0, or lo = hi): here lo = 254.1 < 255 <= hi. *)
        let ball x = Helpers.sphere ~reflective:0.0035 ~center:(v x 0. 5.) ~radius:1. Color.white in
        let camera = match Camera.look_at ~position:Vec3.zero (v 1. 0. 5.) with Ok c -> c | Error (`Msg e) -> Alcotest.fail e in
        let s =
          Helpers.scene ~width:16 ~height:16 ~depth:3 ~background:Color.white ~camera ~spheres:[ ball 1.1; ball (-1.1) ]
            ~lights:[ Light.ambient 1. ] ()
        in
        List.iter
          (fun samples ->
            Helpers.check_images ~max_abs:0 (Printf.sprintf "%d samples: skips on and off" samples)
              ~expected:(Helpers.image_exn ~skips:false ~samples s) (Helpers.image_exn ~samples s))
          [ 1; 2; 3 ]);
    Alcotest.test_case "Mesh.v refuses inconsistent arrays, a bad scale, coordinates beyond the limit and no triangle"
      `Quick (fun () ->
        let p = [| 0.; 0.; 0.; 1.; 0.; 0.; 0.; 1.; 0. |] in
        let mesh ?scale ?(positions = p) ?(triangles = [| 0; 1; 2 |]) ?(tn = [| -1; -1; -1 |]) ?(normals = [||]) () =
          Mesh.v ?scale ~positions ~triangles ~normals ~triangle_normals:tn white
        in
        let refused what m = match m with Ok _ -> Alcotest.failf "%s: accepted" what | Error (`Msg _) -> () in
        refused "positions not a multiple of 3" (mesh ~positions:[| 0.; 0.; 0.; 1.; 0.; 0.; 0.; 1. |] ());
        refused "a vertex number out of range" (mesh ~triangles:[| 0; 1; 3 |] ());
        refused "a negative vertex number" (mesh ~triangles:[| 0; -1; 2 |] ());
        refused "a normal number out of range" (mesh ~tn:[| 0; -1; -1 |] ());
        refused "triangle normals not parallel to the triangles" (mesh ~tn:[| -1; -1 |] ());
        refused "no triangle" (mesh ~triangles:[||] ~tn:[||] ());
        refused "scale 0" (mesh ~scale:0. ());
        refused "scale -1" (mesh ~scale:(-1.) ());
        refused "scale nan" (mesh ~scale:nan ());
        refused "scale infinity" (mesh ~scale:infinity ());
        refused "a coordinate beyond the limit once scaled" (mesh ~scale:(2. *. Limits.max_coordinate) ());
        (match mesh ~scale:2. () with
        | Ok m -> Alcotest.check Helpers.vec3 "placed: scale * p" (v 2. 0. 0.) (Mesh.vertex m 0 1)
        | Error (`Msg e) -> Alcotest.fail e);
        (* A degenerate triangle is kept, and counted out of the objects. *)
        match mesh ~positions:(Array.append p [| 2.; 0.; 0. |]) ~triangles:[| 0; 1; 2; 0; 1; 3 |] ~tn:(Array.make 6 (-1)) () with
        | Ok m ->
            Alcotest.(check int) "both kept" 2 (Mesh.triangle_count m);
            Alcotest.(check bool) "the second is degenerate" true (Mesh.degenerate m 1);
            Alcotest.(check int) "one object" 1 (Mesh.objects m)
        | Error (`Msg e) -> Alcotest.fail e);
  ]
