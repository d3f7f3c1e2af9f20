(* Image textures outside the kernel: the pixels and their bilinear
   lookup, the mappings, OBJ texture coordinates, the scene-text field
   and where the renderer refuses one. *)
open Raytrace
module Texture = Image.Texture
module Texture_map = Material.Texture

let c = Alcotest.float 0.
let near = Alcotest.float 1e-12

(* A 2x2 texture, rows top-down:
     red   (255 0 0)    green (0 255 0)
     blue  (0 0 255)    white (255 255 255) *)
let quad = Texture.v ~width:2 ~height:2 "\255\000\000\000\255\000\000\000\255\255\255\255"

let rgb (col : Color.t) = (col.r, col.g, col.b)
let check_rgb loc (r, g, b) col =
  let r', g', b' = rgb col in
  Alcotest.check c (loc ^ " r") r r';
  Alcotest.check c (loc ^ " g") g g';
  Alcotest.check c (loc ^ " b") b b'

let texture_tests =
  [
    Alcotest.test_case "a lookup at a pixel's centre is that pixel" `Quick (fun () ->
        (* Width 2: centres at u = 0.25, 0.75; v = 1 - (y + 0.5) / 2:
           row 0 at v = 0.75, row 1 at v = 0.25. *)
        check_rgb __LOC__ (255., 0., 0.) (Texture.color quad 0.25 0.75);
        check_rgb __LOC__ (0., 255., 0.) (Texture.color quad 0.75 0.75);
        check_rgb __LOC__ (0., 0., 255.) (Texture.color quad 0.25 0.25);
        check_rgb __LOC__ (255., 255., 255.) (Texture.color quad 0.75 0.25));
    Alcotest.test_case "bilinear: the centre of the image is the mean of the four pixels" `Quick (fun () ->
        (* fx = 0.5 * 2 - 0.5 = 0.5, fy likewise: weights 1/4 each.
           r = (255 + 0 + 0 + 255) / 4 = 127.5; g = (0 + 255 + 0 + 255) / 4
           = 127.5; b = (0 + 0 + 255 + 255) / 4 = 127.5. *)
        check_rgb __LOC__ (127.5, 127.5, 127.5) (Texture.color quad 0.5 0.5));
    Alcotest.test_case "bilinear: a quarter of the way between two pixels of a row" `Quick (fun () ->
        (* u = 0.375: fx = 0.75 - 0.5 = 0.25 between red (x 0) and green
           (x 1) on row 0 (v = 0.75, fy = 0): r = 255 + 0.25 (0 - 255) =
           191.25, g = 0 + 0.25 * 255 = 63.75, b = 0. *)
        check_rgb __LOC__ (191.25, 63.75, 0.) (Texture.color quad 0.375 0.75));
    Alcotest.test_case "Repeat wraps past the right edge to the left column; Clamp keeps the edge" `Quick (fun () ->
        (* u = 1.0 (v on row 0): fx = 2 - 0.5 = 1.5: columns 1 and 2, 2
           wrapping to 0: half green, half red. Clamped: column 2 is 1,
           green twice. *)
        check_rgb __LOC__ (127.5, 127.5, 0.) (Texture.color ~wrap_u:Repeat quad 1.0 0.75);
        check_rgb __LOC__ (0., 255., 0.) (Texture.color ~wrap_u:Clamp quad 1.0 0.75);
        (* Far away, Repeat sees the same place of the image. *)
        check_rgb __LOC__ (rgb (Texture.color quad 0.375 0.75)) (Texture.color quad 1000.375 (-6.25)));
    Alcotest.test_case "Clamp below the bottom edge takes the bottom row" `Quick (fun () ->
        (* v = -3 clamps to the bottom row (blue, white); u = 0.25: blue. *)
        check_rgb __LOC__ (0., 0., 255.) (Texture.color ~wrap_v:Clamp quad 0.25 (-3.)));
    Alcotest.test_case "a NaN or infinite coordinate looks up 0" `Quick (fun () ->
        check_rgb __LOC__ (rgb (Texture.color quad 0. 0.)) (Texture.color quad Float.nan Float.infinity));
    Alcotest.test_case "lookups stay within [0, 255] and between the neighbours" `Quick (fun () ->
        let st = Random.State.make [| 27 |] in
        let t = Texture.v ~width:3 ~height:5 (String.init 45 (fun _ -> Char.chr (Random.State.int st 256))) in
        for _ = 1 to 2000 do
          let u = Random.State.float st 4. -. 2. and v = Random.State.float st 4. -. 2. in
          let r, g, b = rgb (Texture.color t u v) in
          List.iter (fun x -> if not (x >= 0. && x <= 255.) then Alcotest.failf "%g outside [0, 255] at %g %g" x u v) [ r; g; b ]
        done);
    Alcotest.test_case "lookup writes the colour into an array and allocates nothing" `Quick (fun () ->
        let uv = [| 0.375; 0.75 |] and dst = Array.make 3 0. in
        Texture.lookup ~wrap_u:Repeat ~wrap_v:Clamp quad uv 0 dst 0;
        Alcotest.(check (array c)) __LOC__ [| 191.25; 63.75; 0. |] dst;
        let before = Gc.minor_words () in
        for _ = 1 to 1000 do Texture.lookup ~wrap_u:Repeat ~wrap_v:Clamp quad uv 0 dst 0 done;
        Alcotest.(check c) __LOC__ 0. (Gc.minor_words () -. before));
    Alcotest.test_case "of_image keeps the pixels; v refuses a size that does not match" `Quick (fun () ->
        let img = Image.create 2 1 in
        Image.set img 1 0 10 20 30;
        let t = Texture.of_image img in
        Alcotest.(check int) __LOC__ 2 (Texture.width t);
        check_rgb __LOC__ (10., 20., 30.) (Texture.pixel t 1 0);
        Alcotest.check_raises __LOC__ (Invalid_argument "Texture.v: bytes do not match the size") (fun () ->
            ignore (Texture.v ~width:2 ~height:2 "abc")));
  ]

let pair = Alcotest.(pair near near)
let v = Vec3.v

let mapping_tests =
  [
    Alcotest.test_case "spherical: the front, the right, the back seam and the poles" `Quick (fun () ->
        let center = v 1. 2. 3. in
        (* d = (0, 0, -2): atan2 0 2 = 0, u = 0.5; asin 0 = 0, v = 0.5. *)
        Alcotest.check pair __LOC__ (0.5, 0.5) (Texture_map.spherical ~center (v 1. 2. 1.));
        (* d = (3, 0, 0): atan2 3 0 = pi/2, u = 0.5 + 1/4. *)
        Alcotest.check pair __LOC__ (0.75, 0.5) (Texture_map.spherical ~center (v 4. 2. 3.));
        (* d = (-1, 0, 0): u = 0.5 - 1/4. *)
        Alcotest.check pair __LOC__ (0.25, 0.5) (Texture_map.spherical ~center (v 0. 2. 3.));
        (* d = (0, 0, 1): atan2 0 (-1) = pi, u = 1. *)
        Alcotest.check pair __LOC__ (1., 0.5) (Texture_map.spherical ~center (v 1. 2. 4.));
        (* d = (0, 1, 0): asin 1 = pi/2, v = 1; d = (0, -1, 0): v = 0;
           atan2 0 (-0) = pi there too, u = 1. *)
        Alcotest.check near __LOC__ 1. (snd (Texture_map.spherical ~center (v 1. 3. 3.)));
        Alcotest.check near __LOC__ 0. (snd (Texture_map.spherical ~center (v 1. 1. 3.)));
        (* 45 degrees up at the front: asin (1/sqrt 2) = pi/4, v = 0.75. *)
        Alcotest.check pair __LOC__ (0.5, 0.75) (Texture_map.spherical ~center (v 1. 3. 2.)));
    Alcotest.test_case "planar axes: a floor, a wall facing the camera, a tilted plane" `Quick (fun () ->
        let vec = Alcotest.testable Vec3.pp (Vec3.equal_f (fun a b -> Float.abs (a -. b) < 1e-15)) in
        let check n (eu, ev) =
          let au, av = Texture_map.planar_axes n in
          Alcotest.check vec __LOC__ eu au;
          Alcotest.check vec __LOC__ ev av
        in
        check (v 0. 1. 0.) (v 1. 0. 0., v 0. 0. 1.);
        check (v 0. 5. 0.) (v 1. 0. 0., v 0. 0. 1.);
        check (v 0. 0. (-1.)) (v 1. 0. 0., v 0. 1. 0.);
        (* A wall facing +x (seen from +x, looking along -x): right is +z. *)
        check (v 1. 0. 0.) (v 0. 0. 1., v 0. 1. 0.);
        (* n = (0, 1, -1) / sqrt 2: y does not dominate (a tie), so r = y:
           e_u = unit (n x y) = unit ((0*0 - (-1)*1, (-1)*0 - 0*0, 0)) =
           (1, 0, 0); e_v = e_u x n = (0, 1, 1) / sqrt 2, the way up. *)
        let s = 1. /. sqrt 2. in
        check (v 0. 1. (-1.)) (v 1. 0. 0., v 0. s s);
        Alcotest.check_raises __LOC__ (Invalid_argument "Texture_map.planar_axes: normal zero or not finite") (fun () ->
            ignore (Texture_map.planar_axes Vec3.zero)));
    Alcotest.test_case "planar: coordinates along the axes, in copies of size" `Quick (fun () ->
        (* Floor y = -1 through (1, -1, 2), size 2: p = (4, -1, 7) is
           d = (3, 0, 5): u = 3 / 2, v = 5 / 2. *)
        Alcotest.check pair __LOC__ (1.5, 2.5)
          (Texture_map.planar ~point:(v 1. (-1.) 2.) ~normal:(v 0. 1. 0.) ~size:2. (v 4. (-1.) 7.)));
    Alcotest.test_case "box: each face, read left to right from outside" `Quick (fun () ->
        let min = v 0. 0. 0. and max = v 2. 4. 8. in
        let check p face (u, w) =
          let f, a, b = Texture_map.box ~min ~max p in
          if f <> face then Alcotest.failf "%s: wrong face" __LOC__;
          Alcotest.check pair __LOC__ (u, w) (a, b)
        in
        (* sx = x / 2, sy = y / 4, sz = z / 8. *)
        check (v 0.5 1. 0.) Min_z (0.25, 0.25);
        check (v 0.5 1. 8.) Max_z (0.75, 0.25);
        check (v 0. 1. 2.) Min_x (0.75, 0.25);
        check (v 2. 1. 2.) Max_x (0.25, 0.25);
        check (v 0.5 4. 2.) Max_y (0.25, 0.25);
        check (v 0.5 0. 2.) Min_y (0.25, 0.75);
        (* An edge of Min_x and Min_z: the first face in the order. *)
        check (v 0. 1. 0.) Min_x (1., 0.25));
    Alcotest.test_case "barycentric weights and interpolated texture coordinates" `Quick (fun () ->
        let a = v 0. 0. 0. and b = v 2. 0. 0. and c = v 0. 4. 0. in
        (* p = a + 0.25 (b - a) + 0.5 (c - a) = (0.5, 2, 0). *)
        Alcotest.check pair __LOC__ (0.25, 0.5) (Texture_map.barycentric a b c (v 0.5 2. 0.));
        (* (0, 0) + 0.25 ((1, 0) - (0, 0)) + 0.5 ((0, 1) - (0, 0)). *)
        Alcotest.check pair __LOC__ (0.25, 0.5) (Texture_map.interpolate ~b1:0.25 ~b2:0.5 (0., 0.) (1., 0.) (0., 1.));
        (* Corners (0.2, 0.4), (0.6, 0.4), (0.2, 1.0) at weights 0.5, 0.25:
           u = 0.2 + 0.5 * 0.4 = 0.4; v = 0.4 + 0.25 * 0.6 = 0.55. *)
        Alcotest.check pair __LOC__ (0.4, 0.55) (Texture_map.interpolate ~b1:0.5 ~b2:0.25 (0.2, 0.4) (0.6, 0.4) (0.2, 1.0));
        Alcotest.check pair __LOC__ (0., 0.) (Texture_map.barycentric a a a (v 1. 1. 1.)));
    Alcotest.test_case "each mapping's wraps" `Quick (fun () ->
        let w = Alcotest.testable (fun ppf (a, b) ->
            let s = function Texture.Repeat -> "Repeat" | Clamp -> "Clamp" in
            Format.fprintf ppf "%s, %s" (s a) (s b)) ( = ) in
        Alcotest.check w __LOC__ (Repeat, Clamp) (Texture_map.wraps Spherical);
        Alcotest.check w __LOC__ (Repeat, Repeat) (Texture_map.wraps Planar);
        Alcotest.check w __LOC__ (Clamp, Clamp) (Texture_map.wraps Box);
        Alcotest.check w __LOC__ (Repeat, Repeat) (Texture_map.wraps Uv));
  ]

let obj s = match Mesh.Obj.of_string ~name:"t.obj" ~max_vertices:100 ~max_triangles:100 s with
  | Ok m -> m | Error (`Msg e) -> Alcotest.failf "refused: %s" e

