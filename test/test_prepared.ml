(* The passes around the hierarchy's build (Prepared): the twins of a big
   scene's spheres found by a child process while this one makes the
   boxes, the same prepared scene as found here, with twins or none, with
   planes or none; and a mesh's boxes, made in a loop of their own, each
   inside every node above its triangle. *)
open Raytrace

let prepare ?beside s = Prepared.prepare ?beside (Helpers.valid s)

(* A [beside] that computes in this process when waited for, as
   [Parallel.beside] does where it cannot fork, and one that fails. *)
let here = { Bvh.beside = (fun f () -> Some (f ())); min_objects = 1000; floats = Test_bvh.own; idle = (fun () -> true) }
let failing = { Bvh.beside = (fun _ () -> None); min_objects = 1000; floats = Test_bvh.own; idle = (fun () -> true) }

(* The renderer's [beside] from 1000 objects on, counting in [built] the
   computations another process made. *)
let forking built = Test_bvh.counting ~min_objects:1000 built

(* Fails unless [a] and [b] are the same prepared scene, every field, every
   float bit for bit ([compare] has nan equal to nan). *)
let check_same what (a : Prepared.t) (b : Prepared.t) =
  Alcotest.(check int) (what ^ ": slots") a.n_objects b.n_objects;
  Alcotest.(check int) (what ^ ": objects") a.n_scene_objects b.n_scene_objects;
  Alcotest.(check (array int)) (what ^ ": index") a.index b.index;
  Alcotest.(check (array int)) (what ^ ": slot") a.slot b.slot;
  Alcotest.(check (array int)) (what ^ ": material") a.material b.material;
  let bits = Array.map Int64.bits_of_float in
  List.iter
    (fun (name, f) -> Alcotest.(check (array int64)) (what ^ ": " ^ name) (bits (f a)) (bits (f b)))
    Prepared.
      [
        ("cx", fun p -> p.cx); ("cy", fun p -> p.cy); ("cz", fun p -> p.cz); ("radius", fun p -> p.radius);
        ("r2", fun p -> p.r2); ("primary_k3", fun p -> p.primary_k3);
      ];
  (* The hierarchies node by node (their nodes may start at another
     offset of their array in each). *)
  let nodes (p : Prepared.t) =
    match p.bvh with
    | None -> []
    | Some t ->
        List.init t.n_nodes (fun k ->
            (Bvh.tag t k, Bvh.link t k, List.init 6 (fun a -> if a < 3 then Bvh.lo t k a else Bvh.hi t k (a - 3))))
  in
  Alcotest.(check bool) (what ^ ": the same hierarchy") true (compare (nodes a) (nodes b) = 0);
  (* Every other field, the hierarchy (the tenth) left out. *)
  let others (p : Prepared.t) =
    let r = Obj.dup (Obj.repr p) in
    assert (Obj.field r 9 == Obj.repr p.bvh);
    Obj.set_field r 9 (Obj.repr None);
    r
  in
  Alcotest.(check bool) (what ^ ": every other field") true (compare (others a) (others b) = 0)

(* [s] with copies of some of its spheres, one of them at -0. where it had
   0., far from their originals in scene order. *)
let with_twins (s : Scene.t) =
  let l = Private.Spheres.to_list (Scene.spheres s) in
  let negative_zero x = if x = 0. then -0. else x in
  let copies =
    List.filteri (fun i _ -> i mod 997 = 3) l
    |> List.map (fun (sp : Sphere.t) ->
           Sphere.v ~center:(Vec3.v (negative_zero sp.center.x) (negative_zero sp.center.y) sp.center.z) ~radius:sp.radius sp.material)
  in
  Helpers.with_objects ~spheres:(l @ copies) s

let plane = Shape.Plane (Plane.v ~point:(Vec3.v 0. (-1000.) 0.) ~normal:(Vec3.v 0. 1. 0.) (Material.v Color.white))

