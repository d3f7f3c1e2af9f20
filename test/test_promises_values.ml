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
          [ ("width 0", { Viewport.default with width = 0. }); ("height -1", { Viewport.default with height = -1. });
            ("distance nan", { Viewport.default with distance = nan }); ("width inf", { Viewport.default with width = infinity }) ]);
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
        ignore (ok (Camera.validate Scene.cgfs_camera.camera)));
    Alcotest.test_case "Camera.pp leaves out an identity rotation and writes any other" `Quick (fun () ->
        let plain = Camera.show (Camera.v (v 1. 2. 3.)) in
        let turned = Camera.show Scene.cgfs_camera.camera in
        Alcotest.(check bool) plain false (contains ~sub:"rotation" plain);
        Alcotest.(check bool) turned true (contains ~sub:"(rotation (0.7071 0 -0.7071) (0 1 0) (0.7071 0 0.7071))" turned));
  ]

let tests = vec3_tests @ color_tests @ viewport_camera_tests
