(* Transformed CSG operands (issue 26, item 3: a sphere cut by a rotated
   box): the fast tracer against the literal oracle, which carries the
   ray into each operand's frame by its own inverse matrices; a quarter-
   turned operand against the same box built in place, byte for byte
   (quarter turns are exact); scene text read, printed and read back; an
   open object refused as an operand with a located line; nothing
   allocated per ray. *)
open Raytrace
module Transform = Shape.Transform

let v = Vec3.v
let mat c = Material.v ~specular:50. c
let red = mat (Color.v 230. 40. 40.)
let blue = mat (Color.v 40. 60. 230.)
let green = mat (Color.v 40. 200. 60.)
let grey = Material.v (Color.v 200. 200. 200.)
let glass = Material.v ~specular:300. ~transparency:0.8 ~refractive_index:1.5 (Color.v 240. 240. 250.)
let transform ops = match Transform.v ops with Ok t -> t | Error (`Msg m) -> Alcotest.fail m
let lights = [ Light.ambient 0.2; Light.point 0.6 (v 2. 3. 0.); Light.directional 0.2 (v 1. 4. (-2.)) ]

let scene ?epsilon ?(width = 48) ?(height = 36) shapes =
  Scene.v ~width ~height ?epsilon ~objects:(Shape.Plane (Plane.v ~point:(v 0. (-2.) 0.) ~normal:(v 0. 1. 0.) grey) :: shapes) ~lights ()

let parse = Helpers.parse_ok

let error = Helpers.parse_error

let stats (s : Scene.t) = match Helpers.render s with Ok (_, st) -> st | Error (`Msg m) -> Alcotest.fail m
let sphere c r m = Csg.Sphere (Sphere.v ~center:c ~radius:r m)
let box lo hi m = Csg.Box (Box.v ~min:lo ~max:hi m)

