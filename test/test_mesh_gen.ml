open Raytrace

(* Each undirected edge of [m] with the number of triangles that hold it,
   and whether any directed edge occurs twice (two triangles that disagree
   on orientation). *)
let edges (m : Mesh.Obj.t) =
  let undirected = Hashtbl.create 1024 and directed = Hashtbl.create 1024 in
  let twice = ref false in
  for t = 0 to Mesh.Obj.triangle_count m - 1 do
    for c = 0 to 2 do
      let a = m.triangles.((3 * t) + c) and b = m.triangles.((3 * t) + ((c + 1) mod 3)) in
      if Hashtbl.mem directed (a, b) then twice := true;
      Hashtbl.replace directed (a, b) ();
      let key = (min a b, max a b) in
      Hashtbl.replace undirected key (1 + Option.value ~default:0 (Hashtbl.find_opt undirected key))
    done
  done;
  (undirected, !twice)

let get a i = Vec3.v a.(3 * i) a.((3 * i) + 1) a.((3 * i) + 2)

(* The geometric normal of each triangle against the mean of its vertex
   normals: [f] is given the dot product of the two unit vectors. *)
let each_face (m : Mesh.Obj.t) f =
  for t = 0 to Mesh.Obj.triangle_count m - 1 do
    let p k = get m.positions m.triangles.((3 * t) + k) and n k = get m.normals m.triangle_normals.((3 * t) + k) in
    let g = Vec3.(cross (p 1 - p 0) (p 2 - p 0)) in
    let mean = Vec3.(n 0 + n 1 + n 2) in
    f t (Vec3.dot (Vec3.unit g) (Vec3.unit mean))
  done

let unit_normals (m : Mesh.Obj.t) =
  for i = 0 to (Array.length m.normals / 3) - 1 do
    let l = Vec3.norm (get m.normals i) in
    if Float.abs (l -. 1.) > 4e-16 then Alcotest.failf "normal %d has length 1 %+g" i (l -. 1.)
  done

let knots = [ (2, 3, 64, 8); (3, 5, 150, 6); (3, 2, 90, 12); (1, 1, 16, 3) ]
let knot (p, q, segments, sides) = Mesh.Gen.torus_knot ~p ~q ~radius:2. ~tube:0.2 ~segments ~sides

