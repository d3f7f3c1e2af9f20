(* The robust mode (issue: numerically sound). Exact rational arithmetic
   (Zarith) is the oracle: every float input is an exact rational, so the
   true distance of a computed point from a sphere, and whether a ray truly
   misses, can be decided without rounding. *)
open Raytrace

let u = epsilon_float /. 2.

(* The bound that Sphere.roots documents: 16 u (|O - C| + r). *)
let bound = 16.

let cases_per_family = 1500

type tally = { mutable worst : float; mutable misclassified : int; mutable unordered : int }

(* Errors in units of u (|O - C| + r): how far a root's exact point lies from
   the sphere, or, for a hit/miss contradicted by the exact line distance,
   by how much. *)
let measure (roots : Hard_cases.case -> float * float) cases =
  let tally = { worst = 0.; misclassified = 0; unordered = 0 } in
  List.iter
    (fun (c : Hard_cases.case) ->
      let s = c.sphere and origin = c.origin and direction = c.direction in
      let unit = u *. (Vec3.norm (Vec3.sub origin s.center) +. s.radius) in
      let l2 = Exact.line_distance2 s ~origin ~direction in
      let line = sqrt (Q.to_float l2) in
      let note e =
        if e > tally.worst then tally.worst <- e;
        if e > bound then tally.misclassified <- tally.misclassified + 1
      in
      let t0, t1 = roots c in
      if t0 > t1 then tally.unordered <- tally.unordered + 1;
      if t0 = infinity then begin
        (* Reported as a miss: the exact line must not pass inside. *)
        if line < s.radius then note ((s.radius -. line) /. unit)
      end
      else begin
        List.iter
          (fun t ->
            let e = Exact.surface_distance s ~origin ~direction t /. unit in
            if e > tally.worst then tally.worst <- e)
          [ t0; t1 ];
        if line > s.radius then note ((line -. s.radius) /. unit)
      end)
    cases;
  tally

(* The roots the renderer computes: the tracer's own test, in the robust
   mode. *)
let robust (c : Hard_cases.case) =
  let tr = Trace.create (Helpers.prepare (Helpers.scene ~spheres:[ c.sphere ] ~lights:[] ())) in
  Trace.roots tr 0 c.origin c.direction

