(* Parts of an image: rendered alone, they hold exactly the whole image's
   bytes; their headers let merge refuse parts that do not fit. *)
open Raytrace

let ok = function Ok x -> x | Error (`Msg m) -> Alcotest.fail m
let error = function Ok _ -> Alcotest.fail "expected an error" | Error (`Msg m) -> m
let scene = Scene.with_overrides ~width:37 ~height:23 Scene.cgfs_camera
let region_image ?jobs s r = fst (ok (Helpers.render_region ?jobs s r))

let part ?(s = scene) ?settings (r : Render.Region.t) =
  let settings = match settings with Some st -> st | None -> Part.settings s in
  Part.v ~canvas_width:(Scene.width s) ~canvas_height:(Scene.height s) ~region:r ~settings (region_image s r)

let tiles ?(s = scene) n =
  List.init n (fun i ->
      let r = ok (Render.Region.tile ~width:(Scene.width s) ~height:(Scene.height s) ~index:(i + 1) ~count:n) in
      (Printf.sprintf "part-%d.ppm" (i + 1), part ~s r))

let tests =
  [
    Alcotest.test_case "a region renders as the same region of the whole image" `Quick (fun () ->
        let whole = Helpers.image_exn scene in
        let r = (Render.Region.v ~x:5 ~y:3 ~w:20 ~h:11) in
        Helpers.check_images __LOC__ ~expected:(Image.sub whole ~x:5 ~y:3 ~w:20 ~h:11) (region_image scene r);
        Helpers.check_images __LOC__ ~expected:(Image.sub whole ~x:5 ~y:3 ~w:20 ~h:11) (region_image ~jobs:3 scene r));
    Helpers.qcheck ~count:60 "any region of any scene is byte for byte that part of the whole"
      QCheck.(pair Gen_scene.arbitrary (quad small_nat small_nat small_nat small_nat))
      (fun ((s : Scene.t), (a, b, c, d)) ->
        let x = a mod (Scene.width s) and y = b mod (Scene.height s) in
        let w = 1 + (c mod ((Scene.width s) - x)) and h = 1 + (d mod ((Scene.height s) - y)) in
        Image.equal (Image.sub (Helpers.image_exn s) ~x ~y ~w ~h) (region_image s (Render.Region.v ~x ~y ~w ~h)));
    Alcotest.test_case "seven tiles merge into the whole image, byte for byte" `Quick (fun () ->
        Helpers.check_images __LOC__ ~expected:(Helpers.image_exn scene) (ok (Part.merge (tiles 7))));
    Alcotest.test_case "the parts may come in any order" `Quick (fun () ->
        Helpers.check_images __LOC__ ~expected:(Helpers.image_exn scene) (ok (Part.merge (List.rev (tiles 5)))));
    Alcotest.test_case "the header records canvas, region and settings in PPM comments" `Quick (fun () ->
        let img = Image.create 2 1 in
        Image.set img 1 0 1 2 3;
        let p =
          Part.v ~canvas_width:4 ~canvas_height:3 ~region:(Render.Region.v ~x:1 ~y:2 ~w:2 ~h:1)
            ~settings:[ ("depth", "3"); ("scene", "abc") ] img
        in
        Alcotest.(check string) __LOC__
          "P6\n# raytrace-part 1\n# canvas 4 3\n# region 1 2 3 3\n# depth 3\n# scene abc\n2 1\n255\n\000\000\000\001\002\003"
          (Part.to_string p);
        (* Any PPM reader sees the pixels. *)
        Alcotest.(check bool) __LOC__ true (Image.equal img (ok (Image.Ppm.of_string (Part.to_string p)))));
    Alcotest.test_case "a part reads back as written" `Quick (fun () ->
        let p = snd (List.nth (tiles 3) 1) in
        let q = ok (Part.of_string (Part.to_string p)) in
        Alcotest.(check (pair int int)) __LOC__ (37, 23) (q.canvas_width, q.canvas_height);
        Alcotest.(check bool) __LOC__ true (Render.Region.equal p.region q.region);
        Alcotest.(check (list (pair string string))) __LOC__ p.settings q.settings;
        Alcotest.(check bool) __LOC__ true (Image.equal p.image q.image));
    Alcotest.test_case "the settings name depth, samples, renderer, frame and a scene digest" `Quick (fun () ->
        let st = Part.settings ~frame:7 Scene.cgfs in
        Alcotest.(check (list string)) __LOC__ [ "depth"; "samples"; "renderer"; "frame"; "scene" ] (List.map fst st);
        Alcotest.(check (list string)) __LOC__ [ "3"; "1"; "fast"; "7" ]
          (List.filteri (fun i _ -> i < 4) (List.map snd st));
        let digest s = List.assoc "scene" (Part.settings s) in
        Alcotest.(check string) __LOC__ (Digest.to_hex (Digest.string (Scene_file.to_string Scene.cgfs))) (digest Scene.cgfs);
        Alcotest.(check bool) __LOC__ false (digest Scene.cgfs = digest Scene.cgfs_camera);
        Alcotest.(check bool) __LOC__ false (digest Scene.cgfs = digest (Scene.with_overrides ~epsilon:(Some 0.01) Scene.cgfs)));
    Alcotest.test_case "the scene digest covers the contents of the files the scene read, as they were read" `Quick
      (fun () ->
        let dir = Helpers.temp_dir () in
        let f = Filename.concat dir in
        let write name text =
          let oc = open_out_bin (f name) in
          output_string oc text;
          close_out oc
        in
        write "m.obj" "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n";
        write "s.scene" "(canvas (width 4) (height 4))\n(mesh (file \"m.obj\") (color 255 0 0) (translate 0 0 3))\n";
        let loaded = ok (Files.load_scene (f "s.scene")) in
        Alcotest.(check (list (pair string string))) "the inputs" [ ("mesh", f "m.obj") ]
          (List.map (fun (i : Files.input) -> (i.what, i.path)) loaded.inputs);
        let files = ok (Files.inputs_digest loaded.inputs) in
        let s = Scene.of_valid loaded.scene in
        let digest files = List.assoc "scene" (Part.settings ~files s) in
        (* Without files, the text's digest, as before files were digested. *)
        Alcotest.(check string) __LOC__ (Digest.to_hex (Digest.string (Scene_file.to_string s))) (digest "");
        Alcotest.(check bool) "the mesh's contents change the digest" true (digest files <> digest "");
        (* Written to after it was read: the part would not be of what was read. *)
        write "m.obj" "v -1 -1 0\nv 2 -1 0\nv 0 1 0\nf 1 2 3\n";
        Alcotest.(check string) __LOC__
          (f "m.obj" ^ ": the mesh changed after it was read (written to or replaced); render again")
          (error (Files.inputs_digest loaded.inputs));
        let reloaded = ok (Files.load_scene (f "s.scene")) in
        Alcotest.(check bool) "another mesh, another digest" true
          (ok (Files.inputs_digest reloaded.inputs) <> files));
    Alcotest.test_case "merge refuses parts that do not fit together, naming them" `Quick (fun () ->
        let t = tiles 3 in
        let with_part i p = List.mapi (fun j np -> if i = j then p else np) t in
        let r2 = (snd (List.nth t 1)).region in
        let other_depth = Scene.with_overrides ~depth:1 scene in
        Alcotest.(check string) __LOC__
          "d.ppm was rendered with depth 1, part-1.ppm with depth 3: they do not fit together"
          (error (Part.merge (with_part 1 ("d.ppm", part ~s:other_depth r2))));
        Alcotest.(check string) __LOC__
          (Printf.sprintf
             "c.ppm was rendered from a different scene than part-1.ppm (scene digests %s and %s): they do not fit together"
             (List.assoc "scene" (Part.settings (Scene.with_overrides ~camera:Camera.default scene)))
             (List.assoc "scene" (Part.settings scene)))
          (error (Part.merge (with_part 1 ("c.ppm", part ~s:(Scene.with_overrides ~camera:Camera.default scene) r2))));
        let wider = Scene.with_overrides ~width:38 scene in
        Alcotest.(check string) __LOC__
          "w.ppm is a part of a 38x23 image, part-1.ppm of a 37x23 one: they do not fit together"
          (error (Part.merge (with_part 1 ("w.ppm", part ~s:wider (ok (Render.Region.tile ~width:38 ~height:23 ~index:2 ~count:3))))));
        Alcotest.(check string) __LOC__
          "s.ppm was rendered with samples 4, part-1.ppm with samples 1: they do not fit together"
          (error (Part.merge (with_part 1 ("s.ppm", part ~settings:(Part.settings ~samples:4 scene) r2))));
        Alcotest.(check string) __LOC__
          "f.ppm was rendered with frame 2, part-1.ppm with frame (none): they do not fit together"
          (error (Part.merge (with_part 1 ("f.ppm", part ~settings:(Part.settings ~frame:2 scene) r2)))));
    Alcotest.test_case "merge refuses overlaps and gaps" `Quick (fun () ->
        let t = tiles 3 in
        (* Tile 2 of 3 of 23 rows: rows 7 to 14 (23 / 3 = 7, 46 / 3 = 15). *)
        Alcotest.(check string) __LOC__
          "the parts leave 296 of 851 pixels uncovered, the first at (0, 7) (column, row): a part is missing"
          (error (Part.merge [ List.nth t 0; List.nth t 2 ]));
        Alcotest.(check string) __LOC__
          "part-2.ppm and x.ppm overlap at pixel (0, 7) (column, row): they do not fit together"
          (error (Part.merge (t @ [ ("x.ppm", snd (List.nth t 1)) ])));
        Alcotest.(check string) __LOC__ "no parts to merge" (error (Part.merge [])));
    Alcotest.test_case "files that are not parts are refused with the reason" `Quick (fun () ->
        let img = Image.create 2 1 in
        Alcotest.(check string) __LOC__
          "a.ppm: not a part of a raytrace render (its header has no \"# raytrace-part 1\" line); render parts with raytrace render --tile or --region"
          (error (Part.of_string ~file:"a.ppm" (Image.Ppm.to_string img)));
        let header lines = Image.Ppm.to_string ~comments:("raytrace-part 1" :: lines) img in
        Alcotest.(check string) __LOC__ "b.ppm: the part's pixels are 2x1 but its region 0 0 2 2 is 2x2"
          (error (Part.of_string ~file:"b.ppm" (header [ "canvas 4 4"; "region 0 0 2 2" ])));
        Alcotest.(check string) __LOC__ "b.ppm: region columns 3 to 5: need 0 <= x0 < x1 <= 4 (the canvas width)"
          (error (Part.of_string ~file:"b.ppm" (header [ "canvas 4 4"; "region 3 0 5 1" ])));
        Alcotest.(check string) __LOC__ "b.ppm: no region line in the part's header"
          (error (Part.of_string ~file:"b.ppm" (header [ "canvas 4 4" ])));
        Alcotest.(check string) __LOC__ "b.ppm: bad canvas line \"4 x\" in the part's header"
          (error (Part.of_string ~file:"b.ppm" (header [ "canvas 4 x"; "region 0 0 2 1" ])));
        Alcotest.(check string) __LOC__ "b.ppm: the part's header gives depth twice"
          (error (Part.of_string ~file:"b.ppm" (header [ "canvas 4 4"; "region 0 0 2 1"; "depth 3"; "depth 4" ])));
        Alcotest.(check string) __LOC__ "b.ppm: pixel data is truncated: 3 of 6 bytes"
          (let full = header [ "canvas 4 4"; "region 0 0 2 1" ] in
           error (Part.of_string ~file:"b.ppm" (String.sub full 0 (String.length full - 3)))));
    Alcotest.test_case "a malformed part is a programming error" `Quick (fun () ->
        Alcotest.check_raises __LOC__ (Invalid_argument "Part.v: image size differs from the region") (fun () ->
            ignore (Part.v ~canvas_width:4 ~canvas_height:4 ~region:(Render.Region.v ~x:0 ~y:0 ~w:2 ~h:2) ~settings:[] (Image.create 1 1)));
        Alcotest.check_raises __LOC__ (Invalid_argument "Part.v: repeated or reserved setting region") (fun () ->
            ignore
              (Part.v ~canvas_width:4 ~canvas_height:4 ~region:(Render.Region.v ~x:0 ~y:0 ~w:1 ~h:1) ~settings:[ ("region", "x") ]
                 (Image.create 1 1))));
  ]
