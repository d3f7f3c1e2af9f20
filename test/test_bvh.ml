open Raytrace

let random_spheres n seed =
  let rand = Random.State.make [| seed |] in
  let f lo hi = lo +. Random.State.float rand (hi -. lo) in
  ( Array.init n (fun _ -> f (-50.) 50.),
    Array.init n (fun _ -> f (-50.) 50.),
    Array.init n (fun _ -> f 0. 100.),
    Array.init n (fun i -> if i = 0 then 5000. else f 0.01 3.) )

let inside (b : Bvh.t) k x y z e =
  Bvh.lo b k 0 <= x -. e && x +. e <= Bvh.hi b k 0
  && Bvh.lo b k 1 <= y -. e && y +. e <= Bvh.hi b k 1
  && Bvh.lo b k 2 <= z -. e && z +. e <= Bvh.hi b k 2

(* Calls [f leaf slot path] for every slot of [b], with its leaf and the
   nodes from that leaf up to the root. *)
let iter_slots (b : Bvh.t) f =
  let rec walk k path =
    let tag = Bvh.tag b k and link = Bvh.link b k in
    if tag > 0 then
      for slot = link to link + tag - 1 do
        f k slot (k :: path)
      done
    else begin
      if tag < -3 then Alcotest.failf "inner node %d has the tag %d, not an axis" k tag;
      walk (k + 1) (k :: path);
      walk link (k :: path)
    end
  in
  walk 0 []

(* [build ?beside boxes] is the hierarchy over copies of [boxes] (lower
   corners, then upper), and the copies, reordered into slot order;
   none with [beside], which leaves the slots of the part it built in an
   order of their own. *)
let build ?leaf_size ?beside boxes =
  let b = Array.map Array.copy boxes in
  let t = Bvh.build_boxes ?leaf_size ?beside ~x0:b.(0) ~y0:b.(1) ~z0:b.(2) ~x1:b.(3) ~y1:b.(4) ~z1:b.(5) () in
  (t, if beside = None then b else [||])

(* [beside] of the renderer with [min_objects], counting in [built] the
   parts that another process built. A core is taken to be idle (unless
   [idle] says otherwise), whatever else runs beside the tests, and a
   late child is waited for, not taken over: on a loaded host the parent
   would otherwise build the part itself and the count would say 0. *)
let counting ?(idle = fun () -> true) ~min_objects built =
  let b = Render_jobs.bvh_beside ~min_objects ~idle ~take_over:false () in
  let me = Unix.getpid () in
  let beside f =
    let wait = b.beside (fun () -> (Unix.getpid (), f ())) in
    fun () ->
      Option.map
        (fun (pid, x) ->
          if pid <> me then incr built;
          x)
        (wait ())
  in
  { b with Bvh.beside }

