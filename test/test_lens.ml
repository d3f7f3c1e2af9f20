(* The thin lens (issue 27, depth of field): the kernel's lens rays
   against the literal definition (Literal.sample), the plane of focus
   sharp, aperture 0 the pinhole, the same bytes for every --jobs and
   region, blur that grows with the aperture, no allocation per ray.
   focus.scene's golden images are the golden suite's. *)
open Raytrace
module Trace = Private.Trace
module Literal = Private.Literal

(* A row of balls on a checkered floor, under a turned camera (look-at)
   focused on the middle ball; [extra] is added to the camera form. *)
let row_text ?(robust = false) ?(glass = false) ?(size = (48, 27)) camera =
  let w, h = size in
  Printf.sprintf
    "(canvas (width %d) (height %d)) (viewport (width 1.6) (height 0.9) (distance 1)) %s\n\
     (camera (position 0 1.4 -3.5) (look-at 0 0.6 6) %s)\n\
     (plane (point 0 0 0) (normal 0 1 0) (color 225 225 215) (specular 100) (pattern checker (color 60 70 100) (size 1)))\n\
     (sphere (center -1.2 0.6 3.8) (radius 0.6) (color 240 180 30) (specular 300))\n\
     (sphere (center 0 0.6 6) (radius 0.6) (color 40 190 80) (specular 300) (reflective 0.3) %s)\n\
     (sphere (center 1.2 0.6 8.2) (radius 0.6) (color 40 120 230) (specular 300))\n\
     (light ambient (intensity 0.2)) (light point (intensity 0.6) (position -4 6 -1))\n\
     (light directional (intensity 0.2) (direction 1 4 -2))"
    w h
    (if robust then "" else "(epsilon 0.001)")
    camera
    (if glass then "(transparency 0.6) (refractive-index 1.5)" else "")

let row ?robust ?glass ?size camera = Helpers.parse_ok (row_text ?robust ?glass ?size camera)