let obj_error s = match Mesh.Obj.of_string ~name:"t.obj" ~max_vertices:2 ~max_triangles:100 s with
  | Ok _ -> Alcotest.fail "accepted" | Error (`Msg e) -> e

let textured = "v 0 0 0\nv 2 0 0\nv 0 4 0\nv 2 4 0\nvt 0 0\nvt 1 0\nvt 0 1 0.5\nvt 0.5\nf 1/1 2/2 3/3\nf 2 4 3\nf 2/4/ 4/2 3/3\n"

let obj_tests =
  [
    Alcotest.test_case "vt lines are kept, v defaults to 0, w is dropped; f v/vt numbers them" `Quick (fun () ->
        let m = obj textured in
        Alcotest.(check (array c)) __LOC__ [| 0.; 0.; 1.; 0.; 0.; 1.; 0.5; 0. |] m.texcoords;
        (* The second face gives none: -1; "2/4/" is vertex 2, texture 4, no normal. *)
        Alcotest.(check (array int)) __LOC__ [| 0; 1; 2; -1; -1; -1; 3; 1; 2 |] m.triangle_texcoords;
        Alcotest.(check (list (pair string int))) __LOC__ [] m.skipped);
    Alcotest.test_case "a face before the first texture number gets -1s; a mesh without any keeps none" `Quick (fun () ->
        let m = obj "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1 2 3\nf 1/1 2/1 3/1\n" in
        Alcotest.(check (array int)) __LOC__ [| -1; -1; -1; 0; 0; 0 |] m.triangle_texcoords;
        let m = obj "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1 2 3\n" in
        Alcotest.(check (array int)) __LOC__ [||] m.triangle_texcoords;
        Alcotest.(check int) __LOC__ 1 (Mesh.Obj.texcoord_count m));
    Alcotest.test_case "a polygon's texture numbers fan like its vertices" `Quick (fun () ->
        let m = obj "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n" in
        Alcotest.(check (array int)) __LOC__ [| 0; 1; 2; 0; 2; 3 |] m.triangle_texcoords);
    Alcotest.test_case "vt errors: no number, too many, not a number, the bound" `Quick (fun () ->
        Alcotest.(check string) __LOC__ "t.obj:1:3: expected 1 to 3 numbers (vt u [v [w]]), found none" (obj_error "vt\n");
        Alcotest.(check string) __LOC__ "t.obj:1:10: expected at most 3 numbers (vt u [v [w]]), found \"4\"" (obj_error "vt 1 2 3 4\n");
        Alcotest.(check string) __LOC__ "t.obj:1:4: expected a number, found \"x\"" (obj_error "vt x\n");
        Alcotest.(check string) __LOC__ "t.obj:3:1: more than 2 texture coordinates (the limit of vertices)" (obj_error "vt 0\nvt 0\nvt 0\n");
        Alcotest.(check string) __LOC__ "t.obj:4:13: texture index 2 is out of range: 1 texture defined so far"
          (obj_error "v 0 0 0\nv 1 0 0\nvt 0\nf 1/1 2/1 2/2\n"));
    Alcotest.test_case "to_string writes vt and f v/vt/vn, which read back equal" `Quick (fun () ->
        let m = obj (textured ^ "vn 0 0 1\nf 1/1/1 2//1 3/3\n") in
        let back = obj (Mesh.Obj.to_string m) in
        Alcotest.(check bool) __LOC__ true (Mesh.Obj.equal m back));
    Alcotest.test_case "Mesh keeps the coordinates and interpolates them across a triangle" `Quick (fun () ->
        let o = obj textured in
        match Mesh.of_obj ~scale:2. o (Material.v (Color.v 1. 1. 1.)) with
        | Error (`Msg e) -> Alcotest.fail e
        | Ok m ->
            Alcotest.(check bool) __LOC__ true (Mesh.has_texcoords m);
            (* Triangle 0: corners' vt (0, 0), (1, 0), (0, 1): at weights
               0.25, 0.5 it is (0.25, 0.5). The placed corners (0,0,0),
               (4,0,0), (0,8,0) give those weights at (1, 4, 0). *)
            let b1, b2 = Texture_map.barycentric (Mesh.vertex m 0 0) (Mesh.vertex m 0 1) (Mesh.vertex m 0 2) (v 1. 4. 0.) in
            Alcotest.check (Alcotest.option pair) __LOC__ (Some (0.25, 0.5)) (Mesh.texcoord m 0 ~b1 ~b2);
            Alcotest.check (Alcotest.option pair) __LOC__ None (Mesh.texcoord m 1 ~b1 ~b2));
  ]

