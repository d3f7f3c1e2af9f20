(* Scene.validate: its errors say which object or light failed. *)
open Raytrace

let error s = match Scene.validate s with Ok _ -> Alcotest.fail "accepted" | Error (`Msg m) -> m
let sphere ?(radius = 1.) z = Sphere.v ~center:(Vec3.v 0. 0. z) ~radius (Color.v 255. 0. 0.)
let matte = Material.v (Color.v 0. 255. 0.)

let tests =
  [
    Alcotest.test_case "a sphere's error names it: object 3 (sphere), counting from 1" `Quick (fun () ->
        let s =
          Scene.v ~spheres:[ sphere 3.; sphere 5.; sphere ~radius:(-1.) 7. ] ~lights:[ Light.ambient 1. ] ()
        in
        Alcotest.(check string) __LOC__ "object 3 (sphere): sphere radius must be > 0, got -1" (error s));
    Alcotest.test_case "a shape's error counts on from the spheres: object 4 (triangle) after 2 spheres and a plane"
      `Quick (fun () ->
        let plane = Shape.Plane (Plane.v ~point:(Vec3.v 0. (-1.) 0.) ~normal:(Vec3.v 0. 1. 0.) matte) in
        (* Its three vertices on the line y = z = 0: no normal. *)
        let flat = Triangle.v (Vec3.v 0. 0. 0.) (Vec3.v 1. 0. 0.) (Vec3.v 2. 0. 0.) matte in
        let s =
          Scene.v ~spheres:[ sphere 3.; sphere 5. ] ~shapes:[ plane; Shape.Triangle flat ]
            ~lights:[ Light.ambient 1. ] ()
        in
        let own = match Triangle.validate flat with Ok _ -> Alcotest.fail "a flat triangle passed" | Error (`Msg m) -> m in
        Alcotest.(check string) __LOC__ ("object 4 (triangle): " ^ own) (error s));
    Alcotest.test_case "a light's error names it: light 2 (point)" `Quick (fun () ->
        let bad = Light.point Float.nan (Vec3.v 0. 1. 0.) in
        let s = Scene.v ~spheres:[ sphere 3. ] ~lights:[ Light.ambient 0.5; bad ] () in
        let own = match Light.validate bad with Ok _ -> Alcotest.fail "a NaN light passed" | Error (`Msg m) -> m in
        Alcotest.(check string) __LOC__ ("light 2 (point): " ^ own) (error s));
    Alcotest.test_case "a scene file's error keeps its file:line:column, with no object number" `Quick (fun () ->
        match Scene_file.of_string ~file:"s.scene" "(light ambient (intensity 1))\n(sphere (center 0 0 3) (radius -1) (color 1 1 1))" with
        | Ok _ -> Alcotest.fail "accepted"
        | Error (`Msg m) ->
            Alcotest.(check bool) m true (String.length m > 10 && String.sub m 0 10 = "s.scene:2:");
            Alcotest.(check bool) m false (Astring_free.contains m "object"));
  ]