let image ?jobs ?samples ?adaptive s =
  match Helpers.render ?jobs ?samples ?adaptive s with Ok (img, _) -> img | Error (`Msg m) -> Alcotest.fail m

let same a b = Float.abs (a -. b) <= 1e-9 *. Float.max 1. (Float.max (Float.abs a) (Float.abs b))

(* Every sample of an [n x n] grid in every pixel, traced by [f] (which
   leaves its colour in [tr]), against [expected]: the samples whose
   colours differ by more than rounding, and the largest difference. *)
let compare_samples s tr ~n ~f ~expected =
  let differ = ref 0 and total = ref 0 and worst = ref 0. in
  for gx = Canvas.min_x (Scene.width s) to Canvas.max_x (Scene.width s) do
    for gy = Canvas.min_y (Scene.height s) to Canvas.max_y (Scene.height s) do
      for j = 0 to n - 1 do
        for i = 0 to n - 1 do
          f gx gy ~i ~j;
          let (c : Color.t) = expected gx gy ~i ~j in
          incr total;
          if not (same c.r (Trace.red tr) && same c.g (Trace.green tr) && same c.b (Trace.blue tr)) then begin
            incr differ;
            let d =
              Float.max (Float.abs (c.r -. Trace.red tr))
                (Float.max (Float.abs (c.g -. Trace.green tr)) (Float.abs (c.b -. Trace.blue tr)))
            in
            worst := Float.max !worst d
          end
        done
      done
    done
  done;
  (!differ, !total, !worst)

(* The kernel's samples against the literal lens rays: equal to rounding,
   but for the few where rounding decides a different hit (an edge, a
   checker boundary, a shadow's edge). *)
let against_literal what s =
  let tr = Trace.create (Helpers.prepare ~skips:false s) in
  let differ, total, worst =
    compare_samples s tr ~n:3
      ~f:(fun gx gy ~i ~j -> Trace.sample tr gx gy ~i ~j ~n:3)
      ~expected:(fun gx gy ~i ~j -> Literal.sample s gx gy ~i ~j ~n:3)
  in
  Printf.printf "%s: %d of %d samples differ from the literal lens rays, by up to %g\n" what differ total worst;
  if differ * 200 > total then Alcotest.failf "%s: %d of %d samples differ from Literal's" what differ total;
  (* The pixel's centre sample is [pixel]'s ray, in both. *)
  let differ, total, _ =
    compare_samples s tr ~n:1
      ~f:(fun gx gy ~i:_ ~j:_ -> Trace.pixel tr gx gy)
      ~expected:(fun gx gy ~i:_ ~j:_ -> Literal.pixel s gx gy)
  in
  if differ * 200 > total then Alcotest.failf "%s: %d of %d pixels differ from Literal's" what differ total

(* A matte checkered wall across the view axis at distance [wall], seen
   by a camera at the origin focused at [focus]. *)
let wall ~aperture ~focus ~wall =
  Helpers.parse_ok
    (Printf.sprintf
       "(canvas (width 40) (height 40)) (camera (position 0.013 0.029 0) (aperture %g) (focal-distance %g))\n\
        (plane (point 0 0 %g) (normal 0 0 -1) (color 230 230 230) (pattern checker (color 30 30 160) (size 0.7)))\n\
        (sphere (center 0.9 -0.4 %g) (radius 0.3) (color 200 40 40))\n\
        (light ambient (intensity 0.3)) (light point (intensity 0.7) (position 1 2 0))"
       aperture focus wall (wall -. 0.6))

(* A red ball before a grey wall at depth [wall], in ambient light, seen
   through a lens of radius 1 focused at 5. *)
let ball_and_wall ~wall ~ball:(x, y, z) ~radius =
  Helpers.parse_ok
    (Printf.sprintf
       "(canvas (width 40) (height 40)) (camera (position 0 0 0) (aperture 2) (focal-distance 5))\n\
        (plane (point 0 0 %g) (normal 0 0 -1) (color 230 230 230))\n\
        (sphere (center %g %g %g) (radius %g) (color 200 40 40))\n\
        (light ambient (intensity 1))"
       wall x y z radius)

let lens = "(aperture 0.3)"

(* Shirley and Chiu's concentric map undone: the point of the unit square
   that [Literal.lens_point] mapped onto [(x, y)] of the unit disc. *)
let unmap (x, y) =
  let r = sqrt ((x *. x) +. (y *. y)) in
  let q = Float.pi /. 4. in
  let phi = Float.atan2 y x in
  let phi = if phi < -.q then phi +. (2. *. Float.pi) else phi in
  let a, b =
    if r = 0. then (0., 0.)
    else if phi < q then (r, phi /. q *. r)
    else if phi < 3. *. q then (-.(phi -. (2. *. q)) /. q *. r, r)
    else if phi < 5. *. q then (-.r, (phi -. (4. *. q)) /. q *. -.r)
    else ((phi -. (6. *. q)) /. q *. r, -.r)
  in
  ((a +. 1.) /. 2., (b +. 1.) /. 2.)

let stratified = Camera.v ~aperture:1. ~focal_distance:1. Vec3.zero

(* The lens points of the [n x n] camera samples of pixel [(gx, gy)], back
   on the unit square, less the pixel's offset [u0] modulo 1: one in each
   cell of the [n x n] cut if stratified. *)
let cells ~gx ~gy n =
  let hp = Private.Sample_key.pixel ~col:gx ~row:gy ~sample:(-1) in
  let u0 = Private.Sample_key.(unit (key hp 0)) and v0 = Private.Sample_key.(unit (key hp 1)) in
  let seen = Array.make (n * n) 0 in
  for j = 0 to n - 1 do
    for i = 0 to n - 1 do
      let key = Private.Sample_key.camera ~gx ~gy ~di:((2 * i) + 1 - n) ~dj:((2 * j) + 1 - n) in
      let u, v = unmap (Literal.lens_point stratified ~key ~lens:(gx, gy, n, i, j)) in
      (* The map and its inverse round: a hair below 0 is 0 (the centre
         sample lies on the corner of cell 0), and a hair inside the
         cells. *)
      let wrap z = if z < -1e-9 then z +. 1. else Float.max 0. z in
      let cell z = Float.to_int (Float.of_int n *. Float.min (1. -. 1e-12) (wrap z +. 1e-12)) in
      let c = (cell (v -. v0) * n) + cell (u -. u0) in
      seen.(c) <- seen.(c) + 1
    done
  done;
  seen

(* The columns (rows, [along = `Y]) of sub-cells, [1 / n^2] wide, that
   the [n x n] stratified lens points of pixel [(gx, gy)] fall in, back on
   the unit square, less the pixel's offset modulo 1: one in each if
   multi-jittered. *)
