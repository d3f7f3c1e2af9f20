(* Area, sphere and spot lights (issue 27): the scene forms and their
   errors, the kernel against the oracle's own transcription of the
   definition (Light, "Sample points"), soft shadows that are soft,
   the same bytes for every --jobs and tile, and no allocation. *)
open Raytrace

(* A floor, a ball over it and the light [light] (scene text), in the
   document's mode (an epsilon), so that the kernel and the oracle do the
   same arithmetic. *)
let scene ?(size = 48) ?(extra = "") light =
  Helpers.parse_ok
    (Printf.sprintf
       {|(canvas (width %d) (height %d)) (epsilon 0.001)
(camera (position 0 2 -3) (look-at 0 0 2))
(plane (point 0 -1 0) (normal 0 1 0) (color 200 200 200) (specular 20))
(sphere (center 0 0 2) (radius 0.7) (color 255 80 80) (specular 300) %s)
(box (min 0.9 -1 2.5) (max 1.5 -0.2 3.1) (color 80 80 255))
(light ambient (intensity 0.1))
%s|}
       size size extra light)

let area = "(light area (intensity 0.7) (corner -1 3 1) (edge1 2 0 0) (edge2 0 0 2) (samples 3 4))"
let adaptive = "(light area (intensity 0.7) (corner -1 3 1) (edge1 2 0 0) (edge2 0 0 2) (samples 3 4) (adaptive true))"
let uniform = "(light area (intensity 0.7) (corner -1 3 1) (edge1 2 0 0) (edge2 0 0 2) (samples 3 4) (sampling uniform))"
let uniform_adaptive =
  "(light area (intensity 0.7) (corner -1 3 1) (edge1 2 0 0) (edge2 0 0 2) (samples 3 4) (sampling uniform) (adaptive true))"
let sphere = "(light sphere (intensity 0.7) (position 1 3 1) (radius 0.8) (samples 9))"
let spot = "(light spot (intensity 0.8) (position 0 4 1) (direction 0 -1 0.3) (angle 30) (falloff 3))"

