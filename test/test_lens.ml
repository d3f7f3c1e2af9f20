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

let lens = "(aperture 0.3)"

let tests =
  [
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
                  match what with "samples 3" -> (Some 3, None) | "adaptive" -> (Some 5, Some 4) | _ -> (None, None)
                in
                match Helpers.render_region ?samples ?adaptive ~jobs:2 s r with
                | Ok (img, _) -> Helpers.check_images (Format.asprintf "%s, region %a" what Render.Region.pp r) ~expected img
                | Error (`Msg m) -> Alcotest.fail m)
              [ Render.Region.v ~x:5 ~y:3 ~w:20 ~h:11; Render.Region.v ~x:36 ~y:22 ~w:1 ~h:1; Render.Region.v ~x:0 ~y:7 ~w:37 ~h:4 ])
          [
            ("1 sample", fun jobs -> image ~jobs s);
            ("samples 3", fun jobs -> image ~jobs ~samples:3 s);
            ("adaptive", fun jobs -> image ~jobs ~samples:5 ~adaptive:4 s);
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
