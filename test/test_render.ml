(* The fast renderer against the literal oracle, and against itself with
   its skips switched off or its work split over processes. In the
   document's mode (the scene gives an epsilon) the fast renderer does the
   oracle's arithmetic and must give its bytes; in the robust mode it uses
   other formulas and must stay within 1 per channel on 99.9% of pixels. *)
open Raytrace

let small (s : Scene.t) = Scene.with_overrides ~width:80 ~height:80 s
let render ?jobs ?skips s = Helpers.image_exn ?jobs ?skips s

(* The share of pixels within 1 of the oracle in the robust mode: 99.9%,
   but 99% for a scene with a smooth mesh, where the oracle's epsilon
   (1e-4) leaves scattered self-shadowing specks (a shadow ray meets a
   neighbouring triangle just past it) that the robust mode does not have:
   0.4% of the pixels of scenes/mesh.scene, each darker in the oracle. *)
let robust_share (s : Scene.t) =
  if List.exists (function Shape.Mesh m -> m.smooth && m.material.transparency > 0. | _ -> false) (Scene.shapes s) then
    (* Seen through glass, each such speck is seen again, bent: 1.0% of
       the pixels of scenes/glass-knot.scene at 80 x 80, 0.95% at 120 x 120
       (in the document's mode the two are equal byte for byte). *)
    0.98
  else if List.exists (function Shape.Mesh m -> m.smooth | _ -> false) (Scene.shapes s) then 0.99
  else 0.999

let check_against_oracle what (s : Scene.t) =
  match (Scene.epsilon s) with
  | Some _ -> Helpers.check_images what ~expected:(Private.Literal.render (Helpers.valid s)) (render s)
  | None -> Helpers.check_images ~min_share:(robust_share s) what ~expected:(Private.Literal.render (Helpers.valid s)) (render s)

(* Random scenes in the document's mode. *)
let document_mode =
  QCheck.map ~rev:Fun.id
    (fun (s : Scene.t) -> if (Scene.epsilon s) = None then (Scene.with_overrides ~epsilon:(Some 0.001) s) else s)
    Gen_scene.arbitrary

let tests =
  [
    Alcotest.test_case "every scene renders as the literal oracle does" `Quick (fun () ->
        List.iter
          (fun name -> check_against_oracle name (small (Helpers.load_scene name)))
          (Helpers.scene_names ()));
    Alcotest.test_case "every scene in the robust mode is within 1 of the oracle on 99.9% of pixels"
      `Quick (fun () ->
        List.iter
          (fun name ->
            check_against_oracle (name ^ " without epsilon")
              (Scene.with_overrides ~epsilon:None ((Scene.with_overrides ~width:120 ~height:120 (Helpers.load_scene name)))))
          (Helpers.scene_names ()));
    Alcotest.test_case "the reference scene at full size matches the oracle" `Slow (fun () ->
        Helpers.check_images "cgfs 600x600" ~expected:(Private.Literal.render (Helpers.valid Scene.cgfs)) (render Scene.cgfs));
    Helpers.qcheck ~count:150 "random scenes in the document's mode render as the oracle does"
      document_mode (fun s -> Image.equal (Private.Literal.render (Helpers.valid s)) (render s));
    Alcotest.test_case "random scenes in the robust mode are within 1 of the oracle on 99.9% of pixels"
      `Quick (fun () ->
        let scenes = QCheck.Gen.generate ~rand:(Random.State.make [| 7 |]) ~n:300 Gen_scene.gen in
        let pixels = ref 0 and off = ref 0 in
        List.iter
          (fun (s : Scene.t) ->
            let s = (Scene.with_overrides ~epsilon:None s) in
            match Image.Diff.compare (Private.Literal.render (Helpers.valid s)) (render s) with
            | Ok d ->
                pixels := !pixels + d.pixels;
                off := !off + d.differing_gt1
            | Error (`Msg m) -> Alcotest.fail m)
          scenes;
        if Float.of_int !off > 0.001 *. Float.of_int !pixels then
          Alcotest.failf "%d of %d pixels differ by more than 1" !off !pixels);
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
        match Helpers.render (Scene.with_overrides ~width:120 ~height:120 Scene.cgfs) with
        | Ok (_, stats) -> Alcotest.(check (float 0.)) __LOC__ 0. stats.minor_words
        | Error (`Msg m) -> Alcotest.fail m);
    Alcotest.test_case "progress counts every row of every pass and ends with the render's rays" `Quick (fun () ->
        (* 40 x 30, so 30 rows. Adaptive sampling traces first rays on the
           rows of the margin (the whole canvas: 30), then refines 30:
           60. Subsampling traces even rows (15), then odd ones (15): 30. *)
        let s = Scene.with_overrides ~width:40 ~height:30 Scene.cgfs in
        let cases = [ ("one ray", [], 30); ("adaptive", [ `Adaptive ], 60); ("subsampled", [ `Subsample ], 30) ] in
        List.iter
          (fun (what, how, expected_total) ->
            let adaptive = if List.mem `Adaptive how then Some 4 else None in
            let samples = if adaptive = None then 1 else 3 in
            let subsample = List.mem `Subsample how in
            let plain = Helpers.image_exn ~samples ?adaptive ~subsample s in
            List.iter
              (fun jobs ->
                let what = Printf.sprintf "%s, %d jobs" what jobs in
                let calls = ref [] in
                let progress ~rows ~total ~rays = calls := (rows, total, rays) :: !calls in
                match Helpers.render ~jobs ~samples ?adaptive ~subsample ~progress s with
                | Error (`Msg m) -> Alcotest.fail m
                | Ok (img, st) ->
                    Helpers.check_images what ~expected:plain img;
                    let calls = List.rev !calls in
                    List.iter (fun (_, total, _) -> Alcotest.(check int) what expected_total total) calls;
                    let rows = List.map (fun (r, _, _) -> r) calls in
                    Alcotest.(check bool) (what ^ ": rows never decrease") true (rows = List.sort compare rows);
                    (* One job: a call after each row. *)
                    if jobs = 1 then Alcotest.(check (list int)) what (List.init expected_total succ) rows;
                    let last_rows, _, last_rays = List.nth calls (List.length calls - 1) in
                    Alcotest.(check int) (what ^ ": last rows") expected_total last_rows;
                    Alcotest.(check int) (what ^ ": rays") (st.primary + st.shadow + st.reflection) last_rays)
              [ 1; 2; 3 ])
          cases);
    Alcotest.test_case "progress on a region counts the region's rows" `Quick (fun () ->
        let s = Scene.with_overrides ~width:40 ~height:30 Scene.cgfs in
        let last = ref (0, 0) in
        let progress ~rows ~total ~rays:_ = last := (rows, total) in
        List.iter
          (fun jobs ->
            match Helpers.render_region ~jobs ~progress s (Render.Region.v ~x:3 ~y:5 ~w:20 ~h:7) with
            | Ok _ -> Alcotest.(check (pair int int)) __LOC__ (7, 7) !last
            | Error (`Msg m) -> Alcotest.fail m)
          [ 1; 2 ]);
    Alcotest.test_case "reporting progress allocates nothing per pixel" `Quick (fun () ->
        (* The callback allocates; that is the caller's, not the tracer's.
           Workers allocate a few words each, once (not per pixel), with or
           without progress: the counting adds nothing. *)
        let seen = ref [] in
        let progress ~rows ~total:_ ~rays:_ = seen := rows :: !seen in
        let words ?progress jobs =
          match Helpers.render ~jobs ?progress (Scene.with_overrides ~width:120 ~height:120 Scene.cgfs) with
          | Ok (_, stats) -> stats.minor_words
          | Error (`Msg m) -> Alcotest.fail m
        in
        Alcotest.(check (float 0.)) __LOC__ 0. (words ~progress 1);
        Alcotest.(check (float 0.)) __LOC__ (words 2) (words ~progress 2));
    Alcotest.test_case "the counters count the document's rays" `Quick (fun () ->
        (* The C reference reports 360000 primary, 784856 shadow and 367660
           reflection rays for this scene at 600 x 600. With the skips, the
           shadow rays of lights that add nothing are not cast (cfast,
           which skips fewer, casts 598830). *)
        (match Helpers.render ~skips:false Scene.cgfs with
        | Ok (_, st) ->
            Alcotest.(check (list int)) __LOC__ [ 360000; 784856; 367660 ] [ st.primary; st.shadow; st.reflection ]
        | Error (`Msg m) -> Alcotest.fail m);
        match Helpers.render Scene.cgfs with
        | Ok (_, st) ->
            Alcotest.(check (list int)) __LOC__ [ 360000; 558063; 367660 ] [ st.primary; st.shadow; st.reflection ]
        | Error (`Msg m) -> Alcotest.fail m);
    Alcotest.test_case "sample 0 of a 1 x 1 grid is the pixel itself" `Quick (fun () ->
        let tr = Trace.create (Helpers.prepare Scene.cgfs) in
        List.iter
          (fun (x, y) ->
            Trace.pixel tr x y;
            let c = (Trace.red tr, Trace.green tr, Trace.blue tr) in
            Trace.sample tr x y ~i:0 ~j:0 ~n:1;
            Alcotest.(check (triple (float 0.) (float 0.) (float 0.)))
              __LOC__ c
              (Trace.red tr, Trace.green tr, Trace.blue tr))
          [ (0, 0); (-300, 299); (120, -40) ]);
    Alcotest.test_case "the number of cores is what the kernel allows this process" `Quick (fun () ->
        (* /proc/self/status says e.g. "Cpus_allowed_list:\t0-1" for 2 cores *)
        match Raytrace_unix.File_io.read "/proc/self/status" with
        | Error _ -> ()
        | Ok text ->
            let line =
              List.find (fun l -> String.length l > 18 && String.sub l 0 18 = "Cpus_allowed_list:")
                (String.split_on_char '\n' text)
            in
            let expected =
              String.split_on_char ',' (String.trim (String.sub line 18 (String.length line - 18)))
              |> List.fold_left
                   (fun acc r ->
                     match String.split_on_char '-' r with
                     | [ a; b ] -> acc + int_of_string b - int_of_string a + 1
                     | _ -> acc + 1)
                   0
            in
            Alcotest.(check int) __LOC__ expected (Parallel.cores ()));
    Helpers.qcheck ~count:1000 "below a sphere's specular threshold, cos ** s is exactly 0"
      QCheck.(pair (float_range 0. 1.) (oneofl [ 0.; 0.5; 1.; 10.; 500.; 1000.; 1e5; 1e12; 1e300 ]))
      (fun (u, specular) ->
        let p = Helpers.prepare (Helpers.scene ~spheres:[ Helpers.sphere ~specular ~center:Vec3.oz ~radius:1. Color.white ] ~lights:[] ()) in
        let zero = p.specular_zero.(0) in
        (* every cosine at or below the threshold, here u times it *)
        zero >= 0. && zero < 1. && (zero = 0. || Float.pow (u *. zero) specular = 0.)
        && Float.pow zero specular = (if zero = 0. then Float.pow 0. specular else 0.));
    Alcotest.test_case "a busy process on every other core is seen: no core is idle" `Quick (fun () ->
        match Parallel.others_running () with
        | None -> (* No /proc/loadavg: idle_core assumes a core is free. *) Alcotest.(check bool) __LOC__ true (Parallel.idle_core ())
        | Some _ ->
            (* One spinning child per other core (at least one): each is
               running or ready to run at every look. *)
            let spinners = max 1 (Parallel.cores () - 1) in
            let pids =
              List.init spinners (fun _ ->
                  match Unix.fork () with
                  | 0 ->
                      let t = Unix.gettimeofday () in
                      while Unix.gettimeofday () -. t < 10. do () done;
                      Unix._exit 0
                  | pid -> pid)
            in
            Unix.sleepf 0.05;
            let seen = Parallel.others_running () and idle = Parallel.idle_core () in
            List.iter (fun pid -> Unix.kill pid Sys.sigkill; ignore (Unix.waitpid [] pid)) pids;
            (match seen with
            | Some n when n >= spinners -> ()
            | Some n -> Alcotest.failf "%d spinning, %d others seen running" spinners n
            | None -> Alcotest.fail "/proc/loadavg went away");
            Alcotest.(check bool) __LOC__ false idle);
    Alcotest.test_case "beside computes in another process what the caller would" `Quick (fun () ->
        let me = Unix.getpid () in
        let f () = (Unix.getpid (), Array.init 1_000_000 (fun i -> Float.of_int i *. 0.5)) in
        let wait = Parallel.beside f in
        let mine = Array.init 1000 Float.of_int in
        match wait () with
        | Ok (pid, a) ->
            Alcotest.(check bool) "computed in a child" true (pid <> me);
            Alcotest.(check bool) "the same values" true (a = snd (f ()));
            Alcotest.(check int) __LOC__ 1000 (Array.length mine)
        | Error (`Msg m) -> Alcotest.fail m);
    Alcotest.test_case "beside ~take_over does the work of a child that had no CPU time, in the caller" `Quick
      (fun () ->
        let me = Unix.getpid () in
        (* The child sleeps (no CPU time) where the caller works 0.1 s:
           late, it is killed and the caller computes [f ()]. *)
        let f () = if Unix.getpid () <> me then Unix.sleep 30; Unix.getpid () in
        let t0 = Unix.gettimeofday () in
        let wait = Parallel.beside ~take_over:true f in
        let cpu () = let t = Unix.times () in t.tms_utime +. t.tms_stime in
        let c0 = cpu () in
        while cpu () -. c0 < 0.1 do ignore (Sys.opaque_identity (Array.make 100 0.)) done;
        (match wait () with
        | Ok pid -> Alcotest.(check int) "computed here" me pid
        | Error (`Msg m) -> Alcotest.fail m);
        let took = Unix.gettimeofday () -. t0 in
        if took > 10. then Alcotest.failf "waited %.1f s for the sleeping child" took);
    Alcotest.test_case "beside ~take_over waits for a child that is not behind the caller" `Quick (fun () ->
        let me = Unix.getpid () in
        (* The caller waits at once (no CPU time of its own since the fork):
           the child is not late, whatever its pace. *)
        let f () =
          let cpu () = let t = Unix.times () in t.tms_utime +. t.tms_stime in
          let c0 = cpu () in
          while cpu () -. c0 < 0.05 do ignore (Sys.opaque_identity (Array.make 100 0.)) done;
          Unix.getpid ()
        in
        match (Parallel.beside ~take_over:true f) () with
        | Ok pid -> Alcotest.(check bool) "computed in the child" true (pid <> me)
        | Error (`Msg m) -> Alcotest.fail m);
    Alcotest.test_case "beside reports a child that raised, sent a function or was killed" `Quick (fun () ->
        let error_of wait = match wait () with Ok _ -> Alcotest.fail "expected an error" | Error (`Msg m) -> m in
        let contains m sub =
          let n = String.length sub in
          let rec at i = i + n <= String.length m && (String.sub m i n = sub || at (i + 1)) in
          if not (at 0) then Alcotest.failf "%S does not contain %S" m sub
        in
        contains (error_of (Parallel.beside (fun () -> failwith "boom"))) "raised Failure(\"boom\")";
        contains (error_of (Parallel.beside (fun () -> fun x -> x + 1))) "could not send its result";
        contains
          (error_of (Parallel.beside (fun () -> Unix.kill (Unix.getpid ()) Sys.sigkill; Unix.sleepf 5.; 0)))
          "was killed by SIGKILL";
        (* Each child is reaped: none is left for a later wait. *)
        match Unix.waitpid [ WNOHANG ] (-1) with
        | exception Unix.Unix_error (ECHILD, _, _) -> ()
        | pid, _ -> Alcotest.failf "a child was left: %d" pid);
    Alcotest.test_case "a task queue hands every task to exactly one worker" `Quick (fun () ->
        let m = 5000 in
        let taken = Parallel.shared_ints m in
        let q = Parallel.queue m in
        let work _ =
          let rec loop () =
            let t = Parallel.take q in
            if t >= 0 then begin
              taken.{t} <- Int64.add taken.{t} 1L;
              loop ()
            end
          in
          loop ()
        in
        (match Parallel.run 3 work with Ok () -> () | Error (`Msg e) -> Alcotest.fail e);
        Parallel.close_queue q;
        for t = 0 to m - 1 do
          if taken.{t} <> 1L then Alcotest.failf "task %d taken %Ld times" t taken.{t}
        done);
    Alcotest.test_case "every reported task reaches the parent once, before the workers are waited for" `Quick
      (fun () ->
        let m = 3000 in
        let q = Parallel.queue m and r = Parallel.reports () in
        let seen = Array.make m 0 in
        let work _ =
          let rec loop () =
            let t = Parallel.take q in
            if t >= 0 then begin
              Parallel.report r t;
              loop ()
            end
          in
          loop ()
        in
        (match Parallel.run ~reports:(r, fun t -> seen.(t) <- seen.(t) + 1) 3 work with
        | Ok () -> ()
        | Error (`Msg e) -> Alcotest.fail e);
        Parallel.close_queue q;
        Parallel.close_reports r;
        Array.iteri (fun t k -> if k <> 1 then Alcotest.failf "task %d reported %d times" t k) seen);
    Alcotest.test_case "bands cover the rows in order, shrinking to single rows" `Quick (fun () ->
        List.iter
          (fun (n, jobs) ->
            let b = Render_jobs.bands ~jobs n in
            let count = Array.length b - 1 in
            let where = Printf.sprintf "%d rows, %d jobs" n jobs in
            Alcotest.(check int) where 0 b.(0);
            Alcotest.(check int) where n b.(count);
            if count > Parallel.max_tasks then Alcotest.failf "%s: %d bands" where count;
            for k = 0 to count - 1 do
              if b.(k + 1) <= b.(k) then Alcotest.failf "%s: band %d is empty" where k;
              if k > 0 && b.(k + 1) - b.(k) > b.(k) - b.(k - 1) then Alcotest.failf "%s: band %d grows" where k
            done;
            if n > 0 && jobs <= 16 && n <= 100_000 then Alcotest.(check int) where 1 (b.(count) - b.(count - 1));
            if n >= 64 * jobs && count < 8 * jobs then Alcotest.failf "%s: only %d bands" where count)
          [
            (0, 2); (1, 2); (7, 2); (100, 1); (100, 2); (1920, 2); (1920, 3); (50_000, 16); (1_000_000, 1024);
            (3, 1024);
          ]);
    Alcotest.test_case "with two jobs, an image of less split_work than least_split_work is traced here unless forced"
      `Quick (fun () ->
        (* 511 x 512 = 261,632 and 256 x 255 x 2^2 = 261,120 rays through
           four spheres (1 + log2 5 = 3.32 levels), below 2^20 / 3.32 =
           315,800: no worker is forked, whatever the host. *)
        List.iter
          (fun (w, h, samples) ->
            let scene = Scene.with_overrides ~width:w ~height:h Scene.cgfs in
            let render split =
              match Helpers.render ~jobs:2 ~split ~samples scene with
              | Ok r -> r
              | Error (`Msg m) -> Alcotest.fail m
            in
            let one, (st : Render.Stats.t) = render `Auto and forked, (st2 : Render.Stats.t) = render `Always in
            Alcotest.(check int) (Printf.sprintf "%dx%d, %d samples: processes, auto" w h samples) 1 st.jobs;
            Alcotest.(check int) (Printf.sprintf "%dx%d, %d samples: processes, always" w h samples) 2 st2.jobs;
            Helpers.check_images "auto against always" ~expected:forked one)
          [ (511, 512, 1); (256, 255, 2) ];
        Alcotest.(check int) "the threshold" (1 lsl 20) Render_jobs.least_split_work;
        (* The guess grows with the objects: at 400 x 300, ten thousand
           spheres split (14.3 levels) where the reference scene's four
           do not; the reference scene splits at 600 x 600, where it gains
           from two workers on a quiet host. *)
        let work ?(samples = 1) w h scene =
          match Scene.validate (Scene.with_overrides ~width:w ~height:h scene) with
          | Ok v -> Render_jobs.split_work v (Render.Region.full ~width:w ~height:h) ~samples
          | Error (`Msg m) -> Alcotest.fail m
        in
        let least = Float.of_int Render_jobs.least_split_work in
        let grid = Scene.grid 10_000 in
        if work 400 300 grid < least then Alcotest.failf "10,000 spheres at 400 x 300: %.0f" (work 400 300 grid);
        if work 400 300 Scene.cgfs >= least then Alcotest.failf "cgfs at 400 x 300: %.0f" (work 400 300 Scene.cgfs);
        if work 600 600 Scene.cgfs < least then Alcotest.failf "cgfs at 600 x 600: %.0f" (work 600 600 Scene.cgfs);
        if work ~samples:2 300 300 Scene.cgfs <> 4. *. work 300 300 Scene.cgfs then Alcotest.fail "samples squared");
    Alcotest.test_case "with two jobs, rows_done tells of final rows from the top while the workers trace" `Quick
      (fun () ->
        let scene = Scene.with_overrides ~width:90 ~height:160 Scene.cgfs in
        let expected = Helpers.image_exn ~jobs:1 scene in
        let row = 3 * 90 in
        let check ?samples ?adaptive ~jobs ~calls () =
          let seen = ref [] in
          let rows_done img r =
            (* The prefix as it is when told, compared once the image is done. *)
            let b = Bytes.create (r * row) in
            for k = 0 to (r * row) - 1 do
              Bytes.set b k (Char.chr (Image.buffer img).{k})
            done;
            seen := (r, b) :: !seen
          in
          match Result.bind (Scene.validate scene) (Render_jobs.image ~jobs ~split:`Always ?samples ?adaptive ~rows_done) with
          | Error (`Msg m) -> Alcotest.fail m
          | Ok (img, _) ->
              let seen = List.rev !seen in
              let rs = List.map fst seen in
              Alcotest.(check int) "the last call has every row" 160 (List.nth rs (List.length rs - 1));
              if not (calls (List.length rs)) then Alcotest.failf "%d calls" (List.length rs);
              ignore
                (List.fold_left
                   (fun prev r -> if r <= prev then Alcotest.failf "rows %d after %d" r prev else r)
                   0 rs);
              let final = Image.buffer img in
              List.iter
                (fun (r, b) ->
                  for k = 0 to (r * row) - 1 do
                    if Char.code (Bytes.get b k) <> final.{k} then
                      Alcotest.failf "byte %d changed after row %d was final" k r
                  done)
                seen;
              img
        in
        let img = check ~jobs:2 ~calls:(fun n -> n > 1) () in
        Alcotest.(check bool) "same image as one job" true (Image.equal expected img);
        ignore (check ~jobs:1 ~calls:(fun n -> n = 1) ());
        (* Two passes: the image is final only after the second. *)
        ignore (check ~jobs:2 ~samples:3 ~adaptive:8 ~calls:(fun n -> n = 1) ()));
    Alcotest.test_case "a worker that dies fails the render" `Quick (fun () ->
        match Parallel.run 3 (fun w -> if w = 1 then Unix.kill (Unix.getpid ()) Sys.sigkill) with
        | Ok () -> Alcotest.fail "a killed worker went unnoticed"
        | Error (`Msg m) -> Alcotest.(check string) __LOC__ "worker 2 of 3 was killed by SIGKILL" m);
    Alcotest.test_case "a worker that raises fails the render" `Quick (fun () ->
        match Parallel.run 2 (fun w -> if w = 0 then failwith "boom") with
        | Ok () -> Alcotest.fail "a failed worker went unnoticed"
        | Error (`Msg m) -> Alcotest.(check string) __LOC__ "worker 1 of 2 exited with status 2: Failure(\"boom\")" m);
  ]