let tests =
  [
    Alcotest.test_case "twins found beside while the boxes are made: the same prepared scene and image" `Quick
      (fun () ->
        let grid = Scene.with_overrides ~width:40 ~height:40 (Scene.grid 3000) in
        List.iter
          (fun (what, (s : Scene.t), twins) ->
            let alone = prepare s in
            Alcotest.(check int) (what ^ ": twins share a slot") twins (alone.n_scene_objects - alone.n_objects);
            let built = ref 0 in
            let forked = prepare ~beside:(forking built) s in
            (* The twins, and a part of the hierarchy. *)
            if !built < 1 then Alcotest.failf "%s: nothing computed by another process" what;
            check_same (what ^ ", a child process") alone forked;
            check_same (what ^ ", beside computing here") alone (prepare ~beside:here s);
            check_same (what ^ ", a beside that fails") alone (prepare ~beside:failing s);
            (* No idle core: neither the twins nor a part beside. *)
            let busy =
              { failing with Bvh.beside = (fun _ () -> Alcotest.fail "beside without an idle core"); idle = (fun () -> false) }
            in
            check_same (what ^ ", no idle core") alone (prepare ~beside:busy s);
            let image p =
              let tr = Trace.create p in
              Array.init ((Scene.width s) * (Scene.height s)) (fun i ->
                  Trace.pixel tr ((i mod (Scene.width s)) - ((Scene.width s) / 2)) (((Scene.height s) / 2) - (i / (Scene.width s)));
                  (Trace.red tr, Trace.green tr, Trace.blue tr))
            in
            Alcotest.(check bool) (what ^ ": the same pixels") true (image alone = image forked))
          [
            ("grid:3000", grid, 0);
            ("grid:3000 with twins", with_twins grid, 4);
            ("grid:3000 and a plane", Helpers.with_objects ~shapes:[ plane ] grid, 0);
            ("grid:3000 with twins and a plane", Helpers.with_objects ~shapes:[ plane ] (with_twins grid), 4);
          ]);
    Alcotest.test_case "a mesh's boxes: each triangle inside every node above it, degenerate ones left out" `Quick
      (fun () ->
        let rand = Random.State.make [| 15 |] in
        let f () = Random.State.float rand 20. -. 10. in
        (* Slivers around random points, and every seventh triangle
           degenerate (a corner repeated). *)
        let mesh n =
          let positions = Array.init (9 * n) (fun i -> if i mod 9 < 3 then f () else 0.) in
          for t = 0 to n - 1 do
            for c = 1 to 2 do
              for a = 0 to 2 do
                positions.((9 * t) + (3 * c) + a) <- positions.((9 * t) + a) +. Random.State.float rand 0.5
              done
            done
          done;
          let triangles = Array.init (3 * n) (fun i -> if i / 3 mod 7 = 0 && i mod 3 = 2 then i - 1 else i) in
          match
            Mesh.v ~positions ~triangles ~normals:[||] ~triangle_normals:(Array.make (3 * n) (-1))
              (Material.v Color.white)
          with
          | Ok m -> m
          | Error (`Msg e) -> Alcotest.fail e
        in
        let m1 = mesh 700 and m2 = mesh 300 in
        let lone = Shape.Triangle (Triangle.v (Vec3.v 0. 0. 5.) (Vec3.v 1. 0. 5.) (Vec3.v 0. 1. 5.) (Material.v Color.white)) in
        let s =
          Helpers.scene ~width:32 ~height:32
            ~spheres:[ Helpers.sphere ~center:(Vec3.v 0. 0. 20.) ~radius:1. Color.white ]
            ~shapes:[ Shape.Mesh m1; plane; lone; Shape.Mesh m2 ]
            ~lights:[ Light.ambient 0.3; Light.point 0.7 (Vec3.v 2. 5. (-3.)) ] ()
        in
        let p = prepare s in
        (* Object k's mesh and triangle, objects numbered as the
           preparation numbers them. *)
        let triangle_of = Hashtbl.create 1000 in
        let k = ref 1 in
        List.iter
          (function
            | Shape.Mesh m ->
                for t = 0 to Mesh.triangle_count m - 1 do
                  if not (Mesh.degenerate m t) then begin
                    Hashtbl.replace triangle_of !k (m, t);
                    incr k
                  end
                done
            | _ -> incr k)
          (Scene.shapes s);
        Alcotest.(check int) "objects: the degenerate triangles left out" !k p.n_scene_objects;
        Alcotest.(check int) "every seventh triangle degenerate" (1000 - 100 - 43) (Hashtbl.length triangle_of);
        let b = match p.bvh with Some b -> b | None -> Alcotest.fail "no hierarchy" in
        let box = Array.make 6 0. and seen = ref 0 in
        let rec walk j path =
          let tag = Bvh.tag b j and link = Bvh.link b j in
          if tag > 0 then
            for slot = link to link + tag - 1 do
              match Hashtbl.find_opt triangle_of p.index.(slot) with
              | None -> ()
              | Some (m, t) ->
                  incr seen;
                  Mesh.box m t box;
                  List.iter
                    (fun j ->
                      for a = 0 to 2 do
                        if not (Bvh.lo b j a < box.(a) && box.(a + 3) < Bvh.hi b j a) then
                          Alcotest.failf "triangle %d of a mesh sticks out of node %d along axis %d" t j a
                      done)
                    (j :: path)
            done
          else begin
            walk (j + 1) (j :: path);
            walk link (j :: path)
          end
        in
        walk 0 [];
        Alcotest.(check int) "every triangle in a leaf" (Hashtbl.length triangle_of) !seen;
        Helpers.check_images "skips against none" ~expected:(Helpers.image_exn ~skips:false s) (Helpers.image_exn s));
    Alcotest.test_case "a mesh's triangles in one run beside planes: the same hierarchy wherever the planes are" `Quick
      (fun () ->
        (* A mesh between planes numbers its triangles in one run, which
           the preparation takes as a range of objects, not a list. The
           tree is built from the same boxes in the same order wherever
           the planes are: the same nodes, and the slots' objects those
           of the mesh first, moved by the planes before it. *)
        let m =
          let o = Mesh.Gen.torus_knot ~p:2 ~q:3 ~radius:1.5 ~tube:0.2 ~segments:120 ~sides:8 in
          match
            Mesh.v ~smooth:true ~translate:(Vec3.v 0. 0. 3.) ~positions:o.positions ~triangles:o.triangles
              ~normals:o.normals ~triangle_normals:o.triangle_normals (Material.v ~specular:50. Color.white)
          with
          | Ok m -> m
          | Error (`Msg e) -> Alcotest.fail e
        in
        let t = Mesh.objects m in
        let floor = Shape.Plane (Plane.v ~point:(Vec3.v 0. (-2.) 0.) ~normal:(Vec3.v 0. 1. 0.) (Material.v ~reflective:0.3 Color.white)) in
        let scene shapes =
          Helpers.scene ~width:48 ~height:36 ~camera:(Camera.v (Vec3.v 0. 1. (-3.))) ~shapes ~spheres:[]
            ~lights:[ Light.ambient 0.3; Light.point 0.7 (Vec3.v 2. 5. (-3.)) ] ()
        in
        let first = scene [ Shape.Mesh m; floor ] and after = scene [ floor; plane; Shape.Mesh m ] in
        let a = prepare first and b = prepare after in
        let nodes (p : Prepared.t) =
          match p.bvh with
          | None -> Alcotest.fail "no hierarchy"
          | Some t ->
              List.init t.n_nodes (fun k ->
                  (Bvh.tag t k, Bvh.link t k, List.init 6 (fun a -> if a < 3 then Bvh.lo t k a else Bvh.hi t k (a - 3))))
        in
        Alcotest.(check bool) "the same hierarchy" true (compare (nodes a) (nodes b) = 0);
        Alcotest.(check (array int)) "the triangles' slots, the planes' objects before them counted"
          (Array.init t (fun i -> a.index.(i) + 2))
          (Array.sub b.index 0 t);
        Alcotest.(check (array int)) "the planes last, in scene order" [| 0; 1 |] (Array.sub b.index t 2);
        Alcotest.(check (array int)) "the plane last" [| t |] (Array.sub a.index t 1);
        Array.iteri (fun i k -> Alcotest.(check int) "slot is the inverse of index" i b.slot.(k)) b.index;
        Alcotest.(check (array int)) "the triangles' corners" (Array.sub a.at0 0 t) (Array.sub b.at0 0 t);
        Alcotest.(check (array string)) "the triangles' kinds" (Array.map Private.Kind.to_string (Array.sub a.kind 0 t)) (Array.map Private.Kind.to_string (Array.sub b.kind 0 t));
        Alcotest.(check bool) "the triangles' materials" true
          (Array.for_all (fun i -> b.material.(i) = b.material.(0)) (Array.init t Fun.id) && b.material.(0) <> b.material.(t));
        List.iter
          (fun (what, s) -> Helpers.check_images what ~expected:(Helpers.image_exn ~skips:false s) (Helpers.image_exn s))
          [ ("the mesh first: skips against none", first); ("the planes first: skips against none", after) ]);
  ]