let strata ~along ~gx ~gy n =
  let hp = Private.Sample_key.pixel ~col:gx ~row:gy ~sample:(-1) in
  let u0 = Private.Sample_key.(unit (key hp 0)) and v0 = Private.Sample_key.(unit (key hp 1)) in
  let m = n * n in
  let seen = Array.make m 0 in
  for j = 0 to n - 1 do
    for i = 0 to n - 1 do
      let key = Private.Sample_key.camera ~gx ~gy ~di:((2 * i) + 1 - n) ~dj:((2 * j) + 1 - n) in
      let u, v = unmap (Literal.lens_point stratified ~key ~lens:(gx, gy, n, i, j)) in
      let z = match along with `X -> u -. u0 | `Y -> v -. v0 in
      (* As in [cells]: the map and its inverse round. *)
      let wrap z = if z < -1e-9 then z +. 1. else Float.max 0. z in
      let c = Float.to_int (Float.of_int m *. Float.min (1. -. 1e-12) (wrap z +. 1e-12)) in
      seen.(c) <- seen.(c) + 1
    done
  done;
  seen

let tests =
  [
    Alcotest.test_case "a pixel's n x n stratified lens points are multi-jittered: one in each of n^2 columns and rows"
      `Quick (fun () ->
        List.iter
          (fun n ->
            for gx = -3 to 3 do
              for gy = -2 to 2 do
                List.iter
                  (fun along ->
                    let seen = strata ~along ~gx ~gy n in
                    if Array.exists (fun c -> c <> 1) seen then
                      Alcotest.failf "n = %d, pixel (%d, %d), %s: strata hold %s" n gx gy
                        (match along with `X -> "columns" | `Y -> "rows")
                        (String.concat " " (Array.to_list (Array.map string_of_int seen))))
                  [ `X; `Y ]
              done
            done)
          [ 1; 2; 3; 4; 5; 7 ]);
    Alcotest.test_case "a pixel's n x n stratified lens points lie one in each cell of its shifted cut" `Quick (fun () ->
        List.iter
          (fun n ->
            for gx = -3 to 3 do
              for gy = -2 to 2 do
                let seen = cells ~gx ~gy n in
                if Array.exists (fun c -> c <> 1) seen then
                  Alcotest.failf "n = %d, pixel (%d, %d): cells hold %s" n gx gy
                    (String.concat " " (Array.to_list (Array.map string_of_int seen)))
              done
            done)
          [ 1; 2; 3; 4; 5; 7 ]);
    Alcotest.test_case "the centre sample of an odd grid takes the one-sample render's lens point" `Quick (fun () ->
        let point n i j = Literal.lens_point stratified ~key:0 ~lens:(4, -2, n, i, j) in
        let one = point 1 0 0 in
        List.iter (fun n -> Alcotest.(check (pair (float 0.) (float 0.))) (Printf.sprintf "n = %d" n) one (point n (n / 2) (n / 2)))
          [ 3; 5; 7; 9 ]);
    Alcotest.test_case "(lens-sampling uniform): the kernel's lens rays are the literal independent draws'" `Quick (fun () ->
        let s = row (lens ^ " (lens-sampling uniform)") in
        Alcotest.(check bool) __LOC__ true (Camera.lens_sampling (Scene.camera s) = Camera.Uniform);
        against_literal "uniform lens" s;
        (* Not the stratified image. *)
        match Image.Diff.compare (image ~samples:3 s) (image ~samples:3 (row lens)) with
        | Error (`Msg m) -> Alcotest.fail m
        | Ok d -> if d.differing < 100 then Alcotest.failf "uniform and stratified: only %d pixels differ" d.differing);
    Alcotest.test_case "a lens's camera samples are the literal lens rays', to rounding" `Quick (fun () ->
        against_literal "document's mode" (row lens);
        against_literal "robust mode" (row ~robust:true lens);
        against_literal "glass" (row ~glass:true lens);
        against_literal "no rotation" (Helpers.parse_ok
          "(canvas (width 40) (height 30)) (camera (position 0.3 0.5 -1) (aperture 0.4) (focal-distance 6))\n\
           (sphere (center 0 0 6) (radius 1) (color 200 40 40) (specular 50))\n\
           (sphere (center 1.5 0.5 9) (radius 1) (color 40 200 40))\n\
           (box (min -3 -1.5 2) (max -1.5 -0.5 3) (color 40 40 200))\n\
           (light ambient (intensity 0.2)) (light point (intensity 0.7) (position 2 3 0))"));
    Alcotest.test_case "a hierarchy of many spheres under a lens is the literal lens rays' too" `Quick (fun () ->
        (* 100 balls: more than the hierarchy's threshold, so the lens's
           rays run through the boxes, whose margins cover the lens. *)
        let b = Buffer.create 4096 in
        Buffer.add_string b
          "(canvas (width 32) (height 32)) (camera (position 0 2 -4) (look-at 0 0 5) (aperture 0.5))\n\
           (light ambient (intensity 0.3)) (light point (intensity 0.7) (position 2 5 -2))\n";
        for i = 0 to 9 do
          for j = 0 to 9 do
            Printf.bprintf b "(sphere (center %g 0 %g) (radius 0.3) (color %d 90 %d))\n"
              (Float.of_int i -. 4.5) (Float.of_int j +. 1.) (20 * i) (20 * j)
          done
        done;
        let s = Helpers.parse_ok (Buffer.contents b) in
        if (Helpers.prepare s).bvh = None then Alcotest.fail "the scene has no hierarchy";
        against_literal "100 balls" s);
    Alcotest.test_case "the plane of focus is sharp: every lens point sees a point of it where the pinhole does" `Quick
      (fun () ->
        (* The wall lies on the plane of focus (z = 5): every sample's ray
           meets it at the pinhole's point, up to rounding, and the wall is
           matte, so the colour is the pinhole's. The ball in front of it
           (0.6 nearer) is out of focus: there the samples differ. *)
        let pin = wall ~aperture:0. ~focus:1. ~wall:5. and sharp = wall ~aperture:0.5 ~focus:5. ~wall:5. in
        let tp = Trace.create (Helpers.prepare ~skips:false pin) in
        let tl = Trace.create (Helpers.prepare ~skips:false sharp) in
        let on_wall = ref 0 and differ = ref 0 in
        for gx = -20 to 19 do
          for gy = -20 to 19 do
            for j = 0 to 2 do
              for i = 0 to 2 do
                Trace.sample tp gx gy ~i ~j ~n:3;
                Trace.sample tl gx gy ~i ~j ~n:3;
                (* Object 0 is the wall, in both. *)
                if Trace.hit_object tp = 0 && Trace.hit_object tl = 0 then begin
                  incr on_wall;
                  if not (same (Trace.red tp) (Trace.red tl) && same (Trace.blue tp) (Trace.blue tl)) then incr differ
                end
              done
            done
          done
        done;
        Printf.printf "%d of %d samples on the wall differ from the pinhole's\n" !differ !on_wall;
        if !on_wall < 10000 then Alcotest.failf "only %d samples on the wall" !on_wall;
        (* A checker boundary decided the other way by rounding. *)
        if !differ * 1000 > !on_wall then Alcotest.failf "%d of %d samples differ" !differ !on_wall;
        (* Focused elsewhere, the same wall blurs. *)
        let blurred = image ~samples:3 (wall ~aperture:0.5 ~focus:2. ~wall:5.) in
        match Image.Diff.compare (image ~samples:3 pin) blurred with
        | Error (`Msg m) -> Alcotest.fail m
        | Ok d -> if d.differing < 100 then Alcotest.failf "out of focus, only %d pixels differ" d.differing);
    Alcotest.test_case "aperture 0 is the pinhole, byte for byte, and draws no numbers" `Quick (fun () ->
        let pin = row "" and zero = row "(aperture 0) (focal-distance 3)" in
        Alcotest.(check bool) __LOC__ false (Helpers.prepare zero).sampled;
        Alcotest.(check bool) __LOC__ true (Helpers.prepare (row lens)).sampled;
        List.iter
          (fun (what, f) -> Helpers.check_images what ~expected:(f pin) (f zero))
          [
            ("1 sample", fun s -> image s);
            ("samples 3", fun s -> image ~samples:3 s);
            ("adaptive", fun s -> image ~samples:3 ~adaptive:4 s);
          ]);
    Alcotest.test_case "a lens gives the same bytes for 1, 2 and 3 jobs and for any region" `Quick (fun () ->
        let s = row ~size:(37, 23) lens in
        List.iter
          (fun (what, f) ->
            let one = f 1 in
            Helpers.check_images (what ^ ", 2 jobs") ~expected:one (f 2);
            Helpers.check_images (what ^ ", 3 jobs") ~expected:one (f 3);
            List.iter
              (fun (r : Render.Region.t) ->
                let expected = Image.sub one ~x:r.x ~y:r.y ~w:r.w ~h:r.h in
                let samples, adaptive =
                  match what with
                  | "samples 3" -> (Some 3, None)
                  | "adaptive" -> (Some 5, Some 4)
                  | "adaptive, even" -> (Some 4, Some 4)
                  | _ -> (None, None)
                in
                match Helpers.render_region ?samples ?adaptive ~jobs:2 s r with
                | Ok (img, _) -> Helpers.check_images (Format.asprintf "%s, region %a" what Render.Region.pp r) ~expected img
                | Error (`Msg m) -> Alcotest.fail m)
              [ Render.Region.v ~x:5 ~y:3 ~w:20 ~h:11; Render.Region.v ~x:36 ~y:22 ~w:1 ~h:1; Render.Region.v ~x:0 ~y:7 ~w:37 ~h:4 ])
          [
            ("1 sample", fun jobs -> image ~jobs s);
            ("samples 3", fun jobs -> image ~jobs ~samples:3 s);
            ("adaptive", fun jobs -> image ~jobs ~samples:5 ~adaptive:4 s);
            ("adaptive, even", fun jobs -> image ~jobs ~samples:4 ~adaptive:4 s);
          ]);
    Alcotest.test_case "the blur grows with the aperture" `Quick (fun () ->
        let pin = image ~samples:2 (row "") in
        let blur a =
          match Image.Diff.compare pin (image ~samples:2 (row (Printf.sprintf "(aperture %g)" a))) with
          | Ok d -> d.mean_abs
          | Error (`Msg m) -> Alcotest.fail m
        in
        let blurs = List.map blur [ 0.02; 0.1; 0.4; 1. ] in
        Printf.printf "mean difference from the pinhole: %s\n" (String.concat ", " (List.map string_of_float blurs));
        let rec increasing = function a :: (b :: _ as rest) -> a < b && increasing rest | _ -> true in
        if not (List.hd blurs > 0. && increasing blurs) then Alcotest.fail "the blur does not grow with the aperture");
    Alcotest.test_case "tracing through a lens allocates nothing per pixel, whatever the sampling" `Quick (fun () ->
        List.iter
          (fun (what, s) ->
            List.iter
              (fun (how, r) ->
                match r with
                | Ok (_, (st : Render.Stats.t)) -> Alcotest.(check (float 0.)) (what ^ ", " ^ how) 0. st.minor_words
                | Error (`Msg m) -> Alcotest.fail m)
              [
                ("1 sample", Helpers.render ~jobs:1 s);
                ("samples 3", Helpers.render ~jobs:1 ~samples:3 s);
                ("adaptive", Helpers.render ~jobs:1 ~samples:3 ~adaptive:4 s);
                ("subsampling", Helpers.render ~jobs:1 ~subsample:true s);
              ])
          [ ("turned", row lens); ("robust", row ~robust:true lens); ("glass", row ~glass:true lens);
            ("wall", wall ~aperture:0.5 ~focus:5. ~wall:5.) ]);
    Alcotest.test_case "adaptive under a lens: every blurred pixel is --samples n's, every other the one-sample render's or n's"
      `Quick (fun () ->
        (* [classify] counts the pixels of [a] equal to [one]'s, to
           [full]'s (only), and to neither (there must be none). *)
        let classify ~one ~full a =
          let as_one = ref 0 and as_full = ref 0 in
          for y = 0 to Image.height a - 1 do
            for x = 0 to Image.width a - 1 do
              let p = Image.get a x y in
              if p = Image.get one x y then incr as_one
              else if p = Image.get full x y then incr as_full
              else Alcotest.failf "pixel (%d, %d) is neither the one-sample render's nor the full grid's" x y
            done
          done;
          (!as_one, !as_full)
        in
        (* Focused at 2, the wall at 5 is blurred over about 6 pixels
           (0.5 x 40 x 3 / (5 x 1 x 2)): every pixel is blurred, and is
           refined where a probe of its lens sees another object (the
           ball), at threshold 255; elsewhere (one object, colours within
           255) its four probes agree with its first ray and it keeps it.
           At threshold 8 the checker's cells (5.6 pixels) are no wider
           than the circle: nearly every cone meets an edge. *)
        let blurred = wall ~aperture:0.5 ~focus:2. ~wall:5. in
        let one = image blurred and full = image ~samples:3 blurred in
        List.iter
          (fun (th, min_one, min_full) ->
            let as_one, as_full = classify ~one ~full (image ~samples:3 ~adaptive:th blurred) in
            Printf.printf "a blurred wall, threshold %d: %d pixels as one sample, %d as 3 x 3\n" th as_one as_full;
            if as_one < min_one || as_full < min_full then
              Alcotest.failf "threshold %d: %d pixels as one sample, %d as 3 x 3" th as_one as_full)
          [ (255, 1000, 50); (8, 0, 1000) ];
        (* Focused on it, the wall is sharp: its pixels keep their first
           ray, but for those the ball's blur reaches (0.5 x 40 x 0.6 /
           (4.4 x 5): 0.55 pixels) and the edges. *)
        let sharp = wall ~aperture:0.5 ~focus:5. ~wall:5. in
        let one = image sharp and full = image ~samples:3 sharp in
        let as_one, as_full = classify ~one ~full (image ~samples:3 ~adaptive:255 sharp) in
        Printf.printf "focused on the wall, threshold 255: %d pixels as one sample, %d as 3 x 3\n" as_one as_full;
        if as_one < 1000 || as_full < 20 then Alcotest.failf "%d pixels as one sample, %d as 3 x 3" as_one as_full;
        (* A ball blurred over about 3 pixels (2 x 40 x 0.6 / (4.4 x 5)) in
           front of the sharp wall: the wall's pixels around its edge are
           refined too, though their first rays hit the wall as their
           neighbours' do and their own circle is 0: the ball's circle
           reaches them, and a probe from the lens's rim sees the ball. *)
        let spread = ball_and_wall ~wall:5. ~ball:(0., 0., 4.4) ~radius:0.3 in
        let one = image spread and full = image ~samples:3 spread in
        let a = image ~samples:3 ~adaptive:255 spread in
        ignore (classify ~one ~full a);
        (* The pixels whose first ray sees the wall (230, ambient 1) but
           whose full grid sees some of the ball: refined, every one that
           sees it in two or more of its nine samples (green at most
           (7 x 230 + 2 x 40) / 9 = 187.8). One sample of nine (green
           (8 x 230 + 40) / 9 = 208.9, 209) may lie between the probes
           and the first ray: an estimate, below; at most one such pixel
           here (the lens points of issue 27's second round had none, the
           multi-jittered ones have one, (24, 19)). *)
        let beside = ref 0 and missed = ref 0 in
        for y = 0 to 39 do
          for x = 0 to 39 do
            if Image.get one x y = (230, 230, 230) && Image.get full x y <> (230, 230, 230) then begin
              incr beside;
              if Image.get a x y <> Image.get full x y then begin
                let _, g, _ = Image.get full x y in
                if g < 209 then Alcotest.failf "pixel (%d, %d): the ball's blur reaches it, but it was not refined" x y;
                incr missed
              end
            end
          done
        done;
        Printf.printf "%d pixels of the wall under the ball's blur, all refined but %d that see it in one sample of nine\n"
          !beside !missed;
        if !missed > 1 then Alcotest.failf "%d pixels that see the ball in one sample were not refined" !missed;
        if !beside < 8 then Alcotest.failf "only %d pixels of the wall under the ball's blur" !beside);
    Alcotest.test_case "adaptive under a lens with an even grid: each pixel the one-sample render's or --samples n's"
      `Quick (fun () ->
        (* As above for odd grids: the 4 x 4 grid has no centre sample, so
           a refined pixel traces all 16 (its first ray not reused) and is
           exactly --samples 4's; the others keep their first ray. The
           blurred checker wall (circles of about 6 pixels, cells of 5.6)
           at threshold 255 keeps one ray but where a probe sees the ball;
           at threshold 8 nearly every cone meets an edge. *)
        let blurred = wall ~aperture:0.5 ~focus:2. ~wall:5. in
        let one = image blurred and full = image ~samples:4 blurred in
        List.iter
          (fun (th, min_one, min_full) ->
            let a = image ~samples:4 ~adaptive:th blurred in
            let as_one = ref 0 and as_full = ref 0 in
            for y = 0 to 39 do
              for x = 0 to 39 do
                let p = Image.get a x y in
                if p = Image.get one x y then incr as_one
                else if p = Image.get full x y then incr as_full
                else Alcotest.failf "threshold %d, pixel (%d, %d): neither one sample's nor --samples 4's" th x y
              done
            done;
            Printf.printf "a blurred wall, 4 x 4, threshold %d: %d pixels as one sample, %d as 4 x 4\n" th !as_one !as_full;
            if !as_one < min_one || !as_full < min_full then
              Alcotest.failf "threshold %d: %d pixels as one sample, %d as 4 x 4" th !as_one !as_full)
          [ (255, 1000, 50); (8, 0, 1000) ];
        (* Without a lens an even adaptive grid is refused, before any work. *)
        match Helpers.render ~samples:4 ~adaptive:8 (wall ~aperture:0. ~focus:2. ~wall:5.) with
        | Ok _ -> Alcotest.fail "a pinhole rendered --samples 4 --adaptive 8"
        | Error (`Msg m) -> Alcotest.(check string) __LOC__ (Render.Sampling.even_message 4) m);
    Alcotest.test_case "adaptive under a lens: the probes are an estimate, an object between them is missed" `Quick
      (fun () ->
        (* Focused at 5 with a lens of radius 1, the cone of the centre
           pixel's rays crosses z = 10 in the unit disc around the axis
           (mirrored); a ball of radius 0.25 at (0.55, 0.55, 10) lies inside
           it but away from its centre and from the four rim probes at
           distance 1 on the axes. The pixels whose first ray and probes
           all miss it keep their first ray, though their full grid sees
           it: at least one does. *)
        let s = ball_and_wall ~wall:12. ~ball:(0.55, 0.55, 10.) ~radius:0.25 in
        let one = image s and full = image ~samples:7 s and a = image ~samples:7 ~adaptive:8 s in
        let missed = ref 0 and refined = ref 0 in
        for y = 0 to 39 do
          for x = 0 to 39 do
            let p = Image.get a x y in
            if p <> Image.get one x y then begin
              incr refined;
              if p <> Image.get full x y then Alcotest.failf "pixel (%d, %d) is neither one sample's nor 7 x 7's" x y
            end
            else if Image.get full x y <> p then incr missed
          done
        done;
        Printf.printf "%d pixels refined, %d whose full grid sees the ball kept one ray\n" !refined !missed;
        if !missed = 0 then Alcotest.fail "no pixel between the probes: the case is not shown";
        if !refined < 10 then Alcotest.failf "only %d pixels refined" !refined);
    Alcotest.test_case "Trace.probe: fixed rim rays, counted as primary rays, the pixel's ray for a pinhole" `Quick
      (fun () ->
        let colour tr = (Trace.red tr, Trace.green tr, Trace.blue tr) in
        let s = row lens in
        let tr = Trace.create (Helpers.prepare ~skips:false s) in
        let probes () = List.map (fun k -> Trace.probe tr 3 (-2) k; (colour tr, Trace.hit_object tr)) [ 0; 1; 2; 3 ] in
        let before = (Trace.counters tr).primary in
        let first = probes () in
        Alcotest.(check int) "four probes, four primary rays" (before + 4) (Trace.counters tr).primary;
        (* Whatever was traced before, the same rays. *)
        Trace.pixel tr (-7) 5;
        ignore (Trace.average (Trace.create ~averaging:true (Helpers.prepare ~skips:false s)) 3 (-2) ~n:3);
        if probes () <> first then Alcotest.fail "a probe depends on what was traced before";
        (* The four rim points see differently placed things. *)
        if List.length (List.sort_uniq compare first) < 2 then Alcotest.fail "the four probes see the same colour";
        let pin = row "" in
        let tp = Trace.create (Helpers.prepare ~skips:false pin) in
        Trace.pixel tp 3 (-2);
        let c = colour tp in
        List.iter
          (fun k ->
            Trace.probe tp 3 (-2) k;
            if colour tp <> c then Alcotest.failf "pinhole probe %d differs from the pixel's ray" k)
          [ 0; 1; 2; 3 ];
        Alcotest.check_raises "outside the canvas" (Invalid_argument "Trace.probe: no such pixel or probe") (fun () ->
            Trace.probe tr 1000 0 0);
        Alcotest.check_raises "no probe 4" (Invalid_argument "Trace.probe: no such pixel or probe") (fun () ->
            Trace.probe tr 0 0 4));
    Alcotest.test_case "every frame of a camera path takes the camera form's lens" `Quick (fun () ->
        let s =
          Helpers.parse_ok
            "(camera (position 0 0 0) (aperture 0.3) (focal-distance 5))\n\
             (camera-path (key (frame 0) (position 0 0 0) (look-at 0 0 3)) (key (frame 4) (position 4 0 0) (look-at 0 0 3)))"
        in
        match Scene.at_frame (Helpers.valid s) 2 with
        | Error (`Msg m) -> Alcotest.fail m
        | Ok f ->
            let c = Scene.camera (Scene.of_valid f) in
            Alcotest.check Helpers.vec3 __LOC__ (Vec3.v 2. 0. 0.) c.position;
            Alcotest.(check (pair (float 0.) (float 0.))) __LOC__ (0.3, 5.) (Camera.aperture c, Camera.focal_distance c));
  ]
