(* Camera paths: keyframes, linear in between, checked frame by frame. *)
open Raytrace

let camera = Alcotest.testable Camera.pp Camera.equal
let ok = function Ok x -> x | Error (`Msg m) -> Alcotest.fail m
let ok_s = function Ok x -> x | Error (`Msg m) -> Alcotest.fail m
let error_s = function Ok _ -> Alcotest.fail "expected an error" | Error (`Msg m) -> m
let look ?up ~position target = ok_s (Camera.look_at ?up ~position target)

(* Frame 0 at the origin looking along +z; frame 4 at x = 4, looking at
   (4, 0, 1) + (0, 0, 1) too, then frame 8 turned to look at the origin. *)
let path =
  ok_s
    (Camera.Path.v
       [
         Camera.Path.key ~frame:0 ~position:Vec3.zero (Vec3.v 0. 0. 1.);
         Camera.Path.key ~frame:4 ~position:(Vec3.v 4. 0. 0.) (Vec3.v 4. 0. 1.);
         Camera.Path.key ~frame:8 ~position:(Vec3.v 4. 0. 4.) Vec3.zero;
       ])

let tests =
  [
    Alcotest.test_case "at a key's frame the camera is the key's" `Quick (fun () ->
        Alcotest.check camera __LOC__ Camera.default (ok (Camera.Path.camera path 0));
        Alcotest.check camera __LOC__ (look ~position:(Vec3.v 4. 0. 4.) Vec3.zero) (ok (Camera.Path.camera path 8)));
    Alcotest.test_case "between keys, position and target move linearly" `Quick (fun () ->
        (* Frame 1: t = 1/4; position 0.75 * 0 + 0.25 * 4 = 1 on x; target
           (1, 0, 1); looking along +z, so the rotation is the identity. *)
        Alcotest.check camera __LOC__ (Camera.v (Vec3.v 1. 0. 0.)) (ok (Camera.Path.camera path 1));
        (* Frame 6: t = 2/4 from frame 4; position (4, 0, 0.5 * 0 + 0.5 * 4)
           = (4, 0, 2); target 0.5 * (4, 0, 1) + 0.5 * 0 = (2, 0, 0.5). *)
        Alcotest.check camera __LOC__
          (look ~position:(Vec3.v 4. 0. 2.) (Vec3.v 2. 0. 0.5))
          (ok (Camera.Path.camera path 6)));
    Alcotest.test_case "a frame's camera is found in logarithmic time among many keys" `Slow (fun () ->
        (* 300001 keys, one a frame, each at x = frame. A search from the
           first key (as before) took 300001 x 150000 = 4.5e10 steps for
           every frame; a binary search takes 19 steps a frame. *)
        let n = 300_000 in
        let keys =
          List.init (n + 1) (fun f ->
              let x = Float.of_int f in
              Camera.Path.key ~frame:f ~position:(Vec3.v x 0. 0.) (Vec3.v x 0. 1.))
        in
        let p = ok_s (Camera.Path.v keys) in
        let t0 = Unix.gettimeofday () in
        for f = 0 to n do
          let c = ok (Camera.Path.camera p f) in
          if c.Camera.position.x <> Float.of_int f then Alcotest.failf "frame %d: camera at x = %g" f c.position.x
        done;
        let seconds = Unix.gettimeofday () -. t0 in
        Alcotest.(check bool) (Printf.sprintf "every frame in %.2f s, under 30 s" seconds) true (seconds < 30.));
    Alcotest.test_case "frames outside the path are errors" `Quick (fun () ->
        match Camera.Path.camera path 9 with
        | Ok _ -> Alcotest.fail "frame 9 rendered"
        | Error (`Msg m) ->
            Alcotest.(check string) __LOC__ "frame 9 is outside the camera path, which runs from frame 0 to 8" m);
    Alcotest.test_case "keys out of order, and frames without a camera, are refused" `Quick (fun () ->
        let k f p t = Camera.Path.key ~frame:f ~position:p t in
        Alcotest.(check string) __LOC__
          "camera-path keys must come in increasing frame order, but frame 2 follows frame 4"
          (error_s (Camera.Path.v [ k 4 Vec3.zero Vec3.oz; k 2 Vec3.zero Vec3.oz ]));
        (* Position from (0, 0, 0) to (0, 0, 4), target from (0, 0, 2) to
           (0, 0, 2): at frame 1 of 0..2 the camera stands on its target. *)
        Alcotest.(check string) __LOC__
          "at frame 1, between the keys of frames 0 and 2, the camera looks at its own position"
          (error_s (Camera.Path.v [ k 0 Vec3.zero (Vec3.v 0. 0. 2.); k 2 (Vec3.v 0. 0. 4.) (Vec3.v 0. 0. 2.) ]));
        Alcotest.(check string) __LOC__ "camera-path key frame must lie in [0, 1000000], got -1"
          (error_s (Camera.Path.v [ k (-1) Vec3.zero Vec3.oz ]));
        Alcotest.(check string) __LOC__ "a camera path needs at least one key" (error_s (Camera.Path.v [])));
    Alcotest.test_case "a scene's frame is a still scene with that frame's camera" `Quick (fun () ->
        let s = (Scene.with_overrides ~camera_path:(Some path) Scene.cgfs) in
        let f = Scene.of_valid (ok (Scene.at_frame (Helpers.valid s) 6)) in
        Alcotest.check camera __LOC__ (ok (Camera.Path.camera path 6)) (Scene.camera f);
        Alcotest.(check bool) __LOC__ true (Option.is_none (Scene.camera_path f));
        match Scene.at_frame (Helpers.valid Scene.cgfs) 0 with
        | Ok _ -> Alcotest.fail "a still scene has frames"
        | Error (`Msg m) -> Alcotest.(check string) __LOC__ "the scene has no camera-path, so it has no frames to render" m);
  ]
