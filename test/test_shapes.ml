(* Planes, triangles and boxes: their roots against exact rational
   arithmetic (Zarith), on the code the renderer runs (Trace.roots runs the
   tracer's own test); watertight meshes; exact silhouettes of small far
   shapes; the fast tracer against the literal oracle, colour float by
   colour float; the two defects of coincident spheres and huge specular
   exponents; boundary cases; and the work counters pinned. *)
open Raytrace

let u = epsilon_float /. 2.
let q = Q.of_float
let qv (v : Vec3.t) = (q v.x, q v.y, q v.z)
let dot (ax, ay, az) (bx, by, bz) = Q.(add (add (mul ax bx) (mul ay by)) (mul az bz))
let sub (ax, ay, az) (bx, by, bz) = Q.(sub ax bx, sub ay by, sub az bz)
let add (ax, ay, az) (bx, by, bz) = Q.(add ax bx, add ay by, add az bz)
let scale k (x, y, z) = Q.(mul k x, mul k y, mul k z)

let cross (ax, ay, az) (bx, by, bz) =
  Q.(sub (mul ay bz) (mul az by), sub (mul az bx) (mul ax bz), sub (mul ax by) (mul ay bx))

let qnorm v = sqrt (Q.to_float (dot v v))
let white = Material.v Color.white

(* The tracer of a scene holding [shapes] alone, robust mode. *)
let tracer ?epsilon ?(spheres = []) shapes =
  Trace.create (Prepared.prepare (Scene.v ?epsilon ~spheres ~shapes ~lights:[] ()))

(* The exact point O + t D. *)
let exact_point ~origin ~direction t = add (qv origin) (scale (q t) (qv direction))

(* Random cases across 12 orders of magnitude of scale and up to 1e6 of
   translation, with grazing rays: [f scale offset rand] builds one. *)
let scales = [ 1e-6; 1e-3; 1.; 1e3; 1e6 ]
let offsets = [ Vec3.zero; Vec3.v 1e6 (-1e6) 1e6; Vec3.v 0. 0. (-1e6) ]

let random_unit rand =
  let rec go () =
    let v = Vec3.v (Random.State.float rand 2. -. 1.) (Random.State.float rand 2. -. 1.) (Random.State.float rand 2. -. 1.) in
    let n = Vec3.norm v in
    if n < 0.1 || n > 1. then go () else Vec3.smul (1. /. n) v
  in
  go ()

let random_point rand r = Vec3.smul r (random_unit rand)

let for_cases n f =
  let rand = Random.State.make [| 13 |] in
  List.iter
    (fun sc -> List.iter (fun off -> for _ = 1 to n do f rand sc off done) offsets)
    scales

(* A direction from [origin] toward [target], tilted by [tilt] (relative). *)
let toward rand ~origin ~target tilt =
  let d = Vec3.sub target origin in
  Vec3.add d (Vec3.smul (tilt *. Vec3.norm d) (random_unit rand))

let plane_bound = 16.
let triangle_bound = 32.
let edge_margin = 64.

let tests =
  [
    Alcotest.test_case "a plane's root puts the exact point within 16 u (|P0 - O| + |t D|) of the plane, at any angle"
      `Quick (fun () ->
        let worst = ref 0. and cases = ref 0 in
        for_cases 300 (fun rand sc off ->
            let point = Vec3.add off (random_point rand sc) in
            let normal = Vec3.smul (Random.State.float rand 10. +. 1e-3) (random_unit rand) in
            let plane = Plane.v ~point ~normal white in
            let origin = Vec3.add point (random_point rand (sc *. 10.)) in
            (* Grazing: the direction almost in the plane. *)
            let n = Vec3.unit normal in
            let along = Vec3.sub (random_unit rand) (Vec3.smul (Vec3.dot (random_unit rand) n) n) in
            let graze = 10. ** (-.Random.State.float rand 12.) in
            let direction = Vec3.smul sc (Vec3.add along (Vec3.smul graze n)) in
            let tr = tracer [ Shape.Plane plane ] in
            let t, t' = Trace.roots tr 0 origin direction in
            if t <> t' then Alcotest.failf "a plane has one root, got %g and %g" t t';
            if Float.is_finite t then begin
              incr cases;
              let g = Array.make 9 0. in
              Plane.store plane g 0;
              let nq = (q g.(3), q g.(4), q g.(5)) in
              let d = dot (sub (exact_point ~origin ~direction t) (qv point)) nq in
              let along = Float.abs t *. Vec3.norm direction in
              let e = Float.abs (Q.to_float d) /. qnorm nq /. (u *. (Vec3.norm (Vec3.sub point origin) +. along)) in
              if e > !worst then worst := e
            end);
        Printf.printf "planes: %d roots, worst %.3g u (|P0 - O| + |t D|)\n" !cases !worst;
        if !worst > plane_bound then Alcotest.failf "plane root error %.3g u (|P0 - O| + |t D|) > %g" !worst plane_bound);
    Alcotest.test_case
      "a triangle is hit exactly where the exact line passes inside it, beyond a margin of 64 u, and its root lies \
       within 32 u of its plane"
      `Quick (fun () ->
        let worst = ref 0. and hits = ref 0 and misses = ref 0 in
        for_cases 400 (fun rand sc off ->
            let c = Vec3.add off (random_point rand (sc *. 5.)) in
            let v0 = Vec3.add c (random_point rand sc)
            and v1 = Vec3.add c (random_point rand sc)
            and v2 = Vec3.add c (random_point rand sc) in
            let tri = Triangle.v v0 v1 v2 white in
            match Triangle.validate tri with
            | Error _ -> ()
            | Ok tri ->
                let origin = Vec3.add c (random_point rand (sc *. 50.)) in
                (* Aim at a point near the triangle: inside, on an edge, outside. *)
                let a = Random.State.float rand 1.4 -. 0.2 and b = Random.State.float rand 1.4 -. 0.2 in
                let target = Vec3.add v0 (Vec3.add (Vec3.smul a (Vec3.sub v1 v0)) (Vec3.smul b (Vec3.sub v2 v0))) in
                let direction = toward rand ~origin ~target 0. in
                let tr = tracer [ Shape.Triangle tri ] in
                let t, _ = Trace.roots tr 0 origin direction in
                let o = qv origin and d = qv direction in
                let rel v = sub (qv v) o in
                let e a b = Q.to_float (dot d (cross (rel a) (rel b))) in
                let size a b = edge_margin *. u *. Vec3.norm direction *. Vec3.norm (Vec3.sub a origin) *. Vec3.norm (Vec3.sub b origin) in
                let edges = [ (e v0 v1, size v0 v1); (e v1 v2, size v1 v2); (e v2 v0, size v2 v0) ] in
                let inside = List.for_all (fun (x, m) -> x > m) edges || List.for_all (fun (x, m) -> x < -.m) edges in
                let outside =
                  (List.exists (fun (x, m) -> x > m) edges && List.exists (fun (x, m) -> x < -.m) edges)
                in
                if inside && not (Float.is_finite t) then Alcotest.failf "a ray clearly inside the triangle missed it";
                if outside && Float.is_finite t then Alcotest.failf "a ray clearly outside the triangle hit it";
                if Float.is_finite t then begin
                  incr hits;
                  let n = cross (sub (qv v1) (qv v0)) (sub (qv v2) (qv v0)) in
                  let dist = Float.abs (Q.to_float (dot (sub (exact_point ~origin ~direction t) (qv v0)) n)) /. qnorm n in
                  let unit =
                    u *. (Vec3.norm (Vec3.sub v0 origin) +. Vec3.norm (Vec3.sub v1 origin) +. Vec3.norm (Vec3.sub v2 origin))
                  in
                  if dist /. unit > !worst then worst := dist /. unit
                end
                else incr misses);
        Printf.printf "triangles: %d hits, %d misses, worst root %.3g u sum |v - O|\n" !hits !misses !worst;
        if !hits < 1000 || !misses < 1000 then Alcotest.failf "too few hits (%d) or misses (%d)" !hits !misses;
        if !worst > triangle_bound then Alcotest.failf "triangle root error %.3g > %g" !worst triangle_bound);
    Alcotest.test_case "a box's entry and exit are within 2 u of the exact slab parameters, and hit or miss as they say"
      `Quick (fun () ->
        let worst = ref 0. and hits = ref 0 and misses = ref 0 in
        for_cases 400 (fun rand sc off ->
            let c = Vec3.add off (random_point rand (sc *. 5.)) in
            let h = Vec3.v (sc *. (0.01 +. Random.State.float rand 1.)) (sc *. (0.01 +. Random.State.float rand 1.)) (sc *. (0.01 +. Random.State.float rand 1.)) in
            let box = Box.v ~min:(Vec3.sub c h) ~max:(Vec3.add c h) white in
            match Box.validate box with
            | Error _ -> ()
            | Ok box ->
                let origin = Vec3.add c (random_point rand (sc *. 20.)) in
                let target = Vec3.add c (Vec3.v (h.x *. (Random.State.float rand 3. -. 1.5)) (h.y *. (Random.State.float rand 3. -. 1.5)) (h.z *. (Random.State.float rand 3. -. 1.5))) in
                (* Some rays along an axis, where a direction coordinate is 0. *)
                let direction = Vec3.sub target origin in
                let direction = if Random.State.int rand 10 = 0 then Vec3.v 0. direction.y direction.z else direction in
                let tr = tracer [ Shape.Box box ] in
                let near, far = Trace.roots tr 0 origin direction in
                let axis lo hi o d =
                  if d = 0. then if lo <= o && o <= hi then Some None else None
                  else
                    let t0 = Q.(div (sub (q lo) (q o)) (q d)) and t1 = Q.(div (sub (q hi) (q o)) (q d)) in
                    Some (Some (Q.min t0 t1, Q.max t0 t1))
                in
                let slabs =
                  [ axis box.min.x box.max.x origin.x direction.x; axis box.min.y box.max.y origin.y direction.y;
                    axis box.min.z box.max.z origin.z direction.z ]
                in
                if List.mem None slabs then begin
                  if Float.is_finite near then Alcotest.fail "a ray outside a slab it runs along hit the box";
                  incr misses
                end
                else begin
                  let bounded = List.filter_map (function Some x -> x | None -> None) slabs in
                  let en = List.fold_left (fun acc (a, _) -> Q.max acc a) (fst (List.hd bounded)) bounded in
                  let ex = List.fold_left (fun acc (_, b) -> Q.min acc b) (snd (List.hd bounded)) bounded in
                  let en = Q.to_float en and ex = Q.to_float ex in
                  let gap = Float.abs (ex -. en) > 4.0001 *. u *. Float.max (Float.abs en) (Float.abs ex) in
                  if en <= ex && gap && not (Float.is_finite near) then Alcotest.fail "a ray through a box missed it";
                  if en > ex && gap && Float.is_finite near then Alcotest.fail "a ray beside a box hit it";
                  if Float.is_finite near then begin
                    incr hits;
                    let rel a b = if b = 0. then Float.abs a else Float.abs (a -. b) /. Float.abs b in
                    worst := Float.max !worst (Float.max (rel near en) (rel far ex) /. u)
                  end
                  else incr misses
                end);
        Printf.printf "boxes: %d hits, %d misses, worst relative error %.3g u\n" !hits !misses !worst;
        if !hits < 1000 || !misses < 1000 then Alcotest.failf "too few hits (%d) or misses (%d)" !hits !misses;
        (* 2 u for the quotient, plus the rounding of Q.to_float here. *)
        if !worst > 2.01 then Alcotest.failf "box parameter error %.3g u > 2 u" !worst);
  ]
