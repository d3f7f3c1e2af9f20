(* The kernel draws textures (issue 27, item 3): its own mappings and
   lookup (Texturing) against the executable specification's (Literal,
   which calls Texture_map's mappings and Texture's lookup), on every
   mapping, in the document's mode and the robust one, through mirrors and
   glass, in a hierarchy, on transformed and instanced objects, on random
   scenes; the early stop's bound counts the images' colours; and tracing
   a textured scene allocates nothing. *)
open Raytrace
module Texture = Image.Texture

(* A 4 x 2 image of eight distinct colours: every lookup that picks the
   wrong pixel, or none, shows. *)
let image =
  Texture.v ~width:4 ~height:2
    "\255\000\000\000\255\000\000\000\255\255\255\000\000\255\255\255\000\255\128\064\032\032\064\128"

(* A 2 x 2 quad, its corners' vt the unit square's. *)
let quad_obj = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n"

(* A closed cube of side 1 about the origin, each face's two triangles
   given the unit square's vt in another turn (so a corner's vt taken
   from the wrong triangle or corner shows). *)
let cube =
  let face a b c d k =
    let vt i = 1 + ((i + k) mod 4) in
    Printf.sprintf "f %d/%d %d/%d %d/%d\nf %d/%d %d/%d %d/%d\n" a (vt 0) b (vt 1) c (vt 2) a (vt 0) c (vt 2) d (vt 3)
  in
  "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n"
  ^ "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
  ^ face 1 2 3 4 0 ^ face 5 6 7 8 1 ^ face 1 2 6 5 2 ^ face 4 3 7 8 3 ^ face 1 4 8 5 1 ^ face 2 3 7 6 2

(* The scene [text], whose every texture file is [image] and every mesh
   file [mesh]. *)
let read ?(image = image) ?(mesh = quad_obj) text =
  let load_texture _ = Ok image in
  let load_mesh _ = Mesh.Obj.of_string ~name:"m.obj" ~max_vertices:1000 ~max_triangles:1000 mesh in
  match Scene_file.of_string ~load_texture ~load_mesh ~file:"t.scene" text with
  | Ok s -> Scene.of_valid s
  | Error (`Msg m) -> Alcotest.failf "refused: %s" m

let texture = {|(texture (file "t.ppm") (mapping |}

(* Every mapping in one view: a globe, a floor, a box, a textured quad. *)
let scene ?(extra = "") ?(epsilon = "(epsilon 0.001)") () =
  read
    (String.concat "\n"
       [
         "(canvas (width 64) (height 48)) (background 20 20 20) " ^ epsilon;
         "(sphere (center -1.2 0.3 5) (radius 1) (color 9 9 9) (specular 50) " ^ texture ^ "spherical)))";
         "(plane (point 0 -1 0) (normal 0 1 0) (color 9 9 9) " ^ texture ^ "planar) (size 0.75)))";
         "(box (min 0.6 -1 3.5) (max 1.6 0 4.5) (color 9 9 9) " ^ texture ^ "box)))";
         "(mesh (file \"q.obj\") (translate 1.2 1.2 7) (color 9 9 9) " ^ texture ^ "uv)))";
         extra;
         "(light ambient (intensity 0.3)) (light point (intensity 0.5) (position 2 3 -1))";
         "(light directional (intensity 0.2) (direction 1 4 -2))";
       ])

(* The kernel's image against the oracle's, with the skips on and off:
   the (u, v) of each is computed by other formulas (a plane's axes from
   its stored unit normal, a triangle's weights from its stored corners),
   so a lookup may differ in its last bits, and a byte by one where a
   channel lies at a rounding boundary. *)
let as_the_oracle what s =
  let expected, rounding = Test_fast_oracle.oracle s in
  List.iter
    (fun skips ->
      let actual = Helpers.image_exn ~skips s in
      match Image.Diff.compare expected actual with
      | Error (`Msg m) -> Alcotest.failf "%s: %s" what m
      | Ok d ->
          let share = float d.differing /. float (Image.width expected * Image.height expected) in
          if d.max_abs > 1 || share > 0.01 then
            Alcotest.failf "%s (skips %b): %d pixels differ (%d whose rays rounding may decide), by up to %d" what skips
              d.differing (Hashtbl.length rounding) d.max_abs)
    [ true; false ]

