(* Rays per pixel: supersampling, adaptive supersampling and CGFS's
   subsampling (Sampling, the sums in Trace, Helpers.render's options). *)
open Raytrace

let small (s : Scene.t) = Scene.with_overrides ~width:80 ~height:80 s

let render ?jobs ?skips ?samples ?adaptive ?subsample s =
  match Helpers.render ?jobs ?skips ?samples ?adaptive ?subsample s with
  | Ok r -> r
  | Error (`Msg m) -> Alcotest.fail m

let image ?jobs ?skips ?samples ?adaptive ?subsample s = fst (render ?jobs ?skips ?samples ?adaptive ?subsample s)

(* Every pixel through the averaging path with one sample: Trace.average
   ~n:1 on an averaging tracer, then store_average ~count:1. *)
let averaged_one ?skips (scene : Scene.t) =
  let tr = Trace.create ~averaging:true (Helpers.prepare ?skips scene) in
  let width = (Scene.width scene) and height = (Scene.height scene) in
  let img = Image.create width height in
  for r = 0 to height - 1 do
    for c = 0 to width - 1 do
      Trace.average tr (Canvas.x_of_column ~width c) (Canvas.y_of_row ~height r) ~n:1;
      Trace.store_average tr (Image.buffer img) (3 * ((r * width) + c)) ~count:1
    done
  done;
  img

(* A 1 x 1 canvas whose pixel is covered on its left half (canvas x < 0)
   by a huge matte sphere lit by ambient light 2: red 200 * 2 = 400 where it
   is hit, the blue background elsewhere. The sphere's surface crosses the
   plane z = 5 at x = -0.05: rays with V_x < 0 enter it, rays with V_x >= 0
   move away from it and never do. *)
let half_covered =
  Helpers.scene ~width:1 ~height:1 ~background:(Color.v 0. 0. 255.)
    ~spheres:[ Helpers.sphere ~center:(Vec3.v (-1000.) 0. 5.) ~radius:999.95 (Color.v 200. 0. 0.) ]
    ~lights:[ Light.ambient 2. ] ()

let pixel0 img = Image.get img 0 0
let rgb = Alcotest.(triple int int int)

(* Saturated reflections: with ambient light 1.5, the white mirror's local
   colour is at least 255 * 1.5 = 382.5 per channel, and its share
   382.5 * (1 - 0.2) = 306 is already >= 255 whatever the reflection adds:
   the weight bound may stop even averaged samples there. *)
let saturated =
  Helpers.scene ~width:24 ~height:24 ~depth:4
    ~spheres:
      [
        Helpers.sphere ~center:(Vec3.v 0. 0. 4.) ~radius:1.2 ~specular:50. ~reflective:0.2 (Color.v 255. 255. 255.);
        Helpers.sphere ~center:(Vec3.v 0. (-1001.) 0.) ~radius:1000. ~reflective:0.3 (Color.v 255. 200. 255.);
      ]
    ~lights:[ Light.ambient 1.5; Light.point 0.5 (Vec3.v 2. 3. 0.) ]
    ()

let sampling_settings =
  QCheck.(triple Gen_scene.arbitrary (oneofl [ 3; 5 ]) (oneofl [ 0; 2; 30 ]))

(* Random scenes whose mirrors reflect 1% of what the generator chose, and
   lit up to 4 times more: faint reflections, where the weight bound stops
   often; under the byte criterion the stopped samples would be off by up
   to half a byte each, and their mean would round differently. *)
let faint_mirrors =
  let faint (s : Scene.t) =
    Helpers.with_objects
      ~spheres:
        (List.map
           (fun (sp : Sphere.t) -> Helpers.with_sphere_material sp (fun m -> Material.update ~reflective:(m.reflective *. 0.01) m))
           (Helpers.scene_spheres s))
      (Scene.with_overrides ~depth:(max 2 (Scene.depth s)) ~lights:(Light.ambient 0.3 :: Scene.lights s) s)
  in
  QCheck.map ~rev:Fun.id faint Gen_scene.arbitrary

(* Each sampling mode as optional arguments, for tables of modes. *)
let modes =
  [
    ("samples 3", fun ?jobs s r -> Helpers.render_region ?jobs ~samples:3 s r);
    ("adaptive 3 t 4", fun ?jobs s r -> Helpers.render_region ?jobs ~samples:3 ~adaptive:4 s r);
    ("adaptive 5 t 0", fun ?jobs s r -> Helpers.render_region ?jobs ~samples:5 ~adaptive:0 s r);
    ("subsampling", fun ?jobs s r -> Helpers.render_region ?jobs ~subsample:true s r);
  ]

let region_of render ?jobs s r = match render ?jobs s r with Ok (img, _) -> img | Error (`Msg m) -> Alcotest.fail m

let tests =
  [
    Alcotest.test_case "one sample per pixel is the document's image, byte for byte" `Quick (fun () ->
        List.iter
          (fun name ->
            let s = small (Helpers.load_scene name) in
            let expected = Private.Literal.render (Helpers.valid s) in
            (* A robust scene's differences from the oracle are those of
               test_render; the sampling paths add none. *)
            let min_share = if (Scene.epsilon s) = None then Some (Test_render.robust_share s) else None in
            Helpers.check_images ?min_share (name ^ ", samples 1") ~expected (image ~samples:1 s);
            Helpers.check_images ?min_share (name ^ ", averaging path") ~expected (averaged_one s);
            Helpers.check_images (name ^ ", averaging path against samples 1") ~expected:(image ~samples:1 s)
              (averaged_one s))
          (Helpers.scene_names ()));
    Helpers.qcheck ~count:150 "one averaged sample per pixel stores the plain pixel's bytes" Gen_scene.arbitrary
      (fun s -> Image.equal (image s) (averaged_one s) && Image.equal (image s) (image ~samples:1 s));
    Alcotest.test_case "supersampling clamps each sample before averaging" `Quick (fun () ->
        (* n = 1: the centre ray misses: the background.
           n = 2: V_x = -1/4 hits twice, +1/4 misses twice. Clamped first:
             red (255 + 255 + 0 + 0) / 4 = 127.5 -> 128 (ties to even),
             blue (0 + 0 + 255 + 255) / 4 = 127.5 -> 128.
             Averaging unclamped would give red (400 + 400) / 4 = 200.
           n = 3: V_x = -1/3 hits three times; 0 and 1/3 miss:
             red 3 * 255 / 9 = 85, blue 6 * 255 / 9 = 170.
           n = 4: V_x = -3/8 and -1/8 hit: as n = 2. *)
        Alcotest.check rgb __LOC__ (0, 0, 255) (pixel0 (image ~samples:1 half_covered));
        Alcotest.check rgb __LOC__ (128, 0, 128) (pixel0 (image ~samples:2 half_covered));
        Alcotest.check rgb __LOC__ (85, 0, 170) (pixel0 (image ~samples:3 half_covered));
        Alcotest.check rgb __LOC__ (128, 0, 128) (pixel0 (image ~samples:4 half_covered)));
    Alcotest.test_case "the window's antialiasing is supersampling, byte for byte" `Quick (fun () ->
        List.iter
          (fun name ->
            let s = Scene.with_overrides ~width:24 ~height:18 (Helpers.load_scene name) in
            Helpers.check_images name ~expected:(image ~samples:3 s) (Antialias.image ~n:3 (Helpers.valid s)))
          (Helpers.scene_names ()));
    Alcotest.test_case "supersampling traces n x n primary rays per pixel" `Quick (fun () ->
        let _, st = render ~samples:3 (Scene.with_overrides ~width:10 ~height:7 Scene.cgfs) in
        (* 10 * 7 pixels * 9 samples *)
        Alcotest.(check int) __LOC__ 630 st.primary);
    Helpers.qcheck ~count:100 "adaptive sampling never traces more rays than full sampling" sampling_settings
      (fun (s, n, th) ->
        let _, full = render ~samples:n s and _, adaptive = render ~samples:n ~adaptive:th s in
        adaptive.primary <= full.primary && Render.Stats.rays adaptive <= Render.Stats.rays full);
    Helpers.qcheck ~count:100 "each adaptive pixel is the full-sampling pixel or the document's pixel"
      sampling_settings (fun (s, n, th) ->
        let full = image ~samples:n s and one = image s and adaptive = image ~samples:n ~adaptive:th s in
        let ok = ref true in
        for y = 0 to (Scene.height s) - 1 do
          for x = 0 to (Scene.width s) - 1 do
            let a = Image.get adaptive x y in
            if a <> Image.get full x y && a <> Image.get one x y then ok := false
          done
        done;
        !ok);
    Alcotest.test_case "adaptive sampling refines the edges of the reference scene only" `Quick (fun () ->
        let s = small Scene.cgfs in
        let full, full_st = render ~samples:5 s in
        let adaptive, st = render ~samples:5 ~adaptive:3 s in
        (* The hit test alone refines every silhouette: t = 255 refines
           fewer pixels than t = 3, t = 0 more. *)
        let _, edges = render ~samples:5 ~adaptive:255 s and _, all = render ~samples:5 ~adaptive:0 s in
        if not (edges.primary < st.primary && st.primary < all.primary) then
          Alcotest.failf "primary rays: t=255 %d, t=3 %d, t=0 %d" edges.primary st.primary all.primary;
        if st.primary * 2 > full_st.primary then Alcotest.failf "%d primary rays, full sampling %d" st.primary full_st.primary;
        Helpers.check_images ~min_share:0.98 "adaptive against full 5 x 5" ~expected:full adaptive);
    Helpers.qcheck ~count:100 "the reflection early stop changes no byte of averaged samples" sampling_settings
      (fun (s, n, th) ->
        Image.equal (image ~skips:false ~samples:2 s) (image ~samples:2 s)
        && Image.equal (image ~skips:false ~samples:n ~adaptive:th s) (image ~samples:n ~adaptive:th s));
    Helpers.qcheck ~count:300 "the early stop changes no byte of averaged samples behind faint mirrors"
      faint_mirrors (fun s ->
        Image.equal (image ~skips:false ~samples:4 s) (image ~samples:4 s)
        && Image.equal (image ~skips:false ~samples:3 ~adaptive:1 s) (image ~samples:3 ~adaptive:1 s));
    Alcotest.test_case "with averaged samples the early stop still cuts saturated reflections" `Quick (fun () ->
        let img, st = render ~samples:3 saturated in
        if st.early_stops = 0 then Alcotest.fail "no reflection was cut short";
        Helpers.check_images "skips off" ~expected:(image ~skips:false ~samples:3 saturated) img;
        Helpers.check_images "skips off, adaptive" ~expected:(image ~skips:false ~samples:3 ~adaptive:0 saturated)
          (image ~samples:3 ~adaptive:0 saturated));
    Alcotest.test_case "every sampling mode gives the same image for 1, 2 and 3 jobs" `Quick (fun () ->
        let s = Scene.with_overrides ~width:37 ~height:23 Scene.cgfs_camera in
        List.iter
          (fun (what, f) ->
            let one = f 1 in
            Helpers.check_images (what ^ ", 2 jobs") ~expected:one (f 2);
            Helpers.check_images (what ^ ", 3 jobs") ~expected:one (f 3))
          [
            ("samples 3", fun jobs -> image ~jobs ~samples:3 s);
            ("adaptive 5 t 4", fun jobs -> image ~jobs ~samples:5 ~adaptive:4 s);
            ("subsampling", fun jobs -> image ~jobs ~subsample:true s);
          ]);
    Alcotest.test_case "a region is the same region of the whole image in every sampling mode" `Quick (fun () ->
        let s = Scene.with_overrides ~width:37 ~height:23 Scene.cgfs_camera in
        let full = Render.Region.full ~width:37 ~height:23 in
        List.iter
          (fun (what, render) ->
            let whole = region_of render s full in
            List.iter
              (fun (r : Render.Region.t) ->
                let expected = Image.sub whole ~x:r.x ~y:r.y ~w:r.w ~h:r.h in
                let name = Format.asprintf "%s, region %a" what Render.Region.pp r in
                Helpers.check_images name ~expected (region_of render s r);
                Helpers.check_images (name ^ ", 2 jobs") ~expected (region_of render ~jobs:2 s r))
              [ (Render.Region.v ~x:5 ~y:3 ~w:20 ~h:11); (Render.Region.v ~x:0 ~y:0 ~w:1 ~h:1); (Render.Region.v ~x:36 ~y:22 ~w:1 ~h:1);
                       (Render.Region.v ~x:1 ~y:1 ~w:35 ~h:21); (Render.Region.v ~x:0 ~y:7 ~w:37 ~h:4); (Render.Region.v ~x:10 ~y:0 ~w:3 ~h:23) ])
          modes);
    Helpers.qcheck ~count:60 "any region of any scene is that part of the whole, in every sampling mode"
      QCheck.(pair Gen_scene.arbitrary (quad small_nat small_nat small_nat small_nat))
      (fun ((s : Scene.t), (a, b, c, d)) ->
        let x = a mod (Scene.width s) and y = b mod (Scene.height s) in
        let w = 1 + (c mod ((Scene.width s) - x)) and h = 1 + (d mod ((Scene.height s) - y)) in
        List.for_all
          (fun (_, render) ->
            let whole = region_of render s (Render.Region.full ~width:(Scene.width s) ~height:(Scene.height s)) in
            Image.equal (Image.sub whole ~x ~y ~w ~h) (region_of render s (Render.Region.v ~x ~y ~w ~h)))
          modes);
    Alcotest.test_case "tracing allocates nothing per pixel, whatever the sampling" `Quick (fun () ->
        let s = Scene.with_overrides ~width:60 ~height:60 Scene.cgfs in
        List.iter
          (fun (what, (_, (st : Render.Stats.t))) -> Alcotest.(check (float 0.)) what 0. st.minor_words)
          [
            ("samples 3", render ~samples:3 s);
            ("adaptive", render ~samples:3 ~adaptive:4 s);
            ("subsampling", render ~subsample:true s);
            (* Textures: every mapping but uv (texdraw's test has it). *)
            ("globe, adaptive", render ~samples:3 ~adaptive:4 (Scene.with_overrides ~width:60 ~height:45 (Helpers.load_scene "globe.scene")));
          ];
        (* A scene whose lights draw numbers keeps each camera sample's key. *)
        let soft =
          Helpers.parse_ok
            "(canvas (width 30) (height 30)) (sphere (center 0 0 3) (radius 1) (color 255 0 0) (specular 10)) (plane \
             (point 0 -1 0) (normal 0 1 0) (color 200 200 200)) (light area (intensity 0.8) (corner -1 3 1) (edge1 2 0 0) \
             (edge2 0 0 2) (samples 2 3)) (light sphere (intensity 0.2) (position 2 2 0) (radius 0.5) (samples 4))"
        in
        List.iter
          (fun (what, (_, (st : Render.Stats.t))) -> Alcotest.(check (float 0.)) what 0. st.minor_words)
          [
            ("soft lights, samples 3", render ~samples:3 soft);
            ("soft lights, adaptive", render ~samples:3 ~adaptive:4 soft);
            ("soft lights, subsampling", render ~subsample:true soft);
          ]);
    Helpers.qcheck ~count:100 "a primary ray assumed to hit the sphere it hits is traced as without the assumption"
      Gen_scene.arbitrary (fun s ->
        let tr = Trace.create (Helpers.prepare s) in
        let ok = ref true in
        for gy = Canvas.min_y (Scene.height s) to Canvas.max_y (Scene.height s) do
          for gx = Canvas.min_x (Scene.width s) to Canvas.max_x (Scene.width s) do
            Trace.pixel tr gx gy;
            let hit = Trace.hit_object tr and c = (Trace.red tr, Trace.green tr, Trace.blue tr) in
            Trace.pixel_assuming tr gx gy hit;
            if (Trace.red tr, Trace.green tr, Trace.blue tr) <> c || Trace.hit_object tr <> hit then ok := false
          done
        done;
        !ok);
    Alcotest.test_case "subsampling skips searches and stays close to the document's image" `Quick (fun () ->
        let s = Scene.with_overrides ~width:96 ~height:72 (Helpers.load_scene "sphere-grid.scene") in
        let plain, plain_st = render s and sub, st = render ~subsample:true s in
        if st.tests >= plain_st.tests then Alcotest.failf "%d tests, %d without subsampling" st.tests plain_st.tests;
        Helpers.check_images ~min_share:0.97 "subsampled" ~expected:plain sub);
    Alcotest.test_case "subsampling misses a sphere that neither neighbour sees" `Quick (fun () ->
        (* Canvas 3 x 1: columns G_x = -1, 0, 1, V_x = -1/3, 0, 1/3. A ball
           of radius 0.5 at z = 10 meets only the middle ray (the others pass
           3.3 units from its centre). Subsampling traces the outer columns,
           which both see the background, and assumes the middle one does. *)
        let s =
          Helpers.scene ~width:3 ~height:1
            ~spheres:[ Helpers.sphere ~center:(Vec3.v 0. 0. 10.) ~radius:0.5 (Color.v 255. 255. 255.) ]
            ~lights:[ Light.ambient 1. ] ()
        in
        Alcotest.check rgb __LOC__ (255, 255, 255) (Image.get (image s) 1 0);
        Alcotest.check rgb __LOC__ (0, 0, 0) (Image.get (image ~subsample:true s) 1 0));
    Alcotest.test_case "bad sampling settings are refused with a message" `Quick (fun () ->
        List.iter
          (fun (samples, adaptive, subsample, expected) ->
            match Render.Sampling.v ~samples ?adaptive ~subsample () with
            | Ok _ -> Alcotest.failf "accepted %S" expected
            | Error (`Msg m) -> Alcotest.(check string) __LOC__ expected m)
          [
            (0, None, false, "samples must lie in [1, 64] (an N x N grid per pixel), got 0");
            (65, None, false, "samples must lie in [1, 64] (an N x N grid per pixel), got 65");
            (3, Some (-1), false, "the adaptive threshold must lie in [0, 255], got -1");
            (3, Some 256, false, "the adaptive threshold must lie in [0, 255], got 256");
            ( 1,
              Some 8,
              false,
              "adaptive sampling needs an odd number of samples >= 3, whose grid has the pixel's centre in its \
               middle (or, under a lens, any number >= 2), got 1" );
            (2, None, true, "subsampling traces one ray per pixel: it cannot be combined with samples > 1");
          ]);
    Alcotest.test_case "summing samples needs an averaging tracer and, to reuse the centre, an odd grid" `Quick
      (fun () ->
        let p = Helpers.prepare (Scene.with_overrides ~width:4 ~height:4 Scene.cgfs) in
        let plain = Trace.create p and averaging = Trace.create ~averaging:true p in
        let saved = Bigarray.Array1.create Bigarray.float64 Bigarray.c_layout 3 in
        Alcotest.check_raises __LOC__
          (Invalid_argument "Trace.accumulate: the tracer was not created with ~averaging:true") (fun () ->
            Trace.accumulate plain);
        Alcotest.check_raises __LOC__ (Invalid_argument "Trace.average_reusing: n is not odd and positive")
          (fun () -> Trace.average_reusing averaging saved 0 0 0 ~n:4));
    Alcotest.test_case "reusing the centre ray gives the sum of the whole grid" `Quick (fun () ->
        let s = Scene.with_overrides ~width:9 ~height:9 Scene.cgfs in
        let tr = Trace.create ~averaging:true (Helpers.prepare s) in
        let saved = Bigarray.Array1.create Bigarray.float64 Bigarray.c_layout 3 in
        let a = Image.create 1 1 and b = Image.create 1 1 in
        List.iter
          (fun (gx, gy) ->
            Trace.average tr gx gy ~n:5;
            Trace.store_average tr (Image.buffer a) 0 ~count:25;
            Trace.pixel tr gx gy;
            Trace.save tr saved 0;
            Trace.average_reusing tr saved 0 gx gy ~n:5;
            Trace.store_average tr (Image.buffer b) 0 ~count:25;
            Helpers.check_images (Printf.sprintf "pixel %d %d" gx gy) ~expected:a b)
          [ (0, 0); (-4, 4); (2, -3); (3, 1) ]);
  ]