(* Scene text: images are served from a table, as a loader would read
   them; every call is counted. *)
let images = [ ("earth.ppm", quad); ("floor.ppm", Texture.v ~width:1 ~height:1 "\010\020\030") ]

let load_texture path =
  match List.assoc_opt (Filename.basename path) images with
  | Some t -> Ok t
  | None -> Error (`Msg ("cannot read texture file: " ^ path ^ ": No such file or directory"))

let load_mesh _ = Ok (obj textured)
let read text = Scene_file.of_string ~load_texture ~load_mesh ~file:"s.scene" text

let read_error text =
  match read text with Ok _ -> Alcotest.failf "accepted %S" text | Error (`Msg m) -> m

let scene_tests =
  [
    Alcotest.test_case "a texture field on each kind that takes one prints back and reads back the same" `Quick (fun () ->
        let text =
          {|(sphere (center 0 0 3) (radius 1) (color 255 255 255) (texture (file "earth.ppm") (mapping spherical)))
(plane (point 0 -1 0) (normal 0 1 0) (color 9 9 9) (texture (file "floor.ppm") (mapping planar) (size 2)))
(box (min 0 0 0) (max 1 1 1) (color 9 9 9) (texture (file "floor.ppm") (mapping box)))
(mesh (file "m.obj") (color 9 9 9) (texture (file "earth.ppm") (mapping uv)))
(material globe (color 1 2 3) (texture (file "earth.ppm") (mapping spherical)))
(sphere (center 3 0 3) (radius 1) (material globe))|}
        in
        match read text with
        | Error (`Msg m) -> Alcotest.fail m
        | Ok s ->
            let s = Scene.of_valid s in
            let printed = Scene.show s in
            List.iter
              (fun part ->
                if not (Astring_free.contains printed part) then Alcotest.failf "%S not in %s" part printed)
              [ {|(texture (file "earth.ppm") (mapping spherical))|}; {|(texture (file "floor.ppm") (mapping planar) (size 2))|};
                {|(texture (file "floor.ppm") (mapping box))|}; {|(texture (file "earth.ppm") (mapping uv))|} ];
            (match read printed with
            | Error (`Msg m) -> Alcotest.failf "printed scene refused: %s\n%s" m printed
            | Ok back -> Alcotest.(check bool) __LOC__ true (Scene.equal s (Scene.of_valid back))));
    Alcotest.test_case "a texture on a transform, a use or a CSG operand is read where its mapping fits every surface it lies on, refused elsewhere" `Quick (fun () ->
        (* An object's own texture, transformed or used, is drawn in its
           frame; a transform's or use's own lies on its object's every
           surface; a CSG solid's sphere, box and mesh operands take
           theirs. *)
        List.iter
          (fun text -> match read text with Ok _ -> () | Error (`Msg m) -> Alcotest.failf "%s: %s" text m)
          [
            {|(transform ((translate 0 0 1)) (sphere (center 0 0 3) (radius 1) (color 1 1 1) (texture (file "earth.ppm") (mapping spherical))))|};
            "(define ball (sphere (center 0 0 3) (radius 1) (color 1 1 1) (texture (file \"earth.ppm\") (mapping spherical))))\n(use ball)";
            {|(transform ((translate 0 0 1)) (box (min 0 0 0) (max 1 1 1) (color 1 1 1)) (color 1 1 1) (texture (file "earth.ppm") (mapping box)))|};
            "(define ball (sphere (center 0 0 3) (radius 1) (color 1 1 1)))\n(use ball (color 1 1 1) (texture (file \"earth.ppm\") (mapping spherical)))";
            {|(csg union (sphere (center 0 0 3) (radius 1) (color 1 1 1) (texture (file "earth.ppm") (mapping spherical))) (box (min 0 0 0) (max 1 1 1) (color 1 1 1) (texture (file "earth.ppm") (mapping box))))|};
            {|(transform ((rotate-y 30)) (csg difference (box (min 0 0 0) (max 1 1 1) (color 1 1 1)) (box (min 0.5 0.5 0.5) (max 2 2 2) (color 1 1 1))) (color 1 1 1) (texture (file "earth.ppm") (mapping box)))|};
            {|(csg union (transform ((translate 1 0 0)) (sphere (center 0 0 3) (radius 1) (color 1 1 1) (texture (file "earth.ppm") (mapping spherical)))) (box (min 0 0 0) (max 1 1 1) (color 1 1 1)))|};
            "(define m (mesh (file \"m.obj\") (color 1 1 1)))\n(use m (color 1 1 1) (texture (file \"earth.ppm\") (mapping uv)))";
          ];
        let csg_sphere = {|(sphere (center 0 0 3) (radius 1) (color 1 1 1) (texture (file "earth.ppm") (mapping spherical)))|} in
        List.iter
          (fun (expected, text) -> Alcotest.(check string) __LOC__ expected (read_error text))
          [
            ( "s.scene:1:1: its texture lies on its object's surfaces: sphere texture mapping must be spherical, got box",
              {|(transform ((translate 0 0 1)) (sphere (center 0 0 3) (radius 1) (color 1 1 1)) (color 1 1 1) (texture (file "earth.ppm") (mapping box)))|} );
            ( "s.scene:1:1: its texture lies on its object's surfaces: a triangle takes no texture; textures map onto spheres, planes, boxes and meshes",
              {|(transform ((translate 0 0 1)) (triangle (vertices (0 0 1) (1 0 1) (0 1 1)) (color 1 1 1)) (color 1 1 1) (texture (file "earth.ppm") (mapping box)))|} );
            ( "s.scene:2:1: its texture lies on its object's surfaces: csg: sphere texture mapping must be spherical, got box",
              "(define ball (csg union (sphere (center 0 0 3) (radius 1) (color 1 1 1)) (box (min 0 0 0) (max 1 1 1) (color 1 1 1))))\n(use ball (color 1 1 1) (texture (file \"earth.ppm\") (mapping box)))" );
            ( "s.scene:1:104: box texture mapping must be box, got spherical",
              {|(csg union (sphere (center 0 0 3) (radius 1) (color 1 1 1)) (box (min 0 0 0) (max 1 1 1) (color 1 1 1) (texture (file "earth.ppm") (mapping spherical))))|} );
          ];
        (* A closed mesh (a tetrahedron): as an operand, with vt, it takes
           a uv texture of its own or its transform's or use's; without vt
           it is refused as a plain mesh is, at the texture (a mesh form's
           own), or at the object (a use's texture over the solid); a box
           mapping over it is refused at the object. *)
        let tetra = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nf 1/1 3/1 2/1\nf 1/1 2/1 4/1\nf 1/1 4/1 3/1\nf 2/1 3/1 4/1\n" in
        let bare = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n" in
        let read_with mesh text = Scene_file.of_string ~load_texture ~load_mesh:(fun _ -> Ok (obj mesh)) ~file:"s.scene" text in
        let uv_operand = "(csg union " ^ csg_sphere ^ " (mesh (file \"m.obj\") (color 1 1 1) (texture (file \"earth.ppm\") (mapping uv))))" in
        let used mapping =
          "(define d (csg union (mesh (file \"m.obj\") (color 1 1 1)) (mesh (file \"m.obj\") (scale 2) (color 1 1 1))))\n"
          ^ "(use d (color 1 1 1) (texture (file \"earth.ppm\") (mapping " ^ mapping ^ ")))"
        in
        List.iter
          (fun text -> match read_with tetra text with Ok _ -> () | Error (`Msg m) -> Alcotest.failf "%s: %s" text m)
          [ uv_operand; "(transform ((rotate-y 30)) " ^ uv_operand ^ ")"; used "uv" ];
        List.iter
          (fun (mesh, text, expected) ->
            match read_with mesh text with
            | Ok _ -> Alcotest.failf "accepted %S" text
            | Error (`Msg m) -> Alcotest.(check string) __LOC__ expected m)
          [
            ( bare, uv_operand,
              "s.scene:1:145: mesh texture mapping uv needs the file's texture coordinates (vt and f v/vt), which m.obj does not give" );
            ( bare, used "uv",
              "s.scene:2:1: its texture lies on its object's surfaces: csg: mesh texture mapping uv needs the mesh's texture coordinates (vt), which it has none of" );
            (tetra, used "spherical", "s.scene:2:1: its texture lies on its object's surfaces: csg: mesh texture mapping must be uv, got spherical");
          ];
        Alcotest.(check string) __LOC__ "s.scene:1:90: sphere has a pattern and a texture; a material's colour comes from one of them"
          (read_error
             {|(sphere (center 0 0 3) (radius 1) (color 1 1 1) (pattern checker (color 0 0 0) (size 1)) (texture (file "earth.ppm") (mapping spherical)))|});
        (* A missing file is told first, at its name. *)
        Alcotest.(check string) __LOC__ "s.scene:1:58: cannot read texture file: no.ppm: No such file or directory"
          (read_error {|(sphere (center 0 0 3) (radius 1) (color 1 1 1) (texture (file "no.ppm") (mapping spherical)))|}));
    Alcotest.test_case "texture errors are located: mapping, kind, size, fields" `Quick (fun () ->
        let sphere t = {|(sphere (center 0 0 3) (radius 1) (color 1 1 1) |} ^ t ^ ")" in
        Alcotest.(check string) __LOC__ "s.scene:1:49: sphere texture mapping must be spherical, got planar"
          (read_error (sphere {|(texture (file "earth.ppm") (mapping planar))|}));
        Alcotest.(check string) __LOC__
          "s.scene:1:86: unknown sphere texture mapping sphere; expected spherical, planar, box or uv"
          (read_error (sphere {|(texture (file "earth.ppm") (mapping sphere))|}));
        Alcotest.(check string) __LOC__
          "s.scene:1:78: sphere texture size: only a planar mapping takes a size (one copy of the image per size x size square)"
          (read_error (sphere {|(texture (file "earth.ppm") (size 2) (mapping spherical))|}));
        Alcotest.(check string) __LOC__ "s.scene:1:49: sphere texture is missing its (mapping ...) field"
          (read_error (sphere {|(texture (file "earth.ppm"))|}));
        Alcotest.(check string) __LOC__
          "s.scene:1:60: a triangle takes no texture; textures map onto spheres (spherical), planes (planar), boxes (box) and meshes (uv)"
          (read_error {|(triangle (vertices (0 0 1) (1 0 1) (0 1 1)) (color 1 1 1) (texture (file "earth.ppm") (mapping uv)))|});
        Alcotest.(check string) __LOC__ "s.scene:2:37: plane texture mapping must be planar, got spherical"
          (read_error
             "(material globe (color 1 2 3) (texture (file \"earth.ppm\") (mapping spherical)))\n(plane (point 0 0 0) (normal 0 1 0) (material globe))"));
    Alcotest.test_case "a uv mapping needs the mesh file's texture coordinates" `Quick (fun () ->
        let load_mesh _ = Ok (obj "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n") in
        match
          Scene_file.of_string ~load_texture ~load_mesh ~file:"s.scene"
            {|(mesh (file "m.obj") (color 9 9 9) (texture (file "earth.ppm") (mapping uv)))|}
        with
        | Ok _ -> Alcotest.fail "accepted"
        | Error (`Msg m) ->
            Alcotest.(check string) __LOC__
              "s.scene:1:36: mesh texture mapping uv needs the file's texture coordinates (vt and f v/vt), which m.obj does not give" m);
  ]

(* A textured grid of [n x n] squares, two triangles each, with a vt per
   vertex: over the reader's blocks of 65536 numbers for n = 130. *)
let textured_grid n =
  let b = Buffer.create (1 lsl 20) in
  for j = 0 to n do
    for i = 0 to n do
      Printf.bprintf b "v %d %d 0\nvt %g %g\n" i j (float i /. float n) (float j /. float n)
    done
  done;
  let k i j = (j * (n + 1)) + i + 1 in
  for j = 0 to n - 1 do
    for i = 0 to n - 1 do
      let a = k i j and bb = k (i + 1) j and c = k (i + 1) (j + 1) and d = k i (j + 1) in
      Printf.bprintf b "f %d/%d %d/%d %d/%d\nf %d/-%d %d/%d %d/%d\n" a a bb bb c c a
        (((n + 1) * (n + 1)) - a + 1) c c d d
    done
  done;
  Buffer.contents b

(* [contents] written to a temporary file, read by [Files.read_ppm_texture]
   and by [Files.read_ppm] then [Texture.of_image]: the two results. *)
let both_readers contents =
  let path = Filename.temp_file "texture" ".ppm" in
  Fun.protect
    ~finally:(fun () -> Sys.remove path)
    (fun () ->
      let oc = open_out_bin path in
      output_string oc contents;
      close_out oc;
      let msg r = Result.map_error (fun (`Msg m) -> m) r in
      ( msg (Raytrace_unix.Files.read_ppm_texture path),
        msg (Result.map Texture.of_image (Raytrace_unix.Files.read_ppm path)) ))

let file_tests =
  [
    Alcotest.test_case "a PPM texture read straight into its channels is the image read whole, errors included" `Quick (fun () ->
        let p6 ?(maxval = 255) ?(header = "") w h body = Printf.sprintf "P6\n%s%d %d\n%d\n%s" header w h maxval body in
        let pixels n = String.init (3 * n) (fun k -> Char.chr ((k * 37) mod 256)) in
        let small = String.init 12 (fun k -> Char.chr (k * 9)) in
        let below m n = String.init (3 * n) (fun k -> Char.chr ((k * 37) mod m)) in
        List.iter
          (fun (what, contents) ->
            match both_readers contents with
            | Ok a, Ok b -> if not (Texture.equal a b) then Alcotest.failf "%s: the textures differ" what
            | Error a, Error b -> Alcotest.(check string) what b a
            | Ok _, Error m -> Alcotest.failf "%s: only the whole read failed: %s" what m
            | Error m, Ok _ -> Alcotest.failf "%s: only the direct read failed: %s" what m)
          [
            ("P6 at maxval 255", p6 64 48 (pixels (64 * 48)));
            (* 1.5 MB of pixels: past the first read's room of 1 MiB + 4
               KiB, the rest read in chunks of 64 KiB, the last one short. *)
            ("P6 past the first read, in chunks", p6 701 701 (pixels (701 * 701)));
            ("P6 past the first read at maxval 200, scaled", p6 ~maxval:200 701 701 (below 201 (701 * 701)));
            ("a sample above maxval in the last chunk", p6 ~maxval:200 701 701 (below 201 ((701 * 701) - 1) ^ "\201\000\000"));
            ("P6 at maxval 100, scaled", p6 ~maxval:100 2 2 small);
            ("a P6 sample above maxval", p6 ~maxval:50 2 2 small);
            ("a commented header", p6 ~header:"# made by hand\n# twice\n" 64 48 (pixels (64 * 48)));
            (* A header longer than the first read's room: read whole. *)
            ("a header of 2 MB of comments", p6 ~header:(String.concat "" (List.init 40000 (fun _ -> "# " ^ String.make 50 'x' ^ "\n"))) 4 4 (pixels 16));
            ("P3", "P3 2 1 255 1 2 3 4 5 6\n");
            ("truncated pixels", p6 64 48 (pixels 100));
            ("unexpected data after the pixels", p6 2 2 (pixels 4 ^ "xx"));
            ("no whitespace after maxval", "P6 1 1 255");
            ("a bad width", "P6 x 1 255\n...");
            ("not a PPM", "P5 1 1 255\n.");
            ("a header cut short", "P6 4 4");
            ("maxval 0", p6 ~maxval:0 1 1 "abc");
          ]);
    Alcotest.test_case "a textured mesh read in two parts is the mesh read whole" `Quick (fun () ->
        let text = textured_grid 130 in
        let max_vertices = 100_000 and max_triangles = 100_000 in
        let whole = match Mesh.Obj.of_string ~name:"g.obj" ~max_vertices ~max_triangles text with
          | Ok m -> m | Error (`Msg e) -> Alcotest.fail e in
        Alcotest.(check int) __LOC__ (2 * 130 * 130 * 3) (Array.length whole.triangle_texcoords);
        (* Cut at line starts in the vertices, in the first and in the
           last faces. *)
        List.iter
          (fun frac ->
            let cut = String.index_from text (String.length text * frac / 10) '\n' + 1 in
            let p = Mesh.Obj.create ~name:"g.obj" ~max_vertices ~max_triangles in
            (match Mesh.Obj.feed p text 0 cut with Ok () -> () | Error (`Msg e) -> Alcotest.fail e);
            match Helpers.obj_part_joined p ~name:"g.obj" ~max_vertices ~max_triangles text cut (String.length text - cut) with
            | None -> Alcotest.failf "not joined at %d" cut
            | Some m -> if not (Mesh.Obj.equal whole m) then Alcotest.failf "cut at %d: the meshes differ" cut)
          [ 1; 3; 5; 9 ]);
    Alcotest.test_case "the command line renders a textured scene (PNG and PPM); a missing or broken file is one located line, exit 1, no image" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let img = Image.create 2 2 in
        Image.set img 0 0 255 0 0;
        (match Raytrace_png.Png_file.write_file (Filename.concat dir "earth.png") img with
        | Ok () -> () | Error (`Msg e) -> Alcotest.fail e);
        let write name text =
          let oc = open_out_bin (Filename.concat dir name) in
          output_string oc text;
          close_out oc
        in
        write "t.ppm" (Image.Ppm.to_string img);
        write "broken.png" "\137PNG\r\n\026\nnot really";
        let run scene texture =
          write "s.scene" ({|(sphere (center 0 0 3) (radius 1) (color 1 1 1) (texture (file "|} ^ texture ^ {|") (mapping spherical)))|});
          let out = Filename.concat dir "out.ppm" in
          let code, _, err = Helpers.run (Helpers.raytrace ()) [ "render"; Filename.concat dir scene; "-o"; out ] in
          (code, String.trim err, Sys.file_exists out)
        in
        let path = Filename.concat dir "s.scene" in
        List.iter
          (fun tex ->
            let code, _, out = run "s.scene" tex in
            Alcotest.(check (pair int bool)) __LOC__ (0, true) (code, out);
            Sys.remove (Filename.concat dir "out.ppm"))
          [ "earth.png"; "t.ppm" ];
        let code, err, out = run "s.scene" "missing.png" in
        Alcotest.(check (triple int string bool)) __LOC__
          (1, "raytrace: " ^ path ^ ":1:58: cannot read texture file: " ^ Filename.concat dir "missing.png" ^ ": No such file or directory", false)
          (code, err, out);
        let code, err, out = run "s.scene" "broken.png" in
        Alcotest.(check (pair int bool)) __LOC__ (1, false) (code, out);
        let prefix = "raytrace: " ^ path ^ ":1:58: cannot read texture file: " in
        if not (String.length err > String.length prefix && String.sub err 0 (String.length prefix) = prefix && not (String.contains err '\n'))
        then Alcotest.failf "not one located line: %S" err;
        (* A CSG solid's mesh operand with a uv texture: drawn through
           the file's vt; a file without them is refused at the texture,
           as a plain mesh's is. *)
        let faces = "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n" in
        write "bare.obj" ("v 0 0 3\nv 1 0 3\nv 0 1 3\nv 0 0 4\n" ^ faces);
        write "tetra.obj" ("v 0 0 3\nv 1 0 3\nv 0 1 3\nv 0 0 4\nvt 0 0\nvt 1 0\nvt 0 1\n"
          ^ "f 1/1 3/3 2/2\nf 1/1 2/2 4/3\nf 1/1 4/3 3/3\nf 2/2 3/3 4/1\n");
        let csg obj =
          write "c.scene"
            ({|(csg union (box (min 5 5 5) (max 6 6 6) (color 1 1 1)) (mesh (file "|} ^ obj
           ^ {|") (color 1 1 1) (texture (file "t.ppm") (mapping uv))))|} ^ "\n(light ambient (intensity 1))");
          let out = Filename.concat dir "out.ppm" in
          let code, _, err = Helpers.run (Helpers.raytrace ()) [ "render"; Filename.concat dir "c.scene"; "-o"; out ] in
          let made = Sys.file_exists out in
          if made then Sys.remove out;
          (code, String.trim err, made)
        in
        (let code, _, made = csg "tetra.obj" in
         Alcotest.(check (pair int bool)) __LOC__ (0, true) (code, made));
        Alcotest.(check (triple int string bool)) __LOC__
          ( 1,
            "raytrace: " ^ Filename.concat dir "c.scene"
            ^ ":1:94: mesh texture mapping uv needs the file's texture coordinates (vt and f v/vt), which bare.obj does not give",
            false )
          (csg "bare.obj"));
    Alcotest.test_case "a scene built in code with a texture is valid where its mapping fits the object" `Quick (fun () ->
        let ball t = Shape.Sphere (Sphere.v ~center:(v 0. 0. 3.) ~radius:1. (Material.v ~texture:t (Color.v 1. 1. 1.))) in
        let valid t = Scene.validate (Scene.v ~objects:[ ball t ] ~lights:[] ()) in
        Alcotest.(check bool) __LOC__ true (Result.is_ok (valid (Texture_map.v ~file:"e.ppm" Spherical quad)));
        match valid (Texture_map.v ~file:"e.ppm" Planar quad) with
        | Ok _ -> Alcotest.fail "a planar texture on a sphere passed"
        | Error (`Msg m) -> Alcotest.(check bool) __LOC__ true (Astring_free.contains m "texture mapping must be spherical"));
    Alcotest.test_case "a material with a texture is not plain; pp prints the field" `Quick (fun () ->
        let t = Texture_map.v ~file:"a b.ppm" Planar quad ~size:0.5 in
        let m = Material.v ~texture:t (Color.v 1. 2. 3.) in
        Alcotest.(check bool) __LOC__ false (Material.same_plain m m);
        Alcotest.(check string) __LOC__ {|(color 1 2 3) (texture (file "a b.ppm") (mapping planar) (size 0.5))|} (Material.show m);
        Alcotest.(check bool) __LOC__ true (Material.equal m (Material.update ~texture:(Some t) m));
        Alcotest.(check bool) __LOC__ false (Material.equal m (Material.update ~texture:None m)));
  ]

let tests = texture_tests @ mapping_tests @ obj_tests @ scene_tests @ file_tests
