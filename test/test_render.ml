(* The fast renderer against the literal oracle, and against itself with
   its skips switched off or its work split over processes. *)
open Raytrace

let small (s : Scene.t) = Scene.with_overrides ~width:80 ~height:80 s
let render ?jobs ?skips s = Render.image_exn ?jobs ?skips s

let tests =
  [
    Alcotest.test_case "every scene renders as the literal oracle does, byte for byte" `Quick (fun () ->
        List.iter
          (fun name ->
            let s = small (Helpers.load_scene name) in
            Helpers.check_images name ~expected:(Literal.render s) (render s))
          (Helpers.scene_names ()));
    Alcotest.test_case "the reference scene at full size matches the oracle" `Slow (fun () ->
        Helpers.check_images "cgfs 600x600" ~expected:(Literal.render Scene.cgfs) (render Scene.cgfs));
    Helpers.qcheck ~count:150 "random scenes render as the literal oracle does" Gen_scene.arbitrary
      (fun s -> Image.equal (Literal.render s) (render s));
    Helpers.qcheck ~count:150 "switching the skips off changes no byte" Gen_scene.arbitrary (fun s ->
        Image.equal (render ~skips:false s) (render ~skips:true s));
    Alcotest.test_case "switching the skips off changes no byte on any scene" `Quick (fun () ->
        List.iter
          (fun name ->
            let s = small (Helpers.load_scene name) in
            Helpers.check_images name ~expected:(render ~skips:false s) (render s))
          (Helpers.scene_names ()));
    Alcotest.test_case "the image is the same for 1, 2 and 3 jobs" `Quick (fun () ->
        let s = Scene.with_overrides ~width:97 ~height:61 Scene.cgfs_camera in
        let one = render ~jobs:1 s in
        Helpers.check_images "2 jobs" ~expected:one (render ~jobs:2 s);
        Helpers.check_images "3 jobs" ~expected:one (render ~jobs:3 s));
    Alcotest.test_case "more jobs than rows still works" `Quick (fun () ->
        let s = Scene.with_overrides ~width:5 ~height:2 Scene.cgfs in
        Helpers.check_images "8 jobs" ~expected:(render s) (render ~jobs:8 s));
    Alcotest.test_case "tracing allocates nothing per pixel" `Quick (fun () ->
        match Render.image (Scene.with_overrides ~width:120 ~height:120 Scene.cgfs) with
        | Ok (_, stats) -> Alcotest.(check (float 0.)) __LOC__ 0. stats.minor_words
        | Error (`Msg m) -> Alcotest.fail m);
    Alcotest.test_case "the counters count the document's rays" `Quick (fun () ->
        (* The C reference reports 360000 primary, 784856 shadow and 367660
           reflection rays for this scene at 600 x 600. *)
        match Render.image Scene.cgfs with
        | Ok (_, st) ->
            Alcotest.(check (list int)) __LOC__ [ 360000; 784856; 367660 ] [ st.primary; st.shadow; st.reflection ]
        | Error (`Msg m) -> Alcotest.fail m);
    Alcotest.test_case "sample 0 of a 1 x 1 grid is the pixel itself" `Quick (fun () ->
        let tr = Trace.create (Prepared.prepare Scene.cgfs) in
        List.iter
          (fun (x, y) ->
            Trace.pixel tr x y;
            let c = (Trace.red tr, Trace.green tr, Trace.blue tr) in
            Trace.sample tr x y ~i:0 ~j:0 ~n:1;
            Alcotest.(check (triple (float 0.) (float 0.) (float 0.)))
              __LOC__ c
              (Trace.red tr, Trace.green tr, Trace.blue tr))
          [ (0, 0); (-300, 299); (120, -40) ]);
    Alcotest.test_case "a worker that dies fails the render" `Quick (fun () ->
        match Parallel.run 3 (fun w -> if w = 1 then Unix.kill (Unix.getpid ()) Sys.sigkill) with
        | Ok () -> Alcotest.fail "a killed worker went unnoticed"
        | Error (`Msg m) -> Alcotest.(check string) __LOC__ "worker 2 of 3 was killed by SIGKILL" m);
    Alcotest.test_case "a worker that raises fails the render" `Quick (fun () ->
        match Parallel.run 2 (fun w -> if w = 0 then failwith "boom") with
        | Ok () -> Alcotest.fail "a failed worker went unnoticed"
        | Error (`Msg m) -> Alcotest.(check string) __LOC__ "worker 1 of 2 exited with status 2: Failure(\"boom\")" m);
  ]
