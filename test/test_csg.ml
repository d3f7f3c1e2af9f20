(* Constructive solid geometry: the (csg ...) form read, printed back and
   refused with its position; the kernel's interval method against the
   literal algorithm (Literal's own, Literal_geometry.csg_hit) colour float by
   colour float on random scenes; silhouettes of small far CSG solids
   against exact rational arithmetic; the subtracted solid's normals;
   shadows through holes; no self-shadowing at any scale; no allocation
   per pixel; the same with glass and checkered leaves (the solid one
   medium, its first leaf's; each surface point its own leaf's material
   and pattern frame). The golden images and the scale and translation invariance
   of scenes/lens.scene and scenes/die.scene are in Test_golden and
   Test_numerics, with every scene. *)
open Raytrace

let white = Color.white
let u = epsilon_float /. 2.
let sphere ?(color = white) ?specular ?reflective c r = Csg.Sphere (Helpers.sphere ?specular ?reflective ~center:c ~radius:r color)
let box ?(color = white) ?specular ?reflective lo hi = Csg.Box (Box.v ~min:lo ~max:hi (Material.v ?specular ?reflective color))

(* A closed octahedron of half-diagonal [r] around [c], as a mesh. *)
let octahedron_arrays (c : Vec3.t) r =
  let positions =
    Array.concat
      (List.map
         (fun (x, y, z) -> [| c.x +. (r *. x); c.y +. (r *. y); c.z +. (r *. z) |])
         [ (1., 0., 0.); (-1., 0., 0.); (0., 1., 0.); (0., -1., 0.); (0., 0., 1.); (0., 0., -1.) ])
  in
  let triangles = [| 0; 2; 4; 2; 1; 4; 1; 3; 4; 3; 0; 4; 2; 0; 5; 1; 2; 5; 3; 1; 5; 0; 3; 5 |] in
  (positions, triangles)

let octahedron ?(color = white) ?(material = Fun.id) c r =
  let positions, triangles = octahedron_arrays c r in
  match
    Mesh.v ~positions ~triangles ~normals:[||] ~triangle_normals:(Array.make (Array.length triangles) (-1))
      (material (Material.v color))
  with
  | Ok m -> Csg.Mesh m
  | Error (`Msg e) -> Alcotest.fail e

let scene ?epsilon ?(width = 32) ?(height = 32) ?camera ?(spheres = []) shapes =
  Helpers.scene ~width ~height ?camera ?epsilon ~spheres ~shapes
    ~lights:[ Light.ambient 0.2; Light.point 0.6 (Vec3.v 2. 3. 0.); Light.directional 0.2 (Vec3.v 1. 4. (-4.)) ]
    ()

let floor = Shape.Plane (Plane.v ~point:(Vec3.v 0. (-1.2) 0.) ~normal:Vec3.oy (Material.v (Color.v 200. 200. 200.)))

(* {1 Random scenes} *)

let random_color rand = Color.v (Random.State.float rand 255.) (Random.State.float rand 255.) (Random.State.float rand 255.)

let random_point rand =
  Vec3.v (Random.State.float rand 2.4 -. 1.2) (Random.State.float rand 2.4 -. 1.2) (4. +. Random.State.float rand 2.4 -. 1.2)

(* With [~glass], a leaf in two is transparent (up to [1 - reflective],
   index 1, 1.5 or in [0.5, 2.5], Fresnel or not) and a leaf in two
   (sphere or box) has a checker: the draws of the plain generator come
   first and unchanged, so that its scenes stay what they were. *)
let rec random_solid ?(glass = false) rand depth =
  if depth > 0 && Random.State.int rand 3 > 0 then Csg.Csg (random_csg ~glass rand (depth - 1))
  else
    let color = random_color rand in
    let specular = if Random.State.bool rand then Some (Random.State.float rand 500.) else None in
    let reflective = if Random.State.int rand 3 = 0 then Some (Random.State.float rand 0.6) else None in
    let material (m : Material.t) = if glass then random_glass rand m else m in
    match Random.State.int rand 5 with
    | 0 | 1 -> (
        match sphere ~color ?specular ?reflective (random_point rand) (0.3 +. Random.State.float rand 0.9) with
        | Csg.Sphere s ->
            Csg.Sphere (Sphere.v ~center:s.center ~radius:s.radius (material s.material))
        | solid -> solid)
    | 2 | 3 -> (
        let lo = random_point rand in
        let size () = 0.2 +. Random.State.float rand 1.5 in
        match box ~color ?specular ?reflective lo (Vec3.add lo (Vec3.v (size ()) (size ()) (size ()))) with
        | Csg.Box b -> Csg.Box (Box.v ~min:b.min ~max:b.max (material b.material))
        | solid -> solid)
    | _ -> octahedron ~color ~material (random_point rand) (0.4 +. Random.State.float rand 1.)

and random_glass rand (m : Material.t) =
  let m =
    if Random.State.bool rand then m
    else
      let transparency = Float.min (1. -. m.reflective) (Random.State.float rand 1.1) in
      let refractive_index =
        match Random.State.int rand 3 with 0 -> 1. | 1 -> 1.5 | _ -> 0.5 +. Random.State.float rand 2.
      in
      Material.update ~transparency ~refractive_index ~fresnel:(Random.State.bool rand) m
  in
  if Random.State.bool rand then m
  else Material.update ~pattern:(Some (Pattern.checker ~size:(0.05 +. Random.State.float rand 1.) (random_color rand))) m

and random_csg ?glass rand depth =
  let op = match Random.State.int rand 3 with 0 -> Csg.Union | 1 -> Csg.Intersection | _ -> Csg.Difference in
  Csg.v op (random_solid ?glass rand depth) (random_solid ?glass rand depth)

let random_scene ?glass ?epsilon rand =
  let n = 1 + Random.State.int rand 2 in
  let shapes = List.init n (fun _ -> Shape.Csg (random_csg ?glass rand 2)) in
  let spheres =
    if Random.State.bool rand then [ Helpers.sphere ~center:(random_point rand) ~radius:0.4 ~reflective:0.3 (random_color rand) ]
    else []
  in
  scene ?epsilon ~width:24 ~height:24 ~spheres (floor :: shapes)

(* {1 Exact silhouettes} *)

let q = Q.of_float
let qv (v : Vec3.t) = (q v.x, q v.y, q v.z)
let dot (ax, ay, az) (bx, by, bz) = Q.(add (add (mul ax bx) (mul ay by)) (mul az bz))
let qsub (ax, ay, az) (bx, by, bz) = Q.(sub ax bx, sub ay by, sub az bz)

(* The exact [t] interval of the line [origin + t direction] in box [b]
   (empty when [lo >= hi]). *)
let box_interval (b : Box.t) ~(origin : Vec3.t) ~(direction : Vec3.t) =
  let axis lo hi o d =
    let t0 = Q.(div (sub (q lo) (q o)) (q d)) and t1 = Q.(div (sub (q hi) (q o)) (q d)) in
    (Q.min t0 t1, Q.max t0 t1)
  in
  let slabs =
    [ axis b.min.x b.max.x origin.x direction.x; axis b.min.y b.max.y origin.y direction.y; axis b.min.z b.max.z origin.z direction.z ]
  in
  ( List.fold_left (fun acc (a, _) -> Q.max acc a) (fst (List.hd slabs)) slabs,
    List.fold_left (fun acc (_, c) -> Q.min acc c) (snd (List.hd slabs)) slabs )

(* `In, `Out or `Edge for the exact line of a ray and the solid [s op b]:
   the line's sphere interval [s0, s1] (irrational ends, compared through
   f(t) = |O + t D - C|^2 - r^2, which is a ((t - t_mid)^2 - h^2)) and the
   box's [b0, b1]. Less the box it is empty iff b0 <= s0 and s1 <= b1;
   their intersection is empty iff b1 <= s0 or s1 <= b0; their union iff
   both are. `Edge where a comparison is within [64 u] of the larger
   parameter (the roots' stated bounds are a few u). *)
let sphere_box_class op (s : Sphere.t) (b : Box.t) ~origin ~direction =
  let o = qv origin and d = qv direction and c = qv s.center in
  let f = qsub o c in
  let a = dot d d and bb = dot f d and cc = Q.(sub (dot f f) (mul (q s.radius) (q s.radius))) in
  let fq t = Q.(add (add (mul a (mul t t)) (mul (of_int 2) (mul bb t))) cc) in
  let t_mid = Q.(neg (div bb a)) in
  let h2 = Q.(div (sub (mul bb bb) (mul a cc)) (mul a a)) in
  let b0, b1 = box_interval b ~origin ~direction in
  let h = sqrt (Float.max 0. (Q.to_float h2)) and tm = Q.to_float t_mid in
  let s0 = tm -. h and s1 = tm +. h in
  let band = 64. *. u *. Float.max (Float.abs s1) (Float.max (Float.abs (Q.to_float b0)) (Float.abs (Q.to_float b1))) in
  let near x y = Float.abs (x -. y) <= band in
  let fb0 = Q.to_float b0 and fb1 = Q.to_float b1 in
  let sphere = Q.gt h2 Q.zero and box = Q.lt b0 b1 in
  (* The line grazes the sphere: r^2 - dist^2 = a h^2 within the rounding
     of the distance from the center, [64 u |f|] (as the sphere's own
     exact-disk test has it). *)
  let graze = Float.abs (Q.to_float (Q.mul a h2)) <= 128. *. u *. s.radius *. sqrt (Q.to_float (dot f f)) in
  if graze || near fb0 fb1 || (sphere && box && (near fb0 s0 || near fb1 s1 || near fb0 s1 || near fb1 s0)) then `Edge
  else
    (* s0 >= x iff x <= t_mid and f(x) >= 0; s1 <= x iff x >= t_mid and f(x) >= 0. *)
    let below_s0 x = Q.leq x t_mid && Q.geq (fq x) Q.zero and above_s1 x = Q.geq x t_mid && Q.geq (fq x) Q.zero in
    let hit =
      match op with
      | Csg.Difference -> sphere && not (box && below_s0 b0 && above_s1 b1)
      | Csg.Intersection -> sphere && box && (not (below_s0 b1)) && not (above_s1 b0)
      | Csg.Union -> sphere || box
    in
    if hit then `In else `Out

(* Sphere of radius [r] at 1e7 r from the camera, minus a box that cuts
   off part of it, through a viewport that makes it about 30 pixels
   wide, translated by [translate]. *)
let tiny_far ~op ~translate =
  let r = 1e-3 in
  let dist = 1e7 *. r in
  let center = Vec3.add translate (Vec3.v (0.3 *. dist) (-0.2 *. dist) dist) in
  let s = Helpers.sphere ~center ~radius:r white in
  let b =
    Box.v ~min:(Vec3.add center (Vec3.v (0.25 *. r) (-0.4 *. r) (-2. *. r))) ~max:(Vec3.add center (Vec3.v (2. *. r) (2. *. r) (2. *. r)))
      (Material.v white)
  in
  let camera =
    match Camera.look_at ~up:(Vec3.v 0.3 1. 0.2) ~position:translate center with Ok c -> c | Error (`Msg e) -> failwith e
  in
  let scene =
    Helpers.scene ~width:90 ~height:90 ~viewport:(Viewport.v ~width:6e-7 ~height:6e-7 ~distance:1.) ~camera ~spheres:[]
      ~shapes:[ Shape.Csg (Csg.v op (Csg.Sphere s) (Csg.Box b)) ]
      ~lights:[ Light.ambient 1. ] ()
  in
  (scene, s, b)

let exact_mask (scene : Scene.t) classify =
  let w = (Scene.width scene) and h = (Scene.height scene) in
  Array.init h (fun row ->
      Array.init w (fun col ->
          let v =
            Viewport.of_canvas (Scene.viewport scene) ~canvas_width:w ~canvas_height:h (Canvas.x_of_column ~width:w col)
              (Canvas.y_of_row ~height:h row)
          in
          classify ~origin:(Scene.camera scene).position ~direction:(Camera.direction (Scene.camera scene) v)))

(* {1 The kernel on one ray} *)

(* The kernel's hit on [c] for one ray: [t], the outward normal and
   whether the ray enters, by the routines the tracer runs. *)
let kernel_hit c ~origin ~direction =
  let b = Csg.builder () in
  let root = Csg.add b ~material:(fun _ _ -> 0) c in
  let tb = Csg.table b in
  let w = Csg.work tb and s = Private.Scratch.create () in
  Private.Scratch.set_ray s origin direction;
  s.t_min <- 0.;
  if not (Csg.roots tb w s root) then None
  else begin
    let t = s.near in
    s.px <- origin.Vec3.x +. (t *. direction.Vec3.x);
    s.py <- origin.y +. (t *. direction.y);
    s.pz <- origin.z +. (t *. direction.z);
    Csg.normal tb w s;
    Some (t, Vec3.v s.nx s.ny s.nz, Csg.entering w)
  end


(* {1 Closed meshes through their edges and vertices} *)

(* The cube [-1, 1] x [-1, 1] x [4, 8] as a mesh of 12 triangles (each face
   cut along a diagonal), and as the half-spaces [n . p <= b] that make it. *)
let cube_arrays () =
  let positions =
    Array.concat
      (List.map
         (fun (x, y, z) -> [| x; y; z |])
         [ (-1., -1., 4.); (1., -1., 4.); (1., 1., 4.); (-1., 1., 4.); (-1., -1., 8.); (1., -1., 8.); (1., 1., 8.); (-1., 1., 8.) ])
  in
  let quads = [ (0, 3, 2, 1); (4, 5, 6, 7); (0, 1, 5, 4); (3, 7, 6, 2); (0, 4, 7, 3); (1, 2, 6, 5) ] in
  let triangles = Array.of_list (List.concat_map (fun (a, b, c, d) -> [ a; b; c; a; c; d ]) quads) in
  (positions, triangles)

let cube_planes = [ ((1., 0., 0.), 1.); ((-1., 0., 0.), 1.); ((0., 1., 0.), 1.); ((0., -1., 0.), 1.); ((0., 0., 1.), 8.); ((0., 0., -1.), -4.) ]

(* The octahedron of [octahedron (Vec3.v 0. 0. 4.) 1.]: |x| + |y| + |z - 4| <= 1. *)
let octahedron_planes =
  List.concat_map
    (fun sx -> List.concat_map (fun sy -> List.map (fun sz -> ((sx, sy, sz), 1. +. (4. *. sz))) [ 1.; -1. ]) [ 1.; -1. ])
    [ 1.; -1. ]

let mesh_solid (positions, triangles) =
  match
    Mesh.v ~positions ~triangles ~normals:[||] ~triangle_normals:(Array.make (Array.length triangles) (-1)) (Material.v white)
  with
  | Ok m -> Csg.Mesh m
  | Error (`Msg e) -> Alcotest.fail e

(* The exact line [origin + t direction] against the convex solid of
   [planes]: `In if it passes through its inside, `Touch if it meets only
   its surface, `Out if it misses it. Each half-space bounds [t] on one
   side: [a t <= c]. *)
let convex_class planes ~origin ~direction =
  let o = qv origin and d = qv direction in
  let lo = ref None and hi = ref None and parallel = ref `In in
  List.iter
    (fun ((nx, ny, nz), b) ->
      let n = (q nx, q ny, q nz) in
      let a = dot n d and c = Q.sub (q b) (dot n o) in
      let sign = Q.sign a in
      if sign = 0 then (if Q.sign c < 0 then parallel := `Out else if Q.sign c = 0 && !parallel = `In then parallel := `Touch)
      else
        let x = Q.div c a in
        if sign > 0 then hi := Some (match !hi with Some h -> Q.min h x | None -> x)
        else lo := Some (match !lo with Some l -> Q.max l x | None -> x))
    planes;
  match (!parallel, !lo, !hi) with
  | `Out, _, _ -> `Out
  | p, Some l, Some h -> if Q.lt h l then `Out else if Q.equal l h || p = `Touch then `Touch else `In
  | p, _, _ -> p

let csg_mask ?(classify = Fun.id) (scene : Scene.t) planes =
  exact_mask scene (fun ~origin ~direction ->
      match convex_class planes ~origin ~direction with `In -> `In | `Out -> `Out | `Touch -> classify `Out)

(* Of a 64 x 64 canvas through the default viewport: every pixel's ray is
   [(x / 64, y / 64, 1)], exact, and so is everything the triangle test
   computes from these corners, small integers: the rays through the
   edges and corners in the picture pass through them exactly. *)
let through_edges shapes =
  Helpers.scene ~width:64 ~height:64 ~spheres:[] ~shapes
    ~lights:[ Light.ambient 0.3; Light.directional 0.7 (Vec3.v 1. 2. (-3.)) ]
    ()

let count_class cls mask = Array.fold_left (Array.fold_left (fun n c -> if c = cls then n + 1 else n)) 0 mask


(* A union of [n] spheres of radius 0.1 in a row across the view at z = 4,
   seen on an 8 x 8 canvas by ambient light alone: every camera ray meets
   the solid's bounds, and a union tests every leaf. *)
let row_of_spheres n =
  let leaf i = sphere (Vec3.v (-0.5 +. (Float.of_int i /. Float.of_int n)) 0. 4.) 0.1 in
  let rec tree lo hi = if hi - lo = 1 then leaf lo else let mid = (lo + hi) / 2 in Csg.Csg (Csg.v Csg.Union (tree lo mid) (tree mid hi)) in
  let c = match tree 0 n with Csg.Csg c -> c | _ -> assert false in
  Helpers.scene ~width:8 ~height:8 ~depth:0 ~spheres:[] ~shapes:[ Shape.Csg c ] ~lights:[ Light.ambient 1. ] ()


(* A torus knot of [2 segments 12] triangles, closed, at z = 4. *)
let knot segments =
  let o = Mesh.Gen.torus_knot ~p:2 ~q:3 ~radius:1. ~tube:0.15 ~segments ~sides:12 in
  match
    Mesh.v ~translate:(Vec3.v 0. 0. 4.) ~positions:o.positions ~triangles:o.triangles ~normals:[||]
      ~triangle_normals:(Array.make (Array.length o.triangles) (-1)) (Material.v (Color.v 230. 150. 40.))
  with
  | Ok m -> m
  | Error (`Msg m) -> Alcotest.fail m

let stats (s : Scene.t) = match Helpers.render s with Ok (_, st) -> st | Error (`Msg m) -> Alcotest.fail m
let load_octahedron _ =
  let positions, triangles = octahedron_arrays (Vec3.v 0. 0. 0.) 1. in
  Ok (Mesh.Obj.v ~positions ~normals:[||] ~triangles ~triangle_normals:(Array.make (Array.length triangles) (-1)))

let open_mesh _ =
  Ok
    (Mesh.Obj.v ~positions:[| 0.; 0.; 0.; 1.; 0.; 0.; 0.; 1.; 0.; 0.; 0.; 1. |] ~normals:[||]
       ~triangles:[| 0; 1; 2; 0; 1; 3; 0; 2; 3 |] ~triangle_normals:(Array.make 9 (-1)))

let parse ?(load_mesh = load_octahedron) text = Scene_file.of_string ~load_mesh ~file:"t.scene" text

let tests =
  [
    Alcotest.test_case "csg forms of every kind read, print back and read again as the same scene" `Quick (fun () ->
        let text =
          {|(csg difference (sphere (center 0 0 4) (radius 1) (color 255 0 0))
                (box (min 0 0 3) (max 2 2 5) (color 0 255 0)))
            (csg union (csg intersection (sphere (center 0 0 4) (radius 1.5) (color 1 2 3) (specular 10))
                                          (mesh (file "octa.obj") (scale 2) (translate 0 0 4) (color 9 9 9) (reflective 0.5)))
                       (box (min -3 -3 3) (max -2 -2 4) (color 4 5 6)))|}
        in
        match parse text with
        | Error (`Msg m) -> Alcotest.fail m
        | Ok v -> (
            let s = Scene.of_valid v in
            Alcotest.(check int) "two shapes" 2 (List.length (Scene.shapes s));
            (match (Scene.shapes s) with
            | Shape.Csg { op = Csg.Difference; a = Csg.Sphere sp; b = Csg.Box bx } :: _ ->
                Alcotest.(check (float 0.)) "sphere radius" 1. sp.radius;
                Alcotest.(check (float 0.)) "box's green" 255. bx.material.color.g
            | _ -> Alcotest.fail "the first csg is not (difference sphere box)");
            let printed = Scene_file.to_string s in
            match parse printed with
            | Error (`Msg m) -> Alcotest.failf "the printed scene does not read back: %s\n%s" m printed
            | Ok v' ->
                if not (List.equal Shape.equal (Scene.shapes s) (Scene.shapes (Scene.of_valid v'))) then
                  Alcotest.failf "the printed scene reads back different:\n%s" printed));
    Alcotest.test_case "bad csg forms are refused with their file:line:column" `Quick (fun () ->
        List.iter
          (fun (what, load_mesh, text, expected) ->
            match parse ~load_mesh text with
            | Ok _ -> Alcotest.failf "%s: accepted" what
            | Error (`Msg m) ->
                let contains sub =
                  let n = String.length sub in
                  let rec go i = i + n <= String.length m && (String.sub m i n = sub || go (i + 1)) in
                  go 0
                in
                if not (contains expected) then Alcotest.failf "%s: %S does not contain %S" what m expected)
          [
            ( "a plane operand", load_octahedron,
              "(csg union (sphere (center 0 0 4) (radius 1) (color 1 1 1))\n (plane (point 0 0 0) (normal 0 1 0) (color 1 1 1)))",
              "t.scene:2:2: csg: a plane is not a closed solid" );
            ( "a triangle operand", load_octahedron,
              "(csg union (triangle (vertices (0 0 4) (1 0 4) (0 1 4)) (color 1 1 1)) (sphere (center 0 0 4) (radius 1) (color 1 1 1)))",
              "t.scene:1:12: csg: a triangle is not a closed solid" );
            ( "an unknown operation", load_octahedron,
              "(csg unoin (sphere (center 0 0 4) (radius 1) (color 1 1 1)) (sphere (center 0 0 4) (radius 1) (color 1 1 1)))",
              "t.scene:1:6: unknown csg operation unoin" );
            ("one operand", load_octahedron, "(csg union (sphere (center 0 0 4) (radius 1) (color 1 1 1)))", "t.scene:1:1: csg union takes 2 solids, got 1");
            ("no operation", load_octahedron, "(csg)", "t.scene:1:1: csg: expected an operation first");
            ( "an open mesh", open_mesh,
              "(csg difference (sphere (center 0 0 4) (radius 1) (color 1 1 1))\n   (mesh (file \"open.obj\") (color 1 1 1)))",
              "t.scene:2:4: csg: mesh \"open.obj\" is not a closed solid" );
            ( "a bad operand's field", load_octahedron,
              "(csg union (sphere (center 0 0 4) (radius -1) (color 1 1 1)) (sphere (center 0 0 4) (radius 1) (color 1 1 1)))",
              "t.scene:1:" );
            ( "too deep",
              load_octahedron,
              (let leaf = "(sphere (center 0 0 4) (radius 1) (color 1 1 1))" in
               let rec nest n = if n = 0 then leaf else Printf.sprintf "(csg union %s %s)" (nest (n - 1)) leaf in
               nest 40),
              "csg nested deeper than 32 levels" );
          ]);
    Alcotest.test_case "raytrace render refuses a bad csg form: one located line, status 1, no output file" `Quick
      (fun () ->
        let dir = Helpers.temp_dir () in
        let scene = Filename.concat dir "bad.scene" and out = Filename.concat dir "out.ppm" in
        let oc = open_out scene in
        output_string oc
          "(canvas (width 8) (height 8))\n(csg union (sphere (center 0 0 4) (radius 1) (color 1 1 1))\n  (plane (point 0 0 0) (normal 0 1 0) (color 1 1 1)))\n";
        close_out oc;
        let code, stdout, stderr = Helpers.run (Helpers.raytrace ()) [ "render"; scene; "-o"; out ] in
        Alcotest.(check int) "exit status" 1 code;
        Alcotest.(check string) "nothing on stdout" "" stdout;
        Alcotest.(check string) "one line"
          (Printf.sprintf "raytrace: %s:3:3: csg: a plane is not a closed solid; an operand is a sphere, box, %sclosed mesh, csg, or a transform or use of one\n" scene
             (* The described closed kinds join the list of operands. *)
             (String.concat ""
                (List.filter_map
                   (fun (Private.Shape_desc.Any d) -> if Private.Kind.closed d.kind then Some (d.name ^ ", ") else None)
                   Private.Primitives.all)))
          stderr;
        Alcotest.(check bool) "no output file" false (Sys.file_exists out));
    Alcotest.test_case "random CSG scenes: the kernel's colours are the literal algorithm's, to rounding" `Quick
      (fun () ->
        let rand = Random.State.make [| 14 |] in
        for i = 1 to 120 do
          let s = random_scene ~epsilon:0.001 rand in
          (match Scene.validate s with Error (`Msg m) -> Alcotest.failf "scene %d invalid: %s" i m | Ok _ -> ());
          if not (Helpers.oracle_floats s) then Alcotest.failf "scene %d differs:\n%s" i (Scene_file.to_string s)
        done;
        (* The lens's rim, where both spheres are crossed at the same t:
           the point is the first sphere's in both. *)
        List.iter
          (fun name ->
            let s = Scene.with_overrides ~width:40 ~height:40 (Helpers.load_scene name) in
            if not (Helpers.oracle_floats (Scene.with_overrides ~epsilon:(Some 0.001) s)) then Alcotest.failf "%s differs" name)
          [ "lens.scene"; "die.scene" ]);
    Alcotest.test_case "random CSG scenes with glass and checkered leaves: the kernel's colours are the literal algorithm's"
      `Quick (fun () ->
        let rand = Random.State.make [| 1414 |] in
        let glassy = ref 0 and checkered = ref 0 in
        let count n (s : Scene.t) p = if List.exists (fun sh -> List.exists p (Shape.materials sh)) (Scene.shapes s) then incr n in
        for i = 1 to 120 do
          let s = random_scene ~glass:true ~epsilon:0.001 rand in
          (match Scene.validate s with Error (`Msg m) -> Alcotest.failf "scene %d invalid: %s" i m | Ok _ -> ());
          count glassy s (fun m -> m.transparency > 0.);
          count checkered s (fun m -> m.pattern <> None);
          if not (Helpers.oracle_floats s) then Alcotest.failf "scene %d differs:\n%s" i (Scene_file.to_string s)
        done;
        if !glassy < 60 || !checkered < 60 then
          Alcotest.failf "of 120 scenes, only %d have glass and %d a checker" !glassy !checkered;
        (* The glass lens: rays cross both faces, the floor's cells seen
           through it. *)
        let s = Scene.with_overrides ~width:48 ~height:36 (Helpers.load_scene "glass-lens.scene") in
        if not (Helpers.oracle_floats (Scene.with_overrides ~epsilon:(Some 0.001) s)) then Alcotest.fail "glass-lens.scene differs");
    Alcotest.test_case "random CSG scenes with glass and checkered leaves: skips on and off give the same bytes" `Quick
      (fun () ->
        let rand = Random.State.make [| 4114 |] in
        for i = 1 to 60 do
          let epsilon = if Random.State.bool rand then Some 0.001 else None in
          let s = random_scene ~glass:true ?epsilon rand in
          if not (Image.equal (Helpers.image_exn ~skips:false s) (Helpers.image_exn ~skips:true s)) then
            Alcotest.failf "scene %d: the skips change the image:\n%s" i (Scene_file.to_string s)
        done;
        List.iter
          (fun name ->
            let s = Scene.with_overrides ~width:80 ~height:60 (Helpers.load_scene name) in
            Helpers.check_images name ~expected:(Helpers.image_exn ~skips:false s) (Helpers.image_exn ~skips:true s))
          [ "glass-lens.scene"; "glass.scene" ]);
    Alcotest.test_case "a checker on a CSG leaf (sphere, box) lies where the leaf alone shows it" `Quick (fun () ->
        let checker = Some (Pattern.checker ~size:0.3 (Color.v 20. 40. 200.)) in
        let ball =
          (Helpers.sphere ~center:(Vec3.v (-0.8) 0. 4.) ~radius:0.9 ~specular:100. ~reflective:0.2 ?pattern:checker (Color.v 230. 200. 60.))
        in
        (* No pixel's ray passes exactly through one of the cube's edges:
           there the box alone has a hit of zero length, which the CSG
           solid's intervals drop. *)
        let cube = Box.v ~min:(Vec3.v 0.35 (-0.95) 3.5) ~max:(Vec3.v 1.6 0.4 4.8) (Material.v ~specular:10. ?pattern:checker (Color.v 60. 180. 90.)) in
        (* The union with a sphere out of sight, under the floor, and the
           intersection with a sphere that holds the leaf, leave the leaf's
           surface and its pattern's frame as they are. *)
        let far = Csg.Sphere (Helpers.sphere ~center:(Vec3.v 0. (-60.) 4.) ~radius:0.1 white) in
        let around = Csg.Sphere (Helpers.sphere ~center:(Vec3.v 0. 0. 4.) ~radius:5. (Color.v 255. 0. 0.)) in
        List.iter
          (fun epsilon ->
            List.iter
              (fun (what, alone, leaf) ->
                List.iter
                  (fun (how, c) ->
                    let img shapes spheres = Helpers.image_exn (scene ?epsilon ~width:64 ~height:64 ~spheres (floor :: shapes)) in
                    let expected = match alone with `Sphere s -> img [] [ s ] | `Shape sh -> img [ sh ] [] in
                    let actual = img [ Shape.Csg c ] [] in
                    Helpers.check_images ~max_abs:1
                      (Printf.sprintf "%s, %s, %s" what how (if epsilon = None then "robust" else "epsilon"))
                      ~expected actual)
                  [ ("in a union", Csg.v Csg.Union leaf far); ("in an intersection", Csg.v Csg.Intersection leaf around) ])
              [ ("a sphere", `Sphere ball, Csg.Sphere ball); ("a box", `Shape (Shape.Box cube), Csg.Box cube) ])
          [ None; Some 0.001 ]);
    Alcotest.test_case "many CSG solids: the hierarchy over their bounds gives the bytes of testing every one" `Quick
      (fun () ->
        let rand = Random.State.make [| 41 |] in
        for i = 1 to 12 do
          (* A row of solids, each of every kind of operation, spread
             along x so that the hierarchy prunes. *)
          let shapes =
            List.init 12 (fun k ->
                let c = random_csg rand 1 in
                let shift = Vec3.v (Float.of_int (k - 6) *. 1.5) 0. (Float.of_int (k mod 3)) in
                let move = Test_numerics.transform ~scale:1. ~translate:shift in
                match Scene.objects (move (Helpers.scene ~spheres:[] ~shapes:[ Shape.Csg c ] ~lights:[] ())) with
                | [ sh ] -> sh
                | _ -> assert false)
          in
          List.iter
            (fun epsilon ->
              let camera = match Camera.look_at ~position:(Vec3.v 0. 3. (-6.)) (Vec3.v 0. 0. 4.) with Ok c -> c | Error (`Msg e) -> failwith e in
              let s = scene ?epsilon ~width:48 ~height:48 ~camera (floor :: shapes) in
              if (Helpers.prepare s).bvh = None then Alcotest.fail "no hierarchy";
              if not (Image.equal (Helpers.image_exn ~skips:false s) (Helpers.image_exn ~skips:true s)) then
                Alcotest.failf "scene %d: the hierarchy changes the image:\n%s" i (Scene_file.to_string s))
            [ None; Some 0.001 ]
        done);
    Alcotest.test_case "a sphere and a box combined, 1e7 times smaller than their distance, are their exact shape" `Quick
      (fun () ->
        List.iter
          (fun (op, translate) ->
            let scene, s, b = tiny_far ~op ~translate in
            let exact = exact_mask scene (sphere_box_class op s b) in
            let wrong, inside = Helpers.mask_errors (Test_numerics.hit_mask scene) exact in
            let edges = Array.fold_left (Array.fold_left (fun n c -> if c = `Edge then n + 1 else n)) 0 exact in
            (* The band is a few u wide: a pixel's ray lands in it by chance only. *)
            if edges > 2 then Alcotest.failf "%d pixels within the error band" edges;
            let what = Csg.op_name op ^ ", translated by " ^ Vec3.show translate in
            if inside < 100 then Alcotest.failf "%s: the shape covers only %d pixels" what inside;
            Printf.printf "%s: %d pixels inside, %d in the error band, %d wrong\n" what inside edges wrong;
            Alcotest.(check int) (what ^ ": pixels off the exact shape") 0 wrong)
          (List.concat_map
             (fun op -> [ (op, Vec3.zero); (op, Vec3.v 1e6 (-1e6) 1e6) ])
             [ Csg.Difference; Csg.Intersection; Csg.Union ]));
    Alcotest.test_case
      "a closed mesh as a CSG operand, seen through its shared edges and corners, is its exact solid: no seam, no lost pixel"
      `Quick (fun () ->
        let big = box (Vec3.v (-10.) (-10.) 0.) (Vec3.v 10. 10. 20.) in
        List.iter
          (fun (name, mesh, planes, min_in) ->
            let scene = through_edges [ Shape.Csg (Csg.v Csg.Intersection mesh big) ] in
            let exact = csg_mask scene planes in
            let wrong, inside = Helpers.mask_errors (Test_numerics.hit_mask scene) exact in
            Printf.printf "%s: %d pixels inside, %d wrong\n" name inside wrong;
            if inside < min_in then Alcotest.failf "%s covers only %d pixels" name inside;
            Alcotest.(check int) (name ^ " in a CSG: pixels off the exact solid") 0 wrong;
            (* Alone, the mesh is its closest hits: the rays that only touch
               its surface may see it or not. *)
            let alone = through_edges [ (match mesh with Csg.Mesh m -> Shape.Mesh m | _ -> assert false) ] in
            let wrong, _ = Helpers.mask_errors (Test_numerics.hit_mask alone) (csg_mask ~classify:(fun _ -> `Edge) alone planes) in
            Alcotest.(check int) (name ^ " alone: pixels off the exact solid") 0 wrong)
          [
            ("the cube", mesh_solid (cube_arrays ()), cube_planes, 900);
            ("the octahedron", octahedron (Vec3.v 0. 0. 4.) 1., octahedron_planes, 200);
          ];
        (* The cube as a box: the same solid, the same picture, byte for byte
           (the front face's diagonal, crossed by 31 rays, included). *)
        let as_mesh = through_edges [ Shape.Csg (Csg.v Csg.Intersection (mesh_solid (cube_arrays ())) big) ] in
        let as_box = through_edges [ Shape.Csg (Csg.v Csg.Intersection (box (Vec3.v (-1.) (-1.) 4.) (Vec3.v 1. 1. 8.)) big) ] in
        Helpers.check_images "the cube as a mesh and as a box" ~expected:(Helpers.image_exn as_box) (Helpers.image_exn as_mesh));
    Alcotest.test_case "a ray through a closed mesh's shared edge or corner crosses it once; one that touches it, zero or twice"
      `Quick (fun () ->
        let cube = mesh_solid (cube_arrays ()) and octa = octahedron (Vec3.v 0. 0. 4.) 1. in
        let crossings solid ~direction =
          match solid with
          | Csg.Mesh m ->
              List.length
                (List.filter
                   (fun k -> Triangle.crossing (Mesh.triangle m k) ~origin:Vec3.zero ~direction < infinity)
                   (List.init (Mesh.triangle_count m) Fun.id))
          | _ -> assert false
        in
        List.iter
          (fun (what, solid, direction, expected) ->
            Alcotest.(check int) what expected (crossings solid ~direction))
          [
            ("cube: through the front face's diagonal", cube, Vec3.v 0.125 0.125 1., 2);
            ("cube: out through a back corner (3 faces, 6 triangles)", cube, Vec3.v 0.125 (-0.125) 1., 2);
            ("cube: out through a side face's diagonal", cube, Vec3.v (9. /. 64.) (5. /. 64.) 1., 2);
            ("cube: touching a front corner", cube, Vec3.v 0.25 0.25 1., 0);
            ("cube: touching a front edge", cube, Vec3.v 0.25 0.125 1., 0);
            ("octahedron: through both corners on its axis (4 triangles each)", octa, Vec3.oz, 2);
            ("octahedron: through two opposite edges", octa, Vec3.v 0.125 0. 1., 2);
            ("octahedron: touching a corner of its silhouette", octa, Vec3.v 0.25 0. 1., 0);
          ];
        (* Any ray, any closed mesh: an even number. *)
        let rand = Random.State.make [| 29 |] in
        for _ = 1 to 2000 do
          let g () = Float.of_int (Random.State.int rand 9 - 4) /. 16. in
          let direction = Vec3.v (g ()) (g ()) 1. in
          List.iter
            (fun solid ->
              let n = crossings solid ~direction in
              if n mod 2 = 1 then Alcotest.failf "%d crossings along %s" n (Vec3.show direction))
            [ cube; octa ]
        done);
    Alcotest.test_case "every CSG leaf test is counted: --stats tells them, the work bound stops a render of many leaves"
      `Quick (fun () ->
        let scene = row_of_spheres 64 in
        let st = stats scene in
        (* 64 camera rays, each through all 64 leaves of the union; the
           pixels that see it test them again for the normal. *)
        if st.tests < 64 * 64 then Alcotest.failf "%d tests counted for 64 rays through 64 leaves each" st.tests;
        let limits = Limits.with_bound Limits.default `Work 2000. in
        match Helpers.render ~limits ~jobs:1 scene with
        | Ok _ -> Alcotest.fail "rendered past a bound of 2000 tests"
        | Error (`Msg m) ->
            let suffix = "(set RAYTRACE_MAX_WORK to raise it)" in
            Alcotest.(check string) ("names the variable: " ^ m) suffix
              (String.sub m (max 0 (String.length m - String.length suffix)) (min (String.length m) (String.length suffix))));
    Alcotest.test_case "CSG trees of 2^18 leaves, balanced or nested, load, render or are refused at their position" `Slow
      (fun () ->
        let limits = Limits.with_bound Limits.default `Form_bytes 1e9 in
        let leaf = "(sphere (center 0 0 9) (radius 1) (color 255 0 0))" in
        let b = Buffer.create (1 lsl 24) in
        let rec tree depth = if depth = 0 then Buffer.add_string b leaf else begin
            Buffer.add_string b "(csg union ";
            tree (depth - 1);
            Buffer.add_char b ' ';
            tree (depth - 1);
            Buffer.add_char b ')' end
        in
        Buffer.add_string b "(canvas (width 1) (height 1)) (light ambient (intensity 1))\n";
        tree 18;
        (* The passes over its leaves (materials, preparation, the kernel's
           table) overflowed the stack. *)
        (match Helpers.of_string ~limits (Buffer.contents b) with
        | Error (`Msg m) -> Alcotest.fail m
        | Ok scene -> (
            match Helpers.render ~limits ~jobs:1 scene with
            | Error (`Msg m) -> Alcotest.fail m
            | Ok (img, st) ->
                Alcotest.(check (list int)) "the sphere, red" [ 255; 0; 0 ] (let r, g, b = Image.get img 0 0 in [ r; g; b ]);
                if st.tests < 1 lsl 18 then Alcotest.failf "%d tests for 2^18 leaves" st.tests));
        Buffer.clear b;
        Buffer.add_string b "(light ambient (intensity 1))\n";
        for _ = 1 to 1 lsl 18 do Buffer.add_string b "(csg union " done;
        Buffer.add_string b leaf;
        for _ = 1 to 1 lsl 18 do Buffer.add_string b (" " ^ leaf ^ ")") done;
        (* Refused at the 33rd (csg: the search for that position recursed as
           deep as the nesting, overflowed, and put the error at 1:1. *)
        match Helpers.of_string ~limits ~file:"deep.scene" (Buffer.contents b) with
        | Ok _ -> Alcotest.fail "a CSG nested 2^18 deep was accepted"
        | Error (`Msg m) -> Alcotest.(check string) "the message" "deep.scene:2:353: csg nested deeper than 32 levels" m);
    Alcotest.test_case "a big closed mesh as a CSG operand is searched through a hierarchy, with the literal algorithm's colours"
      `Quick (fun () ->
        let big = box (Vec3.v (-10.) (-10.) 0.) (Vec3.v 10. 10. 20.) in
        let on m = scene ~epsilon:0.001 ~width:16 ~height:16 [ Shape.Csg (Csg.v Csg.Intersection (Csg.Mesh m) big) ] in
        (* 48000 triangles: every camera ray's line meets the knot's box,
           and a test of every triangle would be 48000 a ray. *)
        let st = stats (on (knot 2000)) in
        let per_ray = st.tests / st.primary in
        Printf.printf "%d tests, %d box tests, %d rays\n" st.tests st.box_tests (Render.Stats.rays st);
        if st.tests > 2000 * Render.Stats.rays st then Alcotest.failf "%d tests a ray for 48000 triangles" per_ray;
        if st.box_tests = 0 then Alcotest.fail "no box test counted";
        (* Small enough for the oracle: the same colours, float for float. *)
        Alcotest.(check bool) "the literal algorithm's colours" true (Helpers.oracle_floats (on (knot 40))));
    Alcotest.test_case "a mesh operand's hierarchy misses no crossing: rays from near and far find the literal first crossing"
      `Quick (fun () ->
        let c = Csg.v Csg.Difference (Csg.Mesh (knot 100)) (sphere (Vec3.v 0.5 0.5 4.) 0.3) in
        let rand = Random.State.make [| 2029 |] in
        let misses = ref 0 and hits = ref 0 in
        for i = 1 to 3000 do
          (* Origins from 2 to 2e6 away, aimed at points of the knot's box,
             some exactly at its corners' coordinates. *)
          let far = 10. ** Float.of_int (i mod 7) in
          let g () = (Random.State.float rand 2. -. 1.) *. far in
          let origin = Vec3.v (g ()) (g ()) (4. +. g ()) in
          let target = Vec3.v (Random.State.float rand 2.6 -. 1.3) (Random.State.float rand 2.6 -. 1.3) (4. +. Random.State.float rand 0.6 -. 0.3) in
          let direction = Vec3.sub target origin in
          let kernel = kernel_hit c ~origin ~direction and literal = Csg.literal_hit c ~origin ~direction ~t_min:0. ~t_max:infinity in
          match (kernel, literal) with
          | None, None -> incr misses
          | Some (t, n, _), Some (t', _, n') when t = t' && Vec3.equal n n' -> incr hits
          | _ ->
              Alcotest.failf "ray %d from %s along %s: kernel %s, literal %s" i (Vec3.show origin) (Vec3.show direction)
                (match kernel with Some (t, _, _) -> Printf.sprintf "%h" t | None -> "none")
                (match literal with Some (t, _, _) -> Printf.sprintf "%h" t | None -> "none")
        done;
        if !hits < 1000 || !misses < 300 then Alcotest.failf "%d hits, %d misses: not a test of both" !hits !misses);
    Alcotest.test_case "closedness: edges by coordinates (repeated vertices, -0 and 0 one point), the first bad edge named" `Quick
      (fun () ->
        let mesh positions triangles =
          match
            Mesh.v ~source:"m.obj" ~positions ~triangles ~normals:[||]
              ~triangle_normals:(Array.make (Array.length triangles) (-1)) (Material.v white)
          with
          | Ok m -> m
          | Error (`Msg e) -> Alcotest.fail e
        in
        let corners = [| (0., 0., 0.); (1., 0., 0.); (0., 1., 0.); (0., 0., 1.) |] in
        let faces = [ (0, 2, 1); (0, 1, 3); (0, 3, 2); (1, 2, 3) ] in
        (* A tetrahedron whose faces each repeat their corners, the first
           corner written -0 in one face. *)
        let positions =
          Array.concat
            (List.mapi
               (fun f (a, b, c) ->
                 Array.concat
                   (List.map
                      (fun v ->
                        let x, y, z = corners.(v) in
                        if f = 1 && v = 0 then [| -0.; -0.; -0. |] else [| x; y; z |])
                      [ a; b; c ]))
               faces)
        in
        let triangles = Array.init 12 Fun.id in
        Alcotest.(check bool) "closed" true (Csg.check_closed (mesh positions triangles) = Ok ());
        (* Without its last face: three edges border one triangle each. *)
        (match Csg.check_closed (mesh (Array.sub positions 0 27) (Array.init 9 Fun.id)) with
        | Ok () -> Alcotest.fail "an open mesh is closed"
        | Error (`Msg m) ->
            Alcotest.(check string) "the message"
              "csg: mesh \"m.obj\" is not a closed solid: its edge from (0 1 0) to (1 0 0) borders 1 triangle, not 2" m);
        (* A fifth triangle on an edge: three triangles there. *)
        let positions = Array.append positions [| 1.; 0.; 0.; 0.; 1.; 0.; 1.; 1.; 1. |] in
        match Csg.check_closed (mesh positions (Array.init 15 Fun.id)) with
        | Ok () -> Alcotest.fail "an edge of three triangles is closed"
        | Error (`Msg m) ->
            Alcotest.(check string) "the message"
              "csg: mesh \"m.obj\" is not a closed solid: its edge from (0 1 0) to (1 0 0) borders 3 triangles, not 2" m);
    Alcotest.test_case "the surface of a subtracted solid faces into the cavity; hits say whether they enter" `Quick
      (fun () ->
        let o = Vec3.zero and d = Vec3.oz in
        let c = Csg.v Csg.Difference (box (Vec3.v (-1.) (-1.) 3.) (Vec3.v 1. 1. 5.)) (sphere (Vec3.v 0. 0. 3.) 0.5) in
        (match kernel_hit c ~origin:o ~direction:d with
        | Some (t, n, entering) ->
            Alcotest.(check (float 1e-12)) "enters the box at the cavity's far wall" 3.5 t;
            Alcotest.(check Helpers.vec3) "the cavity's wall faces the cavity (toward -z)" (Vec3.v 0. 0. (-1.)) n;
            Alcotest.(check bool) "entering" true entering
        | None -> Alcotest.fail "no hit");
        (* From inside the solid: the ray leaves it through the cavity's wall. *)
        (match kernel_hit c ~origin:(Vec3.v 0. 0. 4.5) ~direction:(Vec3.neg d) with
        | Some (t, n, entering) ->
            Alcotest.(check (float 1e-12)) "leaves at the cavity's wall" 1. t;
            Alcotest.(check Helpers.vec3) "outward: into the cavity, along the ray" (Vec3.v 0. 0. (-1.)) n;
            Alcotest.(check bool) "leaving" false entering
        | None -> Alcotest.fail "no hit from inside");
        (* The literal algorithm says the same. *)
        match Csg.literal_hit c ~origin:o ~direction:d ~t_min:0. ~t_max:infinity with
        | Some (t, _, n) ->
            Alcotest.(check (float 1e-12)) "literal t" 3.5 t;
            Alcotest.(check Helpers.vec3) "literal normal" (Vec3.v 0. 0. (-1.)) n
        | None -> Alcotest.fail "literal: no hit");
    Alcotest.test_case "each surface point shows the material of the solid it belongs to" `Quick (fun () ->
        let red = Color.v 255. 0. 0. and green = Color.v 0. 255. 0. in
        let c = Csg.v Csg.Difference (sphere ~color:red (Vec3.v 0. 0. 4.) 1.) (box ~color:green (Vec3.v 0. (-2.) 2.) (Vec3.v 2. 2. 3.8)) in
        let s = Helpers.scene ~width:21 ~height:21 ~spheres:[] ~shapes:[ Shape.Csg c ] ~lights:[ Light.ambient 1. ] () in
        let tr = Trace.create (Helpers.prepare s) in
        (* Left of center: the sphere's own surface; right of it, where the
           box took the front away: the cut, the box's far face. *)
        Trace.pixel tr (-5) 0;
        Alcotest.(check (list (float 0.))) "the sphere's part is red" [ 255.; 0.; 0. ] [ Trace.red tr; Trace.green tr; Trace.blue tr ];
        Trace.pixel tr 3 0;
        Alcotest.(check (list (float 0.))) "the cut is green" [ 0.; 255.; 0. ] [ Trace.red tr; Trace.green tr; Trace.blue tr ];
        Trace.pixel tr 9 9;
        Alcotest.(check (list (float 0.))) "beyond: the background" [ 0.; 0.; 0. ] [ Trace.red tr; Trace.green tr; Trace.blue tr ]);
    Alcotest.test_case "shadows: a slab with a hole casts a shadow with a lit hole in it, in both modes" `Quick
      (fun () ->
        let slab = box (Vec3.v (-2.) 0. (-2.)) (Vec3.v 2. 0.2 2.) and hole = sphere (Vec3.v 0. 0.1 0.) 0.6 in
        let floor = Shape.Plane (Plane.v ~point:(Vec3.v 0. (-1.) 0.) ~normal:Vec3.oy (Material.v white)) in
        let camera = match Camera.look_at ~position:(Vec3.v 0. (-0.5) (-3.)) (Vec3.v 0. (-1.) 0.) with Ok c -> c | Error (`Msg e) -> failwith e in
        List.iter
          (fun epsilon ->
            let s =
              Helpers.scene ~width:41 ~height:41 ?epsilon ~camera ~spheres:[]
                ~shapes:[ floor; Shape.Csg (Csg.v Csg.Difference slab hole) ]
                ~lights:[ Light.directional 1. Vec3.oy ] ()
            in
            let tr = Trace.create (Helpers.prepare s) in
            (* The floor point right under the hole, and one under the slab. *)
            let lit = Trace.cast tr ~from:(-1) (Vec3.v 0. (-1.) 0.) Vec3.oy in
            let dark = Trace.cast tr ~from:(-1) (Vec3.v 1.5 (-1.) 0.) Vec3.oy in
            Alcotest.(check int) "through the hole: nothing" (-1) lit;
            Alcotest.(check int) "under the slab: the csg" 1 dark;
            if epsilon <> None && not (Helpers.oracle_floats s) then Alcotest.fail "the oracle disagrees")
          [ None; Some 0.001 ]);
    Alcotest.test_case "no acne: a CSG sphere renders as the plain sphere, robust, scaled 1e-6 to 1e6 and moved by 1e6"
      `Quick (fun () ->
        let ball = Helpers.sphere ~center:(Vec3.v 0. 0. 4.) ~radius:1. ~specular:100. ~reflective:0.3 (Color.v 200. 100. 50.) in
        (* The union with a sphere out of sight, under the floor, leaves the
           ball's surface. *)
        let far = Csg.Sphere (Helpers.sphere ~center:(Vec3.v 0. (-60.) 4.) ~radius:0.1 white) in
        List.iter
          (fun (scale, translate) ->
            let t s = Test_numerics.transform ~scale ~translate s in
            let plain = t (scene ~width:48 ~height:48 ~spheres:[ ball ] [ floor ]) in
            let csg = t (scene ~width:48 ~height:48 [ floor; Shape.Csg (Csg.v Csg.Union (Csg.Sphere ball) far) ]) in
            Helpers.check_images ~max_abs:1
              (Printf.sprintf "scale %g, moved by %s" scale (Vec3.show translate))
              ~expected:(Helpers.image_exn plain) (Helpers.image_exn csg))
          [ (1., Vec3.zero); (1e-6, Vec3.zero); (1e6, Vec3.zero); (1., Vec3.v 1e6 (-1e6) 1e6) ]);
    Alcotest.test_case "a CSG scene, opaque or glass, allocates nothing per pixel, in both modes" `Quick (fun () ->
        List.iter
          (fun name ->
            let s = Helpers.load_scene name in
            List.iter
              (fun epsilon ->
                let s = Scene.with_overrides ~width:64 ~height:48 (Scene.with_overrides ~epsilon s) in
                Alcotest.(check (float 0.)) (name ^ ": minor words") 0. (stats s).minor_words)
              [ None; Some 0.001 ])
          [ "die.scene"; "glass-lens.scene" ];
        (* A mesh operand: its hierarchy's descent, its crossings kept in order. *)
        List.iter
          (fun epsilon ->
            let s = scene ?epsilon ~width:32 ~height:32 [ floor; Shape.Csg (Csg.v Csg.Difference (Csg.Mesh (knot 200)) (sphere (Vec3.v 0. 0. 3.5) 0.6)) ] in
            Alcotest.(check (float 0.)) "a knot less a sphere: minor words" 0. (stats s).minor_words)
          [ None; Some 0.001 ]);
  ]
