(* The document's algorithm (Literal) on scenes small enough to compute by
   hand. *)
open Raytrace

let near = Alcotest.(check (float 1e-12))
let sphere ?(specular = Sphere.matte) ?(reflective = 0.) ?(color = Color.white) center radius =
  Helpers.sphere ~specular ~reflective ~center ~radius color

let scene ?(background = Color.black) ?(depth = 3) spheres lights =
  Helpers.scene ~background ~depth ~epsilon:0.001 ~spheres ~lights ()

(* A unit sphere at the origin, seen at its top point P = (0, 1, 0), N = (0, 1, 0). *)
let ball = sphere Vec3.zero 1.
let top = Vec3.oy

let lighting ?(specular = Sphere.matte) ?(view = Vec3.oy) s =
  Private.Literal.compute_lighting s ~epsilon:0.001 ~point:top ~normal:Vec3.oy ~view ~specular

let tests =
  [
    Alcotest.test_case "the closest of several hits wins (section 6.1)" `Quick (fun () ->
        let near_s = sphere (Vec3.v 0. 0. 3.) 1. and far_s = sphere (Vec3.v 0. 0. 10.) 1. in
        match
          Private.Literal.closest_intersection [ far_s; near_s ] ~origin:Vec3.zero ~direction:Vec3.oz
            ~t_min:1. ~t_max:infinity
        with
        | Some (s, t) ->
            (* roots of the near sphere: 2 and 4; the far one: 9 and 11 *)
            Alcotest.(check bool) __LOC__ true (s == near_s);
            near __LOC__ 2. t
        | None -> Alcotest.fail "no hit");
    Alcotest.test_case "hits outside (t_min, t_max) are not seen" `Quick (fun () ->
        let s = sphere (Vec3.v 0. 0. 3.) 1. in
        let hit ~t_min ~t_max =
          Option.map snd
            (Private.Literal.closest_intersection [ s ] ~origin:Vec3.zero ~direction:Vec3.oz ~t_min ~t_max)
        in
        (* roots 2 and 4: the range is open at both ends *)
        Alcotest.(check (option (float 0.))) __LOC__ (Some 4.) (hit ~t_min:2. ~t_max:infinity);
        Alcotest.(check (option (float 0.))) __LOC__ None (hit ~t_min:4. ~t_max:infinity);
        Alcotest.(check (option (float 0.))) __LOC__ None (hit ~t_min:0. ~t_max:2.));
    Alcotest.test_case "ambient light lights every point equally (7.3)" `Quick (fun () ->
        near __LOC__ 0.2 (lighting (scene [ ball ] [ Light.ambient 0.2 ])));
    Alcotest.test_case "intensities add up (7.4)" `Quick (fun () ->
        (* ambient 0.2 + point light straight above: L = (0, 3, 0) - (0, 1, 0)
           = (0, 2, 0), 0.6 * 2 / (1 * 2) = 0.6: total 0.8 *)
        near __LOC__ 0.8
          (lighting (scene [ ball ] [ Light.ambient 0.2; Light.point 0.6 (Vec3.v 0. 3. 0.) ])));
    Alcotest.test_case "a light below the horizon adds nothing diffuse" `Quick (fun () ->
        near __LOC__ 0. (lighting (scene [ ball ] [ Light.directional 0.5 (Vec3.v 1. 0. 0.) ])));
    Alcotest.test_case "specular adds I cos^s for shiny spheres only (7.6)" `Quick (fun () ->
        (* light along (1, 1, 0) from P: diffuse 1 / sqrt 2; R = (-1, 1, 0);
           V = (-1, 1, 0): cos = 1, so specular adds 1: 1 + 1 / sqrt 2 *)
        let s = scene [ ball ] [ Light.directional 1. (Vec3.v 1. 1. 0.) ] in
        let view = Vec3.v (-1.) 1. 0. in
        near __LOC__ (1. +. (1. /. sqrt 2.)) (lighting ~specular:100. ~view s);
        near __LOC__ (1. /. sqrt 2.) (lighting ~view s));
    Alcotest.test_case "a sphere between point and light casts a shadow (7.7)" `Quick (fun () ->
        (* blocker at (0, 2, 0), r = 0.5: the shadow ray (0,1,0) + t (0,2,0)
           meets it at y = 1.5, t = 0.25, inside (0.001, 1) *)
        let blocker = sphere (Vec3.v 0. 2. 0.) 0.5 in
        near __LOC__ 0.2
          (lighting (scene [ ball; blocker ] [ Light.ambient 0.2; Light.point 0.6 (Vec3.v 0. 3. 0.) ])));
    Alcotest.test_case "an object beyond a point light casts no shadow, beyond a directional one does"
      `Quick (fun () ->
        (* blocker at (0, 5, 0), r = 0.5: first hit at y = 4.5, t = (4.5 - 1) / 2
           = 1.75 > 1 for the point light at (0, 3, 0); for the directional
           light L = (0, 1, 0), t = 3.5 < infinity *)
        let blocker = sphere (Vec3.v 0. 5. 0.) 0.5 in
        near __LOC__ 0.6 (lighting (scene [ ball; blocker ] [ Light.point 0.6 (Vec3.v 0. 3. 0.) ]));
        near __LOC__ 0. (lighting (scene [ ball; blocker ] [ Light.directional 0.6 Vec3.oy ])));
    Alcotest.test_case "the surface does not shadow itself thanks to epsilon (7.7)" `Quick (fun () ->
        (* the shadow ray starts on the sphere: its root t = 0 must not count *)
        near __LOC__ 1. (lighting (scene [ ball ] [ Light.directional 1. Vec3.oy ])));
    Alcotest.test_case "a mirror blends its colour with what it reflects (7.8)" `Quick (fun () ->
        (* ray along +z hits the sphere at (0, 0, 2) head-on, local colour
           (200, 100, 0) * ambient 1; the mirror ray goes back to the camera
           side and sees the background (0, 0, 255):
           (200, 100, 0) * 0.5 + (0, 0, 255) * 0.5 = (100, 50, 127.5) *)
        let s =
          scene ~background:(Color.v 0. 0. 255.)
            [ sphere ~reflective:0.5 ~color:(Color.v 200. 100. 0.) (Vec3.v 0. 0. 3.) 1. ]
            [ Light.ambient 1. ]
        in
        let trace depth =
          Private.Literal.trace_ray s ~epsilon:0.001 ~origin:Vec3.zero ~direction:Vec3.oz ~t_min:1.
            ~t_max:infinity ~depth
        in
        Alcotest.check Helpers.color __LOC__ (Color.v 100. 50. 127.5) (trace 3);
        (* with no recursion left, only the local colour *)
        Alcotest.check Helpers.color __LOC__ (Color.v 200. 100. 0.) (trace 0));
    Alcotest.test_case "rendering visits exactly w x h pixels (section 8)" `Quick (fun () ->
        let s = (Scene.with_overrides ~width:7 ~height:4 ~background:(Color.v 1. 2. 3.) ((scene [] [ Light.ambient 1. ]))) in
        let img = Private.Literal.render (Helpers.valid s) in
        Alcotest.(check (pair int int)) __LOC__ (7, 4) (Image.width img, Image.height img);
        Alcotest.(check (triple int int int)) __LOC__ (1, 2, 3) (Image.get img 6 3));
    Alcotest.test_case "what is above the camera lands in the top rows" `Quick (fun () ->
        (* 4 x 4 canvas: rows 0..3 are canvas y = 1, 0, -1, -2, rays
           (V_x, y / 4, 1). A ceiling sphere (center (0, 101, 10), r = 100,
           lowest point y = 1) is met by the rays with y / 4 = 0.25 (at
           z = 10 they are at y = 2.5, inside it) and by none with y <= 0. *)
        let s =
          (Scene.with_overrides ~width:4 ~height:4 ((scene [ sphere (Vec3.v 0. 101. 10.) 100. ] [ Light.ambient 1. ])))
        in
        let img = Private.Literal.render (Helpers.valid s) in
        let white = (255, 255, 255) and black = (0, 0, 0) in
        List.iter
          (fun (row, expected) ->
            for x = 0 to 3 do
              Alcotest.(check (triple int int int)) (Printf.sprintf "row %d" row) expected (Image.get img x row)
            done)
          [ (0, white); (1, black); (2, black); (3, black) ]);
  ]