let tests =
  [
    Alcotest.test_case "every mapping is drawn as the oracle draws it, in the document's mode" `Quick (fun () ->
        let s = scene () in
        as_the_oracle "document's mode" s;
        (* Without the texture every object is (9, 9, 9) under some light:
           a handful of colours, not hundreds. *)
        let n = Hashtbl.length (Test_pattern.colours (Helpers.image_exn s)) in
        if n < 200 then Alcotest.failf "only %d colours: the texture is not drawn" n);
    Alcotest.test_case "every mapping is drawn as the oracle draws it, in the robust mode" `Quick (fun () ->
        as_the_oracle "robust mode" (scene ~epsilon:"" ()));
    Alcotest.test_case "a textured object seen in a mirror and through glass is drawn as the oracle draws it" `Quick (fun () ->
        as_the_oracle "mirror"
          (scene ~extra:"(sphere (center 0.2 -0.6 2.5) (radius 0.4) (color 200 200 200) (reflective 0.6))" ());
        as_the_oracle "glass"
          (scene ~extra:"(sphere (center 0.2 -0.6 2.5) (radius 0.4) (color 200 200 200) (transparency 0.8) (refractive-index 1.3))" ()));
    Alcotest.test_case "a uv texture on a mesh of many triangles, in a hierarchy, is drawn as the oracle draws it" `Quick (fun () ->
        (* 12 x 12 squares of 2 triangles, each vertex's vt its place in
           the grid: the hierarchy's order of triangles and corners is not
           the file's, and every corner must keep its own vt. *)
        as_the_oracle "grid"
          (read ~mesh:(Test_texture.textured_grid 12)
             ("(canvas (width 48) (height 48)) (epsilon 0.001) (mesh (file \"g.obj\") (scale 0.25) (translate -1.5 -1.5 4) "
            ^ "(color 9 9 9) " ^ texture ^ "uv))) (light ambient (intensity 1))")));
    Alcotest.test_case "textured objects transformed and instanced are drawn as the oracle draws them, their textures in their frames" `Quick
      (fun () ->
        (* A globe tilted and moved, two uses of one textured box (turned,
           scaled), a uv-textured quad turned: the lookups happen on the ray
           carried into each object's frame. *)
        let text epsilon =
          String.concat "\n"
            [
              "(canvas (width 64) (height 48)) (background 20 20 20) " ^ epsilon;
              "(transform ((rotate-z 23) (rotate-y 40) (translate -1.2 0.3 5)) (sphere (center 0 0 0) (radius 1) (color 9 9 9) (specular 50) "
              ^ texture ^ "spherical))))";
              "(define crate (box (min -0.5 -0.5 -0.5) (max 0.5 0.5 0.5) (color 9 9 9) " ^ texture ^ "box))))";
              "(use crate (transform ((rotate-y 30) (translate 1.1 -0.5 4))))";
              "(use crate (transform ((scale 0.6) (rotate-x 45) (translate 0.2 1.2 6))))";
              "(transform ((rotate-y 20)) (mesh (file \"q.obj\") (translate 1.2 1.2 7) (color 9 9 9) " ^ texture ^ "uv))))";
              "(plane (point 0 -1 0) (normal 0 1 0) (color 9 9 9) " ^ texture ^ "planar) (size 0.75)))";
              "(light ambient (intensity 0.3)) (light point (intensity 0.5) (position 2 3 -1))";
            ]
        in
        as_the_oracle "document's mode" (read (text "(epsilon 0.001)"));
        as_the_oracle "robust mode" (read (text "")));
    Alcotest.test_case "textures on a CSG solid's operands and as a transform's or use's own material are drawn as the oracle draws them" `Quick
      (fun () ->
        (* A die: the intersection of a textured box and a textured ball,
           turned by a transform (its bottom level); a bare CSG solid with
           a textured ball less a plain box; a globe given its texture by
           its transform; a defined crate used with a textured material,
           and a defined notched box (a CSG solid of two boxes) used with
           one (the texture on every leaf). *)
        let die = "(csg intersection (box (min -0.5 -0.5 -0.5) (max 0.5 0.5 0.5) (color 9 9 9) " ^ texture ^ "box)))"
          ^ " (sphere (center 0 0 0) (radius 0.68) (color 9 9 9) (specular 40) " ^ texture ^ "spherical))))" in
        let text epsilon =
          String.concat "\n"
            [
              "(canvas (width 64) (height 48)) (background 20 20 20) " ^ epsilon;
              "(transform ((rotate-y 30) (rotate-x 20) (translate -1.3 0.6 5)) " ^ die ^ ")";
              "(csg difference (sphere (center 1.3 0.6 5) (radius 0.8) (color 9 9 9) " ^ texture
              ^ "spherical))) (box (min 1.3 0.6 3) (max 3 3 5) (color 200 40 40)))";
              "(transform ((rotate-z 23) (translate -1.1 -0.6 4)) (sphere (center 0 0 0) (radius 0.5) (color 9 9 9)) (color 9 9 9) "
              ^ texture ^ "spherical)))";
              "(define crate (box (min -0.4 -0.4 -0.4) (max 0.4 0.4 0.4) (color 200 40 40)))";
              "(use crate (transform ((rotate-y 35) (translate 0.2 -0.5 4))) (color 9 9 9) " ^ texture ^ "box)))";
              "(define notch (csg difference (box (min -0.5 -0.5 -0.5) (max 0.5 0.5 0.5) (color 1 1 1)) (box (min 0 0 -1) (max 1 1 0) (color 1 1 1))))";
              "(use notch (transform ((scale 0.6) (rotate-x 45) (translate 1.2 -0.6 4))) (color 9 9 9) (specular 10) " ^ texture ^ "box)))";
              (* Transformed operands: a turned textured box, a used
                 textured ball, a ball given its texture by its transform. *)
              (* A mesh with vt used with a uv texture of its own. *)
              "(define quad (mesh (file \"q.obj\") (scale 0.4) (color 200 40 40)))";
              "(use quad (transform ((rotate-y -30) (translate -0.2 1.4 6))) (color 9 9 9) " ^ texture ^ "uv)))";
              "(define globe (sphere (center 0 0 0) (radius 0.35) (color 9 9 9) " ^ texture ^ "spherical))))";
              "(csg union (transform ((rotate-y 40) (rotate-x 25) (translate 0 1.1 4.5)) (box (min -0.3 -0.3 -0.3) (max 0.3 0.3 0.3) (color 9 9 9) "
              ^ texture ^ "box)))) (csg difference (use globe (transform ((rotate-z 60) (translate 0.6 1.2 4.5)))) "
              ^ "(transform ((rotate-y 90) (translate 1.0 1.1 4.2)) (sphere (center 0 0 0) (radius 0.2) (color 1 1 1)) (color 9 9 9) "
              ^ texture ^ "spherical)))))";
              "(plane (point 0 -1 0) (normal 0 1 0) (color 120 120 120) (reflective 0.3))";
              "(light ambient (intensity 0.3)) (light point (intensity 0.5) (position 2 3 -1))";
            ]
        in
        let s = read (text "(epsilon 0.001)") in
        as_the_oracle "document's mode" s;
        as_the_oracle "robust mode" (read (text ""));
        let n = Hashtbl.length (Test_pattern.colours (Helpers.image_exn s)) in
        if n < 200 then Alcotest.failf "only %d colours: the textures are not drawn" n);
    Alcotest.test_case "a uv texture on a CSG solid's mesh operand is drawn as the mesh alone draws it where the solid keeps its surface" `Quick
      (fun () ->
        (* The closed cube [cube], textured through its vt. In a union
           with a box far out of view, or an intersection with a box that holds it, the
           solid's surface is the mesh's: the same hit, the same point in
           the operand's frame (also inside a transformed operand), so the
           same texture coordinates and every pixel the same byte. *)
        let mesh = "(mesh (file \"c.obj\") (scale 1.5) (translate 1 0.9 4) (color 9 9 9) (specular 30) " ^ texture ^ "uv)))" in
        let turned = "(transform ((rotate-y 30) (rotate-x 20) (translate -0.9 -0.5 3.5)) (mesh (file \"c.obj\") (color 9 9 9) " ^ texture ^ "uv))))" in
        let far = "(box (min 50 50 50) (max 51 51 51) (color 200 40 40))" in
        let holder = "(box (min -3 -3 1) (max 3 3 8) (color 200 40 40))" in
        let scene epsilon objects =
          read ~mesh:cube
            (String.concat "\n"
               ([ "(canvas (width 64) (height 48)) (background 20 20 20) " ^ epsilon ]
               @ objects
               @ [ "(light ambient (intensity 0.3)) (light point (intensity 0.6) (position 2 3 -1))" ]))
        in
        let image epsilon objects = Helpers.image_exn (scene epsilon objects) in
        List.iter
          (fun epsilon ->
            let alone = image epsilon [ mesh; turned ] in
            let n = Hashtbl.length (Test_pattern.colours alone) in
            if n < 50 then Alcotest.failf "only %d colours: the texture is not drawn" n;
            List.iter
              (fun (what, objects) -> Helpers.check_images (what ^ ", " ^ epsilon) ~expected:alone (image epsilon objects))
              [
                ("union with a far box", [ "(csg union " ^ mesh ^ " " ^ far ^ ")"; "(csg union " ^ turned ^ " " ^ far ^ ")" ]);
                ("intersection with a box that holds it", [ "(csg intersection " ^ mesh ^ " " ^ holder ^ ")"; "(csg intersection " ^ holder ^ " " ^ turned ^ ")" ]);
              ];
            (* Cut by a box, and as the oracle draws it (which finds the
               triangle again on the line, Literal.texture_point). *)
            let cut = "(box (min 1.2 1.1 2) (max 3 3 4.2) (color 200 40 40))" in
            as_the_oracle ("oracle, " ^ epsilon)
              (scene epsilon [ "(csg difference " ^ mesh ^ " " ^ cut ^ ")"; "(csg union " ^ turned ^ " " ^ far ^ ")" ]))
          [ "(epsilon 0.001)"; "" ]);
    Alcotest.test_case "a globe turned a quarter about y by its transform shows its map a quarter turn on" `Quick (fun () ->
        (* rotate-y 90 takes the object's point (x, y, z) to the world's
           (z, y, -x) (exact: its sines and cosines are 0 and 1). The
           world's point facing the camera, d = (0, 0, -1), is the object's
           (1, 0, 0): u = 0.5 + atan2 1 0 / 2 pi = 0.75, where the unturned
           globe shows u = 0.5. Everywhere the turned globe shows the
           unturned one's colour at u + 0.25: the image rolled left by one
           column of four. Colours within 1 (the turned ray's roots round
           on their own). *)
        let bytes = Texture.channels image in
        (* Pixel (x, y) of the rolled image is pixel (x + 1 mod 4, y). *)
        let rolled = Texture.v ~width:4 ~height:2 (String.init 24 (fun k -> let px = k / 3 in Char.chr bytes.{(3 * ((4 * (px / 4)) + ((px + 1) mod 4))) + (k mod 3)})) in
        let globe ops = "(canvas (width 48) (height 48)) (viewport (width 1) (height 1) (distance 1)) (epsilon 0.001)\n"
          ^ "(transform (" ^ ops ^ "(translate 0 0 3)) (sphere (center 0 0 0) (radius 1) (color 9 9 9)) (color 9 9 9) " ^ texture
          ^ "spherical)))\n(light ambient (intensity 1))" in
        let turned = Helpers.image_exn (read (globe "(rotate-y 90) ")) in
        let plain = Helpers.image_exn (read ~image:rolled (globe "")) in
        Helpers.check_images ~max_abs:1 __LOC__ ~expected:plain turned;
        (* Not the unturned globe with the image as it is. *)
        match Image.Diff.compare (Helpers.image_exn (read (globe ""))) turned with
        | Ok d -> if d.differing < 500 then Alcotest.failf "only %d pixels differ from the unturned map" d.differing
        | Error (`Msg m) -> Alcotest.fail m);
    Alcotest.test_case "random textured scenes are drawn as the oracle draws them, and the skips change no byte" `Slow (fun () ->
        (* The property tests' scenes (every light, material and shape, both
           modes), textures on half their spheres, planes and boxes. *)
        let rand = Random.State.make [| 27 |] in
        let scenes = QCheck.Gen.generate ~rand ~n:40 Gen_scene.gen in
        List.iteri
          (fun i (s : Scene.t) ->
            let s = Gen_scene.with_textures rand s in
            let what = Printf.sprintf "scene %d:\n%s" i (Scene.show s) in
            as_the_oracle what s;
            Helpers.check_images what ~expected:(Helpers.image_exn ~skips:false s) (Helpers.image_exn s))
          scenes);
    Alcotest.test_case "a faint mirror shows a black wall's white texture: the early stop counts the image's colours" `Quick
      (fun () ->
        (* Behind the camera, the wall z = -1, of colour black and a white
           texture, seen only in a mirror of reflectivity 0.02:
           0.02 * 255 = 5.1 per channel, which an early stop that took the
           wall's colour field for its brightest would drop. *)
        let s =
          read ~image:(Texture.v ~width:1 ~height:1 "\255\255\255")
            ("(canvas (width 24) (height 24)) (sphere (center 0 0 3) (radius 1) (color 0 0 0) (reflective 0.02))\n"
           ^ "(plane (point 0 0 -1) (normal 0 0 1) (color 0 0 0) " ^ texture ^ "planar)))\n(light ambient (intensity 1))")
        in
        let img = Helpers.image_exn s in
        Alcotest.(check bool) "the white wall is seen" true (Hashtbl.mem (Test_pattern.colours img) (5, 5, 5));
        Helpers.check_images "skips on and off" ~expected:(Helpers.image_exn ~skips:false s) img);
    Alcotest.test_case "a texture's pixel centre shows its colour exactly: the globe's front is the image's centre" `Quick (fun () ->
        (* A 2 x 2 image (red, green; blue, white) under ambient light 1
           alone: the globe's point facing the camera, the centre pixel's,
           is (u, v) = (0.5, 0.5), the corner where the four pixels meet:
           their mean. *)
        let s =
          read ~image:(Texture.v ~width:2 ~height:2 "\255\000\000\000\255\000\000\000\255\255\255\255")
            ("(canvas (width 3) (height 3)) (viewport (width 1) (height 1) (distance 1)) (epsilon 0.001) "
           ^ "(sphere (center 0 0 3) (radius 1) (color 9 9 9) " ^ texture ^ "spherical))) (light ambient (intensity 1))")
        in
        let img = Helpers.image_exn s in
        (* (255 + 0 + 0 + 255) / 4 = 127.5, (0 + 255 + 0 + 255) / 4, (0 + 0 + 255 + 255) / 4. *)
        Alcotest.(check (triple int int int)) __LOC__ (128, 128, 128) (Image.get img 1 1));
    Alcotest.test_case "tracing a textured scene allocates nothing per pixel, in both modes and through glass" `Quick (fun () ->
        List.iter
          (fun s ->
            match Helpers.render ~samples:2 s with
            | Ok (_, stats) -> Alcotest.(check (float 0.)) __LOC__ 0. stats.minor_words
            | Error (`Msg m) -> Alcotest.fail m)
          [
            scene (); scene ~epsilon:"" ();
            scene ~extra:"(sphere (center 0.2 -0.6 2.5) (radius 0.4) (color 200 200 200) (transparency 0.8) (refractive-index 1.3))" ();
            (* Textured CSG operands, in the world, in a turned object
               and turned themselves, and a use's own texture. *)
            scene
              ~extra:
                ("(csg intersection (box (min -0.5 0.5 3) (max 0.5 1.5 4) (color 9 9 9) " ^ texture
               ^ "box))) (sphere (center 0 1 3.5) (radius 0.68) (color 9 9 9) " ^ texture ^ "spherical))))\n"
               ^ "(transform ((rotate-y 30) (translate 2 1 5)) (csg difference (sphere (center 0 0 0) (radius 0.6) (color 9 9 9) "
               ^ texture ^ "spherical))) (box (min 0 0 -1) (max 1 1 0) (color 9 9 9))))\n"
               ^ "(define b (sphere (center 0 0 0) (radius 0.4) (color 1 1 1)))\n(use b (transform ((rotate-y 90) (translate -2 1.2 4))) (color 9 9 9) "
               ^ texture ^ "spherical)))\n"
               ^ "(csg union (transform ((rotate-y 30) (translate -1 2 5)) (box (min -0.3 -0.3 -0.3) (max 0.3 0.3 0.3) (color 9 9 9) " ^ texture
               ^ "box)))) (sphere (center -1.3 2 5) (radius 0.3) (color 9 9 9)))")
              ();
            (* A textured mesh operand, in the world and turned. *)
            read ~mesh:cube
              ("(canvas (width 32) (height 24)) (csg difference (mesh (file \"c.obj\") (translate 0.5 0.5 4) (color 9 9 9) " ^ texture
             ^ "uv))) (box (min 0.6 0.6 2) (max 2 2 4.2) (color 9 9 9)))\n"
             ^ "(csg union (transform ((rotate-y 30) (translate -0.8 0 3.5)) (mesh (file \"c.obj\") (color 9 9 9) " ^ texture
             ^ "uv)))) (sphere (center -1 1 4) (radius 0.3) (color 9 9 9)))\n(light ambient (intensity 0.3)) (light point (intensity 0.5) (position 2 3 -1))");
            read ~mesh:cube
              ("(canvas (width 32) (height 24)) (csg intersection (mesh (file \"c.obj\") (translate 0 0 4) (color 9 9 9) " ^ texture
             ^ "uv))) (sphere (center 0 0 4) (radius 0.7) (color 9 9 9)))\n(light ambient (intensity 1))");
          ]);
  ]