(* Floats of this process's own memory, for a [beside] that computes here. *)
let own n = (Bigarray.Array1.create Bigarray.float64 Bigarray.c_layout n, fun _ -> ())

(* A generated mesh ([Mesh.Gen]) as a shape of the scene. *)
let mesh_shape ?(smooth = false) ?(translate = Vec3.zero) (o : Mesh.Obj.t) material =
  match
    Mesh.v ~smooth ~translate ~positions:o.positions ~triangles:o.triangles ~normals:o.normals
      ~triangle_normals:o.triangle_normals material
  with
  | Ok m -> Shape.Mesh m
  | Error (`Msg m) -> Alcotest.fail m

let bits = Array.map Int64.bits_of_float

(* Fails unless [a] and [b] are the same tree over the same slots, field
   by field, every float bit for bit. *)
let check_same what ((a : Bvh.t), sa) ((b : Bvh.t), sb) =
  let n = a.n_nodes in
  Alcotest.(check int) (what ^ ": nodes") n b.n_nodes;
  Alcotest.(check int) (what ^ ": depth") a.depth b.depth;
  Alcotest.(check (array int)) (what ^ ": order") a.order b.order;
  (* Boxes, links and tags, node by node: the nodes may start at another
     offset of their array in each. *)
  let node (t : Bvh.t) k =
    List.map Int64.bits_of_float
      [ Bvh.lo t k 0; Bvh.lo t k 1; Bvh.lo t k 2; Bvh.hi t k 0; Bvh.hi t k 1; Bvh.hi t k 2 ]
    @ [ Int64.of_int (Bvh.link t k); Int64.of_int (Bvh.tag t k) ]
  in
  for k = 0 to n - 1 do
    Alcotest.(check (list int64)) (Printf.sprintf "%s: node %d" what k) (node a k) (node b k)
  done;
  if sa <> [||] && sb <> [||] then
    Array.iteri (fun i x -> Alcotest.(check (array int64)) (what ^ ": slot boxes") (bits x) (bits sb.(i))) sa

(* [n] boxes: [kind] `Random, `Same_center (every center the same: one
   bin, split at the median), `One_bin (centers within 1e-9 of each
   other, boxes a million times wider: bins of rounding). *)
let boxes kind n seed =
  let rand = Random.State.make [| seed |] in
  let f lo hi = lo +. Random.State.float rand (hi -. lo) in
  let b = Array.init 6 (fun _ -> Array.make n 0.) in
  for i = 0 to n - 1 do
    for a = 0 to 2 do
      let c = match kind with `Random -> f (-100.) 100. | `Same_center -> 1.5 | `One_bin -> 1. +. f 0. 1e-9 in
      let h = match kind with `Random -> f 0. 2. | _ -> 0.5 +. f 0. 0.25 in
      b.(a).(i) <- c -. h;
      b.(a + 3).(i) <- c +. h
    done
  done;
  b

(* The reference build, as the hierarchy was first built and as
   Bvh.mli describes it: at each node, the bounds of its objects' boxes
   and doubled centers found from its slots, one pass binning its objects
   (16 bins along the centers' longest axis), the split of lowest surface
   area heuristic cost, then one pass moving the slots (slot [i] kept if
   on the left, else exchanged with the last slot not yet placed), or
   Hoare's selection at the median. Plain arrays and lists, nothing
   shared with Bvh: [(order, depth, nodes)], [nodes.(k)] node [k]'s tag
   and link as {!Bvh.tag} and {!Bvh.link} give them. *)
let reference ~leaf_size (boxes : float array array) =
  let n = Array.length boxes.(0) in
  let b = Array.map Array.copy boxes in
  let order = Array.init n Fun.id and bin = Array.make n 0 in
  let swap i j =
    let sw a = let x = a.(i) in a.(i) <- a.(j); a.(j) <- x in
    Array.iter sw b; sw order; sw bin
  in
  let center a s = b.(a).(s) +. b.(a + 3).(s) in
  (* Of equal bounds (0. and -0.), the later one, as Bvh's. *)
  let fmin x y = if x < y then x else y and fmax x y = if x > y then x else y in
  let empty () = [| infinity; infinity; infinity; neg_infinity; neg_infinity; neg_infinity |] in
  let grow u (v : float array) = for i = 0 to 2 do u.(i) <- fmin u.(i) v.(i); u.(i + 3) <- fmax u.(i + 3) v.(i + 3) done in
  let half u = let dx = u.(3) -. u.(0) and dy = u.(4) -. u.(1) and dz = u.(5) -. u.(2) in (dx *. dy) +. (dy *. dz) +. (dz *. dx) in
  let select a lo hi k =
    let lo = ref lo and hi = ref (hi - 1) in
    while !lo < !hi do
      let pivot = center a ((!lo + !hi) / 2) in
      let i = ref !lo and j = ref !hi in
      while !i <= !j do
        while center a !i < pivot do incr i done;
        while center a !j > pivot do decr j done;
        if !i <= !j then begin swap !i !j; incr i; decr j end
      done;
      if k <= !j then hi := !j else if k >= !i then lo := !i else lo := !hi
    done
  in
  let nodes = ref [] and count = ref 0 and depth = ref 0 in
  let rec node lo hi level =
    let cell = ref (0, 0) in
    nodes := cell :: !nodes;
    incr count;
    depth := max !depth level;
    let n = hi - lo in
    let box = empty () and centers = empty () in
    for s = lo to hi - 1 do
      grow box (Array.init 6 (fun i -> b.(i).(s)));
      grow centers (Array.init 6 (fun i -> center (i mod 3) s))
    done;
    let ext = Array.init 3 (fun a -> centers.(a + 3) -. centers.(a)) in
    let a = if ext.(0) >= ext.(1) && ext.(0) >= ext.(2) then 0 else if ext.(1) >= ext.(2) then 1 else 2 in
    let nb = min n 16 in
    let split =
      if n <= 1 then `Leaf
      else if not (ext.(a) > 0.) then if n <= leaf_size then `Leaf else `Median
      else begin
        let scale = Float.of_int nb /. ext.(a) in
        let counts = Array.make nb 0 and bin_box = Array.init nb (fun _ -> empty ()) in
        for s = lo to hi - 1 do
          let x = truncate ((center a s -. centers.(a)) *. scale) in
          let x = if x < 0 then 0 else if x >= nb then nb - 1 else x in
          bin.(s) <- x;
          counts.(x) <- counts.(x) + 1;
          grow bin_box.(x) (Array.init 6 (fun i -> b.(i).(s)))
        done;
        let union b0 b1 = let u = empty () in for x = b0 to b1 do if counts.(x) > 0 then grow u bin_box.(x) done; u in
        let best = ref (-1) and best_cost = ref infinity and right = ref 0 and left = ref n in
        for x = nb - 1 downto 1 do
          right := !right + counts.(x);
          left := !left - counts.(x);
          if !left > 0 && !right > 0 then begin
            let cost = (half (union 0 (x - 1)) *. Float.of_int !left) +. (half (union x (nb - 1)) *. Float.of_int !right) in
            if cost < !best_cost then begin best_cost := cost; best := x - 1 end
          end
        done;
        let parent = half box in
        if !best < 0 then if n <= leaf_size then `Leaf else `Median
        else if n <= leaf_size && Float.of_int n *. parent <= parent +. !best_cost then `Leaf
        else begin
          let i = ref lo and j = ref (hi - 1) in
          while !i <= !j do
            if bin.(!i) <= !best then incr i else begin swap !i !j; decr j end
          done;
          `At !i
        end
      end
    in
    match split with
    | `Leaf -> cell := (n, lo)
    | (`Median | `At _) as split ->
        let m = match split with `At m -> m | `Median -> let m = (lo + hi) / 2 in select a lo hi m; m in
        node lo m (level + 1);
        let right = !count in
        node m hi (level + 1);
        cell := (-1 - a, right)
  in
  node 0 n 1;
  (order, !depth, Array.of_list (List.rev_map ( ! ) !nodes))

(* Fails unless [t] is the reference's tree over [boxes]. *)
let check_reference what ~leaf_size boxes (t : Bvh.t) =
  let order, depth, nodes = reference ~leaf_size boxes in
  Alcotest.(check int) (what ^ ": nodes") (Array.length nodes) t.n_nodes;
  Alcotest.(check int) (what ^ ": depth") depth t.depth;
  Alcotest.(check (array int)) (what ^ ": order") order t.order;
  Array.iteri
    (fun k (tag, link) ->
      Alcotest.(check (pair int int)) (Printf.sprintf "%s: node %d's tag and link" what k) (tag, link) (Bvh.tag t k, Bvh.link t k))
    nodes

let tests =
  [
    Alcotest.test_case "a part built in another process: the same tree, field by field" `Quick (fun () ->
        List.iter
          (fun (what, kind, n, min_objects) ->
            let one = build (boxes kind n n) in
            let built = ref 0 in
            let two = build ~beside:(counting ~min_objects built) (boxes kind n n) in
            check_same what one two;
            Alcotest.(check int) (what ^ ": parts built by another process") 1 !built)
          [
            ("random boxes", `Random, 5000, 1000);
            ("a million-like threshold, n just above", `Random, 2 * 65536 + 20, 65536);
            ("every center the same (one bin, median splits)", `Same_center, 3000, 100);
            ("centers within 1e-9", `One_bin, 3000, 100);
          ]);
    Alcotest.test_case "with no core idle, the renderer's beside forks nothing: the same tree, built here" `Quick
      (fun () ->
        let b = boxes `Random 5000 5000 in
        let one = build b in
        let built = ref 0 and asked = ref 0 in
        let idle () = incr asked; false in
        check_same "no idle core" one (build ~beside:(counting ~idle ~min_objects:1000 built) b);
        Alcotest.(check int) "asked at the fork" 1 !asked;
        Alcotest.(check int) "no part built by another process" 0 !built;
        (* No child was started: none is left to reap. *)
        match Unix.waitpid [ WNOHANG ] (-1) with
        | exception Unix.Unix_error (ECHILD, _, _) -> ()
        | pid, _ -> Alcotest.failf "a child was started: %d" pid);
    Alcotest.test_case "no part beside below the threshold, or where the beside fails" `Quick (fun () ->
        let b = boxes `Random 3000 3 in
        let one = build b in
        let built = ref 0 in
        check_same "threshold above n" one (build ~beside:(counting ~min_objects:3000 built) b);
        Alcotest.(check int) "no part beside" 0 !built;
        (* Leaves of more than 127 objects: tags that a byte cannot send. *)
        check_same "leaves of 200" (build ~leaf_size:200 b) (build ~leaf_size:200 ~beside:(counting ~min_objects:10 built) b);
        Alcotest.(check int) "no part beside for leaves of 200" 0 !built;
        check_same "leaves of 127" (build ~leaf_size:127 b) (build ~leaf_size:127 ~beside:(counting ~min_objects:10 built) b);
        Alcotest.(check int) "a part beside for leaves of 127" 1 !built;
        let calls = ref 0 in
        let failing = { Bvh.beside = (fun _ () -> incr calls; None); min_objects = 10; floats = own; idle = (fun () -> true) } in
        check_same "a beside that fails" one (build ~beside:failing b);
        Alcotest.(check int) "asked once" 1 !calls;
        (* Parallel.beside computes [f] in the caller when it cannot fork. *)
        let here = { Bvh.beside = (fun f () -> Some (f ())); min_objects = 10; floats = own; idle = (fun () -> true) } in
        check_same "a beside that computes here" one (build ~beside:here b);
        (* No shared memory (a full /dev/shm): built here, nothing started. *)
        let calls = ref 0 in
        let no_memory =
          { Bvh.beside = (fun f () -> incr calls; Some (f ())); min_objects = 10; floats = (fun _ -> failwith "no memory"); idle = (fun () -> true) }
        in
        check_same "no shared memory" one (build ~beside:no_memory b);
        Alcotest.(check int) "nothing built beside without shared memory" 0 !calls);
    Alcotest.test_case "grid:140000, above the threshold of 2^16: a part beside, the same tree and pixels" `Slow
      (fun () ->
        let s = (Scene.with_overrides ~width:48 ~height:48 ((Scene.grid 140_000))) in
        let tree (p : Prepared.t) = match p.bvh with Some b -> b | None -> Alcotest.fail "no hierarchy" in
        let built = ref 0 in
        let two = Prepared.prepare ~beside:(counting ~min_objects:(1 lsl 16) built) (Helpers.valid s) in
        (* The spheres' twins are found beside too (Prepared). *)
        Alcotest.(check int) "a part and the twins, by other processes" 2 !built;
        let one = Helpers.prepare s in
        check_same "grid:140000" (tree one, [||]) (tree two, [||]);
        (* The images of the two prepared scenes. *)
        let img p =
          let tr = Trace.create p in
          let w = (Scene.width s) and h = (Scene.height s) in
          Array.init (w * h) (fun i ->
              Trace.pixel tr ((i mod w) - (w / 2)) ((h / 2) - (i / w));
              (Trace.red tr, Trace.green tr, Trace.blue tr))
        in
        Alcotest.(check bool) "the same pixels" true (img one = img two));
    Alcotest.test_case "shared floats reserved later: a child reserves and writes them, the parent reads them" `Quick
      (fun () ->
        let r = Parallel.shared_floats_later 100_000 in
        let wait =
          Parallel.beside (fun () ->
              r.reserve 50_000;
              for i = 0 to 49_999 do
                r.floats.{i} <- Float.of_int (3 * i)
              done;
              7)
        in
        (match wait () with Ok v -> Alcotest.(check int) "the child's result" 7 v | Error (`Msg m) -> Alcotest.fail m);
        for i = 0 to 49_999 do
          if r.floats.{i} <> Float.of_int (3 * i) then Alcotest.failf "float %d is %g" i r.floats.{i}
        done;
        Alcotest.check_raises "more than were mapped" (Invalid_argument "Parallel.shared_floats_later: reserve")
          (fun () -> r.reserve 100_001);
        r.release ();
        r.release ();
        match r.reserve 10 with
        | () -> Alcotest.fail "a reserve after release"
        | exception Failure _ -> ());
    Alcotest.test_case "a part whose shared memory cannot be reserved is built here, the same tree" `Quick (fun () ->
        let b = boxes `Random 3000 4 in
        let one = build b in
        let built = ref 0 in
        let no_room =
          {
            (counting ~min_objects:100 built) with
            Bvh.floats =
              (fun n ->
                let r = Parallel.shared_floats_later n in
                (r.floats, fun _ -> failwith "cannot get 1 bytes of shared memory: No space left on device"));
          }
        in
        check_same "no room" one (build ~beside:no_room b);
        Alcotest.(check int) "nothing built by another process" 0 !built);
    Alcotest.test_case "a part beside below the root: the nodes built after it and their leaves" `Quick (fun () ->
        (* Clusters of 400, 400 and 200 boxes along x, far apart: the root
           splits off the 200 (under a quarter), its left child the two
           400s, whose right one is built beside; the 200 after the graft. *)
        let n = 1000 in
        let rand = Random.State.make [| 5 |] in
        let b = Array.init 6 (fun _ -> Array.make n 0.) in
        for i = 0 to n - 1 do
          let cluster = if i < 400 then 0. else if i < 800 then 100. else 10000. in
          for a = 0 to 2 do
            let c = (if a = 0 then cluster else 0.) +. Random.State.float rand 10. in
            let h = Random.State.float rand 1. in
            b.(a).(i) <- c -. h;
            b.(a + 3).(i) <- c +. h
          done
        done;
        let ((t, _) as one) = build b in
        (* The shape claimed above: node 1 (the root's left child) holds
           the two clusters of 400, its right child all of the second. *)
        let slots k = let rec count k = if Bvh.tag t k > 0 then Bvh.tag t k else count (k + 1) + count (Bvh.link t k) in count k in
        Alcotest.(check (list int)) "the root's children" [ 800; 200 ] [ slots 1; slots (Bvh.link t 0) ];
        Alcotest.(check (list int)) "node 1's children" [ 400; 400 ] [ slots 2; slots (Bvh.link t 1) ];
        let built = ref 0 in
        check_same "clusters" one (build ~beside:(counting ~min_objects:100 built) b);
        Alcotest.(check int) "a part built by another process" 1 !built);
    Helpers.qcheck ~count:30 "random box sets: the same tree with a part beside"
      QCheck.(pair (int_range 20 600) (int_range 0 1000))
      (fun (n, seed) ->
        let kind = match seed mod 3 with 0 -> `Random | 1 -> `Same_center | _ -> `One_bin in
        let b = boxes kind n seed in
        let built = ref 0 in
        check_same "random" (build b) (build ~beside:(counting ~min_objects:2 built) b);
        true);
    Alcotest.test_case "the tree is the reference build's, node for node, with and without a part beside" `Quick
      (fun () ->
        List.iter
          (fun (what, kind, n, leaf_size) ->
            let b = boxes kind n (n + leaf_size) in
            let t, _ = build ~leaf_size b in
            check_reference what ~leaf_size b t;
            let built = ref 0 in
            let t2, _ = build ~leaf_size ~beside:(counting ~min_objects:(n / 8) built) b in
            check_reference (what ^ ", a part beside") ~leaf_size b t2;
            Alcotest.(check int) (what ^ ": a part built by another process") 1 !built)
          [
            ("random boxes, leaves of 4", `Random, 4000, 4);
            ("random boxes, leaves of 16", `Random, 4000, 16);
            ("every center the same (median splits)", `Same_center, 700, 4);
            ("centers within 1e-9 (bins of rounding)", `One_bin, 700, 16);
          ];
        (* Centers at 2^i along x: each split takes off the farthest
           few, a tree of depth 100 or so, deeper than the 48 levels of
           nodes waiting to be built that the build makes room for first. *)
        let n = 400 in
        let b = Array.init 6 (fun _ -> Array.make n 0.) in
        for i = 0 to n - 1 do
          let c = Float.ldexp 1. i in
          b.(0).(i) <- c -. 0.5;
          b.(3).(i) <- c +. 0.5;
          b.(4).(i) <- 1.;
          b.(5).(i) <- 1.
        done;
        let t, _ = build b in
        if t.depth <= 48 then Alcotest.failf "depth %d" t.depth;
        check_reference "a deep tree" ~leaf_size:4 b t);
    Helpers.qcheck ~count:40 "random box sets: the reference build's tree"
      QCheck.(triple (int_range 1 700) (int_range 0 1000) bool)
      (fun (n, seed, sixteen) ->
        let kind = match seed mod 3 with 0 -> `Random | 1 -> `Same_center | _ -> `One_bin in
        let leaf_size = if sixteen then 16 else 4 in
        let b = boxes kind n seed in
        check_reference "random" ~leaf_size b (fst (build ~leaf_size b));
        true);
    Alcotest.test_case "every sphere sits in exactly one leaf, inside every box above it" `Quick (fun () ->
        List.iter
          (fun n ->
            let cx, cy, cz, e = random_spheres n n in
            let b = Bvh.build ~cx ~cy ~cz e in
            let seen = Array.make n 0 in
            iter_slots b (fun k slot path ->
                if Bvh.tag b k > 4 then Alcotest.failf "leaf %d holds %d spheres" k (Bvh.tag b k);
                let i = b.order.(slot) in
                seen.(i) <- seen.(i) + 1;
                List.iter
                  (fun j ->
                    if not (inside b j cx.(i) cy.(i) cz.(i) e.(i)) then
                      Alcotest.failf "sphere %d sticks out of box %d" i j)
                  path);
            Alcotest.(check (array int)) (Printf.sprintf "%d spheres each once" n) (Array.make n 1) seen;
            Alcotest.(check int) "order is a permutation" n
              (List.length (List.sort_uniq compare (Array.to_list b.order))))
          [ 1; 2; 5; 9; 100; 1000 ]);
    Alcotest.test_case "boxes of any shape each sit in one leaf, inside every box above it" `Quick (fun () ->
        (* Slivers, as a mesh's triangles are: thin along a random axis. *)
        let n = 2000 in
        let rand = Random.State.make [| 7 |] in
        let f lo hi = lo +. Random.State.float rand (hi -. lo) in
        let lo = Array.init 3 (fun _ -> Array.make n 0.) and hi = Array.init 3 (fun _ -> Array.make n 0.) in
        for i = 0 to n - 1 do
          let thin = Random.State.int rand 3 in
          for a = 0 to 2 do
            let c = f (-10.) 10. and h = if a = thin then 0. else f 0. 0.5 in
            lo.(a).(i) <- c -. h;
            hi.(a).(i) <- c +. h
          done
        done;
        let copy = Array.map Array.copy in
        let l = copy lo and h = copy hi in
        let b = Bvh.build_boxes ~x0:l.(0) ~y0:l.(1) ~z0:l.(2) ~x1:h.(0) ~y1:h.(1) ~z1:h.(2) () in
        let seen = Array.make n 0 in
        iter_slots b (fun _ slot path ->
            let i = b.order.(slot) in
            seen.(i) <- seen.(i) + 1;
            (* The arrays were reordered into slot order. *)
            if l.(0).(slot) <> lo.(0).(i) || h.(2).(slot) <> hi.(2).(i) then
              Alcotest.failf "slot %d does not hold the box of object %d" slot i;
            List.iter
              (fun j ->
                let inside =
                  Bvh.lo b j 0 <= lo.(0).(i) && hi.(0).(i) <= Bvh.hi b j 0
                  && Bvh.lo b j 1 <= lo.(1).(i) && hi.(1).(i) <= Bvh.hi b j 1
                  && Bvh.lo b j 2 <= lo.(2).(i) && hi.(2).(i) <= Bvh.hi b j 2
                in
                if not inside then Alcotest.failf "box %d sticks out of node %d" i j)
              path);
        Alcotest.(check (array int)) "each box once" (Array.make n 1) seen);
    Alcotest.test_case "a node is one block of 8 floats: its box, link and tag, the box its contents'" `Quick
      (fun () ->
        let n = 3000 in
        let boxes = boxes `Random n 11 in
        let b, slot_boxes = build boxes in
        Alcotest.(check int) __LOC__ ((8 * b.n_nodes) + 7) (Array.length b.nodes);
        Alcotest.(check int) __LOC__ 8 Bvh.node_floats;
        if b.root < 0 || b.root > 7 then Alcotest.failf "node 0 at offset %d" b.root;
        (* The address of the nodes' first float: the array as an int is
           half its pointer, less one half, in tagged arithmetic. *)
        let address = ((Obj.magic b.nodes : int) * 2) + 1 + (8 * b.root) in
        Alcotest.(check int) "node 0 starts a cache line" 0 (address land 63);
        let same what x y =
          if Int64.bits_of_float x <> Int64.bits_of_float y then Alcotest.failf "%s: %h, not %h" what x y
        in
        let slots = ref 0 in
        for k = 0 to b.n_nodes - 1 do
          let o = b.root + (8 * k) in
          Alcotest.(check int) __LOC__ o (Bvh.offset b k);
          (* The layout that the tracer reads, float for float. *)
          for a = 0 to 2 do
            same "lower" b.nodes.(o + a) (Bvh.lo b k a);
            same "upper" b.nodes.(o + 3 + a) (Bvh.hi b k a)
          done;
          let link = Bvh.link b k and tag = Bvh.tag b k in
          (* An inner node's link in [nodes] is its right child's offset. *)
          let raw = if tag > 0 then link else Bvh.offset b link in
          same "link" b.nodes.(o + 6) (Float.of_int raw);
          same "tag" b.nodes.(o + 7) (Float.of_int tag);
          (* Each box the min and max of what it holds, bit for bit. *)
          let expect a f =
            if tag > 0 then begin
              let m = ref slot_boxes.(a).(link) in
              for s = link + 1 to link + tag - 1 do
                m := f !m slot_boxes.(a).(s)
              done;
              !m
            end
            else
              let child c = if a < 3 then Bvh.lo b c a else Bvh.hi b c (a - 3) in
              f (child (k + 1)) (child link)
          in
          (* Of equal bounds (0. and -0.), the later one. *)
          let fmin x y = if x < y then x else y and fmax x y = if x > y then x else y in
          for a = 0 to 2 do
            same "leaf or union, lower" (Bvh.lo b k a) (expect a fmin);
            same "leaf or union, upper" (Bvh.hi b k a) (expect (a + 3) fmax)
          done;
          if tag > 0 then begin
            (* Leaves in depth-first order take the slots in order. *)
            Alcotest.(check int) "a leaf's first slot" !slots link;
            slots := !slots + tag
          end
          else if tag < -3 || link <= k + 1 || link >= b.n_nodes then
            Alcotest.failf "inner node %d: tag %d, right child %d" k tag link
        done;
        Alcotest.(check int) "every slot in a leaf" n !slots;
        let raises what f = match f () with _ -> Alcotest.failf "%s: no exception" what | exception Invalid_argument _ -> () in
        raises "node -1" (fun () -> Bvh.link b (-1));
        raises "node n_nodes" (fun () -> Bvh.tag b b.n_nodes);
        raises "axis 3" (fun () -> Bvh.lo b 0 3);
        raises "axis -1" (fun () -> Bvh.hi b 0 (-1)));
    Alcotest.test_case "the tree of grid:10000 is shallow" `Quick (fun () ->
        let p = Helpers.prepare (Scene.grid 10000) in
        match p.bvh with
        | None -> Alcotest.fail "no hierarchy for 10001 spheres"
        | Some b ->
            (* log2 (10001 / 4) = 11.3; the binned build stays within a small
               factor of it *)
            if b.depth > 40 then Alcotest.failf "depth %d" b.depth);
    Alcotest.test_case "grid:100000, the benchmark's largest scene, is within the default limits" `Quick
      (fun () ->
        match Scene.validate (Scene.grid 100_000) with
        | Ok _ -> ()
        | Error (`Msg m) -> Alcotest.fail m);
    Alcotest.test_case "identical centers do not break the build" `Quick (fun () ->
        let n = 50 in
        let b = Bvh.build ~cx:(Array.make n 1.) ~cy:(Array.make n 2.) ~cz:(Array.make n 3.) (Array.make n 0.5) in
        Alcotest.(check int) __LOC__ n (Array.length b.order));
    Alcotest.test_case "box margins cover the textbook's rounding and stay tiny" `Quick (fun () ->
        (* the reference scene's bounding box (camera and spheres) spans
           10000 x 10002 x 10000: D^2 = 3.0004e8; largest coordinate 10001;
           smallest radius 1: 64 u (3.0004e8 + 1e4) = 2.13e-6 *)
        let s = Scene.cgfs in
        let arr f = Array.of_list (List.map f (Private.Spheres.to_list (Scene.spheres s))) in
        let m =
          Bvh.ray_box_margin ~cx:(arr (fun s -> s.center.x)) ~cy:(arr (fun s -> s.center.y))
            ~cz:(arr (fun s -> s.center.z)) ~radius:(arr (fun s -> s.radius)) (Scene.camera s).position
        in
        Alcotest.(check (float 1e-8)) "radius 1" 2.132e-6 m.(0);
        Array.iter (fun x -> if not (x > 0. && x < 3e-6) then Alcotest.failf "margin %g" x) m);
    Alcotest.test_case "the margin from the bounds of spheres and camera is the margin from the spheres, bit for bit"
      `Quick (fun () ->
        (* Prepared.mesh_boxes finds the bounds as it makes the boxes. *)
        let cx, cy, cz, r = random_spheres 500 7 in
        let camera = Vec3.v 3. (-2.) (-60.) in
        let b = [| camera.x; camera.y; camera.z; camera.x; camera.y; camera.z |] in
        Array.iteri
          (fun i x ->
            b.(0) <- Float.min b.(0) (x -. r.(i));
            b.(1) <- Float.min b.(1) (cy.(i) -. r.(i));
            b.(2) <- Float.min b.(2) (cz.(i) -. r.(i));
            b.(3) <- Float.max b.(3) (x +. r.(i));
            b.(4) <- Float.max b.(4) (cy.(i) +. r.(i));
            b.(5) <- Float.max b.(5) (cz.(i) +. r.(i)))
          cx;
        let terms = Bvh.margin_of_bounds b in
        let margins = Bvh.ray_box_margin ~cx ~cy ~cz ~radius:r camera in
        Array.iteri
          (fun i m ->
            Alcotest.(check int64) (Printf.sprintf "sphere %d" i) (Int64.bits_of_float m)
              (Int64.bits_of_float (Bvh.margin terms r.(i))))
          margins;
        (* The terms themselves: D^2 of the box, M its largest magnitude. *)
        let from = Bvh.margin_terms ~cx ~cy ~cz ~radius:r camera in
        Alcotest.(check (float 0.)) "D^2" from.d2 terms.d2;
        Alcotest.(check (float 0.)) "M" from.m terms.m);
    Alcotest.test_case
      "the work on dense scenes is pinned: a knot of 38,400 thin triangles, a terrain of 45,000, a grid of 40,000 spheres"
      `Quick (fun () ->
        (* The small scenes of the shapes suite never fill a leaf of 16 or
           reach the binned split's choices; these do, so that a change of
           the hierarchy's build (leaf size, bins, the surface area costs,
           the margins) or of its traversal (the order of the children,
           the early exits of shadow rays) shows here as more (or fewer)
           tests. The build is deterministic (Mesh_gen's and Scene.grid's
           floats are the same on every 64-bit platform, the binned build
           has no randomness, one job), so the counts are exact: a change
           here means the tracer does more or less work than it did; say
           why in the commit and update them. *)
        (* The knot of docs/performance.md, smaller, shiny and smooth, in the
           reference scene's light over its yellow ground, beside its
           spheres: primary, shadow and reflected rays all cross the
           mesh's hierarchy. A square tube of 4800 rings: thin triangles,
           short along the tube and long around it, as the 1M-triangle
           knot's are, whose overlapping boxes make the surface area
           heuristic keep leaves of up to 16 (with leaves of 8 or 32 the
           tree differs; with the 24 sides of the first try, no leaf held
           more than 4 and the leaf size changed nothing). *)
        let knot =
          let o = Mesh.Gen.torus_knot ~p:2 ~q:3 ~radius:2. ~tube:0.3 ~segments:4800 ~sides:4 in
          Helpers.with_objects
            ~shapes:[ mesh_shape ~smooth:true ~translate:(Vec3.v 0. 0.5 5.) o (Material.v ~specular:300. ~reflective:0.2 (Color.v 230. 150. 40.)) ]
            (Scene.with_overrides ~width:96 ~height:96 Scene.cgfs)
        in
        (* A terrain seen from above at a slant, lit from the side: long
           shadow rays across the height field. *)
        let terrain =
          let o = Mesh.Gen.terrain ~seed:30 ~nx:150 ~nz:150 ~size:20. ~height:3. in
          let camera = match Camera.look_at ~position:(Vec3.v 0. 9. (-14.)) (Vec3.v 0. 0. 2.) with Ok c -> c | Error (`Msg m) -> Alcotest.fail m in
          Helpers.scene ~width:96 ~height:72 ~camera ~spheres:[]
            ~shapes:[ mesh_shape o (Material.v ~specular:10. (Color.v 90. 160. 60.)) ]
            ~lights:[ Light.ambient 0.2; Light.point 0.5 (Vec3.v (-8.) 6. 0.); Light.directional 0.3 (Vec3.v 1. 0.4 0.2) ] ()
        in
        let grid = Scene.with_overrides ~width:96 ~height:96 (Scene.grid 40_000) in
        let counts (st : Render.Stats.t) = [ st.primary; st.shadow; st.reflection; st.tests; st.box_tests; st.early_stops ] in
        let tree s = match (Helpers.prepare s).bvh with Some b -> [ b.n_nodes; b.depth ] | None -> [] in
        let fails = ref [] in
        List.iter
          (fun (name, s, expected, expected_tree) ->
            let st = match Helpers.render ~jobs:1 s with Ok (_, st) -> st | Error (`Msg m) -> Alcotest.fail m in
            let got = counts st and got_tree = tree s in
            let show l = String.concat "; " (List.map string_of_int l) in
            Printf.printf "%s: primary, shadow, reflection, tests, box tests, early stops [%s]; nodes, depth [%s]\n" name
              (show got) (show got_tree);
            if got <> expected then
              fails :=
                Printf.sprintf "%s: primary, shadow, reflection, tests, box tests, early stops: expected [%s], got [%s]" name
                  (show expected) (show got)
                :: !fails;
            if got_tree <> expected_tree then
              fails := Printf.sprintf "%s: nodes, depth: expected [%s], got [%s]" name (show expected_tree) (show got_tree) :: !fails)
          [
            (* Traced in squares since issue 26's third pass (Sampling_rows):
               each light's last blocker, tried first, is a neighbour's in
               the square, no longer the row's: 3,160 fewer tests. *)
            ("knot", knot, [ 9216; 20622; 14199; 1486809; 1284466; 0 ], [ 8547; 17 ]);
            ("terrain", terrain, [ 6912; 9297; 0; 49807; 600829; 0 ], [ 45085; 17 ]);
            ("grid:40000", grid, [ 9216; 13088; 6874; 29254; 298324; 0 ], [ 43137; 17 ]);
          ];
        if !fails <> [] then Alcotest.fail (String.concat "\n" (List.rev !fails)));
    Alcotest.test_case "leaves cut by planes (Prepared.prepare ~cut): the same image, fewer triangle tests" `Slow (fun () ->
        (* The pinned test's knot: a square tube of 4800 rings, thin
           triangles; shiny, smooth, reflective, over the reference
           scene's ground: primary, shadow and reflected rays. *)
        let o = Mesh.Gen.torus_knot ~p:2 ~q:3 ~radius:2. ~tube:0.3 ~segments:4800 ~sides:4 in
        let m =
          mesh_shape ~smooth:true ~translate:(Vec3.v 0. 0.5 5.) o (Material.v ~specular:300. ~reflective:0.2 (Color.v 230. 150. 40.))
        in
        let s = Helpers.with_objects ~shapes:[ m ] (Scene.with_overrides ~width:96 ~height:96 Scene.cgfs) in
        let run cut =
          let p = Prepared.prepare ~cut (Helpers.valid s) in
          let tr = Trace.create p in
          let img = Helpers.by_pixels tr in
          let c = Trace.counters tr in
          let nodes = match p.bvh with Some b -> b.n_nodes | None -> 0 in
          Printf.printf "cut %b: %d nodes, %d tests, %d box tests\n" cut nodes c.tests c.box_tests;
          (img, nodes, c.tests, c.box_tests)
        in
        let img, nodes, tests, boxes = run false and img', nodes', tests', boxes' = run true in
        Helpers.check_images "the cut tree's image" ~expected:img img';
        Alcotest.(check bool) "the same bytes" true (Image.equal img img');
        (* 38,400 triangles in leaves of about 9: most are cut. *)
        Alcotest.(check bool) "more nodes" true (nodes' > nodes);
        Alcotest.(check bool) "fewer triangle tests" true (tests' < tests);
        Alcotest.(check bool) "fewer tests in all, a box test priced at a third of a triangle's" true
          ((3 * tests') + boxes' < (3 * tests) + boxes));
    Alcotest.test_case "leaves cut twice over (Bvh.split_leaves ~cuts:2): a tree whose boxes hold their children, deeper than one cut"
      `Quick (fun () ->
        (* More than one cut a leaf outgrows the room made for one: the
           node array is grown while it is written. The margin is the
           bounds' of a cube of side 200 around the scene, larger than
           prepare's (so one cut here is not prepare's [~cut] tree). *)
        let o = Mesh.Gen.torus_knot ~p:2 ~q:3 ~radius:2. ~tube:0.3 ~segments:4800 ~sides:4 in
        let m = mesh_shape ~translate:(Vec3.v 0. 0.5 5.) o (Material.v (Color.v 230. 150. 40.)) in
        let s = Helpers.valid (Helpers.with_objects ~shapes:[ m ] (Scene.with_overrides ~width:32 ~height:32 Scene.cgfs)) in
        let p = Prepared.prepare s in
        let b = match p.bvh with Some b -> b | None -> Alcotest.fail "no hierarchy" in
        let margin = Bvh.margin_of_bounds [| -100.; -100.; -100.; 100.; 100.; 100. |] in
        let n = Array.length p.kind in
        let triangle s = s < n && Kind.is_triangle p.kind.(s) in
        let cut cuts = Bvh.split_leaves ~cuts b ~triangle ~vertex:p.vertex ~at0:p.at0 ~at1:p.at1 ~at2:p.at2 ~margin in
        let one = cut 1 and two = cut 2 in
        Printf.printf "nodes: %d, one cut %d, two cuts %d; depth %d, %d, %d\n" b.n_nodes one.n_nodes two.n_nodes b.depth one.depth
          two.depth;
        Alcotest.(check bool) "more nodes" true (two.n_nodes > one.n_nodes && one.n_nodes > b.n_nodes);
        (* Every inner node's box the union of its children's, every leaf
           over slots of the tree, the depth the longest path. *)
        let check (t : Bvh.t) =
          let rec walk k level =
            let g = Bvh.tag t k in
            if g > 0 then begin
              if Bvh.link t k < 0 || Bvh.link t k + g > n then Alcotest.failf "leaf %d over slots out of range" k;
              level
            end
            else begin
              let r = Bvh.link t k in
              List.iter
                (fun a ->
                  if Bvh.lo t k a <> Float.min (Bvh.lo t (k + 1) a) (Bvh.lo t r a)
                     || Bvh.hi t k a <> Float.max (Bvh.hi t (k + 1) a) (Bvh.hi t r a)
                  then Alcotest.failf "node %d: not its children's union" k)
                [ 0; 1; 2 ];
              max (walk (k + 1) (level + 1)) (walk r (level + 1))
            end
          in
          Alcotest.(check int) "depth" t.depth (walk 0 1)
        in
        check one;
        check two);
    Alcotest.test_case "a terrain's leaves of one grid cell are not cut: the same nodes with the cut as without" `Quick
      (fun () ->
        (* Leaves of one or two triangles (a cell's two, whose boxes are
           the cell's) are not tried: no fewer than [cost] = 3 slots
           ever pays. The tree is then not copied at all. *)
        let o = Mesh.Gen.terrain ~seed:30 ~nx:60 ~nz:60 ~size:20. ~height:3. in
        let m = mesh_shape o (Material.v (Color.v 90. 160. 60.)) in
        let s = Helpers.with_objects ~shapes:[ m ] (Scene.with_overrides ~width:32 ~height:32 Scene.cgfs) in
        let tree cut = match (Prepared.prepare ~cut (Helpers.valid s)).bvh with Some b -> b | None -> Alcotest.fail "no hierarchy" in
        let a = tree false and b = tree true in
        Alcotest.(check int) "nodes" a.n_nodes b.n_nodes;
        for k = 0 to a.n_nodes - 1 do
          let node (t : Bvh.t) = (List.init 3 (Bvh.lo t k), List.init 3 (Bvh.hi t k), Bvh.link t k, Bvh.tag t k) in
          if node a <> node b then Alcotest.failf "node %d differs" k;
          if Bvh.tag a k > 3 then Alcotest.failf "leaf %d holds %d triangles" k (Bvh.tag a k)
        done);
    Helpers.qcheck ~count:150 "crowded scenes: the hierarchy gives the brute force's bytes"
      (QCheck.make ~print:Scene_file.to_string Gen_scene.crowd)
      (fun s ->
        let render skips s = Helpers.image_exn ~skips s in
        Image.equal (render false s) (render true s)
        && Image.equal (render false (Scene.with_overrides ~epsilon:None s)) (render true (Scene.with_overrides ~epsilon:None s)));
    Helpers.qcheck ~count:60 "crowded scenes in the document's mode: the oracle's bytes"
      (QCheck.make ~print:Scene_file.to_string Gen_scene.crowd)
      (fun s ->
        let s = (Scene.with_overrides ~epsilon:(Some 0.001) s) in
        Image.equal (Private.Literal.render (Helpers.valid s)) (Helpers.image_exn s));
    Alcotest.test_case
      "a ray of every octant, and along the axes, finds through the hierarchy the closest triangle of all, first of equals"
      `Quick (fun () ->
        (* The traversal tests a box's near planes, chosen once a ray by
           the signs of its slab inverses (a zero coordinate, [0.] or
           [-0.], counts as positive), and a node's children at the
           node, the nearer first. Whatever it visits, its hit must be
           every triangle's closest root beyond [t_min] (here 0: the
           robust mode), the first of equal roots in the scene's order:
           each triangle's own root by [Trace.roots], the same test. *)
        let o = Mesh.Gen.torus_knot ~p:2 ~q:3 ~radius:2. ~tube:0.35 ~segments:300 ~sides:8 in
        let mesh = mesh_shape o (Material.v (Color.v 230. 150. 40.)) in
        let tr = Trace.create (Helpers.prepare (Helpers.scene ~spheres:[] ~shapes:[ mesh ] ~lights:[] ())) in
        let n = Array.length o.triangles / 3 in
        if (Trace.prepared tr).bvh = None then Alcotest.fail "no hierarchy";
        let brute origin direction =
          let best = ref infinity and hit = ref (-1) in
          for k = 0 to n - 1 do
            let t, _ = Trace.roots tr k origin direction in
            if t > 0. && t < !best then begin
              best := t;
              hit := k
            end
          done;
          !hit
        in
        let rand = Random.State.make [| 28 |] in
        let f lo hi = lo +. Random.State.float rand (hi -. lo) in
        let wrong = ref 0 and hits = ref 0 and rays = ref 0 in
        let try_ray origin direction =
          incr rays;
          let expected = brute origin direction and got = Trace.cast tr ~from:(-1) origin direction in
          if expected >= 0 then incr hits;
          if got <> expected then begin
            incr wrong;
            Printf.printf "ray %s %s: hierarchy %d, every triangle %d\n" (Format.asprintf "%a" Vec3.pp origin) (Format.asprintf "%a" Vec3.pp direction) got
              expected
          end
        in
        let signs = [ -1.; 1. ] in
        List.iter
          (fun sx ->
            List.iter
              (fun sy ->
                List.iter
                  (fun sz ->
                    for _ = 1 to 40 do
                      (* From outside the knot, toward a point near it. *)
                      let origin = Vec3.v (-.sx *. f 3. 6.) (-.sy *. f 3. 6.) (-.sz *. f 3. 6.) in
                      let target = Vec3.v (f (-2.) 2.) (f (-2.) 2.) (f (-0.5) 0.5) in
                      let d = Vec3.sub target origin in
                      try_ray origin (Vec3.v (sx *. Float.abs d.x) (sy *. Float.abs d.y) (sz *. Float.abs d.z))
                    done)
                  signs)
              signs)
          signs;
        (* Along the axes and in the axes' planes: zero coordinates of
           both signs, whose slab inverse is huge and positive. *)
        List.iter
          (fun z ->
            for _ = 1 to 40 do
              let y = f (-2.) 2. and x = f (-2.) 2. in
              try_ray (Vec3.v x y (-6.)) (Vec3.v z z 1.);
              try_ray (Vec3.v x y 6.) (Vec3.v z z (-1.));
              try_ray (Vec3.v (-6.) y 0.1) (Vec3.v 1. z z);
              try_ray (Vec3.v x (-6.) 0.) (Vec3.v z 1. z);
              try_ray (Vec3.v (-6.) (-6.) (f (-0.3) 0.3)) (Vec3.v 1. 1. z)
            done)
          [ 0.; -0. ];
        Printf.printf "%d rays, %d hits, %d differ\n" !rays !hits !wrong;
        if !hits < !rays / 4 then Alcotest.failf "only %d of %d rays hit: the rays test little" !hits !rays;
        Alcotest.(check int) "rays whose hit differs" 0 !wrong);
  ]
