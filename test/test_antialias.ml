(* Antialiasing: each pixel the rounded mean of its clamped samples. *)
open Raytrace

let small (s : Scene.t) = Scene.with_overrides ~width:40 ~height:30 s

(* The definition, spelled out with Color's clamp and rounding. *)
let reference tr gx gy n =
  let sum = Array.make 3 0. in
  for j = 0 to n - 1 do
    for i = 0 to n - 1 do
      Trace.sample tr gx gy ~i ~j ~n;
      sum.(0) <- sum.(0) +. Color.clamp (Trace.red tr);
      sum.(1) <- sum.(1) +. Color.clamp (Trace.green tr);
      sum.(2) <- sum.(2) +. Color.clamp (Trace.blue tr)
    done
  done;
  Array.map (fun x -> Color.to_byte (x /. Float.of_int (n * n))) sum

let tests =
  [
    Alcotest.test_case "one sample per pixel is the plain render" `Quick (fun () ->
        List.iter
          (fun name ->
            let s = small (Helpers.load_scene name) in
            Helpers.check_images name ~expected:(Helpers.image_exn s) (Antialias.image ~n:1 (Helpers.valid s)))
          (Helpers.scene_names ()));
    Alcotest.test_case "a pixel is the rounded mean of its clamped samples" `Quick (fun () ->
        let s = small Scene.cgfs in
        let img = Antialias.image ~n:3 (Helpers.valid s) in
        let tr = Trace.create ~averaging:true (Helpers.prepare s) in
        for row = 0 to 29 do
          for col = 0 to 39 do
            let expected = reference tr (Canvas.x_of_column ~width:40 col) (Canvas.y_of_row ~height:30 row) 3 in
            let r, g, b = Image.get img col row in
            Alcotest.(check (array int)) (Printf.sprintf "pixel %d,%d" col row) expected [| r; g; b |]
          done
        done);
    Alcotest.test_case "an overexposed sample counts as 255, not more" `Quick (fun () ->
        (* A white sphere lit by ambient 3 is 765 per channel everywhere on
           it; against a black background an edge pixel with k of 4 samples
           on the sphere is 255 k / 4, never 765 k / 4 clamped. *)
        let s =
          Helpers.scene ~width:2 ~height:1
            ~spheres:[ Helpers.sphere ~center:(Vec3.v (-1.) 0. 2.) ~radius:1. (Color.v 255. 255. 255.) ]
            ~lights:[ Light.ambient 3. ] ()
        in
        (* The sphere covers x < 0 at depth 2 around the pixel column
           gx = -1 (V_x in [-0.75, -0.25]) fully and gx = 0 (V_x in [-0.25,
           0.25]) for its samples left of the center: V_x = -0.125. *)
        let img = Antialias.image ~n:2 (Helpers.valid s) in
        Alcotest.(check (list int)) __LOC__ [ 255; 255; 255 ] (let r, g, b = Image.get img 0 0 in [ r; g; b ]);
        (* 2 of 4 samples white: 127.5 rounds half to even, to 128 *)
        Alcotest.(check (list int)) __LOC__ [ 128; 128; 128 ] (let r, g, b = Image.get img 1 0 in [ r; g; b ]));
    Alcotest.test_case "n < 1 is refused" `Quick (fun () ->
        Alcotest.check_raises __LOC__ (Invalid_argument "Antialias.image: n < 1") (fun () ->
            ignore (Antialias.image ~n:0 (Helpers.valid Scene.cgfs))));
  ]
