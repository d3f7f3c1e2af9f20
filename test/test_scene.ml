(* Scene.validate: its errors say which object or light failed. *)
open Raytrace

let error s = match Scene.validate s with Ok _ -> Alcotest.fail "accepted" | Error (`Msg m) -> m
let sphere ?(radius = 1.) z = Helpers.sphere ~center:(Vec3.v 0. 0. z) ~radius (Color.v 255. 0. 0.)
let matte = Material.v (Color.v 0. 255. 0.)

let tests =
  [
    Alcotest.test_case "a sphere's error names it: object 3 (sphere), counting from 1" `Quick (fun () ->
        let s =
          Helpers.scene ~spheres:[ sphere 3.; sphere 5.; sphere ~radius:(-1.) 7. ] ~lights:[ Light.ambient 1. ] ()
        in
        Alcotest.(check string) __LOC__ "object 3 (sphere): sphere radius must be > 0, got -1" (error s));
    Alcotest.test_case "a shape's error counts on from the spheres: object 4 (triangle) after 2 spheres and a plane"
      `Quick (fun () ->
        let plane = Shape.Plane (Plane.v ~point:(Vec3.v 0. (-1.) 0.) ~normal:(Vec3.v 0. 1. 0.) matte) in
        (* Its three vertices on the line y = z = 0: no normal. *)
        let flat = Triangle.v (Vec3.v 0. 0. 0.) (Vec3.v 1. 0. 0.) (Vec3.v 2. 0. 0.) matte in
        let s =
          Helpers.scene ~spheres:[ sphere 3.; sphere 5. ] ~shapes:[ plane; Shape.Triangle flat ]
            ~lights:[ Light.ambient 1. ] ()
        in
        let own = match Triangle.validate flat with Ok _ -> Alcotest.fail "a flat triangle passed" | Error (`Msg m) -> m in
        Alcotest.(check string) __LOC__ ("object 4 (triangle): " ^ own) (error s));
    Alcotest.test_case "a light's error names it: light 2 (point)" `Quick (fun () ->
        let bad = Light.point Float.nan (Vec3.v 0. 1. 0.) in
        let s = Helpers.scene ~spheres:[ sphere 3. ] ~lights:[ Light.ambient 0.5; bad ] () in
        let own = match Light.validate bad with Ok _ -> Alcotest.fail "a NaN light passed" | Error (`Msg m) -> m in
        Alcotest.(check string) __LOC__ ("light 2 (point): " ^ own) (error s));
    Alcotest.test_case "a scene file's error keeps its file:line:column, with no object number" `Quick (fun () ->
        match Scene_file.of_string ~file:"s.scene" "(light ambient (intensity 1))\n(sphere (center 0 0 3) (radius -1) (color 1 1 1))" with
        | Ok _ -> Alcotest.fail "accepted"
        | Error (`Msg m) ->
            Alcotest.(check bool) m true (String.length m > 10 && String.sub m 0 10 = "s.scene:2:");
            Alcotest.(check bool) m false (Astring_free.contains m "object"));
    Alcotest.test_case "objects count in the list's order: a sphere after a plane is object 2" `Quick (fun () ->
        let plane = Shape.Plane (Plane.v ~point:(Vec3.v 0. (-1.) 0.) ~normal:(Vec3.v 0. 1. 0.) matte) in
        let bad = Shape.Sphere (sphere ~radius:(-1.) 7.) in
        let s = Scene.v ~objects:[ Shape.Sphere (sphere 3.); plane; bad; plane ] ~lights:[ Light.ambient 1. ] () in
        Alcotest.(check string) __LOC__ "object 3 (sphere): sphere radius must be > 0, got -1" (error s);
        (* The first failure in the list, whichever kind it is. *)
        let flat = Shape.Triangle (Triangle.v (Vec3.v 0. 0. 0.) (Vec3.v 1. 0. 0.) (Vec3.v 2. 0. 0.) matte) in
        let s = Scene.v ~objects:[ plane; flat; bad ] ~lights:[ Light.ambient 1. ] () in
        Alcotest.(check bool) __LOC__ true (Astring_free.contains (error s) "object 2 (triangle)"));
    Alcotest.test_case "objects keeps the list's order, spheres among the others" `Quick (fun () ->
        let plane = Shape.Plane (Plane.v ~point:(Vec3.v 0. (-1.) 0.) ~normal:(Vec3.v 0. 1. 0.) matte) in
        let objects = [ plane; Shape.Sphere (sphere 3.); plane; Shape.Sphere (sphere 5.); Shape.Sphere (sphere 6.) ] in
        let s = Scene.v ~objects ~lights:[] () in
        Alcotest.(check bool) __LOC__ true (List.equal Shape.equal objects (Scene.objects s));
        Alcotest.(check int) __LOC__ 5 (Scene.n_objects s);
        (* And through the text. *)
        match Scene_file.of_string (Scene.show s) with
        | Error (`Msg m) -> Alcotest.fail m
        | Ok v -> Alcotest.(check bool) __LOC__ true (Scene.equal s (Scene.of_valid v)));
    Alcotest.test_case "of equal roots the earlier object in the list is seen, in the tracer and the literal one" `Quick
      (fun () ->
        (* The ray of the one pixel meets the box's face z = 4 and the
           sphere's near point at exactly t = 4. *)
        let red = Shape.Sphere (sphere 5.) in
        let blue = Shape.Box (Box.v ~min:(Vec3.v (-1.) (-1.) 4.) ~max:(Vec3.v 1. 1. 6.) (Material.v (Color.v 0. 0. 255.))) in
        List.iter
          (fun (objects, expected, what) ->
            List.iter
              (fun epsilon ->
                let s = Scene.v ~width:1 ~height:1 ?epsilon ~objects ~lights:[ Light.ambient 1. ] () in
                let valid = Helpers.valid s in
                let img = Helpers.image_exn s in
                let r, _, b = Image.get img 0 0 in
                Alcotest.(check (pair int int)) (what ^ ": fast") expected (r, b);
                let c = Private.Literal.pixel (Scene.of_valid valid) 0 0 in
                Alcotest.(check (pair int int)) (what ^ ": literal") expected (Color.to_byte c.r, Color.to_byte c.b))
              [ None; Some 0.001 ])
          [ ([ blue; red ], (0, 255), "box first"); ([ red; blue ], (255, 0), "sphere first") ]);
  ]