(* [Sphere.roots], the library's readable copy, is held to the same bound. *)
let readable (c : Hard_cases.case) = Sphere.roots c.sphere ~origin:c.origin ~direction:c.direction

let textbook (c : Hard_cases.case) =
  let a, b, k = Sphere.quadratic c.sphere ~origin:c.origin ~direction:c.direction in
  Sphere.textbook_roots a b k

let cases gen = QCheck.Gen.generate ~rand:(Random.State.make [| 1121 |]) ~n:cases_per_family gen

(* One camera ray per pixel (as Trace builds it) toward a scene of one white
   sphere under ambient light 1: the mask of pixels that see it. *)
let hit_mask scene =
  let tr = Trace.create (Helpers.prepare scene) in
  let w = (Scene.width scene) and h = (Scene.height scene) in
  Array.init h (fun row ->
      Array.init w (fun col ->
          Trace.pixel tr (Canvas.x_of_column ~width:w col) (Canvas.y_of_row ~height:h row);
          Trace.hit_object tr >= 0))

(* The exact disk/ellipse: pixel (col, row) sees sphere [s] iff the exact
   distance from its center to the pixel's float ray is <= r. Pixels within
   the documented rounding band of the silhouette are left out. *)
let exact_mask (scene : Scene.t) (s : Sphere.t) =
  let w = (Scene.width scene) and h = (Scene.height scene) in
  Array.init h (fun row ->
      Array.init w (fun col ->
          let v =
            Viewport.of_canvas (Scene.viewport scene) ~canvas_width:w ~canvas_height:h
              (Canvas.x_of_column ~width:w col) (Canvas.y_of_row ~height:h row)
          in
          let direction = Camera.direction (Scene.camera scene) v and origin = (Scene.camera scene).position in
          let line = sqrt (Q.to_float (Exact.line_distance2 s ~origin ~direction)) in
          let band = bound *. u *. (Vec3.norm (Vec3.sub origin s.center) +. s.radius) in
          if line <= s.radius -. band then `In else if line > s.radius +. band then `Out else `Edge))


(* A sphere of radius [r] at distance [1e7 r] from the camera, seen through
   a viewport narrowed so that it covers about 30 pixels across. With
   [~aim], the camera is turned (look-at [aim] radii beside the sphere, a
   tilted up vector) and the viewport is twice as high as wide: the sphere
   then projects to an ellipse off the center of the picture. *)
let tiny_far_scene ?(epsilon : float option) ?aim ?(translate = Vec3.zero) () =
  let r = 1e-3 in
  let dist = 1e7 *. r in
  let center = Vec3.add translate (Vec3.v (0.3 *. dist) (-0.2 *. dist) dist) in
  let sphere = Helpers.sphere ~center ~radius:r Color.white in
  (* The disk spans 2 r / dist = 2e-7 of the viewport distance. *)
  let vp, target =
    match aim with
    | None -> (Viewport.v ~width:6e-7 ~height:6e-7 ~distance:1., center)
    | Some (ax, ay) ->
        ( Viewport.v ~width:6e-7 ~height:12e-7 ~distance:1.,
          Vec3.add center (Vec3.v (ax *. r) (ay *. r) 0.) )
  in
  let up = if aim = None then Vec3.oy else Vec3.v 0.3 1. 0.2 in
  let camera =
    match Camera.look_at ~up ~position:translate target with Ok c -> c | Error (`Msg e) -> failwith e
  in
  let scene =
    Helpers.scene ~width:90 ~height:90 ~viewport:vp ~camera ?epsilon ~spheres:[ sphere ]
      ~lights:[ Light.ambient 1. ] ()
  in
  (scene, sphere)

(* Every scene of scenes/ in the robust mode, scaled or translated. *)
let transform ~scale ~translate (s : Scene.t) =
  let p (v : Vec3.t) = Vec3.add (Vec3.smul scale v) translate in
  (* A checker's cells scale with the scene. In world coordinates they do
     not move with it: the scenes' cells divide the translations (1e6) an
     even number of times, so that the picture stays. (A mesh is placed
     anew at scale 1: its cells would be the world's; no scene has a
     patterned mesh.) *)
  let pattern = Option.map (fun (Pattern.Checker c) -> Pattern.checker ~size:(scale *. c.size) c.color) in
  (* A planar texture's copies likewise; the other mappings are relative
     to their object. *)
  let texture =
    Option.map (fun (t : Material.Texture.t) -> Material.Texture.v ~size:(scale *. t.size) ~file:t.file t.mapping t.image)
  in
  let material (m : Material.t) = Material.update ~pattern:(pattern m.pattern) ~texture:(texture m.texture) m in
  let sphere (sp : Sphere.t) = Sphere.v ~center:(p sp.center) ~radius:(scale *. sp.radius) (material sp.material) in
  Scene.with_overrides ~epsilon:None
    ~viewport:
      (Viewport.v ~width:(scale *. (Scene.viewport s).width) ~height:(scale *. (Scene.viewport s).height)
        ~distance:(scale *. (Scene.viewport s).distance))
    ~camera:(Camera.v ~rotation:(Scene.camera s).rotation (p (Scene.camera s).position))
    ~objects:
      (let mesh (m : Mesh.t) =
         let positions = Array.copy m.positions in
         for i = 0 to (Array.length positions / 3) - 1 do
           let v = p (Vec3.v positions.(3 * i) positions.((3 * i) + 1) positions.((3 * i) + 2)) in
           positions.(3 * i) <- v.x;
           positions.((3 * i) + 1) <- v.y;
           positions.((3 * i) + 2) <- v.z
         done;
         match
           Mesh.v ~smooth:m.smooth ~positions ~triangles:m.triangles ~normals:m.normals
             ~triangle_normals:m.triangle_normals (material m.material)
         with
         | Ok m -> m
         | Error (`Msg e) -> Alcotest.fail e
       in
       let box (b : Box.t) : Box.t = Box.v ~min:(p b.min) ~max:(p b.max) (material b.material) in
       let primitive prim = Shape_kinds.map_primitive ~point:p ~length:(fun x -> scale *. x) ~material prim in
       let rec csg (c : Csg.t) =
         let solid = function
           | Csg.Sphere sp -> Csg.Sphere (sphere sp)
           | Csg.Box b -> Csg.Box (box b)
           | Csg.Mesh m -> Csg.Mesh (mesh m)
           | Csg.Csg c -> Csg.Csg (csg c)
           | Csg.Primitive q -> Csg.Primitive (primitive q)
           | Csg.Transformed _ -> Alcotest.fail "no scene here has a transformed operand"
         in
         Csg.v c.op (solid c.a) (solid c.b)
       in
       List.map
         (function
           | Shape.Sphere sp -> Shape.Sphere (sphere sp)
           | Shape.Plane pl -> Shape.Plane (Plane.v ~point:(p pl.point) ~normal:pl.normal (material pl.material))
           | Shape.Triangle t -> Shape.Triangle (Triangle.v (p t.v0) (p t.v1) (p t.v2) (material t.material))
           | Shape.Box b -> Shape.Box (box b)
           | Shape.Mesh m -> Shape.Mesh (mesh m)
           | Shape.Csg c -> Shape.Csg (csg c)
           | Shape.Instance i ->
               (* The same object, its transform followed by the scene's. *)
               let scene_map = Result.get_ok (Shape.Transform.v [ Scale (Vec3.v scale scale scale); Translate translate ]) in
               Shape.instance ?material:(Option.map material i.own_material) ?name:i.name (Shape.Transform.compose i.transform scene_map) i.shape
           | Shape.Primitive q -> Shape.Primitive (primitive q))
         (Scene.objects s))
    ~lights:
      (List.map
         (function
           | Light.Point { intensity; position } -> Light.point intensity (p position)
           | Light.Area { intensity; corner; edge1; edge2; samples_u; samples_v; adaptive; sampling } ->
               Light.area ~adaptive ~sampling intensity ~corner:(p corner) ~edge1:(Vec3.smul scale edge1)
                 ~edge2:(Vec3.smul scale edge2) ~samples:(samples_u, samples_v)
           | Light.Sphere { intensity; position; radius; samples } ->
               Light.sphere intensity ~position:(p position) ~radius:(scale *. radius) ~samples
           | Light.Spot { intensity; position; direction; angle; falloff } ->
               Light.spot intensity ~position:(p position) ~direction ~angle ~falloff
           | l -> l)
         (Scene.lights s))
    s

let small (s : Scene.t) = Scene.with_overrides ~width:64 ~height:64 s

let tests =
  [
    Alcotest.test_case "the tracer's robust roots stay within 16 u (|O - C| + r) of the sphere; the textbook's do not"
      `Quick (fun () ->
        Printf.printf "%-32s %22s %22s\n" "family (1500 cases each)" "textbook max error" "robust max error";
        List.iter
          (fun (name, gen) ->
            let cs = cases gen in
            let ours = measure robust cs and theirs = measure textbook cs in
            let library = measure readable cs in
            if library.worst > bound || library.misclassified > 0 then
              Alcotest.failf "%s: Sphere.roots error %.3g u (|O-C|+r), %d wrong" name library.worst
                library.misclassified;
            Printf.printf "%-32s %12.3g (%4d wrong) %12.3g (%4d wrong)\n" name theirs.worst
              theirs.misclassified ours.worst ours.misclassified;
            if ours.worst > bound then
              Alcotest.failf "%s: robust error %.3g u (|O-C|+r) exceeds the bound %g" name ours.worst bound;
            Alcotest.(check int) (name ^ ": robust roots ordered") 0 ours.unordered;
            Alcotest.(check int) (name ^ ": robust hit/miss") 0 ours.misclassified;
            (* This suite would fail the document's formula: *)
            if (name = "far, tiny spheres" || name = "grazing rays") && theirs.worst <= bound then
              Alcotest.failf "%s: the textbook formula unexpectedly meets the bound" name)
          Hard_cases.families);
    Helpers.qcheck ~count:500 "a ray leaving a surface outward does not re-hit it; inward it does"
      (QCheck.make (List.assoc "rays from a surface point" Hard_cases.families))
      (fun c ->
        let scene = Helpers.scene ~spheres:[ c.sphere ] ~lights:[] () in
        let tr = Trace.create (Helpers.prepare scene) in
        let n = Vec3.sub c.origin c.sphere.center in
        let cos = Vec3.dot (Vec3.unit n) (Vec3.unit c.direction) in
        let hit = Trace.cast tr ~from:0 c.origin c.direction in
        (* Within 1e-6 of tangent either answer is right. *)
        if cos > 1e-6 then hit = -1 else if cos < -1e-6 then hit = 0 else true);
    Alcotest.test_case "with a fixed epsilon, a scaled-down surface re-hits itself" `Quick (fun () ->
        (* The document's epsilon is in t units: at scale 1e-6 with |D| = 1e-6,
           the self-root's rounding (about u r / |D|) is no longer below it. *)
        let c = List.assoc "rays from a surface point" Hard_cases.families in
        let self_hits =
          List.length
            (List.filter
               (fun (hc : Hard_cases.case) ->
                 let scene = Helpers.scene ~epsilon:1e-12 ~spheres:[ hc.sphere ] ~lights:[] () in
                 let tr = Trace.create (Helpers.prepare scene) in
                 let n = Vec3.sub hc.origin hc.sphere.center in
                 Vec3.dot n hc.direction > 0. && Trace.cast tr ~from:0 hc.origin hc.direction = 0)
               (cases c))
        in
        if self_hits = 0 then Alcotest.fail "expected the textbook mode to show self-intersection";
        Printf.printf "textbook, epsilon 1e-12: %d of %d outward rays re-hit their own sphere\n" self_hits
          cases_per_family);
    Alcotest.test_case "a blocker a hair's breadth away still casts its shadow, at any scale" `Quick
      (fun () ->
        (* Unit sphere A at the origin; B of radius 1e-10 just above A's top
           with a gap of 1e-9: the ray from A's top (0, 1, 0) straight up
           meets B at t = 1e-9 and 1.2e-9. The robust mode sees it at every
           scale; a fixed epsilon of 0.001 (in t units) skips it. *)
        List.iter
          (fun scale ->
            let a = Helpers.sphere ~center:Vec3.zero ~radius:scale Color.white in
            let b =
              Helpers.sphere ~center:(Vec3.v 0. (scale *. (1. +. 1.1e-9)) 0.) ~radius:(scale *. 1e-10) Color.white
            in
            let top = Vec3.v 0. scale 0. and up = Vec3.v 0. scale 0. in
            let cast epsilon =
              let scene = Helpers.scene ?epsilon ~spheres:[ a; b ] ~lights:[] () in
              Trace.cast (Trace.create (Helpers.prepare scene)) ~from:0 top up
            in
            Alcotest.(check int) (Printf.sprintf "robust, scale %g" scale) 1 (cast None);
            Alcotest.(check int) (Printf.sprintf "epsilon 0.001, scale %g" scale) (-1) (cast (Some 0.001)))
          [ 1e-6; 1.; 1e6 ]);
    Alcotest.test_case "a sphere 1e7 times smaller than its distance is its exact disk" `Quick (fun () ->
        List.iter
          (fun (what, aim, translate) ->
            let scene, sphere = tiny_far_scene ?aim ~translate () in
            let wrong, inside = Helpers.mask_errors (hit_mask scene) (exact_mask scene sphere) in
            if inside < 300 then Alcotest.failf "%s: the disk covers only %d pixels" what inside;
            Alcotest.(check int) (what ^ ": pixels off the exact shape") 0 wrong;
            (* The document's formula on the same scene: *)
            let doc, _ = tiny_far_scene ~epsilon:0.001 ?aim ~translate () in
            let wrong_doc, _ = Helpers.mask_errors (hit_mask doc) (exact_mask doc sphere) in
            Printf.printf "%s: %d pixels inside; robust 0 wrong, textbook %d wrong\n" what inside wrong_doc)
          [
            ("centered disk", None, Vec3.zero);
            ("off-center ellipse", Some (1.2, -2.5), Vec3.zero);
            ("disk, translated by 1e6", None, Vec3.v 1e6 (-1e6) 1e6);
            ("ellipse, translated by 1e6", Some (-1.5, 3.), Vec3.v (-1e6) 1e6 1e6);
          ]);
    Alcotest.test_case "every scene is the same picture scaled from 1e-6 to 1e6 and translated by 1e6"
      `Slow (fun () ->
        List.iter
          (fun name ->
            let base = small (Helpers.load_scene name) in
            let expected = Helpers.image_exn (transform ~scale:1. ~translate:Vec3.zero base) in
            List.iter
              (fun (scale, translate) ->
                let what = Printf.sprintf "%s scaled by %g, moved by %s" name scale (Vec3.show translate) in
                Helpers.check_images ~min_share:0.999 what ~expected
                  (Helpers.image_exn (transform ~scale ~translate base)))
              [
                (1e-6, Vec3.zero); (1e-3, Vec3.zero); (0.37, Vec3.zero); (1e3, Vec3.zero); (1e6, Vec3.zero);
                (1., Vec3.v 1e6 0. 0.); (1., Vec3.v (-1e6) 1e6 (-1e6)); (1., Vec3.v 0. 0. 1e6);
              ])
          (Helpers.scene_names ()));
    Alcotest.test_case "degenerate scenes render finite colours" `Quick (fun () ->
        let ball = Helpers.sphere ~center:(Vec3.v 0. 0. 3.) ~radius:1. ~specular:10. ~reflective:0.5 Color.white in
        let lights = [ Light.ambient 0.1; Light.point 0.5 (Vec3.v 0. 0. 2.); Light.directional 0.4 Vec3.ox ] in
        List.iter
          (fun (what, spheres, lights, camera, epsilon) ->
            let scene = Helpers.scene ~width:33 ~height:33 ~camera ?epsilon ~spheres ~lights () in
            let tr = Trace.create (Helpers.prepare scene) in
            for gx = Canvas.min_x 33 to Canvas.max_x 33 do
              for gy = Canvas.min_y 33 to Canvas.max_y 33 do
                Trace.pixel tr gx gy;
                if not (Float.is_finite (Trace.red tr) && Float.is_finite (Trace.green tr) && Float.is_finite (Trace.blue tr))
                then Alcotest.failf "%s: pixel (%d, %d) is not finite" what gx gy
              done
            done;
            let lit = Private.Literal.pixel scene 0 0 in
            if not (Color.is_finite lit) then Alcotest.failf "%s: the oracle is not finite" what)
          (List.concat_map
             (fun epsilon ->
               [
                 ("a point light on the surface", [ ball ], lights, Camera.default, epsilon);
                 ("a point light at the center", [ ball ], [ Light.point 1. (Vec3.v 0. 0. 3.) ], Camera.default, epsilon);
                 ("the camera inside a sphere", [ ball ], lights, Camera.v (Vec3.v 0. 0. 3.), epsilon);
                 ("the camera on a surface", [ ball ], lights, Camera.v (Vec3.v 0. 0. 2.), epsilon);
                 ("two identical spheres", [ ball; ball ], lights, Camera.default, epsilon);
                 ("touching spheres", [ ball; Sphere.v ~center:(Vec3.v 2. 0. 3.) ~radius:ball.radius ball.material ], lights, Camera.default, epsilon);
                 ("concentric spheres", [ ball; Sphere.v ~center:ball.center ~radius:0.5 ball.material ], lights, Camera.default, epsilon);
                 ("zero intensities", [ ball ], [ Light.point 0. Vec3.oy; Light.ambient 0. ], Camera.default, epsilon);
                 ("lights parallel to the view", [ ball ], [ Light.directional 1. (Vec3.v 0. 0. (-1.)) ], Camera.default, epsilon);
                 ("a huge intensity", [ ball ], [ Light.point 1e6 (Vec3.v 0. 5. 0.) ], Camera.default, epsilon);
               ])
             [ None; Some 0.001; Some 0. ]));
  ]