let tests =
  [
    Alcotest.test_case "a torus knot has segments x sides vertices and twice as many triangles" `Quick (fun () ->
        List.iter
          (fun ((_, _, s, r) as k) ->
            let m = knot k in
            Alcotest.(check int) __LOC__ (s * r) (Mesh.Obj.vertex_count m);
            Alcotest.(check int) __LOC__ (s * r) (Array.length m.normals / 3);
            Alcotest.(check int) __LOC__ (2 * s * r) (Mesh.Obj.triangle_count m);
            Alcotest.(check bool) __LOC__ true (m.triangles = m.triangle_normals))
          knots);
    Alcotest.test_case "a torus knot is closed: every edge in two triangles, once each way" `Quick (fun () ->
        List.iter
          (fun k ->
            let undirected, twice = edges (knot k) in
            Alcotest.(check bool) __LOC__ false twice;
            Hashtbl.iter (fun (a, b) n -> if n <> 2 then Alcotest.failf "edge %d-%d in %d triangles" a b n) undirected)
          knots);
    Alcotest.test_case "a torus knot's normals are unit length and its faces face them" `Quick (fun () ->
        List.iter
          (fun k ->
            let m = knot k in
            unit_normals m;
            (* Thin triangles on a tube of 8 or more sides: within 45 degrees. *)
            each_face m (fun t c -> if c < 0.7 then Alcotest.failf "triangle %d: cos %g" t c))
          knots);
    Alcotest.test_case "a torus knot's vertices lie at tube distance from its curve" `Quick (fun () ->
        (* Vertex (i, j) minus tube times its normal is the curve at
           t = 2 pi i / segments, whose z is -radius/3 sin (q t). *)
        let segments = 64 and sides = 8 in
        let m = knot (2, 3, segments, sides) in
        for i = 0 to segments - 1 do
          for j = 0 to sides - 1 do
            let k = (i * sides) + j in
            let c = Vec3.(get m.positions k - smul 0.2 (get m.normals k)) in
            let t = 8. *. atan 1. *. Float.of_int i /. Float.of_int segments in
            Alcotest.(check (float 1e-12)) __LOC__ (-2. /. 3. *. sin (3. *. t)) c.z
          done
        done);
    Alcotest.test_case "a terrain of nx x nz cells has 2 nx nz triangles facing up" `Quick (fun () ->
        List.iter
          (fun (nx, nz) ->
            let m = Mesh.Gen.terrain ~seed:7 ~nx ~nz ~size:10. ~height:2. in
            Alcotest.(check int) __LOC__ ((nx + 1) * (nz + 1)) (Mesh.Obj.vertex_count m);
            Alcotest.(check int) __LOC__ (2 * nx * nz) (Mesh.Obj.triangle_count m);
            unit_normals m;
            for t = 0 to Mesh.Obj.triangle_count m - 1 do
              let p k = get m.positions m.triangles.((3 * t) + k) in
              let g = Vec3.(cross (p 1 - p 0) (p 2 - p 0)) in
              if not (g.y > 0.) then Alcotest.failf "triangle %d faces down" t
            done;
            for i = 0 to Mesh.Obj.vertex_count m - 1 do
              let p = get m.positions i in
              if not (p.y >= 0. && p.y <= 2. && Float.abs p.x <= 5. && Float.abs p.z <= 5.) then
                Alcotest.failf "vertex %d outside the box" i
            done)
          [ (1, 1); (3, 5); (64, 48) ]);
    Alcotest.test_case "a terrain is the same for the same seed and differs for another" `Quick (fun () ->
        let t s = Mesh.Gen.terrain ~seed:s ~nx:20 ~nz:20 ~size:4. ~height:1. in
        Alcotest.(check bool) __LOC__ true (Mesh.Obj.equal (t 1) (t 1));
        Alcotest.(check bool) __LOC__ false (Mesh.Obj.equal (t 1) (t 2));
        (* Not flat: heights span a good part of [0, height]. *)
        let ys = Array.init (Mesh.Obj.vertex_count (t 1)) (fun i -> (t 1).positions.((3 * i) + 1)) in
        let lo = Array.fold_left min infinity ys and hi = Array.fold_left max neg_infinity ys in
        Alcotest.(check bool) (Printf.sprintf "heights %g..%g" lo hi) true (hi -. lo > 0.3));
    Alcotest.test_case "generated meshes read back from their OBJ text unchanged" `Quick (fun () ->
        List.iter
          (fun m ->
            match Mesh.Obj.of_string ~name:"gen.obj" ~max_vertices:100_000 ~max_triangles:100_000 (Mesh.Obj.to_string m) with
            | Error (`Msg e) -> Alcotest.fail e
            | Ok back -> Alcotest.(check bool) __LOC__ true (Mesh.Obj.equal m back))
          [ knot (2, 3, 64, 8); Mesh.Gen.terrain ~seed:3 ~nx:30 ~nz:20 ~size:8. ~height:1.5 ]);
    Alcotest.test_case "generators refuse meaningless arguments" `Quick (fun () ->
        let bad f = match f () with _ -> Alcotest.fail "accepted" | exception Invalid_argument _ -> () in
        bad (fun () -> Mesh.Gen.torus_knot ~p:0 ~q:3 ~radius:1. ~tube:0.1 ~segments:10 ~sides:4);
        bad (fun () -> Mesh.Gen.torus_knot ~p:2 ~q:3 ~radius:1. ~tube:0.1 ~segments:2 ~sides:4);
        bad (fun () -> Mesh.Gen.torus_knot ~p:2 ~q:3 ~radius:1. ~tube:nan ~segments:10 ~sides:4);
        bad (fun () -> Mesh.Gen.terrain ~seed:0 ~nx:0 ~nz:3 ~size:1. ~height:1.);
        bad (fun () -> Mesh.Gen.terrain ~seed:0 ~nx:3 ~nz:3 ~size:infinity ~height:1.));
  ]
