(* The document's kernel (Trace on spheres alone with the textbook roots and
   the skips on) against the reference path of [~skips:false], with each of
   its own skips switched off in turn: the same bytes every time. The
   images are made by the renderer's own entry points, [Trace.row] (what
   [Sampling] calls) and [Trace.pixel]. *)
open Raytrace
open Raytrace.Private

(* Every pixel of the canvas of [tr]'s scene, a row at a time, as the
   renderer does. *)
let by_rows_with tr =
  let p = Trace.prepared tr in
  let img = Image.create p.width p.height in
  let buf = Image.buffer img in
  for r = 0 to p.height - 1 do
    Trace.row tr buf (3 * r * p.width) (Canvas.x_of_column ~width:p.width 0) (Canvas.y_of_row ~height:p.height r) p.width
  done;
  img

let by_rows p = by_rows_with (Trace.create p)

(* The same, a pixel at a time, in columns (tiles are entered in another
   order). *)
let by_pixels p = Helpers.by_pixels (Trace.create p)

let variants (p : Prepared.t) =
  [
    ("all skips", p);
    ("no rejection of spheres behind", Prepared.without Behind p);
    ("shadow rays for every light", Prepared.without Shadow_rays p);
    ("no culling by tile", Prepared.without Culling p);
    ("no negligible specular terms", Prepared.without Negligible_terms p);
  ]

(* Random scenes in the kernel's reach: spheres alone, of plain materials
   (no glass, no pattern), the document's mode, canvases of a few tiles,
   the camera often turned. *)
let textbook =
  let open QCheck.Gen in
  let gen =
    let* s = Gen_scene.gen in
    let* width = int_range 1 40 and* height = int_range 1 40 in
    let* epsilon = oneof [ return 0.001; float_range 0. 0.01 ] in
    let plain (sp : Sphere.t) =
      Sphere.v ~center:sp.center ~radius:sp.radius
        (Material.update ~transparency:0. ~refractive_index:1. ~fresnel:false ~pattern:None sp.material)
    in
    return
      (Helpers.with_objects
         ~spheres:(List.map plain (Helpers.scene_spheres s))
         ~shapes:[]
         (Scene.with_overrides ~width ~height ~epsilon:(Some epsilon) ~camera_path:None s))
  in
  QCheck.make ~print:Scene_file.to_string gen

let same what ~expected img =
  if not (Image.equal expected img) then Alcotest.failf "%s: the bytes differ" what

