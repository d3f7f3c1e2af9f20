(* Progressive rendering ends in the very image that Render makes. *)
open Raytrace

let small (s : Scene.t) = Scene.with_overrides ~width:61 ~height:37 s
let create ?samples ?workers s = Progressive.create ?samples ?workers (Helpers.valid s)

let run_to_end r =
  let bands = ref [] in
  let rec go () = match Progressive.step r with Some b -> bands := b :: !bands; go () | None -> () in
  go ();
  List.rev !bands

let primary r = (Trace.counters (Progressive.tracer r)).primary

(* A pixel of this scene's ray tree has tens of thousands of rays,
   several looks of the front end. *)
let deep_glass () =
  match Helpers.of_string (Helpers.glass_planes ~width:5 ~height:4 ~depth:20) with
  | Ok s -> s
  | Error (`Msg m) -> Alcotest.fail m

let tests =
  [
    Alcotest.test_case "the first step traces one band of 16-pixel blocks" `Quick (fun () ->
        let r = create Scene.cgfs in
        (match Progressive.step r with
        | Some b -> Alcotest.(check (list int)) __LOC__ [ 16; 0; 16 ] [ b.size; b.top; b.rows ]
        | None -> Alcotest.fail "no band");
        (* columns 0, 16, ..., 592: ceil (600 / 16) = 38 pixels *)
        Alcotest.(check int) __LOC__ 38 (primary r);
        Alcotest.(check bool) __LOC__ false (Progressive.finished r));
    Alcotest.test_case "passes refine the blocks down to single pixels, band after band" `Quick (fun () ->
        let bands = run_to_end (create (small Scene.cgfs)) in
        (* 37 rows: ceil (37 / s) bands per pass s = 16, 8, 4, 1: 3 + 5 + 10 + 37 *)
        Alcotest.(check int) __LOC__ 55 (List.length bands);
        Alcotest.(check (list int)) __LOC__ [ 16; 16; 16; 8; 8; 8; 8; 8; 4 ]
          (List.map (fun (b : Progressive.band) -> b.size) (List.filteri (fun i _ -> i < 9) bands));
        let last = List.nth bands 54 in
        Alcotest.(check (list int)) __LOC__ [ 1; 36; 1 ] [ last.size; last.top; last.rows ];
        let third = List.nth bands 2 in
        (* the last 16-pixel band holds rows 32 to 36 *)
        Alcotest.(check (list int)) __LOC__ [ 16; 32; 5 ] [ third.size; third.top; third.rows ]);
    Alcotest.test_case "every pixel is traced exactly once" `Quick (fun () ->
        let r = create (small Scene.cgfs) in
        ignore (run_to_end r);
        Alcotest.(check int) __LOC__ (61 * 37) (primary r);
        Alcotest.(check bool) __LOC__ true (Progressive.finished r);
        Alcotest.(check bool) __LOC__ true (Progressive.step r = None));
    Alcotest.test_case "the finished image is Render's, byte for byte, for every scene" `Quick (fun () ->
        List.iter
          (fun name ->
            let s = small (Helpers.load_scene name) in
            let r = create s in
            ignore (run_to_end r);
            Helpers.check_images name ~expected:(Helpers.image_exn s) (Progressive.image r))
          (Helpers.scene_names ()));
    Helpers.qcheck ~count:50 "random scenes end as Render renders them" Gen_scene.arbitrary (fun s ->
        let r = create s in
        ignore (run_to_end r);
        Image.equal (Helpers.image_exn s) (Progressive.image r));
    Alcotest.test_case "with antialiasing, the finished image is Antialias's" `Quick (fun () ->
        let s = small Scene.cgfs_camera in
        let r = create ~samples:3 s in
        (* 55 bands as without antialiasing, then 37 rows of 3 x 3 samples *)
        Alcotest.(check int) __LOC__ 92 (List.length (run_to_end r));
        Helpers.check_images __LOC__ ~expected:(Antialias.image ~n:3 (Helpers.valid s)) (Progressive.image r));
    Alcotest.test_case "worker processes trace the same image, in bands of any height" `Quick (fun () ->
        List.iter
          (fun (jobs, rows, samples) ->
            let s = small Scene.cgfs_camera in
            let shared = Progressive_workers.v ~jobs ~width:61 ~height:37 in
            let r = create ~samples ~workers:shared s in
            let rec go () = match Progressive.step ~rows r with Some _ -> go () | None -> () in
            go ();
            let expected = if samples = 1 then Helpers.image_exn s else Antialias.image ~n:samples (Helpers.valid s) in
            let what = Printf.sprintf "%d jobs, %d rows, %d samples" jobs rows samples in
            Helpers.check_images what ~expected (Progressive.image r);
            Alcotest.(check (option string)) what None (Progressive.failure r);
            (* the workers' rays are counted as one process counts them *)
            let alone = create ~samples s in
            ignore (run_to_end alone);
            let rays r =
              let c = Trace.counters (Progressive.tracer r) in
              [ c.primary; c.shadow; c.reflection ]
            in
            Alcotest.(check (list int)) what (rays alone) (rays r);
            (* every pixel once, plus 9 per pixel with antialiasing *)
            Alcotest.(check int) what (61 * 37 * (if samples = 1 then 1 else 10)) (primary r))
          [ (2, 5, 1); (3, 37, 1); (2, 1, 1); (2, 8, 3) ]);
    Alcotest.test_case "when a worker dies, this process traces its rows: same image" `Quick (fun () ->
        (* Memprof's callback is inherited by the forked workers: there it
           kills the worker at its first sampled allocation (antialiasing
           allocates a boxed float per sample). *)
        let parent = Unix.getpid () in
        let kill_workers _ =
          if Unix.getpid () <> parent then Unix.kill (Unix.getpid ()) Sys.sigkill;
          None
        in
        let s = small Scene.cgfs in
        let shared = Progressive_workers.v ~jobs:2 ~width:61 ~height:37 in
        let r = create ~samples:3 ~workers:shared s in
        Gc.Memprof.start ~sampling_rate:0.01 { Gc.Memprof.null_tracker with alloc_minor = kill_workers };
        Fun.protect ~finally:Gc.Memprof.stop (fun () ->
            let rec go () = match Progressive.step ~rows:8 r with Some _ -> go () | None -> () in
            go ());
        (* Both workers die; which one is reported depends on which the
           parent reaps first. *)
        (match Progressive.failure r with
        | Some ("worker 1 of 2 was killed by SIGKILL" | "worker 2 of 2 was killed by SIGKILL") -> ()
        | f -> Alcotest.failf "%s: the failure is %s" __LOC__ (Option.value f ~default:"none"));
        Helpers.check_images __LOC__ ~expected:(Antialias.image ~n:3 (Helpers.valid s)) (Progressive.image r));
    Alcotest.test_case "the front end is asked inside a deep glass pixel; paused anywhere, the image is Render's" `Quick
      (fun () ->
        let s = deep_glass () in
        let paused_in r ~samples =
          let inside = ref 0 and paused = ref 0 and last = ref min_int in
          (* Pauses at every look inside a pixel but inside the pixel of
             the last pause, traced again: a front end that always paused
             there would never see it finished. A pixel casts [samples]
             primary rays. *)
          let poll = function
            | Progressive.Inside_pixel ->
                incr inside;
                let p = primary r in
                if p > !last + samples then (last := p; true) else false
            | Between_pixels -> true
          in
          let rec go () = match Progressive.advance ~rows:3 ~poll r with Done -> () | Paused -> incr paused; go () | Band _ -> go () in
          go ();
          Printf.printf "%d looks inside pixels, %d pauses\n" !inside !paused;
          Alcotest.(check bool) "paused inside pixels" true (!paused > 10)
        in
        let r = create s in
        paused_in r ~samples:1;
        Helpers.check_images __LOC__ ~expected:(Helpers.image_exn s) (Progressive.image r);
        let r = create ~samples:2 s in
        paused_in r ~samples:4;
        Helpers.check_images __LOC__ ~expected:(Antialias.image ~n:2 (Helpers.valid s)) (Progressive.image r));
    Alcotest.test_case "a front end that pauses at every look between pixels sees the image finished" `Quick (fun () ->
        let s = Scene.cgfs in
        let r = create s in
        let paused = ref 0 in
        let rec go () =
          match Progressive.advance ~rows:50 ~poll:(fun _ -> true) r with
          | Done -> ()
          | Paused -> incr paused; go ()
          | Band _ -> go ()
        in
        go ();
        Alcotest.(check bool) (Printf.sprintf "paused (%d times)" !paused) true (!paused > 0);
        Helpers.check_images __LOC__ ~expected:(Helpers.image_exn s) (Progressive.image r));
    Alcotest.test_case "a shared image of another size is refused" `Quick (fun () ->
        let shared = Progressive_workers.v ~jobs:2 ~width:10 ~height:10 in
        Alcotest.check_raises __LOC__ (Invalid_argument "Progressive.create: the workers' image is not of the canvas size")
          (fun () -> ignore (create ~workers:shared (small Scene.cgfs))));
    Alcotest.test_case "bad arguments are refused" `Quick (fun () ->
        Alcotest.check_raises __LOC__ (Invalid_argument "Progressive.create: samples < 1") (fun () ->
            ignore (create ~samples:0 Scene.cgfs)));
  ]
