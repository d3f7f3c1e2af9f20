open Raytrace

let vec = Alcotest.(option Helpers.vec3)

let tests =
  [
    Alcotest.test_case "L points from P to a point light (7.1)" `Quick (fun () ->
        (* Q - P = (2, 1, 0) - (0, -1, 2) = (2, 2, -2) *)
        Alcotest.check vec __LOC__ (Some (Vec3.v 2. 2. (-2.)))
          (Light.vector (Light.point 0.6 (Vec3.v 2. 1. 0.)) (Vec3.v 0. (-1.) 2.)));
    Alcotest.test_case "L is the same everywhere for a directional light (7.2)" `Quick (fun () ->
        let l = Light.directional 0.2 (Vec3.v 1. 4. 4.) in
        Alcotest.check vec __LOC__ (Some (Vec3.v 1. 4. 4.)) (Light.vector l Vec3.zero);
        Alcotest.check vec __LOC__ (Some (Vec3.v 1. 4. 4.)) (Light.vector l (Vec3.v 9. 9. 9.)));
    Alcotest.test_case "an ambient light has no direction (7.3)" `Quick (fun () ->
        Alcotest.check vec __LOC__ None (Light.vector (Light.ambient 0.2) Vec3.zero));
    Alcotest.test_case "shadow rays end at the point light, not at the directional" `Quick (fun () ->
        Alcotest.(check (float 0.)) __LOC__ 1. (Light.shadow_t_max (Light.point 1. Vec3.zero));
        Alcotest.(check (float 0.)) __LOC__ infinity (Light.shadow_t_max (Light.directional 1. Vec3.oy)));
    Alcotest.test_case "the document's {k; i; v} record converts" `Quick (fun () ->
        let light = Alcotest.testable Light.pp Light.equal in
        let ok d = match Light.of_document d with Ok l -> l | Error (`Msg m) -> Alcotest.fail m in
        Alcotest.check light __LOC__ (Light.point 0.6 (Vec3.v 2. 1. 0.))
          (ok { k = 'p'; i = 0.6; v = Some (2., 1., 0.) });
        Alcotest.check light __LOC__ (Light.directional 0.2 (Vec3.v 1. 4. 4.))
          (ok { k = 'd'; i = 0.2; v = Some (1., 4., 4.) });
        Alcotest.check light __LOC__ (Light.ambient 0.2) (ok { k = 'a'; i = 0.2; v = None });
        List.iter
          (fun l -> Alcotest.check light __LOC__ l (ok (Light.to_document l)))
          (Scene.lights Scene.cgfs));
    Alcotest.test_case "malformed document records are errors" `Quick (fun () ->
        let bad d = Alcotest.(check bool) __LOC__ true (Result.is_error (Light.of_document d)) in
        bad { k = 'x'; i = 0.2; v = None };
        bad { k = 'p'; i = 0.2; v = None };
        bad { k = 'a'; i = 0.2; v = Some (0., 0., 0.) };
        bad { k = 'd'; i = 0.2; v = Some (0., 0., 0.) };
        bad { k = 'a'; i = -0.2; v = None };
        bad { k = 'a'; i = nan; v = None };
        Alcotest.check_raises __LOC__ (Invalid_argument "Light.of_document: unknown light kind 'x': expected 'a', 'p' or 'd'")
          (fun () -> ignore (Light.of_document_exn { k = 'x'; i = 0.2; v = None })));
  ]