(* {1 The oracle against exact arithmetic, where the old oracle shared the
   kernel's blind spots} *)

(* Scenes seen from the origin along +z through a 1 x 1 viewport at
   distance 1 on a [n x n] canvas, [n] a power of 2: pixel (gx, gy)'s ray
   has the direction (gx / n, gy / n, 1), exactly. *)
let exact_scene ?(lights = [ Light.ambient 1. ]) n shapes =
  Helpers.scene ~epsilon:0.001 ~width:n ~height:n ~background:Color.black ~spheres:[] ~shapes ~lights ()

let pixel_direction n gx gy = Vec3.v (Float.of_int gx /. Float.of_int n) (Float.of_int gy /. Float.of_int n) 1.

(* The image whose pixel (gx, gy) has colour [f gx gy] (channels 0-255). *)
let expected_image n f =
  let img = Image.create n n in
  for gx = Canvas.min_x n to Canvas.max_x n do
    for gy = Canvas.min_y n to Canvas.max_y n do
      let r, g, b = f gx gy in
      Image.set img (Canvas.column ~width:n gx) (Canvas.row ~height:n gy) r g b
    done
  done;
  img

(* The exact parameters where the line O + t D enters and leaves the
   closed box [lo, hi] (rationals; O and D floats), if it meets it. *)
let exact_box_interval (lo : Vec3.t) (hi : Vec3.t) (o : Vec3.t) (d : Vec3.t) =
  let axis l h o d (enter, exit) =
    match (enter, exit) with
    | None, _ | _, None -> (None, None)
    | Some enter, Some exit ->
        if d = 0. then if l <= o && o <= h then (Some enter, Some exit) else (None, None)
        else
          let t0 = Q.(div (sub (of_float l) (of_float o)) (of_float d))
          and t1 = Q.(div (sub (of_float h) (of_float o)) (of_float d)) in
          (Some (Q.max enter (Q.min t0 t1)), Some (Q.min exit (Q.max t0 t1)))
  in
  let start = (Some Q.minus_inf, Some Q.inf) in
  match axis lo.z hi.z o.z d.z (axis lo.y hi.y o.y d.y (axis lo.x hi.x o.x d.x start)) with
  | Some enter, Some exit when Q.leq enter exit -> Some (enter, exit)
  | _ -> None

let white_box lo hi = Shape.Box (Box.v ~min:lo ~max:hi (Material.v Color.white))

let exact_tests =
  [
    Alcotest.test_case "rays that touch a box's edges and corners hit it, pixel by pixel as exact arithmetic says"
      `Quick (fun () ->
        (* The box [-1, 1]^2 x [4, 5] on a 16 x 16 canvas: the rays with
           gx = +-4 meet x = +-1 at z = 4 exactly, where they enter and
           leave at once (t = 4): 32 rays touch an edge or a corner. *)
        let n = 16 and lo = Vec3.v (-1.) (-1.) 4. and hi = Vec3.v 1. 1. 5. in
        let s = exact_scene n [ white_box lo hi ] in
        let touching = ref 0 in
        let expected =
          expected_image n (fun gx gy ->
              match exact_box_interval lo hi Vec3.zero (pixel_direction n gx gy) with
              | Some (enter, exit) ->
                  if Q.equal enter exit then incr touching;
                  (255, 255, 255)
              | None -> (0, 0, 0))
        in
        Alcotest.(check int) "rays that touch the box" 32 !touching;
        Helpers.check_images "the oracle" ~expected (Private.Literal.render (Helpers.valid s));
        Helpers.check_images "the fast renderer" ~expected (Helpers.image_exn s));
    Alcotest.test_case "inside a union of two boxes that share a face, the shared face is not seen" `Quick
      (fun () ->
        (* The camera is inside A = [-3, 3]^2 x [-3, 2]; B = [-3, 3]^2 x [2, 8]
           touches it at z = 2. Every ray (|D_x|, |D_y| <= 1/2) leaves the
           union through B: by its far face or its sides, at
           t = min (3 / |D_x|, 3 / |D_y|, 8), exactly, never at z = 2. *)
        let n = 8 in
        let a = Csg.Box (Box.v ~min:(Vec3.v (-3.) (-3.) (-3.)) ~max:(Vec3.v 3. 3. 2.) (Material.v (Color.v 255. 0. 0.))) in
        let b = Csg.Box (Box.v ~min:(Vec3.v (-3.) (-3.) 2.) ~max:(Vec3.v 3. 3. 8.) (Material.v (Color.v 0. 255. 0.))) in
        let union = Shape.Csg (Csg.v Csg.Union a b) in
        let s = exact_scene n [ union ] in
        for gx = Canvas.min_x n to Canvas.max_x n do
          for gy = Canvas.min_y n to Canvas.max_y n do
            let d = pixel_direction n gx gy in
            let exit =
              List.fold_left Q.min (Q.of_int 8)
                (List.filter_map (fun c -> if c = 0. then None else Some (Q.div (Q.of_int 3) (Q.of_float (Float.abs c)))) [ d.x; d.y ])
            in
            match Private.Literal.closest_hit s ~origin:Vec3.zero ~direction:d ~t_min:1. ~t_max:infinity with
            | Some (Private.Literal.Csg_surface (_, leaf, _), t) ->
                if not (leaf == b) then Alcotest.failf "pixel (%d, %d): the surface of A is seen" gx gy;
                if not (Q.equal (Q.of_float t) exit) then
                  Alcotest.failf "pixel (%d, %d): t = %h, exactly %s" gx gy t (Q.to_string exit)
            | _ -> Alcotest.failf "pixel (%d, %d): the union's surface is not seen" gx gy
          done
        done;
        Helpers.check_images "ambient light: all green" ~expected:(expected_image n (fun _ _ -> (0, 255, 0)))
          (Private.Literal.render (Helpers.valid s));
        (* Lit from a point: the shared face would be lit differently. *)
        let lit = (Scene.with_overrides ~lights:([ Light.ambient 0.2; Light.point 0.8 (Vec3.v 1. 1. 1.) ]) s) in
        Helpers.check_images "the fast renderer, lit" ~max_abs:1 ~expected:(Private.Literal.render (Helpers.valid lit)) (Helpers.image_exn lit));
  ]

let mesh_exn ~positions ~triangles =
  match
    Mesh.v ~positions ~triangles ~normals:[||] ~triangle_normals:(Array.make (Array.length triangles) (-1))
      (Material.v Color.white)
  with
  | Ok m -> m
  | Error (`Msg e) -> Alcotest.fail e

(* The octahedron |x| + |y| + |z - 4| <= 1, and the cube [-1, 1]^2 x [4, 6]
   with each face cut by a diagonal (those of z = 4 and z = 6 along x = y). *)
let octahedron =
  mesh_exn
    ~positions:[| 1.; 0.; 4.; -1.; 0.; 4.; 0.; 1.; 4.; 0.; -1.; 4.; 0.; 0.; 5.; 0.; 0.; 3. |]
    ~triangles:[| 0; 2; 4; 2; 1; 4; 1; 3; 4; 3; 0; 4; 2; 0; 5; 1; 2; 5; 3; 1; 5; 0; 3; 5 |]

let cube =
  let corner i = [| (if i land 1 = 0 then -1. else 1.); (if i land 2 = 0 then -1. else 1.); (if i land 4 = 0 then 4. else 6.) |] in
  mesh_exn
    ~positions:(Array.concat (List.init 8 corner))
    ~triangles:
      [| 0; 1; 3; 0; 3; 2; 4; 7; 5; 4; 6; 7; 0; 2; 6; 0; 6; 4; 1; 5; 7; 1; 7; 3; 0; 4; 5; 0; 5; 1; 2; 3; 7; 2; 7; 6 |]

(* Pixel (gx, gy) of a 16 x 16 canvas sees the solid iff its line goes
   through the inside over a positive length: for the octahedron
   4 (|D_x| + |D_y|) < 1, for the cube 4 |D_x| < 1 and 4 |D_y| < 1
   (exactly: |gx| + |gy| < 4, |gx| < 4 and |gy| < 4); the lines with
   |gx| + |gy| = 4 (|gx| or |gy| = 4) only touch it. *)
let closed_meshes = [ ("a cut cube", cube, fun gx gy -> abs gx < 4 && abs gy < 4); ("an octahedron", octahedron, fun gx gy -> abs gx + abs gy < 4) ]

let mesh_operand_scene m =
  let big = Csg.Box (Box.v ~min:(Vec3.v (-5.) (-5.) 0.5) ~max:(Vec3.v 5. 5. 10.) (Material.v Color.white)) in
  exact_scene 16 [ Shape.Csg (Csg.v Csg.Intersection (Csg.Mesh m) big) ]

let mesh_tests =
  [
    Alcotest.test_case "a closed mesh as a CSG operand: rays through its shared edges and vertices cross it once"
      `Quick (fun () ->
        List.iter
          (fun (what, m, inside) ->
            let expected = expected_image 16 (fun gx gy -> if inside gx gy then (255, 255, 255) else (0, 0, 0)) in
            Helpers.check_images what ~expected (Private.Literal.render (Helpers.valid (mesh_operand_scene m))))
          closed_meshes);
    Alcotest.test_case "the watertight crossing counts a line through a closed mesh's edge or vertex once" `Quick
      (fun () ->
        (* The octahedron's axis (0, 0, 1) passes through two vertices; the
           line (1/8, 0, 1) through an edge of each side. Each meets the
           closed surface twice, once per side, whatever the tie. *)
        let crossings d =
          List.length
            (List.filter
               (fun k ->
                 Literal_geometry.triangle_crossing ~origin:Vec3.zero ~direction:d (Mesh.vertex octahedron k 0)
                   (Mesh.vertex octahedron k 1) (Mesh.vertex octahedron k 2))
               (List.init (Mesh.triangle_count octahedron) Fun.id))
        in
        List.iter
          (fun (what, d) -> Alcotest.(check int) what 2 (crossings d))
          [
            ("through two vertices", Vec3.oz);
            ("through two edges", Vec3.v 0.125 0. 1.);
            ("through two edges, on the other side", Vec3.v (-0.125) 0. 1.);
            ("through two edges, in x = 0", Vec3.v 0. 0.1875 1.);
          ];
        (* (1/8, 1/8, 1) meets the equator's edge from (1, 0, 4) to (0, 1, 4)
           at t = 4 and nothing else: it touches the solid, crossing none. *)
        Alcotest.(check bool) "touching at a fold: an even count" true (crossings (Vec3.v 0.125 0.125 1.) mod 2 = 0));
    Alcotest.test_case "the oracle counts every CSG leaf it tests and stops at the work bound" `Quick (fun () ->
        (* 64 spheres in a balanced union (6 levels), 16 x 16 pixels: 64
           tests per ray, 16384 at least for the primary rays; the bound
           is 5000 and the render stops at test 5001. *)
        let rec tree lo n =
          if n = 1 then Csg.Sphere (Helpers.sphere ~center:(Vec3.v (Float.of_int (lo mod 8) -. 3.5) (Float.of_int (lo / 8) -. 3.5) 10.) ~radius:0.4 Color.white)
          else Csg.Csg (Csg.v Csg.Union (tree lo (n / 2)) (tree (lo + (n / 2)) (n / 2)))
        in
        let solid = match tree 0 64 with Csg.Csg c -> c | _ -> assert false in
        let limits = Limits.with_bound Limits.default `Work 5000. in
        List.iter
          (fun (what, shape) ->
            match Private.Literal.render ~limits (Helpers.valid (exact_scene 16 [ shape ])) with
            | exception Limits.Work_exceeded n -> Alcotest.(check int) what 5001 n
            | _ -> Alcotest.failf "%s: not stopped" what)
          [ ("64 spheres", Shape.Csg solid); ("a mesh", Shape.Csg (Csg.v Csg.Union (Csg.Mesh cube) (Csg.Mesh octahedron))) ]);
  ]

let tests = tests @ exact_tests @ mesh_tests

(* {1 Where the kernel and the oracle were seen to disagree} *)

let qv (v : Vec3.t) = (Q.of_float v.x, Q.of_float v.y, Q.of_float v.z)
let qsub (ax, ay, az) (bx, by, bz) = Q.(sub ax bx, sub ay by, sub az bz)
let qcross (ax, ay, az) (bx, by, bz) = Q.(sub (mul ay bz) (mul az by), sub (mul az bx) (mul ax bz), sub (mul ax by) (mul ay bx))
let qdot (ax, ay, az) (bx, by, bz) = Q.(add (add (mul ax bx) (mul ay by)) (mul az bz))

(* The exact edge function <D, (p - O) x (q - O)>. *)
let edge ~o ~d p q = qdot (qv d) (qcross (qsub (qv p) (qv o)) (qsub (qv q) (qv o)))

let disagreement_tests =
  [
    Alcotest.test_case "a shadow ray 2^-49 outside a triangle's edge misses it, as exact arithmetic says" `Quick (fun () ->
        (* The floor point (-1.2, -1, 4) as rounded, toward the light
           (2, 3, 0): in decimal the ray meets the edge from (-2, -1, 2) to
           (2, 1, 6) at t = 1/6; as rounded it passes beside it, the edge
           function 2^-49 against the other two's -28.8 and -14.4. *)
        let o = Vec3.v (-1.2) (-1.) 4. in
        let d = Vec3.sub (Vec3.v 2. 3. 0.) o in
        let a = Vec3.v (-2.) (-1.) 2. and b = Vec3.v 2. 1. 6. and c = Vec3.v 0. 1.5 4. in
        Alcotest.(check string) "exact edge function of a b" (Q.to_string (Q.of_ints 1 562949953421312)) (Q.to_string (edge ~o ~d a b));
        Alcotest.(check bool) "the others negative" true (Q.sign (edge ~o ~d b c) < 0 && Q.sign (edge ~o ~d c a) < 0);
        let tri = Shape.Triangle (Triangle.v a b c (Material.v Color.white)) in
        let s = Helpers.scene ~epsilon:0.001 ~spheres:[] ~shapes:[ tri ] ~lights:[] () in
        Alcotest.(check bool) "the oracle: no blocker" true (Private.Literal.closest_hit s ~origin:o ~direction:d ~t_min:0.001 ~t_max:1. = None));
    Alcotest.test_case "a ray beside a mesh's silhouette vertex hits the triangle it meets first, exactly" `Quick
      (fun () ->
        (* Along (1/4 - 2^-55, 0, 1) the line passes 2^-53 inside the
           octahedron's vertex (1, 0, 4), in the plane y = 0: it enters
           through the front edge to it at z = 4 - 16/3 2^-55 (about) and
           leaves through the back edge at z = 4 + 16/5 2^-55, both 4 once
           rounded. Front: triangles 4 and 7; back: 0 and 3, listed first.
           The nearest exactly is triangle 4. *)
        let d = Vec3.v (Float.pred 0.25) 0. 1. in
        let s = Helpers.scene ~epsilon:0.001 ~spheres:[] ~shapes:[ Shape.Mesh octahedron ] ~lights:[] () in
        let hits =
          List.filter
            (fun k ->
              Literal_geometry.triangle_root ~origin:Vec3.zero ~direction:d (Mesh.vertex octahedron k 0)
                (Mesh.vertex octahedron k 1) (Mesh.vertex octahedron k 2)
              < infinity)
            (List.init (Mesh.triangle_count octahedron) Fun.id)
        in
        Alcotest.(check (list int)) "the triangles met" [ 0; 3; 4; 7 ] hits;
        match Private.Literal.closest_hit s ~origin:Vec3.zero ~direction:d ~t_min:1. ~t_max:infinity with
        | Some (Private.Literal.Mesh_triangle (_, k), _) -> Alcotest.(check int) "the first met" 4 k
        | _ -> Alcotest.fail "no triangle");
  ]

let tests = tests @ disagreement_tests

(* Floats of every magnitude from 2^-40 to 2^40, either sign, some equal
   or nearly: where an exact sign is hard. *)
let hard_float =
  QCheck.Gen.(
    map3
      (fun m e s -> (if s then -1. else 1.) *. Float.ldexp (1. +. m) e)
      (oneof [ return 0.; return 0.5; float_bound_inclusive 1. ])
      (int_range (-40) 40) bool)

let exact_float_tests =
  [
    Helpers.qcheck ~count:2000 "exact signs of a b - c d and of fractions are the rationals' signs"
      QCheck.(make Gen.(pair (pair hard_float hard_float) (pair hard_float hard_float)))
      (fun ((a, b), (c, d)) ->
        let e = Exact_float.of_float in
        let q = Q.of_float in
        Exact_float.sign (Exact_float.sub (Exact_float.mul (e a) (e b)) (Exact_float.mul (e c) (e d)))
        = Q.sign Q.(sub (mul (q a) (q b)) (mul (q c) (q d)))
        && Exact_float.sign (Exact_float.sub (Exact_float.diff a b) (Exact_float.diff c d))
           = Q.sign Q.(sub (sub (q a) (q b)) (sub (q c) (q d)))
        && (b = 0. || d = 0.
           || Exact_float.compare_fractions (Exact_float.diff a c) (e b) (Exact_float.diff c a) (e d)
              = Q.compare Q.(div (sub (q a) (q c)) (q b)) Q.(div (sub (q c) (q a)) (q d))));
  ]

let tests = tests @ exact_float_tests

(* {1 The range of a camera ray is strict}

   The camera (0, -0.75, 0.5) and the plane through (0.625, 0, 3.75) of
   normal (-0.5, -1, 0.25): the ray of pixel (gx, gy) of a 16 x 16 canvas
   meets it at t = -0.25 / (0.25 - gx / 32 - gy / 16): exactly 1 where
   gx + 2 gy = 16, below 1 beyond, above 1 before. The document sees only
   t > 1: the pixels at exactly 1 show the
   background, as the kernel's do, whatever the plane's rounded t (the
   oracle's is 1 + ulp at some of them). *)
let range_tests =
  [
    Alcotest.test_case "a plane met at exactly t = 1 is not seen by the camera, one met just beyond is" `Quick (fun () ->
        let s =
          match
            Helpers.of_string
              "(canvas (width 16) (height 16)) (viewport (width 1) (height 1) (distance 1)) (camera (position 0 -0.75 0.5)) \
               (background 0 0 255) (plane (point 0.625 0 3.75) (normal -0.5 -1 0.25) (color 255 0 0)) (light ambient (intensity 1))"
          with
          | Ok s -> s
          | Error (`Msg m) -> Alcotest.fail m
        in
        let tr = Trace.create (Helpers.prepare ~skips:true s) in
        List.iter
          (fun (gx, gy, seen) ->
            let c = Private.Literal.pixel s gx gy in
            Trace.pixel tr gx gy;
            let expected = if seen then 255. else 0. in
            Alcotest.(check (float 0.)) (Printf.sprintf "the oracle's red at (%d, %d)" gx gy) expected c.r;
            Alcotest.(check (float 0.)) (Printf.sprintf "the kernel's red at (%d, %d)" gx gy) expected (Trace.red tr))
          [ (2, 7, false); (4, 6, false); (6, 5, false); (3, 7, false); (1, 7, true); (2, 6, true); (0, 7, true) ]);
  ]

let tests = tests @ range_tests