(* A closed cube of 12 triangles, [lo, hi]. *)
let cube_mesh (lo : Vec3.t) (hi : Vec3.t) m =
  let positions = Array.concat (List.init 8 (fun k -> [| (if k land 1 = 0 then lo.x else hi.x); (if k land 2 = 0 then lo.y else hi.y); (if k land 4 = 0 then lo.z else hi.z) |])) in
  let quad a b c d = [| a; b; c; a; c; d |] in
  let triangles = Array.concat [ quad 0 2 3 1; quad 4 5 7 6; quad 0 1 5 4; quad 2 6 7 3; quad 0 4 6 2; quad 1 3 7 5 ] in
  match Mesh.v ~positions ~triangles ~normals:[||] ~triangle_normals:(Array.make 36 (-1)) m with Ok m -> m | Error (`Msg e) -> Alcotest.fail e

(* A union whose every ray through its box is carried into a closed
   mesh operand's frame. *)
let wide () =
  Csg.v Csg.Union (sphere (v (-2.5) (-1.) 7.) 0.3 green)
    (Csg.placed (transform [ Rotate_y 20.; Translate (v 2.5 1. 7.) ]) (Csg.Mesh (cube_mesh (v (-0.3) (-0.3) (-0.3)) (v 0.3 0.3 0.3) red)))

(* Union, intersection and difference with rotated, scaled and nested
   transformed operands of every closed kind the library builds here:
   spheres, boxes, a closed mesh, a CSG solid, a capped cylinder (by
   scene text below), with a material of their own or not; a mesh beside
   them at the top level, whose triangle tests read the ray's shear after
   the CSG solids changed it. *)
let solids () =
  let rot_box = Csg.placed (transform [ Rotate_y 30.; Rotate_x 20.; Translate (v (-1.6) 0.6 7.) ]) (box (v (-0.8) (-0.3) (-0.8)) (v 0.8 0.3 0.8) blue) in
  let cut =
    Csg.v Csg.Difference (sphere (v (-1.6) 0.4 7.) 1. red) rot_box
  in
  let ellipsoid = Csg.placed (transform [ Scale (v 1.4 0.5 0.7); Rotate_z 25.; Translate (v 1.5 0.3 7.) ]) (sphere Vec3.zero 1. green) in
  let meet = Csg.v Csg.Intersection ellipsoid (Csg.placed ~material:blue (transform [ Rotate (v 1. 1. 0., 35.); Translate (v 1.5 0.3 7.) ]) (Csg.Mesh (cube_mesh (v (-0.6) (-0.6) (-0.6)) (v 0.6 0.6 0.6) red))) in
  let inner = Csg.v Csg.Difference (box (v (-0.5) (-0.5) (-0.5)) (v 0.5 0.5 0.5) red) (sphere (v 0. 0. (-0.5)) 0.4 blue) in
  let nested =
    Csg.v Csg.Union
      (Csg.placed (transform [ Rotate_x 40.; Translate (v 0. (-0.6) 5.5) ]) (Csg.placed (transform [ Scale (v 1. 1.5 1.); Rotate_y 30. ]) (Csg.Csg inner)))
      (sphere (v 0.6 (-0.6) 5.5) 0.3 green)
  in
  let lens = Csg.v Csg.Intersection (Csg.placed ~material:glass (transform [ Scale (v 1. 1. 0.4); Translate (v 0. 1.1 5.) ]) (sphere Vec3.zero 0.7 glass)) (sphere (v 0. 1.1 5.) 0.65 glass) in
  let knot scale at =
    Shape.Mesh (Mesh.of_obj ~scale ~translate:at ~source:"knot" (Mesh.Gen.torus_knot ~p:2 ~q:3 ~radius:1. ~tube:0.3 ~segments:24 ~sides:6) red |> Result.get_ok)
  in
  (* Knots before and behind the wide union. *)
  [ knot 0.4 (v 0. 0.1 4.); Shape.Csg cut; Shape.Csg meet; Shape.Csg nested; Shape.Csg lens; Shape.Csg (wide ()); knot 1.2 (v 0. 0. 10.) ]

let text_scene =
  "(canvas (width 48) (height 36))\n\
   (define peg (cylinder (base 0 -1 0) (top 0 1 0) (radius 0.3) (color 20 20 200)))\n\
   (define ring (torus (center 0 0 0) (axis 0 1 0) (major 0.6) (minor 0.2) (color 200 200 20)))\n\
   (csg difference\n\
  \  (sphere (center 0 0 4) (radius 1.2) (color 240 200 40) (specular 50))\n\
  \  (csg union\n\
  \    (transform ((rotate-y 30) (rotate-x 20) (translate 0 0.6 4)) (box (min -0.8 -0.3 -0.8) (max 0.8 0.3 0.8) (color 200 30 30)))\n\
  \    (use peg (transform ((rotate-z 90) (translate 0 0 3))) (color 30 200 30))))\n\
   (csg union (use ring (transform ((rotate-x 60) (translate 2 0 5)))) (transform ((scale 0.5 1 0.5) (translate -2 0 5)) (cone (base 0 -1 0) (top 0 1 0) (radius 0.8) (top-radius 0.2) (color 200 100 0))))\n\
   (plane (point 0 -1.5 0) (normal 0 1 0) (color 90 120 90))\n\
   (light ambient (intensity 0.2))\n\
   (light point (intensity 0.7) (position 3 4 0))"

let against_literal what s =
  List.iter
    (fun epsilon ->
      let s = Scene.with_overrides ~epsilon s in
      Helpers.check_images ~max_abs:2 what ~expected:(Private.Literal.render (Helpers.valid s)) (Helpers.image_exn s))
    [ None; Some 0.001 ]

(* The box [lo, hi] placed by quarter turns about the origin, and the same
   box built in place: its corners mapped (exactly), their extremes. *)
let quarter_turned ops (lo : Vec3.t) (hi : Vec3.t) m =
  let t = transform ops in
  let cs = List.init 8 (fun k -> Transform.point t (v (if k land 1 = 0 then lo.x else hi.x) (if k land 2 = 0 then lo.y else hi.y) (if k land 4 = 0 then lo.z else hi.z))) in
  let fold f get = List.fold_left (fun a c -> f a (get c)) (get (List.hd cs)) cs in
  let x (p : Vec3.t) = p.x and y (p : Vec3.t) = p.y and z (p : Vec3.t) = p.z in
  let wlo = v (fold Float.min x) (fold Float.min y) (fold Float.min z) and whi = v (fold Float.max x) (fold Float.max y) (fold Float.max z) in
  (Csg.placed t (box lo hi m), box wlo whi m)

let tests =
  [
    Alcotest.test_case "a transformed operand puts back the ray and the triangle test's shear" `Quick (fun () ->
        (* The traversal finds the shear once per ray and reads it after
           a CSG test: the operand's frame must not leak out. *)
        let b = Csg.builder () in
        let root = Csg.add b ~material:(fun _ _ -> 0) (wide ()) in
        let tb = Csg.table b in
        let w = Csg.work tb and s = Scratch.create () in
        Scratch.set_ray s Vec3.zero (v (2.5 /. 7.) (1. /. 7.) 1.);
        s.t_min <- 0.;
        s.sx <- 0.125;
        s.sy <- 0.25;
        s.sz <- 0.5;
        s.okx <- 1.;
        s.oky <- 2.;
        s.okz <- 3.;
        Alcotest.(check bool) "hits the cube" true (Csg.roots tb w s root);
        Alcotest.(check (list (float 0.))) "ray and shear" [ 0.; 0.; 0.; 2.5 /. 7.; 1. /. 7.; 1.; 0.125; 0.25; 0.5; 1.; 2.; 3. ]
          [ s.ox; s.oy; s.oz; s.dx; s.dy; s.dz; s.sx; s.sy; s.sz; s.okx; s.oky; s.okz ]);
    Alcotest.test_case "the fast tracer matches the literal oracle on rotated, scaled and nested operands, glass too" `Quick (fun () ->
        against_literal "library solids" (scene (solids ()));
        against_literal "scene text: a box, a cylinder, a torus and a cone placed" (parse text_scene));
    Alcotest.test_case "a quarter-turned operand is the box built in place, byte for byte" `Quick (fun () ->
        (* [Rotate_z 90; Rotate_y 180] maps (x, y, z) to (y, x, -z): the
           box lands at x 0.13..1.37, y -0.41..0.53, z 4.1..5.9, its
           faces off the pixel grid. *)
        let ops = [ Transform.Rotate_z 90.; Rotate_y 180. ] in
        let placed, built = quarter_turned ops (v (-0.41) 0.13 (-5.9)) (v 0.53 1.37 (-4.1)) blue in
        (match built with
        | Csg.Box b -> Alcotest.(check bool) "where it lands" true (Vec3.equal b.min (v 0.13 (-0.41) 4.1) && Vec3.equal b.max (v 1.37 0.53 5.9))
        | _ -> assert false);
        List.iter
          (fun (op, glassy) ->
            let ball = sphere (v 0.5 0. 5.) 1.1 (if glassy then glass else red) in
            let a = scene [ Shape.Csg (Csg.v op ball placed) ] and b = scene [ Shape.Csg (Csg.v op ball built) ] in
            List.iter
              (fun epsilon ->
                let a = Scene.with_overrides ~epsilon a and b = Scene.with_overrides ~epsilon b in
                Helpers.check_images (Csg.op_name op) ~expected:(Helpers.image_exn b) (Helpers.image_exn a))
              [ None; Some 0.001 ])
          [ (Csg.Difference, false); (Csg.Intersection, false); (Csg.Union, false); (Csg.Difference, true) ]);
    Alcotest.test_case "without the transform the operand is another solid (the test sees the carrying)" `Quick (fun () ->
        let ops = [ Transform.Rotate_z 90.; Rotate_y 180. ] in
        let lo = v (-0.41) 0.13 (-5.9) and hi = v 0.53 1.37 (-4.1) in
        let _, built = quarter_turned ops lo hi blue in
        let ball = sphere (v 0.5 0. 5.) 1.1 red in
        let a = Helpers.image_exn (scene [ Shape.Csg (Csg.v Csg.Difference ball (box lo hi blue)) ]) in
        let b = Helpers.image_exn (scene [ Shape.Csg (Csg.v Csg.Difference ball built) ]) in
        Alcotest.(check bool) "images differ" false (Image.equal a b));
    Alcotest.test_case "scene text with transformed operands prints and reads back" `Quick (fun () ->
        let s = parse text_scene in
        let again = parse (Scene.show s) in
        Alcotest.(check bool) "read back" true (Scene.equal s again);
        match Scene.shapes s with
        | [ Shape.Csg { b = Csg.Csg { a = Csg.Transformed { name = None; _ }; b = Csg.Transformed { name = Some "peg"; own_material = Some _; _ }; _ }; _ }; Shape.Csg _; Shape.Plane _ ] -> ()
        | _ -> Alcotest.fail "expected the transform and the use as operands");
    Alcotest.test_case "an open or patterned object placed as an operand gets one located line" `Quick (fun () ->
        let ball = "(sphere (center 0 0 5) (radius 1) (color 1 2 3))" in
        List.iter
          (fun (text, expected) -> Alcotest.(check string) text expected (error text))
          [
            ( "(csg difference " ^ ball ^ "\n (transform ((rotate-y 30)) (cylinder (base 0 0 5) (top 0 1 5) (radius 0.5) (capped false) (color 1 2 3))))",
              "t.scene:2:2: csg: the object placed here, a cylinder without its caps (capped false), is not a closed solid; an operand is a sphere, box, cylinder, cone, torus, closed mesh, csg, or a transform or use of one" );
            ( "(define d (disk (center 0 0 0) (normal 0 0 1) (radius 1) (color 1 2 3)))\n(csg union " ^ ball ^ " (use d (transform ((translate 0 0 5)))))",
              "t.scene:2:61: csg: the object placed here, a disk, is not a closed solid; an operand is a sphere, box, cylinder, cone, torus, closed mesh, csg, or a transform or use of one" );
            ( "(csg union " ^ ball ^ " (transform ((rotate-x 10)) (plane (point 0 0 0) (normal 0 1 0) (color 1 2 3))))",
              "t.scene:1:61: csg: the object placed here, a plane, is not a closed solid; an operand is a sphere, box, cylinder, cone, torus, closed mesh, csg, or a transform or use of one" );
            ( "(csg union " ^ ball ^ " (transform ((rotate-x 10)) (box (min 0 0 0) (max 1 1 1) (color 1 2 3) (pattern checker (color 20 20 20) (size 1)))))",
              "t.scene:1:61: csg: a transformed operand cannot have a pattern (patterns are not carried into an object's frame yet)" );
            ( "(csg union " ^ ball ^ " (use nothing))", "t.scene:1:66: unknown object nothing: no (define nothing ...) form comes before it" );
          ]);
    Alcotest.test_case "the library refuses an open or patterned transformed operand" `Quick (fun () ->
        let disk = Csg.Primitive (Private.Shape_desc.Primitive (Private.Disk.desc, Private.Disk.v ~center:Vec3.zero ~normal:(v 0. 0. 1.) ~radius:1. red)) in
        let patterned = Material.v ~pattern:(Pattern.checker ~size:1. (Color.v 0. 0. 0.)) (Color.v 1. 1. 1.) in
        List.iter
          (fun (what, c) ->
            match Csg.validate c with Ok _ -> Alcotest.failf "%s accepted" what | Error (`Msg _) -> ())
          [
            ("a placed disk", Csg.v Csg.Union (sphere Vec3.zero 1. red) (Csg.placed (transform [ Rotate_x 10. ]) disk));
            ("a placed patterned box", Csg.v Csg.Union (sphere Vec3.zero 1. red) (Csg.placed (transform [ Rotate_x 10. ]) (box Vec3.zero (v 1. 1. 1.) patterned)));
          ]);
    Alcotest.test_case "transformed operands allocate nothing per pixel, in both modes" `Quick (fun () ->
        List.iter
          (fun s ->
            List.iter
              (fun epsilon -> Alcotest.(check (float 0.)) "minor words" 0. (stats (Scene.with_overrides ~epsilon s)).minor_words)
              [ None; Some 0.001 ])
          [ scene (solids ()); parse text_scene ]);
  ]
