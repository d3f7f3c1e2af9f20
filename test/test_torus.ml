(* The torus (issue 26): its quartic roots proved in exact rational
   arithmetic (Zarith) on the routine the renderer runs, no root lost on
   grazing rays (Sturm's theorem on the exact quartic), an exact
   silhouette of a small far torus, no allocation per ray, both sides, its
   scene text, the oracle's answer, CSG and glass. *)
open Raytrace

let u = epsilon_float /. 2.

(* The stated bound (torus.mli): a root's point lies within [bound u
   (|O - C| + R + r)] of the exact surface. *)
let bound = 8.
let white = Material.v Color.white

(* {1 Exact arithmetic} *)

let q = Q.of_float
let qv (v : Vec3.t) = (q v.x, q v.y, q v.z)
let dot (ax, ay, az) (bx, by, bz) = Q.(add (add (mul ax bx) (mul ay by)) (mul az bz))
let sub (ax, ay, az) (bx, by, bz) = Q.(sub ax bx, sub ay by, sub az bz)

(* Polynomials in [t] with rational coefficients, lowest degree first. *)
module P = struct
  let trim p =
    let n = ref (Array.length p) in
    while !n > 0 && Q.equal p.(!n - 1) Q.zero do decr n done;
    Array.sub p 0 !n

  let degree p = Array.length (trim p) - 1
  let get p i = if i < Array.length p then p.(i) else Q.zero
  let add a b = trim (Array.init (max (Array.length a) (Array.length b)) (fun i -> Q.add (get a i) (get b i)))
  let scale k a = trim (Array.map (Q.mul k) a)

  let mul a b =
    if Array.length a = 0 || Array.length b = 0 then [||]
    else begin
      let r = Array.make (Array.length a + Array.length b - 1) Q.zero in
      Array.iteri (fun i x -> Array.iteri (fun j y -> r.(i + j) <- Q.add r.(i + j) (Q.mul x y)) b) a;
      trim r
    end

  let eval p x = Array.fold_right (fun c acc -> Q.add c (Q.mul acc x)) p Q.zero
  let deriv p = trim (Array.init (max 0 (Array.length p - 1)) (fun i -> Q.mul (Q.of_int (i + 1)) p.(i + 1)))

  (* The remainder of [a] divided by [b] ([b] not zero). *)
  let rem a b =
    let b = trim b in
    let db = Array.length b - 1 in
    let r = ref (trim a) in
    while Array.length !r - 1 >= db && Array.length !r > 0 do
      let dr = Array.length !r - 1 in
      let k = Q.div !r.(dr) b.(db) in
      let shifted = Array.init (dr + 1) (fun i -> if i >= dr - db then Q.mul k b.(i - (dr - db)) else Q.zero) in
      r := trim (Array.mapi (fun i c -> if i = dr then Q.zero else Q.sub c (get shifted i)) !r)
    done;
    !r

  (* Sturm's chain of [p]: the number of its distinct real roots is the
     change in sign variations from minus to plus infinity. *)
  let sturm p =
    let rec go a b acc = if Array.length b = 0 then List.rev acc else go b (scale Q.minus_one (rem a b)) (b :: acc) in
    go p (deriv p) [ p ]

  let variations signs =
    let signs = List.filter (fun s -> s <> 0) signs in
    let rec go n = function a :: (b :: _ as l) -> go (if a <> b then n + 1 else n) l | _ -> n in
    go 0 signs

  (* The distinct real roots of [p] in [(a, b]], [p] not zero. *)
  let roots_in p a b =
    let chain = sturm (trim p) in
    let at x = List.map (fun c -> Q.sign (eval c x)) chain in
    variations (at a) - variations (at b)

  let real_roots p =
    let p = trim p in
    if Array.length p <= 1 then 0
    else begin
      let chain = sturm p in
      let lead c = Q.sign c.(Array.length c - 1) in
      let at_minus = List.map (fun c -> if (Array.length c - 1) mod 2 = 0 then lead c else -lead c) chain in
      let at_plus = List.map lead chain in
      variations at_minus - variations at_plus
    end
end

(* The torus's quartic for minor radius [rr] along the exact line
   [O + t D], as a polynomial in [t]: [(|v|^2 + R^2 - rr^2)^2 - 4 R^2
   (|v|^2 - <v, a>^2 / |a|^2)] with [v = O + t D - C] and [a] the torus's
   float unit axis (normalised exactly here). Negative inside. *)
let quartic (x : Torus.t) ~origin ~direction rr =
  let a = qv (Torus.unit_axis x) in
  let aa = dot a a in
  let w = sub (qv origin) (qv x.center) and d = qv direction in
  let vv = [| dot w w; Q.mul (Q.of_int 2) (dot w d); dot d d |] in
  let za = [| dot w a; dot d a |] in
  let big2 = Q.mul (q x.major) (q x.major) in
  let e = P.add vv [| Q.sub big2 (Q.mul rr rr) |] in
  let rho2 = P.add vv (P.scale (Q.div Q.minus_one aa) (P.mul za za)) in
  P.add (P.mul e e) (P.scale (Q.mul (Q.of_int (-4)) big2) rho2)

let size (x : Torus.t) ~origin = Vec3.norm (Vec3.sub origin x.center) +. x.major +. x.minor
let delta x ~origin = bound *. u *. size x ~origin

(* Is the exact point of parameter [t] within [delta] of the surface:
   inside the torus of minor radius [r + delta], outside that of [r -
   delta]? *)
let near_surface ?(k = bound) (x : Torus.t) ~origin ~direction t =
  let d = q (k *. u *. size x ~origin) and t = q t in
  let at rr = P.eval (quartic x ~origin ~direction rr) t in
  let r = q x.minor in
  Q.sign (at (Q.add r d)) <= 0 && (Q.leq r d || Q.sign (at (Q.sub r d)) >= 0)

(* {1 The kernel's answer} *)

(* The roots of the kernel's routine (through the kernel's dispatch, as
   the traversal and the CSG table call it): every interval of the line,
   asked from each exit on. *)
let kernel_roots (x : Torus.t) ~origin ~direction =
  let g = Array.make Kind.stride 0. in
  Torus.store x g 0;
  let s = Scratch.create () in
  Scratch.set_ray s origin direction;
  s.t_min <- neg_infinity;
  s.t_max <- infinity;
  let rec go acc n =
    if n = 0 || not (Kind_dispatch.roots Kind.Torus s g 0) then List.rev acc
    else begin
      let e = s.near and f = s.far in
      s.t_min <- f;
      go (f :: e :: acc) (n - 1)
    end
  in
  go [] 3

(* {1 Cases} *)

let random_unit = Test_shapes.random_unit
let scales = Test_shapes.scales
let offsets = Test_shapes.offsets

let random_torus rand sc off =
  let major = sc *. (0.5 +. Random.State.float rand 1.5) in
  let minor = major *. (0.05 +. Random.State.float rand 0.6) in
  let center = Vec3.add off (Vec3.smul (sc *. Random.State.float rand 3.) (random_unit rand)) in
  let axis = Vec3.smul (0.1 +. Random.State.float rand 3.) (random_unit rand) in
  Torus.v ~center ~axis ~major ~minor white

(* A point of the surface, its outward normal: angles [th] around the
   axis and [ph] around the tube. *)
let surface_point (x : Torus.t) th ph =
  let a = Torus.unit_axis x in
  let e1 = Vec3.unit (Vec3.cross a (if Float.abs a.x < 0.9 then Vec3.ox else Vec3.oy)) in
  let e2 = Vec3.cross a e1 in
  let radial = Vec3.add (Vec3.smul (cos th) e1) (Vec3.smul (sin th) e2) in
  let n = Vec3.add (Vec3.smul (cos ph) radial) (Vec3.smul (sin ph) a) in
  (Vec3.add x.center (Vec3.add (Vec3.smul x.major radial) (Vec3.smul x.minor n)), n)

(* A ray along a tangent of the surface, moved off it along the normal by
   [depth] (negative: into the solid), from [far] sizes away. *)
let grazing rand (x : Torus.t) ~depth ~far =
  let p, n = surface_point x (Random.State.float rand 6.3) (Random.State.float rand 6.3) in
  let t = Vec3.unit (Vec3.cross n (random_unit rand)) in
  let p = Vec3.add p (Vec3.smul depth n) in
  let direction = Vec3.smul (0.1 +. Random.State.float rand 10.) t in
  let origin = Vec3.sub p (Vec3.smul (far *. (x.major +. x.minor) /. Vec3.norm direction) direction) in
  (origin, direction)

(* A ray from [far] sizes away toward a random point within the torus's
   bounding sphere. *)
let through rand (x : Torus.t) ~far =
  let size = x.major +. x.minor in
  let target = Vec3.add x.center (Vec3.smul (size *. Random.State.float rand 1.) (random_unit rand)) in
  let origin = Vec3.add target (Vec3.smul (far *. size) (random_unit rand)) in
  (origin, Vec3.smul (0.1 +. Random.State.float rand 10.) (Vec3.sub target origin))

let depths = [ 1e-1; 1e-3; 1e-5; 1e-7; 1e-9; 1e-11; 1e-13; 1e-15 ]

(* [n] cases per scale and offset: through rays, grazing rays at each
   depth on both sides, from 3 and 1e4 sizes away. *)
let cases n =
  let rand = Random.State.make [| 26 |] in
  List.concat_map
    (fun sc ->
      List.concat_map
        (fun off ->
          List.init n (fun i ->
              let x = random_torus rand sc off in
              let far = if i mod 2 = 0 then 3. else 1e4 in
              let depth = List.nth depths (i mod List.length depths) *. x.minor in
              let depth = if i mod 3 = 0 then -.depth else depth in
              if i mod 4 = 0 then (x, through rand x ~far) else (x, grazing rand x ~depth ~far)))
        offsets)
    scales

(* The exact verdict on one case, as the kernel must match it: the
   kernel's roots are on the surface within the bound, alternate entries
   and exits as the exact quartic's sign says between them, and are as
   many as the exact quartic's real roots, unless the line passes within
   twice the bound of tangency (the tori of minor radius [r -+ 2 delta]
   then have other numbers of roots). *)
type verdict = { off_surface : int; wrong_sign : int; lost : int; grazes : int; worst : float }

(* The least of 1/4, 1/2, 1, ..., [bound] for which the root of parameter
   [t] passes, or infinity: the bound as measured. *)
let measured x ~origin ~direction t =
  let rec go k = if k > bound then infinity else if near_surface ~k x ~origin ~direction t then k else go (2. *. k) in
  go 0.25

let check ?(roots_of = kernel_roots) (x : Torus.t) ~origin ~direction v =
  let roots = roots_of x ~origin ~direction in
  let ks = List.map (measured x ~origin ~direction) roots in
  let off = List.length (List.filter (fun k -> k = infinity) ks) in
  let g = quartic x ~origin ~direction (q x.minor) in
  let rec signs inside = function
    | a :: (b :: _ as rest) ->
        let m = Q.div (Q.add (q a) (q b)) (Q.of_int 2) in
        let s = Q.sign (P.eval g m) in
        (if (inside && s > 0) || ((not inside) && s < 0) then 1 else 0) + signs (not inside) rest
    | _ -> 0
  in
  let wrong = signs true roots in
  let d2 = Q.mul (Q.of_int 2) (q (delta x ~origin)) and r = q x.minor in
  let exact = P.real_roots g in
  let outer = P.real_roots (quartic x ~origin ~direction (Q.add r d2)) in
  let inner = if Q.leq r d2 then 0 else P.real_roots (quartic x ~origin ~direction (Q.sub r d2)) in
  let graze = outer <> exact || inner <> exact in
  {
    off_surface = v.off_surface + off;
    wrong_sign = v.wrong_sign + (if graze then 0 else wrong);
    lost = v.lost + (if (not graze) && List.length roots <> exact then 1 else 0);
    grazes = (v.grazes + if graze then 1 else 0);
    worst = List.fold_left Float.max v.worst ks;
  }

let zero = { off_surface = 0; wrong_sign = 0; lost = 0; grazes = 0; worst = 0. }

(* {1 Images} *)

let hit_mask = Test_numerics.hit_mask

(* A torus of size [r] (major + minor) at 1e7 [r] from the camera, seen
   through a viewport so narrow that it covers some 40 pixels across. *)
let tiny_far_scene ~translate =
  let size = 1e-3 in
  let dist = 1e7 *. size in
  let center = Vec3.add translate (Vec3.v (0.3 *. dist) (-0.2 *. dist) dist) in
  let x = Torus.v ~center ~axis:(Vec3.v 0.3 1. (-0.6)) ~major:(0.7 *. size) ~minor:(0.3 *. size) white in
  let camera = match Camera.look_at ~position:translate center with Ok c -> c | Error (`Msg e) -> failwith e in
  let scene =
    Helpers.scene ~width:64 ~height:64
      ~viewport:(Viewport.v ~width:3e-7 ~height:3e-7 ~distance:1.)
      ~camera ~spheres:[] ~shapes:[ Shape.Primitive (Shape_desc.Primitive (Torus.desc, x)) ] ~lights:[ Light.ambient 1. ] ()
  in
  (scene, x)

(* `In, `Out or `Edge for a pixel's exact line: it meets the torus shrunk
   by twice the bound, it misses the one grown by it, or neither. *)
let exact_class (x : Torus.t) ~origin ~direction =
  let d2 = Q.mul (Q.of_int 2) (q (delta x ~origin)) and r = q x.minor in
  if P.real_roots (quartic x ~origin ~direction (Q.sub r d2)) > 0 then `In
  else if P.real_roots (quartic x ~origin ~direction (Q.add r d2)) = 0 then `Out
  else `Edge

let torus_shape x = Shape.Primitive (Shape_desc.Primitive (Torus.desc, x))

let tests =
  [
    Alcotest.test_case "each torus root is on the exact surface within 8 u (|O - C| + R + r), and none is lost" `Quick
      (fun () ->
        let cs = cases 40 in
        let v = List.fold_left (fun v (x, (origin, direction)) -> check x ~origin ~direction v) zero cs in
        Printf.printf
          "%d rays: %d roots off the surface (worst within %g u (|O - C| + R + r)), %d wrong signs between roots, %d lost, %d grazing within the bound\n"
          (List.length cs) v.off_surface v.worst v.wrong_sign v.lost v.grazes;
        Alcotest.(check int) "roots off the surface" 0 v.off_surface;
        Alcotest.(check int) "intervals the exact quartic's sign contradicts" 0 v.wrong_sign;
        Alcotest.(check int) "rays whose roots are not as many as the exact quartic's" 0 v.lost);
    Alcotest.test_case "the oracle's crossings (sphere tracing, not the kernel's method) pass the same exact checks" `Quick
      (fun () ->
        let literal x ~origin ~direction = List.map fst (Torus.literal x ~origin ~direction) in
        let cs = cases 40 in
        let v = List.fold_left (fun v (x, (origin, direction)) -> check ~roots_of:literal x ~origin ~direction v) zero cs in
        Printf.printf "%d rays: %d crossings off the surface (worst within %g u (|O - C| + R + r)), %d wrong signs, %d lost, %d grazing\n"
          (List.length cs) v.off_surface v.worst v.wrong_sign v.lost v.grazes;
        Alcotest.(check int) "crossings off the surface" 0 v.off_surface;
        Alcotest.(check int) "wrong signs" 0 v.wrong_sign;
        Alcotest.(check int) "rays with crossings lost or added" 0 v.lost);
    Alcotest.test_case "a thousand grazing rays lose no root that Sturm's theorem finds in exact arithmetic" `Quick (fun () ->
        let rand = Random.State.make [| 1000 |] in
        let v = ref zero and with_roots = ref 0 in
        for i = 0 to 999 do
          let sc = List.nth scales (i mod 5) and off = List.nth offsets (i mod 3) in
          let x = random_torus rand sc off in
          (* Depths from 1e-2 to 1e-14 of the tube's radius, both sides. *)
          let depth = x.minor *. (10. ** -.(2. +. Random.State.float rand 12.)) in
          let depth = if i mod 2 = 0 then -.depth else depth in
          let origin, direction = grazing rand x ~depth ~far:(if i mod 3 = 0 then 1e3 else 3.) in
          if kernel_roots x ~origin ~direction <> [] then incr with_roots;
          v := check x ~origin ~direction !v
        done;
        Printf.printf
          "1000 grazing rays (%d with roots): %d off the surface (worst within %g u (|O - C| + R + r)), %d wrong signs, %d lost, %d within the bound of tangency\n"
          !with_roots !v.off_surface !v.worst !v.wrong_sign !v.lost !v.grazes;
        Alcotest.(check int) "roots off the surface" 0 !v.off_surface;
        Alcotest.(check int) "wrong signs" 0 !v.wrong_sign;
        Alcotest.(check int) "rays with roots lost or added" 0 !v.lost);
    Alcotest.test_case "a torus 1e7 times smaller than its distance is its exact silhouette, also moved by 1e6" `Quick
      (fun () ->
        List.iter
          (fun translate ->
            let scene, x = tiny_far_scene ~translate in
            let exact =
              Test_shapes.exact_mask scene (fun ~origin ~direction -> exact_class x ~origin ~direction)
            in
            let wrong, inside = Helpers.mask_errors (hit_mask scene) exact in
            let edge = Array.fold_left (fun n row -> Array.fold_left (fun n c -> if c = `Edge then n + 1 else n) n row) 0 exact in
            Printf.printf "moved by %s: %d pixels inside, %d within the bound, %d wrong\n" (Vec3.show translate) inside edge
              wrong;
            if inside < 200 then Alcotest.failf "the torus covers only %d pixels" inside;
            Alcotest.(check int) "pixels off the exact silhouette" 0 wrong)
          [ Vec3.zero; Vec3.v 1e6 (-1e6) 1e6 ]);
    Alcotest.test_case "a torus's bounds hold its surface, and are tight along its axis" `Quick (fun () ->
        let rand = Random.State.make [| 5 |] in
        List.iter
          (fun sc ->
            List.iter
              (fun off ->
                for _ = 1 to 20 do
                  let x = random_torus rand sc off in
                  let lo, hi = Torus.bounds x in
                  for _ = 1 to 200 do
                    let p, _ = surface_point x (Random.State.float rand 6.3) (Random.State.float rand 6.3) in
                    if p.x < lo.x || p.y < lo.y || p.z < lo.z || p.x > hi.x || p.y > hi.y || p.z > hi.z then
                      Alcotest.failf "%s outside the bounds of %s" (Vec3.show p) (Torus.desc.name ^ Format.asprintf " %a" Torus.pp x)
                  done
                done)
              offsets)
          scales;
        (* Axis y, R = 2, r = 0.5: y in [-0.5, 0.5], x and z in [-2.5, 2.5]. *)
        let lo, hi = Torus.bounds (Torus.v ~center:Vec3.zero ~axis:Vec3.oy ~major:2. ~minor:0.5 white) in
        Alcotest.(check (float 1e-12)) "y below" (-0.5) lo.y;
        Alcotest.(check (float 1e-12)) "y above" 0.5 hi.y;
        Alcotest.(check (float 1e-12)) "x above" 2.5 hi.x);
    Alcotest.test_case "the torus's roots and normal allocate nothing" `Quick (fun () ->
        let x = Torus.v ~center:(Vec3.v 0. 0. 5.) ~axis:(Vec3.v 0.2 1. 0.1) ~major:1. ~minor:0.3 white in
        let g = Array.make Kind.stride 0. in
        Torus.store x g 0;
        let s = Scratch.create () in
        let run () =
          for i = 0 to 999 do
            Scratch.set_ray s Vec3.zero (Vec3.v (Float.of_int (i - 500) *. 0.003) 0.05 1.);
            s.t_min <- 0.;
            if Kind_dispatch.roots Kind.Torus s g 0 then begin
              s.px <- s.near *. s.dx;
              s.py <- s.near *. s.dy;
              s.pz <- s.near *. s.dz;
              Kind_dispatch.normal Kind.Torus s g 0
            end
          done
        in
        run ();
        (* What the loop itself allocates (its rays), measured without the torus. *)
        let overhead =
          let b = Gc.minor_words () in
          for i = 0 to 999 do
            Scratch.set_ray s Vec3.zero (Vec3.v (Float.of_int (i - 500) *. 0.003) 0.05 1.)
          done;
          Gc.minor_words () -. b
        in
        let before = Gc.minor_words () in
        run ();
        let words = Gc.minor_words () -. before -. overhead in
        Alcotest.(check (float 0.)) "minor words for 1,000 rays" 0. words);
    Alcotest.test_case "rendering the tori's scene allocates nothing per pixel: glass, shadows, CSG" `Quick (fun () ->
        let s = Scene.with_overrides ~width:60 ~height:45 (Helpers.load_scene "torus.scene") in
        List.iter
          (fun (what, samples) ->
            match Helpers.render ?samples s with
            | Ok (_, (st : Render.Stats.t)) -> Alcotest.(check (float 0.)) what 0. st.minor_words
            | Error (`Msg m) -> Alcotest.fail m)
          [ ("one sample", None); ("samples 2", Some 2) ]);
    Alcotest.test_case "a ray from inside the tube meets its exit; one through the hole, two intervals" `Quick (fun () ->
        (* Axis y, R = 2, r = 0.5 about the origin: the x axis crosses the
           tube at x = -2.5, -1.5, 1.5, 2.5. *)
        let x = Torus.v ~center:Vec3.zero ~axis:Vec3.oy ~major:2. ~minor:0.5 white in
        let roots = kernel_roots x ~origin:(Vec3.v (-10.) 0. 0.) ~direction:Vec3.ox in
        List.iter2
          (fun e t -> Alcotest.(check (float 1e-14)) "root" e t)
          [ 7.5; 8.5; 11.5; 12.5 ] roots;
        let g = Array.make Kind.stride 0. in
        Torus.store x g 0;
        let s = Scratch.create () in
        Scratch.set_ray s (Vec3.v 2. 0. 0.) Vec3.ox;
        s.t_min <- 0.;
        Alcotest.(check bool) "hit from inside" true (Kind_dispatch.roots Kind.Torus s g 0);
        Alcotest.(check (float 1e-15)) "exit" 0.5 s.far;
        Alcotest.(check bool) "entry behind" true (s.near < 0.);
        s.px <- 2.5;
        s.py <- 0.;
        s.pz <- 0.;
        Kind_dispatch.normal Kind.Torus s g 0;
        Alcotest.check Helpers.vec3 "outward normal" Vec3.ox (Vec3.v s.nx s.ny s.nz));
    Alcotest.test_case "the torus's image is the same scaled from 1e-6 to 1e6 and moved by 1e6" `Quick (fun () ->
        let base = Test_numerics.small (Helpers.load_scene "torus.scene") in
        let expected = Helpers.image_exn (Test_numerics.transform ~scale:1. ~translate:Vec3.zero base) in
        List.iter
          (fun (scale, translate) ->
            Helpers.check_images ~min_share:0.999
              (Printf.sprintf "scaled by %g, moved by %s" scale (Vec3.show translate))
              ~expected
              (Helpers.image_exn (Test_numerics.transform ~scale ~translate base)))
          [ (1e-6, Vec3.zero); (1e6, Vec3.zero); (1., Vec3.v 1e6 (-1e6) 1e6); (1e-3, Vec3.v 0. 0. 1e6) ]);
    Alcotest.test_case "the fast renderer draws the tori as the oracle does, also moved by 1e6" `Slow
      (fun () ->
        (* Shadows of a torus on itself, glass, a checker and a CSG cut:
           the oracle's crossings are its own (sphere tracing), and its
           secondary rays start past the document's epsilon (in world
           units for refracted rays: not scaled, as the renderer's rule
           is). *)
        let base = Scene.with_overrides ~width:48 ~height:36 (Helpers.load_scene "torus.scene") in
        List.iter
          (fun (scale, translate) ->
            let s = Test_numerics.transform ~scale ~translate base in
            let expected = Private.Literal.render (Helpers.valid s) in
            Helpers.check_images ~min_share:0.99
              (Printf.sprintf "scaled by %g, moved by %s" scale (Vec3.show translate))
              ~expected (Helpers.image_exn s))
          [ (1., Vec3.zero); (1., Vec3.v 1e6 (-1e6) 1e6) ]);
    Alcotest.test_case "the torus's scene text reads, prints back, and its errors name file:line:column" `Quick (fun () ->
        let text = "(torus (center 0 0 5) (axis 0 2 0) (major 1) (minor 0.25) (color 200 50 50))" in
        let parse text = Helpers.of_string ~file:"t.scene" text in
        let x = Torus.v ~center:(Vec3.v 0. 0. 5.) ~axis:(Vec3.v 0. 2. 0.) ~major:1. ~minor:0.25 (Material.v (Color.v 200. 50. 50.)) in
        (match parse text with
        | Ok sc ->
            (match Scene.objects sc with
            | [ Shape.Primitive p ] ->
                Alcotest.(check bool) "equal to Torus.v" true (Shape_desc.equal_primitive p (Shape_desc.Primitive (Torus.desc, x)));
                let printed = Format.asprintf "%a" Shape_desc.pp_primitive p in
                (match parse printed with
                | Ok sc' -> (
                    match Scene.objects sc' with
                    | [ Shape.Primitive p' ] -> Alcotest.(check bool) ("reads back: " ^ printed) true (Shape_desc.equal_primitive p p')
                    | _ -> Alcotest.fail "one object expected")
                | Error (`Msg m) -> Alcotest.failf "%s does not read back: %s" printed m)
            | _ -> Alcotest.fail "one torus expected")
        | Error (`Msg m) -> Alcotest.fail m);
        List.iter
          (fun (text, expected) ->
            match parse text with
            | Ok _ -> Alcotest.failf "no error for %s" text
            | Error (`Msg m) -> Alcotest.(check string) text expected m)
          [
            ("\n (torus (center 0 0 5) (axis 0 1 0) (major 1) (minor 1) (color 1 2 3))",
             "t.scene:2:2: torus minor (1) must be less than major (1)");
            ("(torus (center 0 0 5) (axis 0 0 0) (major 1) (minor 0.2) (color 1 1 1))", "t.scene:1:1: torus axis must not be zero");
            ("(torus (center 0 0 5) (axis 0 1 0) (minor 0.2) (color 1 1 1))", "t.scene:1:1: torus is missing its (major ...) field");
            ("(torus (center 0 0 5) (axis 0 1 0) (major -1) (minor 0.2) (color 1 1 1))", "t.scene:1:1: torus major must be > 0, got -1");
          ]);
    Alcotest.test_case "a bad torus stops the command line: exit 1, a located message, no image" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let file = Filename.concat dir "bad.scene" and out = Filename.concat dir "out.ppm" in
        let oc = open_out_bin file in
        output_string oc "(torus (center 0 0 5) (axis 0 1 0) (major 1) (minor 2) (color 1 2 3))\n";
        close_out oc;
        let code, _, err = Helpers.run (Helpers.raytrace ()) [ "render"; file; "-o"; out ] in
        Alcotest.(check int) "exit" 1 code;
        Alcotest.(check string) "message" (Printf.sprintf "raytrace: %s:1:1: torus minor (2) must be less than major (1)\n" file) err;
        Alcotest.(check bool) "no output file" false (Sys.file_exists out));
    Alcotest.test_case "a torus minus a ball over its near tube is seen through the hole: the second interval" `Quick
      (fun () ->
        (* Axis y, R = 2, r = 0.5 at the origin; the ball of radius 1 at
           (-2, 0, 0) takes the near tube away. From (-10, 0, 0) along x
           the solid is entered at the far tube's x = 1.5: t = 11.5. *)
        let x = Torus.v ~center:Vec3.zero ~axis:Vec3.oy ~major:2. ~minor:0.5 white in
        let ball = Sphere.v ~center:(Vec3.v (-2.) 0. 0.) ~radius:1. white in
        let c = Csg.v Csg.Difference (Csg.Primitive (Shape_desc.Primitive (Torus.desc, x))) (Csg.Sphere ball) in
        let scene = Helpers.scene ~spheres:[] ~shapes:[ Shape.Csg c ] ~lights:[] () in
        let tr = Trace.create (Helpers.prepare scene) in
        let near, _ = Trace.roots tr 0 (Vec3.v (-10.) 0. 0.) Vec3.ox in
        Alcotest.(check (float 1e-14)) "kernel" 11.5 near;
        match Private.Literal.closest_hit scene ~origin:(Vec3.v (-10.) 0. 0.) ~direction:Vec3.ox ~t_min:0. ~t_max:infinity with
        | Some (_, t) -> Alcotest.(check (float 1e-12)) "oracle" 11.5 t
        | None -> Alcotest.fail "the oracle sees nothing");
    Alcotest.test_case "a lit torus shadows itself exactly where its exact shadow rays say, at any scale" `Quick (fun () ->
        (* A matte torus under one point light: a pixel is lit iff the
           exact segment from its float hit point to the light crosses
           the exact torus nowhere past a hair of its start (Sturm's
           count on (1e-6, 1)), where the light is well above the
           horizon there (cos > 0.05: rays that graze the surface are
           left out). No epsilon: the robust mode's offset alone. *)
        List.iter
          (fun (k, off) ->
            let p (v : Vec3.t) = Vec3.add off (Vec3.smul k v) in
            let x = Torus.v ~center:(p (Vec3.v 0. 0. 5.)) ~axis:(Vec3.v 0.3 1. (-0.4)) ~major:k ~minor:(0.35 *. k) white in
            let light = p (Vec3.v 5.75 (-0.5) 5.) in
            let camera = match Camera.look_at ~position:(p (Vec3.v 0.8 2.7 3.9)) x.center with Ok c -> c | Error (`Msg e) -> failwith e in
            let scene =
              Helpers.scene ~width:48 ~height:48 ~camera
                ~viewport:(Viewport.v ~width:(0.6 *. k) ~height:(0.6 *. k) ~distance:k)
                ~spheres:[] ~shapes:[ torus_shape x ] ~lights:[ Light.point 1. light ] ()
            in
            let tr = Trace.create (Helpers.prepare scene) in
            let tested = ref 0 and shadowed = ref 0 and wrong = ref 0 and edge = ref 0 in
            for row = 0 to 47 do
              for col = 0 to 47 do
                let gx = Canvas.x_of_column ~width:48 col and gy = Canvas.y_of_row ~height:48 row in
                Trace.pixel tr gx gy;
                if Trace.hit_object tr = 0 then begin
                  let lit = Trace.red tr > 0. in
                  let v = Viewport.of_canvas (Scene.viewport scene) ~canvas_width:48 ~canvas_height:48 gx gy in
                  let origin = (Scene.camera scene).position and direction = Camera.direction (Scene.camera scene) v in
                  let t, _ = Trace.roots tr 0 origin direction in
                  let hit = Vec3.add origin (Vec3.smul t direction) in
                  let g = Array.make Kind.stride 0. and sc = Scratch.create () in
                  Torus.store x g 0;
                  sc.px <- hit.x;
                  sc.py <- hit.y;
                  sc.pz <- hit.z;
                  Torus.normal sc g 0;
                  let l = Vec3.sub light hit in
                  if Vec3.dot (Vec3.v sc.nx sc.ny sc.nz) l /. Vec3.norm l > 0.05 then begin
                    incr tested;
                    let count rr = P.roots_in (quartic x ~origin:hit ~direction:l rr) (Q.of_float 1e-6) Q.one in
                    let d2 = Q.mul (Q.of_int 2) (q (delta x ~origin:hit)) and r = q x.minor in
                    let exact = count r in
                    if exact <> count (Q.add r d2) || exact <> count (Q.sub r d2) then incr edge
                    else begin
                      if exact > 0 then incr shadowed;
                      if lit = (exact > 0) then incr wrong
                    end
                  end
                end
              done
            done;
            Printf.printf "scale %g, moved by %s: %d lit-side pixels, %d in the torus's own shadow, %d within the bound, %d wrong\n" k
              (Vec3.show off) !tested !shadowed !edge !wrong;
            if !shadowed < 20 || !tested - !shadowed < 20 then Alcotest.fail "the scene should show both light and shadow";
            Alcotest.(check int) "pixels lit or shadowed against the exact shadow ray" 0 !wrong)
          [ (1., Vec3.zero); (1e-6, Vec3.zero); (1e6, Vec3.zero); (1., Vec3.v 1e6 (-1e6) 1e6); (1e-3, Vec3.v 0. 0. 1e6) ]);
    Alcotest.test_case "a torus in each CSG operation is the oracle's picture" `Quick (fun () ->
        let text op =
          Printf.sprintf
            "(canvas (width 48) (height 36)) (camera (position 0 2.5 -2) (look-at 0 0 4)) (light ambient (intensity 0.3)) \
             (light point (intensity 0.7) (position 2 4 0)) \
             (csg %s (torus (center 0 0 4) (axis 0.2 1 0.1) (major 1.2) (minor 0.4) (color 200 60 50) (specular 100)) \
             (sphere (center 1 0.2 4) (radius 0.9) (color 60 160 220)))"
            op
        in
        List.iter
          (fun op ->
            match Helpers.of_string ~file:"t.scene" (text op) with
            | Error (`Msg m) -> Alcotest.fail m
            | Ok s ->
                let expected = Private.Literal.render (Helpers.valid s) in
                Helpers.check_images ~min_share:0.995 op ~expected (Helpers.image_exn s))
          [ "union"; "intersection"; "difference" ]);
  ]
