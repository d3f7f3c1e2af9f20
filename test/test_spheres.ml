open Raytrace

(* Sphere [i] of [n]: one of 7 materials (a pattern every 5th, which is
   never shared), centers all different. *)
let sphere i =
  let pattern = if i mod 5 = 0 then Some (Pattern.checker ~size:1. (Color.v 1. 2. 3.)) else None in
  Helpers.sphere ?pattern ~specular:(Float.of_int (i mod 7)) ~reflective:0.25
    ~center:(Vec3.v (Float.of_int i) (-.Float.of_int i) 0.5) ~radius:(1. +. Float.of_int (i mod 3))
    (Color.v 10. 20. 30.)

let tests =
  [
    Alcotest.test_case "of_list then to_list is the list, across blocks of spheres" `Quick (fun () ->
        (* 40000 spheres fill two blocks of 16384 and part of a third. *)
        List.iter
          (fun n ->
            let l = List.init n sphere in
            let s = Private.Spheres.of_list l in
            Alcotest.(check int) __LOC__ n (Private.Spheres.length s);
            if not (List.equal Sphere.equal l (Private.Spheres.to_list s)) then Alcotest.failf "%d spheres differ" n;
            List.iteri
              (fun i (sp : Sphere.t) ->
                if Private.Spheres.center_x s i <> sp.center.x || Private.Spheres.radius s i <> sp.radius then
                  Alcotest.failf "sphere %d of %d: fields differ" i n)
              l)
          [ 0; 1; 16383; 16384; 16385; 40000 ]);
    Alcotest.test_case "equal materials are stored once, patterned ones each time" `Quick (fun () ->
        (* 100 spheres: 20 patterned (i mod 5 = 0) get one entry each; the
           other 80 share the 7 exponents. *)
        let s = Private.Spheres.of_list (List.init 100 sphere) in
        Alcotest.(check int) __LOC__ (20 + 7) (Array.length (Private.Spheres.materials s)));
    Alcotest.test_case "0 and -0 are different materials: sharing changes no bit" `Quick (fun () ->
        let a = Helpers.sphere ~reflective:0. ~center:Vec3.zero ~radius:1. Color.white in
        let b = Helpers.with_sphere_material a (Material.update ~reflective:(-0.)) in
        let s = Private.Spheres.of_list [ a; b; a ] in
        Alcotest.(check int) __LOC__ 2 (Array.length (Private.Spheres.materials s));
        Alcotest.(check bool) __LOC__ true (Float.sign_bit (Private.Spheres.get s 1).material.reflective));
    Alcotest.test_case "get outside the spheres raises Invalid_argument" `Quick (fun () ->
        let s = Private.Spheres.of_list [ sphere 1 ] in
        List.iter
          (fun i ->
            match Private.Spheres.get s i with
            | _ -> Alcotest.failf "get %d returned" i
            | exception Invalid_argument _ -> ())
          [ -1; 1 ]);
    Alcotest.test_case "add_fields refuses a material the builder did not give" `Quick (fun () ->
        let b = Private.Spheres.builder () in
        match Private.Spheres.add_fields b ~x:0. ~y:0. ~z:0. ~radius:1. 0 with
        | () -> Alcotest.fail "added"
        | exception Invalid_argument _ -> ());
    Alcotest.test_case "equal compares spheres, not how their materials are numbered" `Quick (fun () ->
        let a = sphere 1 and b = sphere 2 in
        let b1 = Private.Spheres.builder () and b2 = Private.Spheres.builder () in
        (* b2 numbers b's material first. *)
        ignore (Private.Spheres.material b2 (Sphere.material b));
        List.iter (Private.Spheres.add b1) [ a; b ];
        List.iter (Private.Spheres.add b2) [ a; b ];
        Alcotest.(check bool) __LOC__ true (Private.Spheres.equal (Private.Spheres.build b1) (Private.Spheres.build b2));
        Alcotest.(check bool) __LOC__ false (Private.Spheres.equal (Private.Spheres.of_list [ a; b ]) (Private.Spheres.of_list [ b; a ])));
    Alcotest.test_case "spheres appended are the spheres added one by one, materials in the same order" `Quick
      (fun () ->
        (* Across the blocks of either side, with the appended spheres'
           materials numbered alike (copied whole) or not (renumbered);
           sphere [i + 3] shares the material of [i], so a tail starting
           at 3 meets old materials first. *)
        let same what a b =
          let n = Private.Spheres.length a in
          Alcotest.(check int) (what ^ ": length") n (Private.Spheres.length b);
          for i = 0 to n - 1 do
            if not (Sphere.equal (Private.Spheres.get a i) (Private.Spheres.get b i))
               || Private.Spheres.material_index a i <> Private.Spheres.material_index b i
            then Alcotest.failf "%s: sphere %d differs" what i
          done;
          if not (Array.for_all2 Material.equal (Private.Spheres.materials a) (Private.Spheres.materials b)) then
            Alcotest.failf "%s: the material tables differ" what
        in
        List.iter
          (fun (n1, n2, offset) ->
            let head = List.init n1 sphere and tail = List.init n2 (fun i -> sphere (i + offset)) in
            let b = Private.Spheres.builder () in
            List.iter (Private.Spheres.add b) head;
            Private.Spheres.append b (Private.Spheres.of_list tail);
            same (Printf.sprintf "%d then %d from %d" n1 n2 offset) (Private.Spheres.of_list (head @ tail)) (Private.Spheres.build b))
          [
            (0, 0, 0); (0, 5, 0); (5, 0, 0); (3, 20, 1); (16384, 16384, 1); (16385, 40000, 3); (20000, 40000, 0);
            (40000, 16383, 7); (16383, 2, 2); (17, 70000, 3);
          ]);
  ]
