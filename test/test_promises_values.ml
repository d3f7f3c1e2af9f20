(* The promises of the value, colour, camera, light, material and image
   interfaces ([lib/*.mli]) that no other suite asserted: each case names
   the promise and checks it on values whose results are exact in floats
   (or whole numbers of bytes), so that the expected value is the promise
   itself. The geometry and optics interfaces are in {!Test_promises}. *)
open Raytrace

let v = Vec3.v
let ok = function Ok x -> x | Error (`Msg m) -> Alcotest.fail m
let error what = function Ok _ -> Alcotest.failf "%s: accepted" what | Error (`Msg m) -> m
let refused what r = ignore (error what r)
let raises_invalid what f = match f () with _ -> Alcotest.failf "%s: no Invalid_argument" what | exception Invalid_argument _ -> ()
let exact = Alcotest.float 0.
let white_material = Material.v Color.white

let contains ~sub s =
  let n = String.length sub in
  let rec at i = i + n <= String.length s && (String.sub s i n = sub || at (i + 1)) in
  at 0

let is_nan what x = if not (Float.is_nan x) then Alcotest.failf "%s: %h is not nan" what x

let vec3_tests =
  [
    Alcotest.test_case "Vec3.unit of the zero vector is nan in every coordinate, never a finite direction" `Quick
      (fun () ->
        let u = Vec3.unit Vec3.zero in
        is_nan "x" u.x;
        is_nan "y" u.y;
        is_nan "z" u.z;
        Alcotest.(check bool) "is_finite" false (Vec3.is_finite u));
    Alcotest.test_case "Vec3.is_finite is false for any nan or infinite coordinate, true otherwise" `Quick (fun () ->
        List.iter
          (fun (what, p, expected) -> Alcotest.(check bool) what expected (Vec3.is_finite p))
          [ ("finite", v max_float (-.max_float) 0., true); ("nan x", v nan 0. 0., false); ("inf y", v 0. infinity 0., false);
            ("-inf z", v 0. 0. neg_infinity, false) ]);
    Alcotest.test_case "Vec3.compare is lexicographic x, y, z with Float.compare" `Quick (fun () ->
        Alcotest.(check int) "x first" (-1) (Vec3.compare (v 0. 9. 9.) (v 1. 0. 0.));
        Alcotest.(check int) "then y" 1 (Vec3.compare (v 1. 2. 0.) (v 1. 1. 9.));
        Alcotest.(check int) "then z" (-1) (Vec3.compare (v 1. 1. (-1.)) (v 1. 1. 0.));
        Alcotest.(check int) "equal" 0 (Vec3.compare (v 1. 2. 3.) (v 1. 2. 3.));
        (* Float.compare: nan equals itself and is below everything. *)
        Alcotest.(check int) "nan = nan" 0 (Vec3.compare (v nan 0. 0.) (v nan 0. 0.));
        Alcotest.(check int) "nan < -inf" (-1) (Vec3.compare (v nan 0. 0.) (v neg_infinity 0. 0.)));
    Alcotest.test_case "Vec3.dot sums x, then y, then z: the rounding of that order" `Quick (fun () ->
        (* (1e16 + 1) - 1e16 = 0 in floats (1e16 + 1 rounds to 1e16), while
           1e16 + (1 - 1e16) = 2: only the order x, y, z gives 0. *)
        Alcotest.check exact "x + y + z" 0. (Vec3.dot (v 1e16 1. (-1e16)) (v 1. 1. 1.)));
    Alcotest.test_case "Vec3.pp and pp_components write (x y z) and x y z, shortest round-trip decimals" `Quick
      (fun () ->
        Alcotest.(check string) "pp" "(1 -2.5 0.1)" (Vec3.show (v 1. (-2.5) 0.1));
        Alcotest.(check string) "pp_components" "1 -2.5 0.1" (Format.asprintf "%a" Vec3.pp_components (v 1. (-2.5) 0.1));
        Alcotest.(check (triple exact exact exact)) "to_tuple" (1., 2., 3.) (Vec3.to_tuple (Vec3.of_tuple (1., 2., 3.))));
  ]

let color_tests =
  [
    Alcotest.test_case "Color.in_gamut is [0, 255] inclusive, never nan" `Quick (fun () ->
        List.iter
          (fun (what, c, expected) -> Alcotest.(check bool) what expected (Color.in_gamut c))
          [ ("black", Color.black, true); ("white", Color.white, true); ("-0.", Color.v (-0.) 0. 0., true);
            ("255.5", Color.v 0. 255.5 0., false); ("-1", Color.v 0. 0. (-1.), false); ("nan", Color.v nan 0. 0., false);
            ("infinity", Color.v infinity 0. 0., false) ]);
    Alcotest.test_case "Color.is_finite is false for a nan or infinite channel, true for any finite one" `Quick
      (fun () ->
        Alcotest.(check bool) "unclamped" true (Color.is_finite (Color.v (-1e300) 1e300 0.));
        Alcotest.(check bool) "nan" false (Color.is_finite (Color.v 0. nan 0.));
        Alcotest.(check bool) "inf" false (Color.is_finite (Color.v 0. 0. neg_infinity)));
    Alcotest.test_case "Color.blend is local (1 - r) + reflected r, unclamped" `Quick (fun () ->
        (* r = 0.25: 100 * 0.75 + 200 * 0.25 = 125; 400 * 0.75 + 0 = 300
           (stays above 255); 8 * 0.75 + 16 * 0.25 = 10. *)
        let c = Color.blend ~reflective:0.25 ~local:(Color.v 100. 400. 8.) ~reflected:(Color.v 200. 0. 16.) in
        Alcotest.(check bool) (Color.show c) true (Color.equal c (Color.v 125. 300. 10.));
        let same = Color.blend ~reflective:0. ~local:(Color.v 1. 2. 3.) ~reflected:(Color.v nan nan nan) in
        Alcotest.(check bool) "r = 0 still multiplies: nan * 0 is nan" true (Float.is_nan same.r));
    Alcotest.test_case "Color.to_byte: infinities clamp to 0 and 255, 254.5 rounds to 254, 0.5 to 0" `Quick (fun () ->
        List.iter
          (fun (x, b) -> Alcotest.(check int) (Printf.sprintf "%h" x) b (Color.to_byte x))
          [ (infinity, 255); (neg_infinity, 0); (254.5, 254); (0.5, 0); (1.5, 2); (255., 255); (-0., 0) ]);
    Alcotest.test_case "Color.pp writes (r g b), pp_components r g b" `Quick (fun () ->
        Alcotest.(check string) "pp" "(255 0.5 0)" (Color.show (Color.v 255. 0.5 0.));
        Alcotest.(check string) "components" "255 0.5 0" (Format.asprintf "%a" Color.pp_components (Color.v 255. 0.5 0.)));
  ]

let viewport_camera_tests =
  [
    Alcotest.test_case "Viewport.of_canvas_f on whole coordinates is of_canvas, bit for bit" `Quick (fun () ->
        let vp = Viewport.v ~width:1.5 ~height:0.75 ~distance:2. in
        List.iter
          (fun (gw, gh, x, y) ->
            let a = Viewport.of_canvas vp ~canvas_width:gw ~canvas_height:gh x y in
            let b = Viewport.of_canvas_f vp ~canvas_width:gw ~canvas_height:gh (float x) (float y) in
            if not (Vec3.equal_f (fun a b -> Int64.equal (Int64.bits_of_float a) (Int64.bits_of_float b)) a b) then
              Alcotest.failf "%d x %d at (%d, %d): %s and %s" gw gh x y (Vec3.show a) (Vec3.show b))
          [ (600, 600, -300, 299); (7, 3, 3, -1); (601, 333, 0, 0); (1, 1, 0, 0); (640, 480, -17, 101) ]);
    Alcotest.test_case "Viewport.of_canvas multiplies before dividing: 1 * 0.1 / 3, not 1 * (0.1 / 3)" `Quick (fun () ->
        (* G_x V_w / G_w with G_x = 1, V_w = 0.1, G_w = 3. *)
        let vp = Viewport.v ~width:0.1 ~height:1. ~distance:1. in
        let p = Viewport.of_canvas vp ~canvas_width:3 ~canvas_height:1 1 0 in
        Alcotest.check exact "V_x" (1. *. 0.1 /. 3.) p.x;
        Alcotest.check exact "V_z = d" 1. p.z);
    Alcotest.test_case "Viewport.validate refuses a zero, negative, nan or infinite dimension, naming it" `Quick
      (fun () ->
        ignore (ok (Viewport.validate Viewport.default));
        List.iter
          (fun (what, vp) ->
            let m = error what (Viewport.validate vp) in
            let name = List.hd (String.split_on_char ' ' what) in
            if not (contains ~sub:name m) then Alcotest.failf "%s: %S does not name it" what m)
          [ ("width 0", (Viewport.v ~width:0. ~height:1. ~distance:1.)); ("height -1", (Viewport.v ~width:1. ~height:(-1.) ~distance:1.));
            ("distance nan", (Viewport.v ~width:1. ~height:1. ~distance:nan)); ("width inf", (Viewport.v ~width:infinity ~height:1. ~distance:1.)) ]);
    Alcotest.test_case "Camera.direction is M v, each row dotted with v" `Quick (fun () ->
        (* rows (1 2 3) (0 1 0) (-1 0 2) times (1, -1, 2) = (5, -1, 3). *)
        let m = Camera.{ row0 = Vec3.v 1. 2. 3.; row1 = Vec3.v 0. 1. 0.; row2 = Vec3.v (-1.) 0. 2. } in
        Alcotest.check Helpers.vec3 "M v" (v 5. (-1.) 3.) (Camera.direction (Camera.v ~rotation:m Vec3.zero) (v 1. (-1.) 2.));
        Alcotest.check exact "det = 1 * 2 - 2 * 0 + 3 * 1" 5. (Camera.determinant m));
    Alcotest.test_case "Camera.look_at's matrix is orthonormal, with up in the picture's upper half" `Quick (fun () ->
        let cam = ok (Camera.look_at ~up:(v 1. 1. 0.) ~position:(v 1. 2. 3.) (v (-2.) 0. 7.)) in
        let r = cam.rotation in
        (* The columns of M are the camera's right, up and forward: M^T M = I
           means the rows are orthonormal too. *)
        let rows = [ r.row0; r.row1; r.row2 ] in
        List.iteri
          (fun i a ->
            List.iteri
              (fun j b -> Alcotest.(check (float 1e-15)) (Printf.sprintf "<row%d, row%d>" i j) (if i = j then 1. else 0.) (Vec3.dot a b))
              rows)
          rows;
        Alcotest.(check (float 1e-15)) "det" 1. (Camera.determinant r);
        let up = Camera.direction cam Vec3.oy in
        Alcotest.(check bool) "up . (1, 1, 0) > 0" true (Vec3.dot up (v 1. 1. 0.) > 0.));
    Alcotest.test_case "Camera.check_rotation refuses nan and infinite entries; validate checks the position" `Quick
      (fun () ->
        let m = Camera.identity in
        refused "nan" (Camera.check_rotation { m with row1 = v 0. nan 0. });
        refused "inf" (Camera.check_rotation { m with row2 = v 0. 0. infinity });
        refused "position nan" (Camera.validate (Camera.v (v nan 0. 0.)));
        refused "position beyond the limit" (Camera.validate (Camera.v (v 1e300 0. 0.)));
        ignore (ok (Camera.validate (Scene.camera Scene.cgfs_camera))));
    Alcotest.test_case "Camera.pp leaves out an identity rotation and writes any other" `Quick (fun () ->
        let plain = Camera.show (Camera.v (v 1. 2. 3.)) in
        let turned = Camera.show (Scene.camera Scene.cgfs_camera) in
        Alcotest.(check bool) plain false (contains ~sub:"rotation" plain);
        Alcotest.(check bool) turned true (contains ~sub:"(rotation (0.7071 0 -0.7071) (0 1 0) (0.7071 0 0.7071))" turned));
  ]

(* Minor words allocated by [n] rounds of [f] (after one to warm up). *)
let words_of n f =
  f ();
  let before = Gc.minor_words () in
  for _ = 1 to n do
    f ()
  done;
  Gc.minor_words () -. before

let limits_light_material_tests =
  [
    Alcotest.test_case "Limits: coordinates up to 1e12 and sizes from 1e-30 pass, the next floats and nan do not" `Quick
      (fun () ->
        let above = Float.succ Limits.max_coordinate and below = Float.pred Limits.min_size in
        List.iter
          (fun (what, x, coordinate, size) ->
            Alcotest.(check bool) ("coordinate_ok " ^ what) coordinate (Limits.coordinate_ok x);
            Alcotest.(check bool) ("check_coordinate " ^ what) coordinate (Result.is_ok (Limits.check_coordinate "x" x));
            Alcotest.(check bool) ("size_ok " ^ what) size (Limits.size_ok x);
            Alcotest.(check bool) ("check_size " ^ what) size (Result.is_ok (Limits.check_size "radius" x)))
          [ ("1e12", 1e12, true, true); ("-1e12", -1e12, true, false); ("succ 1e12", above, false, false);
            ("-succ 1e12", -.above, false, false); ("1e-30", 1e-30, true, true); ("pred 1e-30", below, true, false);
            ("0", 0., true, false); ("nan", nan, false, false); ("infinity", infinity, false, false) ];
        let m = error "sphere radius" (Limits.check_size "sphere radius" 0.) in
        if not (contains ~sub:"sphere radius" m) then Alcotest.failf "%S does not name the sphere radius" m);
    Alcotest.test_case "Limits.coordinate_ok and size_ok allocate nothing" `Quick (fun () ->
        let xs = [ 1.; -1e12; nan; 1e-31; infinity; 0.5 ] in
        let count = ref 0 in
        let f x = if Limits.coordinate_ok x && Limits.size_ok x then incr count in
        let words = words_of 10_000 (fun () -> List.iter f xs) in
        if words > 50. then Alcotest.failf "%.0f minor words for 120000 checks" words);
    Alcotest.test_case "Limits.of_lookup reads 1_000 and 1e13, ignores empty text, names the first bad variable" `Quick
      (fun () ->
        let lookup env name = List.assoc_opt name env in
        let l = ok (Limits.of_lookup (lookup [ ("RAYTRACE_MAX_PIXELS", "1_000"); ("RAYTRACE_MAX_WORK", "1e13"); ("RAYTRACE_MAX_DEPTH", "") ])) in
        Alcotest.check exact "pixels" 1000. (Limits.bound l `Pixels);
        Alcotest.check exact "work" 1e13 (Limits.bound l `Work);
        Alcotest.check exact "depth: empty is the default" (float Limits.max_depth) (Limits.bound l `Depth);
        List.iter
          (fun value ->
            let m = error value (Limits.of_lookup (lookup [ ("RAYTRACE_MAX_LIGHTS", value) ])) in
            if not (contains ~sub:"RAYTRACE_MAX_LIGHTS" m) then Alcotest.failf "%S: %S does not name the variable" value m)
          [ "-1"; "0"; "ten"; "1.5"; "nan" ]);
    Alcotest.test_case "Limits.exceeded says the value, the bound and the variable that raises it" `Quick (fun () ->
        Alcotest.(check string) "pixels"
          "canvas 70000x70000 has 4900000000 pixels, more than the limit of 268435456 (set RAYTRACE_MAX_PIXELS to raise it)"
          (Limits.exceeded Limits.default `Pixels "canvas 70000x70000 has 4900000000 pixels"));
    Alcotest.test_case "Limits.check_image_size never overflows: max_int x max_int pixels is an error" `Quick (fun () ->
        refused "max_int^2" (Limits.check_image_size Limits.default max_int max_int);
        refused "0 wide" (Limits.check_image_size Limits.default 0 5);
        (* No max_dimension for files: 100000 x 1 is 100000 pixels. *)
        ignore (ok (Limits.check_image_size Limits.default 100_000 1));
        refused "canvas 100000 wide" (Limits.check_canvas Limits.default 100_000 1);
        let small = Limits.with_bound Limits.default `Pixels 12. in
        ignore (ok (Limits.check_canvas small 3 4));
        refused "13 pixels" (Limits.check_canvas small 13 1));
    Alcotest.test_case "Limits.check_jobs is [1, 1024]; check_depth [0, the bound]" `Quick (fun () ->
        Alcotest.(check (list bool)) "jobs 0, 1, 1024, 1025" [ false; true; true; false ]
          (List.map (fun n -> Result.is_ok (Limits.check_jobs n)) [ 0; 1; 1024; 1025 ]);
        Alcotest.(check (list bool)) "depth -1, 0, 64, 65" [ false; true; true; false ]
          (List.map (fun n -> Result.is_ok (Limits.check_depth Limits.default n)) [ -1; 0; 64; 65 ]));
    Alcotest.test_case "Light.check_intensity is [0, 1e6]: -1, nan and the float above 1e6 are refused" `Quick (fun () ->
        Alcotest.(check (list bool)) "0, 1e6, -1, succ 1e6, nan, infinity" [ true; true; false; false; false; false ]
          (List.map (fun i -> Result.is_ok (Light.check_intensity i)) [ 0.; 1e6; -1.; Float.succ 1e6; nan; infinity ]));
    Alcotest.test_case "Light.validate refuses a zero, tiny or nan direction and a point light beyond the limit" `Quick
      (fun () ->
        refused "zero" (Light.validate (Light.directional 0.5 Vec3.zero));
        refused "1e-31 long" (Light.validate (Light.directional 0.5 (v 1e-31 0. 0.)));
        refused "nan" (Light.validate (Light.directional 0.5 (v nan 1. 0.)));
        refused "position 2e12" (Light.validate (Light.point 0.5 (v 0. 2e12 0.)));
        refused "intensity" (Light.validate (Light.ambient (-0.5)));
        ignore (ok (Light.validate (Light.directional 0.5 (v 0. 1e-20 0.)))));
    Alcotest.test_case "Material.v's defaults are the sphere's: matte, no mirror, opaque, index 1, no Fresnel, no pattern"
      `Quick (fun () ->
        let m = Material.v (Color.v 1. 2. 3.) in
        Alcotest.check exact "specular" Sphere.matte m.specular;
        Alcotest.(check (list (float 0.))) "reflective, transparency, index" [ 0.; 0.; 1. ] [ m.reflective; m.transparency; m.refractive_index ];
        Alcotest.(check bool) "fresnel" false m.fresnel;
        Alcotest.(check bool) "pattern" true (m.pattern = None);
        Alcotest.(check string) "pp writes the colour only" "(color 1 2 3)" (Material.show m));
    Alcotest.test_case "Material.same_plain: bit for bit (0. differs from -0.), never with a pattern; Plain finds by it"
      `Quick (fun () ->
        let a = Material.v ~reflective:0. Color.white and b = Material.v ~reflective:(-0.) Color.white in
        Alcotest.(check bool) "equal" true (Material.equal a b);
        Alcotest.(check bool) "0. and -0." false (Material.same_plain a b);
        Alcotest.(check bool) "itself" true (Material.same_plain a (Material.v Color.white));
        let p = Material.v ~pattern:(Pattern.checker ~size:1. Color.black) Color.white in
        Alcotest.(check bool) "a pattern" false (Material.same_plain p p);
        let t = Material.Plain.create 4 in
        Material.Plain.replace t a 1;
        Alcotest.(check (option int)) "found" (Some 1) (Material.Plain.find_opt t (Material.v Color.white));
        Alcotest.(check (option int)) "-0. not found" None (Material.Plain.find_opt t b));
    Alcotest.test_case "Material.validate and Pattern.validate name the form in their messages" `Quick (fun () ->
        let starts what prefix m =
          if not (String.length m >= String.length prefix && String.sub m 0 (String.length prefix) = prefix) then
            Alcotest.failf "%s: %S does not start with %S" what m prefix
        in
        starts "colour" "plane color channels must lie in [0, 255], got"
          (error "colour" (Material.validate ~form:"plane" (Material.v (Color.v 256. 0. 0.))));
        refused "split" (Material.validate ~form:"box" (Material.v ~reflective:0.6 ~transparency:0.5 Color.white));
        refused "index 0" (Material.validate ~form:"box" (Material.v ~refractive_index:0. Color.white));
        Alcotest.(check string) "pattern size" "sphere pattern size must be > 0, got 0"
          (error "size" (Pattern.check_size ~form:"sphere" 0.));
        let m = error "pattern colour" (Pattern.validate ~form:"triangle" (Pattern.checker ~size:1. (Color.v 0. (-1.) 0.))) in
        starts "pattern colour" "triangle" m;
        let m = error "material's pattern" (Material.validate ~form:"mesh" (Material.v ~pattern:(Pattern.checker ~size:nan Color.black) Color.white)) in
        starts "material's pattern" "mesh" m);
  ]

let region = Alcotest.testable Render.Region.pp Render.Region.equal

let image_tests =
  [
    Alcotest.test_case "Render.Region.contains: non-empty and inside the canvas; pixels is w h; pp_corners is x0 y0 x1 y1" `Quick
      (fun () ->
        let r x y w h = Render.Region.v ~x ~y ~w ~h in
        List.iter
          (fun (what, reg, expected) -> Alcotest.(check bool) what expected (Render.Region.contains reg ~width:10 ~height:5))
          [ ("whole", r 0 0 10 5, true); ("corner pixel", r 9 4 1 1, true); ("empty", r 2 2 0 1, false);
            ("one column too wide", r 1 0 10 5, false); ("one row too low", r 0 1 10 5, false); ("x = -1", r (-1) 0 2 2, false) ];
        Alcotest.(check int) "pixels" 15 (Render.Region.pixels (r 1 2 5 3));
        Alcotest.(check string) "pp_corners" "0 86 600 172" (Format.asprintf "%a" Render.Region.pp_corners (r 0 86 600 86));
        let back = ok (Render.Region.of_corners ~width:600 ~height:600 0 86 600 172) in
        Alcotest.check region "of_corners reads pp_corners back" (r 0 86 600 86) back);
    Alcotest.test_case "Image: create, of_buffer, get, set, blit and sub raise Invalid_argument outside their domain"
      `Quick (fun () ->
        raises_invalid "create 0 1" (fun () -> Image.create 0 1);
        raises_invalid "create 1 -1" (fun () -> Image.create 1 (-1));
        let buffer n = Bigarray.(Array1.create int8_unsigned c_layout n) in
        raises_invalid "of_buffer 2 x 2 of 11 bytes" (fun () -> Image.of_buffer 2 2 (buffer 11));
        raises_invalid "of_buffer 2 x 2 of 13 bytes" (fun () -> Image.of_buffer 2 2 (buffer 13));
        let img = Image.create 3 2 in
        List.iter
          (fun (x, y) ->
            raises_invalid (Printf.sprintf "get %d %d" x y) (fun () -> Image.get img x y);
            raises_invalid (Printf.sprintf "set %d %d" x y) (fun () -> Image.set img x y 0 0 0))
          [ (-1, 0); (3, 0); (0, -1); (0, 2) ];
        raises_invalid "set 256" (fun () -> Image.set img 0 0 0 256 0);
        raises_invalid "set -1" (fun () -> Image.set img 0 0 0 0 (-1));
        Alcotest.(check (triple int int int)) "a refused set changes nothing" (0, 0, 0) (Image.get img 0 0);
        raises_invalid "blit 2 x 2 at (2, 0)" (fun () -> Image.blit ~src:(Image.create 2 2) ~dst:img ~x:2 ~y:0);
        raises_invalid "blit at (0, -1)" (fun () -> Image.blit ~src:(Image.create 1 1) ~dst:img ~x:0 ~y:(-1));
        raises_invalid "sub 2 x 2 at (0, 1)" (fun () -> Image.sub img ~x:0 ~y:1 ~w:2 ~h:2);
        raises_invalid "sub 0 wide" (fun () -> Image.sub img ~x:0 ~y:0 ~w:0 ~h:1));
    Alcotest.test_case "Image: of_buffer shares, copy and sub do not; blit puts src's top-left at (x, y); channel k is \
                        pixel k / 3's channel k mod 3" `Quick (fun () ->
        let buf = Bigarray.(Array1.create int8_unsigned c_layout 12) in
        Bigarray.Array1.fill buf 0;
        let img = Image.of_buffer 2 2 buf in
        Image.set img 1 0 10 20 30;
        Alcotest.(check int) "set wrote the buffer: byte 3 * 1 + 1" 20 buf.{4};
        Alcotest.(check int) "channel 5" 30 (Image.channel img 5);
        let c = Image.copy img and part = Image.sub img ~x:1 ~y:0 ~w:1 ~h:2 in
        Alcotest.(check bool) "copy equal" true (Image.equal c img);
        Image.set img 1 0 0 0 0;
        Alcotest.(check (triple int int int)) "copy kept" (10, 20, 30) (Image.get c 1 0);
        Alcotest.(check (triple int int int)) "sub kept" (10, 20, 30) (Image.get part 0 0);
        let dst = Image.create 3 3 in
        Image.blit ~src:c ~dst ~x:1 ~y:1;
        Alcotest.(check (triple int int int)) "(1, 0) of src is (2, 1) of dst" (10, 20, 30) (Image.get dst 2 1);
        Alcotest.(check (triple int int int)) "outside the blit" (0, 0, 0) (Image.get dst 2 0);
        Alcotest.(check bool) "1 x 2 and 2 x 1 black images differ" false (Image.equal (Image.create 1 2) (Image.create 2 1)));
    Alcotest.test_case "Ppm: a comment with a line break raises; header is to_string up to the pixels; header_comments \
                        reads the comments back" `Quick (fun () ->
        let img = Image.create 2 1 in
        Image.set img 1 0 1 2 3;
        raises_invalid "to_string" (fun () -> Image.Ppm.to_string ~comments:[ "a\nb" ] img);
        raises_invalid "header" (fun () -> Image.Ppm.header ~comments:[ "a\rb" ] img);
        let comments = [ "made by raytrace"; " two spaces"; "" ] in
        let text = Image.Ppm.to_string ~comments img in
        Alcotest.(check string) "the bytes" "P6\n# made by raytrace\n#  two spaces\n# \n2 1\n255\n\000\000\000\001\002\003" text;
        let header = Image.Ppm.header ~comments img in
        Alcotest.(check string) "header" (String.sub text 0 (String.length text - 6)) header;
        Alcotest.(check (list string)) "header_comments" comments (Image.Ppm.header_comments text);
        Alcotest.(check (list string)) "not a PPM" [] (Image.Ppm.header_comments "P5\n# x\n1 1\n255\n\000");
        Alcotest.(check bool) "reads back" true (Image.equal img (ok (Image.Ppm.of_string text))));
    Alcotest.test_case "Image.Ppm.of_string never raises: every prefix of a file cut inside its data is an Error, the file is Ok" `Quick
      (fun () ->
        let img = Image.create 3 2 in
        Image.set img 2 1 255 128 7;
        List.iter
          (fun text ->
            (* A P3 file's last sample ends at its last digit: the line end
               after it is optional. *)
            let complete = String.length (String.trim text) in
            for n = 0 to String.length text do
              let prefix = String.sub text 0 n in
              match Image.Ppm.of_string prefix with
              | Ok back -> if n < complete || not (Image.equal back img) then Alcotest.failf "%S read" prefix
              | Error _ -> if n = String.length text then Alcotest.failf "the whole file %S refused" text
              | exception e -> Alcotest.failf "%S raised %s" prefix (Printexc.to_string e)
            done)
          [ Image.Ppm.to_string ~comments:[ "c" ] img; "P3\n3 2\n255\n0 0 0 0 0 0 0 0 0\n0 0 0 0 0 0 255 128 7\n" ]);
    Alcotest.test_case "Image.Ppm.check_file_size allows 3 bytes a pixel plus 1 MiB, and names the variable beyond" `Quick
      (fun () ->
        let limits = Limits.with_bound Limits.default `Pixels 100. in
        let bound = (3 * 100) + (1024 * 1024) in
        Alcotest.(check int) "at the bound" bound (ok (Image.Ppm.check_file_size ~limits bound));
        let m = error "a byte more" (Image.Ppm.check_file_size ~limits (bound + 1)) in
        if not (contains ~sub:"RAYTRACE_MAX_PIXELS" m) then Alcotest.failf "%S does not name RAYTRACE_MAX_PIXELS" m);
    Alcotest.test_case "Image.Ppm.output_rows refuses rows outside 0 <= first <= stop <= height" `Quick (fun () ->
        let img = Image.create 2 3 in
        let dev_null = open_out_bin Filename.null in
        Fun.protect ~finally:(fun () -> close_out dev_null) (fun () ->
            List.iter
              (fun (first, stop) ->
                raises_invalid (Printf.sprintf "rows %d to %d" first stop) (fun () -> Image.Ppm.output_rows dev_null img ~first ~stop))
              [ (-1, 1); (2, 1); (0, 4) ];
            Image.Ppm.output_rows dev_null img ~first:3 ~stop:3));
    Alcotest.test_case "Image.Diff.compare of images of different sizes is an Error; pp_summary is one line of the figures"
      `Quick (fun () ->
        refused "2 x 1 and 1 x 2" (Image.Diff.compare (Image.create 2 1) (Image.create 1 2));
        let a = Image.create 2 1 and b = Image.create 2 1 in
        Image.set b 1 0 0 0 3;
        let d = ok (Image.Diff.compare a b) in
        let line = Format.asprintf "%a" Image.Diff.pp_summary d in
        let prefix = "pixels=2 differing=1 differing_gt1=1 max_abs=3 mean_abs=0.5" in
        if not (String.length line >= String.length prefix && String.sub line 0 (String.length prefix) = prefix) then
          Alcotest.failf "%S" line;
        Alcotest.(check bool) "one line" false (String.contains line '\n');
        Alcotest.(check bool) "psnr" true (contains ~sub:" psnr=" line));
    Alcotest.test_case "Render.Stats.rays is primary + shadow + reflection; pp_table of no time and no pixel has no nan or inf" `Quick (fun () ->
        let s =
          Render.Stats.{ pixels = 1; primary = 3; shadow = 50; reflection = 700; tests = 9; box_tests = 9; early_stops = 9; decided = 0; penumbra = 0; umbra = 0; whole = 0; jobs = 1;
                  prepare_s = 0.; trace_s = 0.; minor_words = 0. }
        in
        Alcotest.(check int) "rays" 753 (Render.Stats.rays s);
        (* No time and no pixel (a render of nothing, a clock too coarse):
           the table shows "-" and 0, never nan or inf. *)
        let table = Format.asprintf "%a" Render.Stats.pp_table { s with pixels = 0; trace_s = 0.; minor_words = 5. } in
        List.iter
          (fun bad -> if contains ~sub:bad table then Alcotest.failf "%S in\n%s" bad table)
          [ "nan"; "inf" ];
        Alcotest.(check bool) "rays per second: -" true (contains ~sub:"rays per second          -" table);
        Alcotest.(check bool) "tests per ray: 9 / 753" true (contains ~sub:(Printf.sprintf "%.2f" (9. /. 753.)) table));
  ]

let sphere_at x = Helpers.sphere ~center:(v x 0. 5.) ~radius:1. Color.white

let scene_tests =
  [
    Alcotest.test_case "Helpers.scene is the document's scene: 600 x 600, default viewport and camera, black, depth 3, robust"
      `Quick (fun () ->
        let s = Helpers.scene ~spheres:[] ~lights:[] () in
        Alcotest.(check (pair int int)) "canvas" (600, 600) ((Scene.width s), (Scene.height s));
        Alcotest.(check bool) "viewport" true (Viewport.equal (Scene.viewport s) Viewport.default);
        Alcotest.(check bool) "camera" true (Camera.equal (Scene.camera s) Camera.default);
        Alcotest.(check bool) "background" true (Color.equal (Scene.background s) Color.black);
        Alcotest.(check int) "depth" 3 (Scene.depth s);
        Alcotest.(check bool) "no epsilon, no path, no shapes" true ((Scene.epsilon s) = None && (Scene.camera_path s) = None && (Scene.shapes s) = []));
    Alcotest.test_case "Scene.validate refuses a bad canvas, depth, epsilon, background, viewport or camera" `Quick
      (fun () ->
        let base = Helpers.scene ~spheres:[ sphere_at 0. ] ~lights:[ Light.ambient 1. ] () in
        ignore (ok (Scene.validate base));
        List.iter
          (fun (what, s) -> refused what (Scene.validate s))
          [ ("width 0", (Scene.with_overrides ~width:0 base)); ("height 65537", (Scene.with_overrides ~height:65537 base));
            ("depth -1", (Scene.with_overrides ~depth:(-1) base)); ("depth 65", (Scene.with_overrides ~depth:65 base));
            ("epsilon nan", (Scene.with_overrides ~epsilon:(Some nan) base)); ("epsilon -0.5", (Scene.with_overrides ~epsilon:(Some (-0.5)) base));
            ("background 256", (Scene.with_overrides ~background:(Color.v 0. 256. 0.) base));
            ("background nan", (Scene.with_overrides ~background:(Color.v nan 0. 0.) base));
            ("viewport 0", (Scene.with_overrides ~viewport:(Viewport.v ~width:1. ~height:1. ~distance:0.) base));
            ("camera nan", (Scene.with_overrides ~camera:(Camera.v (v 0. nan 0.)) base));
            ("light", (Scene.with_overrides ~lights:([ Light.point 0.5 (v infinity 0. 0.) ]) base));
            ("sphere radius 0", Helpers.with_objects ~spheres:[ Helpers.sphere ~center:Vec3.zero ~radius:0. Color.white ] base) ];
        ignore (ok (Scene.check_epsilon 0.));
        refused "epsilon infinity" (Scene.check_epsilon infinity);
        ignore (ok (Scene.check_background Color.white)));
    Alcotest.test_case "Scene.override checks what it replaces and keeps the rest" `Quick (fun () ->
        let valid = Helpers.valid Scene.cgfs in
        refused "width 0" (Scene.override ~width:0 valid);
        refused "depth 65" (Scene.override ~depth:65 valid);
        refused "viewport nan" (Scene.override ~viewport:(Viewport.v ~width:nan ~height:1. ~distance:1.) valid);
        refused "singular camera"
          (Scene.override ~camera:(Camera.v ~rotation:{ Camera.identity with row2 = Vec3.ox } Vec3.zero) valid);
        refused "pixels beyond the limits"
          (Scene.override ~limits:(Limits.with_bound Limits.default `Pixels 99.) ~width:10 ~height:10 valid);
        let s = Scene.of_valid (ok (Scene.override ~width:7 ~depth:0 valid)) in
        Alcotest.(check bool) "the rest kept" true
          (Scene.equal s (Scene.with_overrides ~width:7 ~depth:0 Scene.cgfs) && Scene.equal s (Scene.with_overrides ~width:7 ~depth:0 Scene.cgfs)));
    Alcotest.test_case "Scene.grid: sphere i at (i mod k - (k - 1) / 2, i / k - 0.6, 2 k); grid 0 raises" `Quick (fun () ->
        raises_invalid "grid 0" (fun () -> Scene.grid 0);
        (* n = 5: k = 3 (9 >= 5), centers x in {-1, 0, 1}, z = 6; sphere 4 is
           (4 mod 3 - 1, 4 / 3 - 0.6, 6) = (0, 0.4, 6), then the ground. *)
        let s = Scene.grid 5 in
        Alcotest.(check int) "5 spheres and the ground" 6 (Private.Spheres.length (Scene.spheres s));
        let c = (Private.Spheres.get (Scene.spheres s) 4).center in
        Alcotest.check Helpers.vec3 "sphere 4" (v 0. (1. -. 0.6) 6.) c;
        Alcotest.check exact "radius" 0.4 (Private.Spheres.get (Scene.spheres s) 4).radius;
        Alcotest.(check (pair int int)) "800 x 800" (800, 800) ((Scene.width s), (Scene.height s)));
    Alcotest.test_case "Scene.at_frame of a scene without a camera path is an Error" `Quick (fun () ->
        refused "no path" (Scene.at_frame (Helpers.valid Scene.cgfs) 0));
    Alcotest.test_case "Scene_file.to_string then of_string gives the same floats bit for bit: -0., the smallest \
                        subnormal, 1e12, 1e-30, 0.1 + 0.2" `Quick (fun () ->
        let sphere = Helpers.sphere ~center:(v (-0.) 5e-324 1e12) ~radius:1e-30 ~specular:0. ~reflective:(0.1 +. 0.2) (Color.v 254.99999999999997 0. 1e-300) in
        let s =
          Helpers.scene ~width:3 ~height:2 ~epsilon:(-0.) ~background:(Color.v 0.1 (-0.) 255.)
            ~viewport:(Viewport.v ~width:(1. /. 3.) ~height:1e-30 ~distance:1e12)
            ~spheres:[ sphere ] ~lights:[ Light.directional 1e6 (v (-0.) 1e-30 (-1e12)) ] ()
        in
        let text = Scene_file.to_string s in
        let back = Scene.of_valid (ok (Scene_file.of_string text)) in
        Alcotest.(check string) "prints the same" text (Scene_file.to_string back);
        let bits = Alcotest.testable (fun ppf x -> Format.fprintf ppf "%h" x) (fun a b -> Int64.equal (Int64.bits_of_float a) (Int64.bits_of_float b)) in
        let b = Private.Spheres.get (Scene.spheres back) 0 in
        Alcotest.(check (list bits)) "sphere"
          [ -0.; 5e-324; 1e12; 1e-30; 0.; 0.1 +. 0.2; 254.99999999999997; 1e-300 ]
          [ b.center.x; b.center.y; b.center.z; b.radius; b.material.specular; b.material.reflective; b.material.color.r; b.material.color.b ];
        Alcotest.(check (list bits)) "scene" [ -0.; 0.1; -0.; 1. /. 3. ]
          [ Option.get (Scene.epsilon back); (Scene.background back).r; (Scene.background back).g; (Scene.viewport back).width ]);
    Alcotest.test_case "Private.Spheres.append_fields refuses a short array or a bad material and appends nothing; blit_fields \
                        refuses short arrays" `Quick (fun () ->
        let b = Private.Spheres.builder () in
        let m = Private.Spheres.material b (Material.v Color.white) in
        let a n = Array.make n 1. in
        raises_invalid "short radius" (fun () ->
            Private.Spheres.append_fields b ~x:(a 2) ~y:(a 2) ~z:(a 2) ~radius:(a 1) ~material:[| m; m |] 2);
        raises_invalid "material 1" (fun () ->
            Private.Spheres.append_fields b ~x:(a 2) ~y:(a 2) ~z:(a 2) ~radius:(a 2) ~material:[| m; m + 1 |] 2);
        Alcotest.(check int) "nothing appended" 0 (Private.Spheres.builder_length b);
        let s = Private.Spheres.of_list [ sphere_at 1.; sphere_at 2. ] in
        raises_invalid "blit into 1" (fun () ->
            Private.Spheres.blit_fields s ~x:(a 2) ~y:(a 2) ~z:(a 1) ~radius:(a 2) ~material:[| 0; 0 |]);
        let x = a 2 in
        Private.Spheres.blit_fields s ~x ~y:(a 2) ~z:(a 2) ~radius:(a 2) ~material:[| 7; 7 |];
        Alcotest.(check (array (float 0.))) "x" [| 1.; 2. |] x);
    Alcotest.test_case "Render.image refuses bad sampling settings; region_image raises for a region outside the canvas"
      `Quick (fun () ->
        let s = Helpers.valid (Scene.with_overrides ~width:4 ~height:3 Scene.cgfs) in
        refused "samples 0" (Render.image ~samples:0 s);
        refused "adaptive with 2 x 2" (Render.image ~samples:2 ~adaptive:8 s);
        refused "subsampled 2 x 2" (Render.image ~samples:2 ~subsample:true s);
        raises_invalid "5 wide" (fun () -> Render.region_image s (Render.Region.v ~x:0 ~y:0 ~w:5 ~h:1));
        raises_invalid "from row 3" (fun () -> Render.region_image s (Render.Region.v ~x:0 ~y:3 ~w:1 ~h:1));
        let img, _ = ok (Render.region_image s (Render.Region.v ~x:3 ~y:2 ~w:1 ~h:1)) in
        let whole, _ = ok (Render.image s) in
        Alcotest.(check (triple int int int)) "the corner pixel" (Image.get whole 3 2) (Image.get img 0 0));
  ]

(* A scratch holding the ray O + t D and its hit point P with normal N. *)
let scratch_at (o : Vec3.t) (d : Vec3.t) (p : Vec3.t) (n : Vec3.t) =
  let s = Scratch.create () in
  s.ox <- o.x; s.oy <- o.y; s.oz <- o.z;
  s.dx <- d.x; s.dy <- d.y; s.dz <- d.z;
  s.px <- p.x; s.py <- p.y; s.pz <- p.z;
  s.nx <- n.x; s.ny <- n.y; s.nz <- n.z;
  s

let kernel_tests =
  [
    Alcotest.test_case "Pattern.odd: object coordinates (W - origin) / scale; on a boundary, the cell on the ray's side; \
                        it writes nothing and allocates nothing" `Quick (fun () ->
        (* Checker of side 1, object origin (10, 0, 0), scale 2. *)
        let table = Array.make Pattern.stride nan in
        Pattern.store (Pattern.checker ~size:1. Color.black) ~origin:(v 10. 0. 0.) ~scale:2. ~extent:20. table 0;
        let odd o d p n = Pattern.odd (scratch_at o d p n) table 0 in
        let up = v 0. 0. 1. in
        (* (13, 0.5, 0.5) is (1.5, 0.25, 0.25): cell (1, 0, 0), odd;
           (11, 0.5, 0.5) is (0.5, 0.25, 0.25): cell (0, 0, 0), even. *)
        Alcotest.(check bool) "cell (1, 0, 0)" true (odd (v 13. 0.5 (-5.)) up (v 13. 0.5 0.5) up);
        Alcotest.(check bool) "cell (0, 0, 0)" false (odd (v 11. 0.5 (-5.)) up (v 11. 0.5 0.5) up);
        (* The hit point (11, 0.5, 0) lies on the boundary z = 0: seen from
           below, cell (0, 0, -1) (odd), from above cell (0, 0, 0) (even),
           whichever side the normal was given with. *)
        List.iter
          (fun n ->
            Alcotest.(check bool) "from below" true (odd (v 11. 0.5 (-5.)) up (v 11. 0.5 0.) n);
            Alcotest.(check bool) "from above" false (odd (v 11. 0.5 5.) (Vec3.neg up) (v 11. 0.5 0.) n))
          [ up; Vec3.neg up ];
        let s = scratch_at (v 11. 0.5 (-5.)) up (v 11. 0.5 0.) up in
        s.t <- 3.;
        let f () = ignore (Pattern.odd s table 0) in
        let words = words_of 10_000 f in
        if words > 50. then Alcotest.failf "%.0f minor words for 10000 lookups" words;
        Alcotest.(check (list (float 0.))) "the scratch is unchanged" [ 11.; 0.5; 0.; 0.; 0.; 1.; 3. ]
          [ s.px; s.py; s.pz; s.nx; s.ny; s.nz; s.t ]);
    Alcotest.test_case "Sampling: to_string, is_one, averaging and the passes of each mode" `Quick (fun () ->
        let sv ?samples ?adaptive ?subsample () = ok (Render.Sampling.v ?samples ?adaptive ?subsample ()) in
        let modes = [ Render.Sampling.one; sv ~samples:4 (); sv ~samples:5 ~adaptive:8 (); sv ~subsample:true () ] in
        Alcotest.(check (list string)) "to_string" [ "1x1"; "4x4"; "adaptive 5x5 t=8"; "subsampled" ]
          (List.map Render.Sampling.to_string modes);
        Alcotest.(check (list bool)) "is_one" [ true; false; false; false ] (List.map Render.Sampling.is_one modes);
        Alcotest.(check bool) "v () is one" true (Render.Sampling.is_one (sv ()));
        Alcotest.(check (list bool)) "averaging" [ false; true; true; false ] (List.map Render.Sampling.averaging modes);
        let img = Image.create 4 3 in
        let passes = List.map (fun m -> Sampling_rows.passes (Sampling_rows.plan m img ~canvas:(4, 3) ~at:(0, 0))) modes in
        Alcotest.(check (list int)) "passes" [ 1; 1; 2; 2 ] passes;
        let pl = Sampling_rows.plan Render.Sampling.one img ~canvas:(4, 3) ~at:(0, 0) in
        Alcotest.(check int) "pass 0 works on the 3 rows" 3 (Sampling_rows.pass_rows pl 0);
        raises_invalid "pass 1 of a one-pass plan" (fun () -> Sampling_rows.pass_rows pl 1);
        raises_invalid "a rectangle past the canvas" (fun () -> Sampling_rows.plan Render.Sampling.one img ~canvas:(4, 3) ~at:(1, 0));
        Alcotest.(check (list bool)) "64 and 65 samples" [ true; false ]
          (List.map (fun samples -> Result.is_ok (Render.Sampling.v ~samples ())) [ Render.Sampling.max_samples; Render.Sampling.max_samples + 1 ]);
        Alcotest.(check (list bool)) "adaptive 0, 255, 256, -1" [ true; true; false; false ]
          (List.map (fun adaptive -> Result.is_ok (Render.Sampling.v ~samples:3 ~adaptive ())) [ 0; 255; 256; -1 ]);
        (* Sampling_rows.rows: a step below 1, another canvas, another averaging. *)
        let scene w = Helpers.prepare (Scene.with_overrides ~width:w ~height:3 Scene.cgfs) in
        let four = sv ~samples:4 () in
        let pl4 = Sampling_rows.plan four img ~canvas:(4, 3) ~at:(0, 0) in
        let averaging = Trace.create ~averaging:true (scene 4) in
        raises_invalid "step 0" (fun () -> Sampling_rows.rows pl4 0 averaging ~first:0 ~step:0);
        raises_invalid "pass 1" (fun () -> Sampling_rows.rows pl4 1 averaging ~first:0 ~step:1);
        raises_invalid "a 5-wide canvas" (fun () -> Sampling_rows.rows pl4 0 (Trace.create ~averaging:true (scene 5)) ~first:0 ~step:1);
        raises_invalid "a tracer that does not average" (fun () -> Sampling_rows.rows pl4 0 (Trace.create (scene 4)) ~first:0 ~step:1);
        Sampling_rows.rows pl4 0 averaging ~first:0 ~step:1);
    Alcotest.test_case "Obj_file: feed raises outside its string and after finish; finish twice raises; ~digits writes %g"
      `Quick (fun () ->
        let p = Mesh.Obj.create ~name:"m.obj" ~max_vertices:10 ~max_triangles:10 in
        raises_invalid "off 4 len 2 of 5 bytes" (fun () -> Mesh.Obj.feed p "v 1 " 4 2);
        raises_invalid "len -1" (fun () -> Mesh.Obj.feed p "v" 0 (-1));
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3" in
        ok (Mesh.Obj.feed p text 0 (String.length text));
        let m = ok (Mesh.Obj.finish p) in
        Alcotest.(check int) "one triangle, the last line without line end" 1 (Mesh.Obj.triangle_count m);
        raises_invalid "feed after finish" (fun () -> Mesh.Obj.feed p "\n" 0 1);
        raises_invalid "finish twice" (fun () -> Mesh.Obj.finish p);
        let m = Mesh.Obj.v ~positions:[| 1. /. 3.; 2.; -0.5 |] ~normals:[||] ~triangles:[||] ~triangle_normals:[||] in
        Alcotest.(check string) "3 digits" "v 0.333 2 -0.5\n" (Mesh.Obj.to_string ~digits:3 m));
    Alcotest.test_case "Literal: of two spheres hit at the same t the first wins; a point light at the point adds nothing"
      `Quick (fun () ->
        let red = Helpers.sphere ~center:(v 0. 0. 5.) ~radius:1. (Color.v 255. 0. 0.) in
        let blue = Helpers.sphere ~center:(v 0. 0. 5.) ~radius:1. (Color.v 0. 0. 255.) in
        let first spheres =
          match Private.Literal.closest_intersection spheres ~origin:Vec3.zero ~direction:Vec3.oz ~t_min:1. ~t_max:infinity with
          | Some (s, t) -> Alcotest.check exact "t" 4. t; s.material.color
          | None -> Alcotest.fail "missed"
        in
        Alcotest.check Helpers.color "red first" red.material.color (first [ red; blue ]);
        Alcotest.check Helpers.color "blue first" blue.material.color (first [ blue; red ]);
        let scene = Helpers.scene ~spheres:[] ~lights:[ Light.ambient 0.25; Light.point 0.5 (v 0. 0. 4.) ] () in
        let lighting point =
          Private.Literal.compute_lighting scene ~epsilon:0.001 ~point ~normal:(v 0. 0. (-1.)) ~view:(v 0. 0. (-1.)) ~specular:Sphere.matte
        in
        Alcotest.check exact "L = 0: ambient only" 0.25 (lighting (v 0. 0. 4.));
        (* From (0, 0, 5) the light is at L = (0, 0, -1): <N, L> / |N| |L| = 1. *)
        Alcotest.check exact "facing the light" 0.75 (lighting (v 0. 0. 5.)));
    Alcotest.test_case "Private.Literal.normal turns a plane's or a triangle's normal toward the ray, never a sphere's" `Quick
      (fun () ->
        let floor = Plane.v ~point:Vec3.zero ~normal:Vec3.oy white_material in
        let n d = Private.Literal.normal (Private.Literal.Shape (Shape.Plane floor, Vec3.oy)) ~point:Vec3.zero ~direction:d in
        Alcotest.check Helpers.vec3 "from above" Vec3.oy (n (v 1. (-1.) 0.));
        Alcotest.check Helpers.vec3 "from below" (v 0. (-1.) 0.) (n (v 0. 1. 3.));
        let ball = Helpers.sphere ~center:Vec3.zero ~radius:2. Color.white in
        Alcotest.check Helpers.vec3 "a sphere from inside: outward" (v 0. 0. 1.)
          (Private.Literal.normal (Private.Literal.Sphere ball) ~point:(v 0. 0. 2.) ~direction:Vec3.oz));
    Alcotest.test_case "Camera_path: frames in [0, max_frame]; pp_key leaves out up = (0 1 0); first and last frames" `Quick
      (fun () ->
        let key ?up frame = Camera.Path.key ?up ~frame ~position:Vec3.zero (v 0. 0. 1.) in
        Alcotest.(check (list bool)) "frames -1, 0, 1000000, 1000001" [ false; true; true; false ]
          (List.map (fun f -> Result.is_ok (Camera.Path.check_key (key f))) [ -1; 0; Camera.Path.max_frame; Camera.Path.max_frame + 1 ]);
        refused "up along the view" (Camera.Path.check_key (key ~up:(v 0. 0. 2.) 0));
        let plain = Camera.Path.show_key (key 3) and tilted = Camera.Path.show_key (key ~up:(v 1. 1. 0.) 3) in
        Alcotest.(check bool) plain false (contains ~sub:"up" plain);
        Alcotest.(check bool) tilted true (contains ~sub:"(up 1 1 0)" tilted);
        let path = ok (Camera.Path.v [ key 2; key 10 ]) in
        Alcotest.(check (pair int int)) "frames" (2, 10) (Camera.Path.first_frame path, Camera.Path.last_frame path);
        refused "frame 1" (Camera.Path.camera path 1);
        refused "frame 11" (Camera.Path.camera path 11);
        refused "equal frames" (Camera.Path.v [ key 2; key 2 ]));
    Alcotest.test_case "adaptive sampling: each pixel is exactly the document's or exactly full supersampling's, and it \
                        traces 1 + (n^2 - 1) k rays for k refined pixels" `Quick (fun () ->
        let s = Helpers.valid (Scene.with_overrides ~width:48 ~height:48 Scene.cgfs) in
        let one, _ = ok (Render.image s) in
        let full, full_st = ok (Render.image ~samples:5 s) in
        let adaptive, st = ok (Render.image ~samples:5 ~adaptive:3 s) in
        let pixels = 48 * 48 and as_one = ref 0 and as_full = ref 0 in
        for y = 0 to 47 do
          for x = 0 to 47 do
            let a = Image.get adaptive x y and o = Image.get one x y and f = Image.get full x y in
            if a = o && a <> f then incr as_one
            else if a = f && a <> o then incr as_full
            else if a <> o && a <> f then Alcotest.failf "pixel (%d, %d) is neither the document's nor full sampling's" x y
          done
        done;
        if !as_one = 0 || !as_full = 0 then Alcotest.failf "%d pixels as the document's, %d as full sampling's" !as_one !as_full;
        let extra = st.primary - pixels in
        if extra mod 24 <> 0 || extra / 24 < !as_full || st.primary > full_st.primary then
          Alcotest.failf "%d primary rays for %d pixels (%d refined at least), full sampling %d" st.primary pixels !as_full
            full_st.primary;
        let _, sub = ok (Render.image ~subsample:true s) in
        Alcotest.(check int) "subsampling: one primary ray a pixel" pixels sub.primary);
    Alcotest.test_case "Light.pp, Viewport.pp and Pattern.pp write their scene-file forms" `Quick (fun () ->
        Alcotest.(check string) "point" "(light point (intensity 0.6) (position 2 1 0))" (Light.show (Light.point 0.6 (v 2. 1. 0.)));
        Alcotest.(check string) "viewport" "(viewport (width 1) (height 0.5) (distance 2))"
          (Viewport.show (Viewport.v ~width:1. ~height:0.5 ~distance:2.));
        let p = Pattern.checker ~size:0.25 (Color.v 0. 0. 255.) in
        Alcotest.(check string) "pattern" "(pattern checker (color 0 0 255) (size 0.25))" (Format.asprintf "%a" Pattern.pp p);
        Alcotest.(check string) "pp_optional" " (pattern checker (color 0 0 255) (size 0.25))"
          (Format.asprintf "%a" Pattern.pp_optional (Some p));
        Alcotest.(check string) "pp_optional None" "" (Format.asprintf "%a" Pattern.pp_optional None));
  ]

let tests = vec3_tests @ color_tests @ viewport_camera_tests @ limits_light_material_tests @ image_tests @ scene_tests @ kernel_tests