let tests =
  [
    Helpers.qcheck ~count:200 "each skip of the document's kernel, on or off, gives the reference's bytes" textbook
      (fun s ->
        let p = Helpers.prepare s in
        (* Otherwise the kernel is not what runs. *)
        if not (p.textbook_all && p.skips) then QCheck.Test.fail_report "not the kernel's scene";
        let expected = by_rows (Helpers.prepare ~skips:false s) in
        same "pixel by pixel" ~expected (by_pixels p);
        List.iter (fun (what, p) -> same what ~expected (by_rows p)) (variants p);
        true);
    Alcotest.test_case "the reference scenes, each skip on or off, at 160 x 160" `Quick (fun () ->
        List.iter
          (fun (name, s) ->
            let s = Scene.with_overrides ~width:160 ~height:160 s in
            let expected = by_rows (Helpers.prepare ~skips:false s) in
            List.iter (fun (what, p) -> same (name ^ ", " ^ what) ~expected (by_rows p)) (variants (Helpers.prepare s)))
          [ ("cgfs", Scene.cgfs); ("cgfs, camera", Scene.cgfs_camera) ]);
    Alcotest.test_case "each skip saves work on the reference scene" `Quick (fun () ->
        (* So that the tests above compare the skips, not two copies of
           the same loop. *)
        let count p =
          let tr = Trace.create p in
          ignore (by_rows_with tr);
          Trace.counters tr
        and p = Helpers.prepare (Scene.with_overrides ~width:160 ~height:160 Scene.cgfs) in
        let all = count p in
        let fewer what (off : Trace.counters) f =
          if not (f all < f off) then Alcotest.failf "%s: no fewer with the skip (%d, %d without)" what (f all) (f off)
        in
        (* The rejection of spheres behind does the same tests, with
           less arithmetic: it shows in instruction counts only. *)
        fewer "tests, culling" (count (Prepared.without Culling p)) (fun c -> c.tests);
        fewer "shadow rays" (count (Prepared.without Shadow_rays p)) (fun c -> c.shadow);
        fewer "shadow rays, negligible terms" (count (Prepared.without Negligible_terms p)) (fun c -> c.shadow));
    Alcotest.test_case "the general path's skips of shadow rays, on or off, give the same bytes" `Quick (fun () ->
        (* A mesh with a plane, a box and a sphere (scenes/mesh.scene,
           robust); patterns on a plane, spheres and a box; glass, whose
           shadow rays go through [transmit]: every scene outside the
           document's kernel, lit by [lighting]. Each skip off in turn,
           then both, then the reference of [~skips:false] (no hierarchy)
           for the small scenes. *)
        List.iter
          (fun (name, reference) ->
            let s = Scene.with_overrides ~width:96 ~height:72 (Helpers.load_scene name) in
            let p = Helpers.prepare s in
            if p.textbook_all || not p.shadow_skip then Alcotest.failf "%s: not the general path with its skips" name;
            let expected = by_rows p in
            let both = Prepared.without Shadow_rays (Prepared.without Negligible_terms p) in
            List.iter
              (fun (what, q) -> same (name ^ ", " ^ what) ~expected (by_rows q))
              ([ ("shadow rays for every light", Prepared.without Shadow_rays p);
                 ("no negligible specular terms", Prepared.without Negligible_terms p);
                 ("neither", both) ]
              @ if reference then [ ("the reference", Helpers.prepare ~skips:false s) ] else []))
          [ ("mesh.scene", false); ("checker.scene", true); ("glass.scene", true); ("room.scene", true) ]);
    Helpers.qcheck ~count:150 "on random scenes, the general path's skips of shadow rays change no byte"
      (* Few objects or a crowd in a hierarchy, with shapes, glass and
         patterns on some. *)
      (QCheck.make ~print:Scene_file.to_string
         QCheck.Gen.(
           let* s = oneof [ Gen_scene.gen; Gen_scene.crowd ] and* seed = int in
           return (if seed land 1 = 0 then s else Gen_scene.with_patterns (Random.State.make [| seed |]) s)))
      (fun s ->
        let s = Scene.with_overrides ~width:(min (Scene.width s) 24) ~height:(min (Scene.height s) 24) s in
        let p = Helpers.prepare s in
        let expected = by_rows p in
        same "shadow rays for every light" ~expected (by_rows (Prepared.without Shadow_rays p));
        same "no negligible specular terms" ~expected (by_rows (Prepared.without Negligible_terms p));
        true);
    Alcotest.test_case "the skips cast fewer shadow rays through a mesh" `Quick (fun () ->
        (* So that the test above compares the skips, not the same rays:
           the knot's back faces, and its highlights too weak to count. *)
        let count p =
          let tr = Trace.create p in
          ignore (by_rows_with tr);
          (Trace.counters tr).shadow
        and p = Helpers.prepare (Scene.with_overrides ~width:96 ~height:72 (Helpers.load_scene "mesh.scene")) in
        let all = count p and off = count (Prepared.without Shadow_rays p) in
        if not (all < off) then Alcotest.failf "shadow rays: %d with the skip, %d without" all off;
        let negligible = count (Prepared.without Negligible_terms p) in
        if not (all < negligible) then Alcotest.failf "shadow rays: %d with the cut, %d without" all negligible);
    Alcotest.test_case "a negligible specular term changes no sum, at its cut" `Quick (fun () ->
        (* The cut's claim at its worst (the cosine itself), for the
           reference scene's and a spread of exponents and intensities. *)
        let check ~ambient ~li s =
          let scene =
            Helpers.scene ~width:4 ~height:4 ~epsilon:0.001
              ~spheres:[ Helpers.sphere ~specular:s ~center:(Vec3.v 0. 0. 3.) ~radius:1. Color.white ]
              ~lights:[ Light.ambient ambient; Light.point li (Vec3.v 1. 1. 0.) ]
              ()
          in
          let p = Helpers.prepare scene in
          let cut = p.specular_cut.(1) in
          if cut > 0. && ambient +. (li *. Float.pow cut s) <> ambient then
            Alcotest.failf "s = %g, ambient %g, light %g: the term at the cut %h changes the sum" s ambient li cut
        in
        List.iter
          (fun s ->
            List.iter
              (fun (ambient, li) -> check ~ambient ~li s)
              [ (0.2, 0.6); (0.2, 0.2); (1e-3, 1.); (0.5, 1e-9); (1., 1.); (0.75, 0.25) ])
          [ 0.5; 1.; 10.; 500.; 1000.; 12345.; 1e6 ]);
    Alcotest.test_case "Trace.to_byte rounds every half to even" `Quick (fun () ->
        for k = 0 to 255 do
          let x = Float.of_int k in
          List.iter
            (fun x -> if Trace.to_byte x <> Color.to_byte x then Alcotest.failf "%h: %d, not %d" x (Trace.to_byte x) (Color.to_byte x))
            [ x; x +. 0.5; Float.pred (x +. 0.5); Float.succ (x +. 0.5); Float.pred x; Float.succ x ]
        done);
  ]