(* The oracle's image of [s], pixel by pixel. *)
let oracle (s : Scene.t) =
  let v = Scene.of_valid (Helpers.valid s) in
  let img = Image.create (Scene.width v) (Scene.height v) in
  for gx = Canvas.min_x (Scene.width v) to Canvas.max_x (Scene.width v) do
    for gy = Canvas.min_y (Scene.height v) to Canvas.max_y (Scene.height v) do
      let c = Private.Literal.pixel v gx gy in
      Image.set img (Canvas.column ~width:(Scene.width v) gx) (Canvas.row ~height:(Scene.height v) gy)
        (Color.to_byte c.r) (Color.to_byte c.g) (Color.to_byte c.b)
    done
  done;
  img

(* The share of pixels that differ at all, and the most they differ by. *)
let difference ~expected actual =
  match Image.Diff.compare expected actual with
  | Ok d -> (d.differing, d.max_abs)
  | Error (`Msg m) -> Alcotest.fail m

let as_the_oracle what s =
  let expected = oracle s in
  List.iter
    (fun skips ->
      let differing, most = difference ~expected (Helpers.image_exn ~skips s) in
      (* The kernel and the oracle do the same operations on every
         sample: any pixel that differs is a mistake, but for a
         last-bit difference of a cosine's power rounding a byte. *)
      if differing > 2 || most > 1 then
        Alcotest.failf "%s, skips %b: %d pixels differ from the oracle's, by up to %d" what skips differing most)
    [ true; false ]

let light_of text = match Scene.lights (Helpers.parse_ok ("(canvas (width 2) (height 2)) " ^ text)) with [ l ] -> l | _ -> Alcotest.fail "one light"

let parse_cases =
  [
    ("(light area (intensity 0.5) (corner 0 3 0) (edge1 1 0 0) (edge2 1 0 0) (samples 2 2))", "1:1", "must not be parallel");
    ("(light area (intensity 0.5) (corner 0 3 0) (edge1 1 0 0) (edge2 0 0 1) (samples 2 0))", "1:83", "samples must lie in [1, 4096], got 0");
    ("(light area (intensity 0.5) (corner 0 3 0) (edge1 1 0 0) (edge2 0 0 1) (samples 2))", "1:72", "takes 2 integers, got 1");
    ("(light area (intensity 0.5) (corner 0 3 0) (edge1 1 0 0) (samples 2 2))", "1:1", "missing its (edge2 ...) field");
    ("(light area (intensity 0.5) (corner 0 3 0) (edge1 1 0 0) (edge2 0 0 1) (samples 2 2) (sampling random))", "1:96",
     "sampling: expected stratified or uniform, got random");
    ("(light area (intensity 0.5) (corner 0 3 0) (edge1 1 0 0) (edge2 0 0 1) (samples 2 2) (sampling uniform true))", "1:86",
     "sampling takes 1 value, got 2");
    ("(light sphere (intensity 0.5) (position 0 3 0) (radius 0) (samples 4))", "1:1", "radius must lie in");
    ("(light sphere (intensity 0.5) (position 0 3 0) (radius 1) (samples 1.5))", "1:68", "expected an integer, got 1.5");
    ("(light spot (intensity 0.5) (position 0 3 0) (direction 0 0 0) (angle 20) (falloff 1))", "1:1", "direction must not be the zero vector");
    ("(light spot (intensity 0.5) (position 0 3 0) (direction 0 -1 0) (angle 200) (falloff 1))", "1:1", "angle must lie in (0, 180]");
    ("(light spot (intensity 0.5) (position 0 3 0) (direction 0 -1 0) (angle 20))", "1:1", "missing its (falloff ...) field");
    ("(light spot (intensity 0.5) (position 0 3 0) (direction 0 -1 0) (angle 20) (falloff 1) (radius 2))", "1:89", "unknown light spot field radius");
  ]

let contains s sub = Astring_free.contains s sub

let tests =
  [
    Alcotest.test_case "each new light prints as a form that reads back as the same light" `Quick (fun () ->
        List.iter
          (fun text ->
            let l = light_of text in
            Alcotest.(check string) __LOC__ text (Light.show l);
            Alcotest.(check bool) text true (Light.equal l (light_of (Light.show l))))
          [ area; adaptive; uniform; uniform_adaptive; sphere; spot ]);
    Alcotest.test_case "a bad area, sphere or spot light is one located line" `Quick (fun () ->
        List.iter
          (fun (text, at, expected) ->
            let m = Helpers.parse_error text in
            if not (contains m ("t.scene:" ^ at ^ ":") && contains m expected) then
              Alcotest.failf "%S: expected t.scene:%s: ... %S, got %S" text at expected m)
          parse_cases);
    Alcotest.test_case "the kernel draws area, sphere and spot lights as the oracle does, skips on and off" `Quick
      (fun () ->
        List.iter (fun (what, l) -> as_the_oracle what (scene l)) [ ("area", area); ("sphere", sphere); ("spot", spot) ];
        as_the_oracle "all three" (scene (String.concat "\n" [ area; sphere; spot ]));
        as_the_oracle "adaptive area" (scene adaptive);
        as_the_oracle "uniform area" (scene uniform);
        as_the_oracle "uniform adaptive area" (scene uniform_adaptive));
    Alcotest.test_case "through glass too (the ray tree's lighting)" `Quick (fun () ->
        as_the_oracle "area, glass ball" (scene ~extra:"(transparency 0.5) (refractive-index 1.3)" area);
        as_the_oracle "adaptive area, glass ball" (scene ~extra:"(transparency 0.5) (refractive-index 1.3)" adaptive);
        as_the_oracle "uniform area, glass ball" (scene ~extra:"(transparency 0.5) (refractive-index 1.3)" uniform));
    Alcotest.test_case "an area light's shadow is soft: the floor under the ball's edge takes values between" `Quick
      (fun () ->
        (* With a point light at the panel's centre the floor is lit or in
           shadow: two values (at the ball's shadow, where the plane's
           shading is almost flat). Under the panel, the penumbra fills
           the values between. Count the distinct bytes along the row. *)
        let distinct light =
          let img = Helpers.image_exn (scene ~size:96 light) in
          let row = 90 in
          List.length (List.sort_uniq compare (List.init 96 (fun x -> let r, _, _ = Image.get img x row in r)))
        in
        let hard = distinct "(light point (intensity 0.7) (position 0 3 2))" and soft = distinct area in
        if soft < hard + 5 then Alcotest.failf "%d shades under the area light, %d under the point light" soft hard);
    Alcotest.test_case "a sphere light's samples are stratified in angle: a wall over half its disc stops 7 to 9 of 16, for every key" `Quick
      (fun () ->
        (* The light 10 above the point P = 0, of radius 1, P's normal up:
           w = (0, 1, 0), so e1 = (1, 0, 0) x w = (0, 0, 1) and
           e2 = w x e1 = (1, 0, 0), and sample j is at x = rho sin phi.
           The slab x in [0, 5], y in [4, 5] stops the shadow rays of the
           samples with phi in (0, pi) (turns 0 to 1/2). Of 16 samples
           (c = 4 sectors of a quarter turn, turned by r; q = 4 blocks of
           4 rings, one sample a sector each) the half turn holds one
           whole sector, 4 samples, and two parts of sectors that add up
           to one: the left part f of one, the right part 1 - f of the
           other, each sector's 4 samples one in each quarter of it
           (their blocks' b), so 4 +- 1 of those 8: 7 to 9 stopped, for
           every key. Each seen sample adds (0.8 / 16) 10 / sqrt (100 +
           rho^2), in (0.04975, 0.05]: 7 to 9 of them, (0.348, 0.45].
           Angles drawn independently stop 8 +- 2 (binomial): outside
           7 to 9 for about half the keys. *)
        let scene =
          Helpers.parse_ok
            "(box (min 0 4 -5) (max 5 5 5) (color 1 1 1)) (light sphere (intensity 0.8) (position 0 10 0) (radius 1) (samples 16))"
        in
        for key = 0 to 199 do
          let i =
            Private.Literal.compute_lighting ~key scene ~epsilon:1e-3 ~point:Vec3.zero ~normal:(Vec3.v 0. 1. 0.)
              ~view:(Vec3.v 0. 1. 0.) ~specular:Sphere.matte
          in
          if not (i > 0.348 && i <= 0.45) then Alcotest.failf "key %d: intensity %g, not 7 to 9 samples' (0.348, 0.45]" key i
        done);
    Alcotest.test_case "a 1 x 1 area light of no extent is the point light at its jittered corner cell" `Quick (fun () ->
        (* Tiny edges: every sample lies within 1e-9 of the corner. *)
        let tiny = "(light area (intensity 0.7) (corner 0 3 2) (edge1 1e-9 0 0) (edge2 0 0 1e-9) (samples 1 1))" in
        let differing, most =
          difference ~expected:(Helpers.image_exn (scene "(light point (intensity 0.7) (position 0 3 2))"))
            (Helpers.image_exn (scene tiny))
        in
        if most > 1 then Alcotest.failf "%d pixels differ, by up to %d" differing most);
    Alcotest.test_case "the samples are the same for every --jobs, tile and sampling grid" `Quick (fun () ->
        let s = scene ~size:40 (String.concat "\n" [ area; sphere ]) in
        let whole = Helpers.image_exn s in
        Helpers.check_images "4 jobs" ~expected:whole (Helpers.image_exn ~jobs:4 s);
        (match Helpers.render_region ~jobs:2 s (Render.Region.v ~x:7 ~y:11 ~w:20 ~h:13) with
        | Ok (img, _) -> Helpers.check_images "a tile" ~expected:(Image.sub whole ~x:7 ~y:11 ~w:20 ~h:13) img
        | Error (`Msg m) -> Alcotest.fail m);
        let grid = Helpers.image_exn ~samples:3 s in
        Helpers.check_images "3 x 3, 3 jobs" ~expected:grid (Helpers.image_exn ~jobs:3 ~samples:3 s);
        Helpers.check_images "adaptive, 2 jobs" ~expected:(Helpers.image_exn ~samples:3 ~adaptive:4 s)
          (Helpers.image_exn ~jobs:2 ~samples:3 ~adaptive:4 s));
    Alcotest.test_case "the camera samples draw different light samples: the grid smooths the penumbra" `Quick (fun () ->
        let s = scene ~size:40 area in
        let one = Helpers.image_exn s and grid = Helpers.image_exn ~samples:3 s in
        if Image.equal one grid then Alcotest.fail "3 x 3 camera samples gave the image of one");
    Alcotest.test_case "tracing soft lights allocates nothing per pixel" `Quick (fun () ->
        List.iter
          (fun (what, s, samples) ->
            match Helpers.render ~samples s with
            | Ok (_, st) -> Alcotest.(check (float 0.)) what 0. st.minor_words
            | Error (`Msg m) -> Alcotest.fail m)
          [
            ("area, sphere, spot", scene ~size:30 (String.concat "\n" [ area; sphere; spot ]), 1);
            ("with glass", scene ~size:30 ~extra:"(transparency 0.5)" (String.concat "\n" [ area; sphere; spot ]), 1);
            ("3 x 3 samples", scene ~size:20 area, 3);
          ];
        (* And counted here, in this process, pixel by pixel. *)
        List.iter
          (fun (what, s) ->
            let tr = Trace.create (Helpers.prepare s) in
            Trace.pixel tr 0 0;
            let before = Gc.minor_words () in
            for gy = -10 to 9 do
              for gx = -10 to 9 do
                Trace.pixel tr gx gy
              done
            done;
            Alcotest.(check (float 0.)) what 0. (Gc.minor_words () -. before))
          [
            ("each kind", scene ~size:20 (String.concat "\n" [ area; adaptive; uniform; uniform_adaptive; sphere; spot ]));
            ("each kind, glass", scene ~size:20 ~extra:"(transparency 0.5)" (String.concat "\n" [ area; adaptive; sphere; spot ]));
          ]);
    Alcotest.test_case "a scene with a soft light does not take the document's kernel" `Quick (fun () ->
        (* Spheres alone, plain, with an epsilon: the document's kernel's
           scenes, but for the light. *)
        let spheres light =
          Helpers.parse_ok
            ("(canvas (width 8) (height 8)) (epsilon 0.001) (sphere (center 0 0 3) (radius 1) (color 255 0 0)) " ^ light)
        in
        Alcotest.(check bool) "a point light: the document's kernel" true (Helpers.prepare (spheres "(light point (intensity 1) (position 0 3 0))")).textbook_all;
        let p = Helpers.prepare (spheres area) in
        Alcotest.(check bool) "sampled" true p.sampled;
        Alcotest.(check bool) "textbook_all" false p.textbook_all;
        let q = Helpers.prepare (spheres spot) in
        Alcotest.(check bool) "a spot: not the document's kernel" false q.textbook_all;
        Alcotest.(check bool) "a spot draws no numbers" false q.sampled);
      Alcotest.test_case "an adaptive area light traces its samples only in the penumbra, and --stats counts it" `Quick
      (fun () ->
        let stats light =
          match Helpers.render (scene ~size:64 light) with Ok (img, st) -> (img, st) | Error (`Msg m) -> Alcotest.fail m
        in
        let full, st_full = stats area and img, st = stats adaptive in
        Alcotest.(check (list int)) "full sampling counts nothing" [ 0; 0 ] [ st_full.decided; st_full.penumbra ];
        if st.decided = 0 || st.penumbra = 0 then Alcotest.failf "decided %d, penumbra %d" st.decided st.penumbra;
        (* 12 samples a point: 4 corner rays instead where they agree
           (the points that see the panel whole cast none either way:
           11,092 shadow rays against 14,979). *)
        if st.shadow * 4 > st_full.shadow * 3 then Alcotest.failf "%d shadow rays, %d without" st.shadow st_full.shadow;
        (* The ball and the box are larger than the light seen from the
           floor, but the ball's outline, seen from a floor point at the
           edge of its penumbra, can cut one side of the panel and cover
           none of its corners: the estimate takes that point as fully
           lit. Two pixels (17, 41) and (47, 41) of this render have one
           sample of twelve in that sliver: 0.7 / 12 of 200, 10 levels. *)
        let differing, most = difference ~expected:full img in
        if differing > 2 || most > 10 then Alcotest.failf "%d pixels differ from full sampling's, by up to %d" differing most);
    Alcotest.test_case "the estimate: a blocker that hides no corner of an adaptive light casts no shadow" `Quick (fun () ->
        (* A 0.1 ball 1 under the middle of a 4 x 4 panel 2 above the
           floor: from the floor below, every corner is seen past it. *)
        let s light =
          Helpers.parse_ok
            ("(canvas (width 16) (height 16)) (epsilon 0.001) (camera (position 0 1.5 -0.01) (look-at 0 0 0))\n\
              (plane (point 0 0 0) (normal 0 1 0) (color 200 200 200))\n\
              (sphere (center 0 1 0) (radius 0.1) (color 255 0 0))\n" ^ light)
        in
        let panel extra = "(light area (intensity 1) (corner -2 2 -2) (edge1 4 0 0) (edge2 0 0 4) (samples 8 8)" ^ extra ^ ")" in
        let sharp = Helpers.image_exn (s (panel "")) and estimated = Helpers.image_exn (s (panel " (adaptive true)")) in
        let differing, _ = difference ~expected:sharp estimated in
        if differing = 0 then Alcotest.fail "the small ball's faint shadow should be missed");
      Alcotest.test_case "in the umbra of one convex object, the samples inside the corner cells' cast no shadow ray" `Quick
      (fun () ->
        (* The ball hides the whole panel from the floor under it (0.7 at
           distance 1: 44 degrees; the panel's corners 19.5 degrees off
           the vertical). The image is the one without the skips, and the
           oracle's (tested above). *)
        List.iter
          (fun (what, light, boxed) ->
            let s = scene ~size:64 ~extra:boxed light in
            match (Helpers.render s, Helpers.render ~skips:false s) with
            | Ok (img, st), Ok (plain, st_plain) ->
                if st.umbra = 0 then Alcotest.failf "%s: no sample skipped" what;
                let table = Format.asprintf "%a" Render.Stats.pp_table st in
                if not (contains table (Printf.sprintf "soft light, umbra        %d" st.umbra)) then
                  Alcotest.failf "%s: --stats's table has no umbra row:\n%s" what table;
                Alcotest.(check int) (what ^ ": nothing skipped without the skips") 0 st_plain.umbra;
                if st.shadow >= st_plain.shadow then Alcotest.failf "%s: %d shadow rays, %d without the skips" what st.shadow st_plain.shadow;
                let differing, most = difference ~expected:plain img in
                if differing > 0 then Alcotest.failf "%s: %d pixels differ, by up to %d" what differing most
            | Error (`Msg m), _ | _, Error (`Msg m) -> Alcotest.fail m)
          [ ("3 x 4 samples", area, ""); ("8 x 8 samples", "(light area (intensity 0.7) (corner -1 3 1) (edge1 2 0 0) (edge2 0 0 2) (samples 8 8))", "") ]);
    Alcotest.test_case "a blocker that is not convex decides nothing: a torus" `Quick (fun () ->
        let s =
          Helpers.parse_ok
            "(canvas (width 24) (height 24)) (epsilon 0.001) (camera (position 0 3 -3) (look-at 0 0 0))\n\
             (plane (point 0 0 0) (normal 0 1 0) (color 200 200 200))\n\
             (torus (center 0 1 0) (axis 0 1 0) (major 0.6) (minor 0.3) (color 255 0 0))\n\
             (light area (intensity 1) (corner -0.2 3 -0.2) (edge1 0.4 0 0) (edge2 0 0 0.4) (samples 4 4))"
        in
        match Helpers.render s with
        | Ok (img, st) ->
            Alcotest.(check int) "no umbra skip" 0 st.umbra;
            Helpers.check_images "skips on and off" ~expected:(Helpers.image_exn ~skips:false s) img
        | Error (`Msg m) -> Alcotest.fail m);
      Alcotest.test_case "a spotlight gives intensity cos^falloff of the angle off its axis, none outside its cone" `Quick
      (fun () ->
        (* Spot at (0, 1, 0) aimed down, cone 60 degrees, falloff 2, over
           the floor y = 0 (N = (0, 1, 0)), nothing else. At P = (1, 0, 0):
           L = (-1, 1, 0), 45 degrees off the axis, cos^2 = 1/2; diffuse
           <N, L> / |L| = 1/sqrt 2: 0.5 / sqrt 2 = 0.35355... At (2, 0, 0):
           atan 2 = 63.4 degrees > 60: nothing. *)
        let s =
          Helpers.parse_ok
            "(canvas (width 2) (height 2)) (light spot (intensity 1) (position 0 1 0) (direction 0 -1 0) (angle 60) (falloff 2))"
        in
        let at x = Private.Literal.compute_lighting s ~epsilon:0.001 ~point:(Vec3.v x 0. 0.) ~normal:Vec3.oy ~view:Vec3.oy ~specular:Sphere.matte in
        Alcotest.(check (float 1e-12)) __LOC__ (0.5 /. sqrt 2.) (at 1.);
        Alcotest.(check (float 0.)) __LOC__ 0. (at 2.);
        (* Straight below: cos 0 = 1, diffuse 1. *)
        Alcotest.(check (float 1e-15)) __LOC__ 1. (at 0.));
    Alcotest.test_case "an unshadowed area light is the mean of its samples' point lights: a 1 x 1 light is one point" `Quick
      (fun () ->
        (* A 2 x 2 panel at height 1 over P = 0, 1 x 1 sample: a point
           light at (-1 + 2 s, 1, -1 + 2 t) for the cell's jittered (s, t)
           = (unit h, unit (mix h)) (the one cell's one sub-stratum), with
           h = key (key k 0) 0, k the key given: diffuse 1 / |L|,
           L = Q - P. *)
        let s =
          Helpers.parse_ok
            "(canvas (width 2) (height 2)) (light area (intensity 1) (corner -1 1 -1) (edge1 2 0 0) (edge2 0 0 2) (samples 1 1))"
        in
        let key = 12345 in
        let h = Private.Sample_key.(key (key 12345 0) 0) in
        let su = Private.Sample_key.unit h and sv = Private.Sample_key.(unit (mix h)) in
        let l = Vec3.v (-1. +. (su *. 2.)) 1. (-1. +. (sv *. 2.)) in
        Alcotest.(check (float 1e-15)) __LOC__ (1. /. Vec3.norm l)
          (Private.Literal.compute_lighting ~key s ~epsilon:0.001 ~point:Vec3.zero ~normal:Vec3.oy ~view:Vec3.oy
             ~specular:Sphere.matte));
    Alcotest.test_case "the work bound counts every sample's shadow ray" `Quick (fun () ->
        let s samples =
          Helpers.parse_ok
            (Printf.sprintf
               "(canvas (width 600) (height 600)) (sphere (center 0 0 3) (radius 1) (color 255 0 0))\n\
                (light area (intensity 1) (corner -1 3 1) (edge1 2 0 0) (edge2 0 0 2) (samples %d %d))" samples samples)
        in
        (match Scene.check_work (Helpers.valid (s 4)) with Ok () -> () | Error (`Msg m) -> Alcotest.fail m);
        match Scene.check_work (Helpers.valid (s 4096)) with
        | Ok () -> Alcotest.fail "16 million shadow rays a point passed the work bound"
        | Error (`Msg m) -> if not (contains m "(1 + 16777216 lights)") then Alcotest.failf "%S" m);
      Alcotest.test_case "a uniform area light draws each sample over the whole panel: unit, not stratum" `Quick (fun () ->
        (* A 2 x 2 panel at height 1 over P = 0, 2 x 1 uniform samples:
           point lights at (-1 + 2 s, 1, -1 + 2 t), with s = unit h and
           t = unit (mix h) for h = key (key k 0) j, j = 0, 1, each of
           intensity 1/2; stratified, s would be (j + unit h) / 2 (one
           sub-stratum a cell when v = 1). *)
        let s sampling =
          Helpers.parse_ok
            ("(canvas (width 2) (height 2)) (light area (intensity 1) (corner -1 1 -1) (edge1 2 0 0) (edge2 0 0 2) (samples 2 1)"
           ^ sampling ^ ")")
        in
        let k0 = 777 in
        let term j =
          let h = Private.Sample_key.(key (key k0 0) j) in
          let su = Private.Sample_key.unit h and sv = Private.Sample_key.(unit (mix h)) in
          0.5 /. Vec3.norm (Vec3.v (-1. +. (su *. 2.)) 1. (-1. +. (sv *. 2.)))
        and lighting sc =
          Private.Literal.compute_lighting ~key:k0 sc ~epsilon:0.001 ~point:Vec3.zero ~normal:Vec3.oy ~view:Vec3.oy
            ~specular:Sphere.matte
        in
        Alcotest.(check (float 1e-15)) __LOC__ (term 0 +. term 1) (lighting (s " (sampling uniform)"));
        if lighting (s "") = lighting (s " (sampling uniform)") then Alcotest.fail "uniform and stratified agree";
        (* The kernel: the panel over a floor, unshadowed, differs too. *)
        let lit sampling = Helpers.image_exn (scene ~size:24 sampling) in
        let differing, _ = difference ~expected:(lit area) (lit uniform) in
        if differing = 0 then Alcotest.fail "the kernel draws uniform samples as stratified ones");
    Alcotest.test_case "the work bound counts an adaptive area light's four corner rays too" `Quick (fun () ->
        (* An adaptive light sends a shadow ray to each corner, then its
           u v samples' where the corners disagree: u v + 4 at most. The
           estimate counted u v, 9 of the 13 rays of (samples 3 3), and
           the render was stopped midway instead of refused at once. With
           fewer than four samples no corner is traced: (samples 1 1) is 1. *)
        let s ?(n = 3) adaptive =
          Helpers.parse_ok
            (Printf.sprintf
               "(canvas (width 600) (height 600)) (sphere (center 0 0 3) (radius 1) (color 255 0 0))\n\
                (light area (intensity 1) (corner -1 3 1) (edge1 2 0 0) (edge2 0 0 2) (samples %d %d) (adaptive %b))" n n adaptive)
        in
        let limits = Limits.with_bound Limits.default `Work 1e5 in
        let message ?n adaptive =
          match Scene.check_work ~limits (Helpers.valid (s ?n adaptive)) with
          | Ok () -> Alcotest.fail "360000 pixels passed a work bound of 1e5"
          | Error (`Msg m) -> m
        in
        if not (contains (message false) "(1 + 9 lights)") then Alcotest.failf "%S" (message false);
        if not (contains (message true) "(1 + 13 lights)") then Alcotest.failf "%S" (message true);
        if not (contains (message ~n:1 true) "(1 + 1 lights)") then Alcotest.failf "%S" (message ~n:1 true));
      Alcotest.test_case "a point that sees a light whole casts no shadow ray to it: the same bytes as without the test, fewer rays"
        `Quick (fun () ->
          (* The floor in front of the ball and the box sees the panel, and
             the sphere light, past every blocker's box: its hull with the
             light meets none. Robust mode (no epsilon) and the document's
             mode; the room's five planes test the planes' side. *)
          let image p =
            let tr = Trace.create p in
            let img = Helpers.by_pixels tr in
            (img, Trace.counters tr)
          in
          let room ?(mode = "") light =
            Helpers.parse_ok
              (mode ^ "(canvas (width 40) (height 30)) (camera (position 0 1.3 -2.5) (look-at 0 0.9 4))\n\
                (plane (point 0 0 0) (normal 0 1 0) (color 200 190 170)) (plane (point 0 3 0) (normal 0 -1 0) (color 230 230 230))\n\
                (plane (point 0 0 7) (normal 0 0 -1) (color 120 160 220)) (plane (point -2.5 0 0) (normal 1 0 0) (color 220 120 100))\n\
                (sphere (center -0.7 0.6 4) (radius 0.6) (color 255 240 200) (specular 300))\n\
                (box (min 0.4 0 3.6) (max 1.3 1.1 4.6) (color 250 200 60))\n" ^ light)
          in
          let panel extra = "(light area (intensity 0.55) (corner -0.6 2.95 3.4) (edge1 1.2 0 0) (edge2 0 0 1.2) " ^ extra ^ ")" in
          List.iter
            (fun (what, s) ->
              let p = Helpers.prepare s in
              let img, c = image p and img', c' = image (Private.Prepared.without Whole_light p) in
              Helpers.check_images ("without the test: " ^ what) ~expected:img' img;
              Alcotest.(check int) (what ^ ": none whole without the test") 0 c'.whole;
              if c.whole = 0 || c.shadow >= c'.shadow then
                Alcotest.failf "%s: %d points whole, %d shadow rays against %d" what c.whole c.shadow c'.shadow)
            [
              ("ball, 3 x 4", scene ~size:40 area);
              ("ball, adaptive", scene ~size:40 adaptive);
              ("ball, sphere light", scene ~size:40 sphere);
              ("room, 4 x 4", room (panel "(samples 4 4)"));
              ("room, adaptive 2 x 2", room (panel "(samples 2 2) (adaptive true)"));
              ("room, sphere light", room "(light sphere (intensity 0.3) (position 1.6 2 2) (radius 0.25) (samples 6))");
              ("room, epsilon", room ~mode:"(epsilon 0.001) " (panel "(samples 3 3)"));
            ];
          (* Fewer than four samples, and uniform sampling (the plain Monte
             Carlo baseline): the test is not made. *)
          let _, c = image (Helpers.prepare (room (panel "(samples 1 1)"))) in
          Alcotest.(check int) "1 x 1: not tested" 0 c.whole;
          let _, c = image (Helpers.prepare (scene ~size:40 uniform)) in
          Alcotest.(check int) "uniform: not tested" 0 c.whole;
          (* A few objects with an instance, no hierarchy: no boxes (an
             instance's hits are found in its frame; its box's margin is
             the hierarchy's). *)
          let p =
            Helpers.prepare
              (room
                 ("(define ball (sphere (center 0 0 0) (radius 0.3) (color 255 255 255)))\n\
                   (use ball (transform ((translate 0.5 0.3 2))))\n" ^ panel "(samples 2 2)"))
          in
          Alcotest.(check int) "with an instance: no boxes" 0 (Array.length p.casters));
      Alcotest.test_case "Prepared.without Umbra turns the umbra skip off alone: the same bytes, more rays" `Quick (fun () ->
        let image p =
          let tr = Trace.create p in
          let img = Helpers.by_pixels tr in
          (img, Trace.counters tr)
        in
        let p = Helpers.prepare (scene ~size:40 area) in
        let img, c = image p and img', c' = image (Private.Prepared.without Umbra p) in
        Helpers.check_images "without the umbra skip" ~expected:img' img;
        Alcotest.(check int) "none skipped" 0 c'.umbra;
        if c.umbra = 0 || c.shadow >= c'.shadow then Alcotest.failf "%d skipped, %d shadow rays against %d" c.umbra c.shadow c'.shadow);
  ]
