let region_image ?(limits = Limits.default) ?(clock = Sys.time) ?skips ?beside ?samples ?adaptive ?subsample ?progress
    scene (region : Region.t) =
  Render_work.inside "Render.region_image" scene region;
  (* Nothing here holds the scene past [Prepared.prepare], which lets its
     spheres go as it builds the hierarchy: matches, not [let*], whose
     closure would keep [scene] with the values the render reads after it
     (docs/performance.md, "Numbers moved out of the library's comments"). *)
  match Sampling.v ?samples ?adaptive ?subsample () with
  | Error _ as e -> e
  | Ok sampling -> (
  match Render_work.check ~limits scene region sampling with
  | Error _ as e -> e
  | Ok () ->
  let canvas = (let s = Scene.of_valid scene in (Scene.width s, Scene.height s)) in
  match Image.create region.w region.h with
  | exception Out_of_memory -> Render_work.out_of_memory region
  | img ->
      let t0 = clock () in
      let p = Prepared.prepare ?skips ?beside scene in
      let t1 = clock () in
      let plan = Sampling_rows.plan sampling img ~canvas ~at:(region.x, region.y) in
      let ints = Bigarray.Array1.create Bigarray.int64 Bigarray.c_layout Render_work.counter_fields in
      (* One tracer for every pass. *)
      let tr = Trace.create ~averaging:(Sampling.averaging sampling) p in
      Trace.set_budget tr (Limits.work_budget limits);
      (* What the caller's [progress] allocates is not the tracer's. *)
      let progress_words = Array.make 1 0. in
      let before = Gc.minor_words () in
      match
      match progress with
      | None ->
          for i = 0 to Sampling_rows.passes plan - 1 do
            Sampling_rows.rows plan i tr ~first:0 ~step:1
          done
      | Some progress ->
          let total = Render_work.total_rows plan in
          let finished = ref 0 in
          for i = 0 to Sampling_rows.passes plan - 1 do
            let n = Sampling_rows.pass_rows plan i in
            (* A band of rows at a time, square by square where the
               pass allows ([Sampling_rows.band]); then the progress of
               each of its rows. *)
            let r = ref 0 and rows = Sampling_rows.band_rows plan tr in
            while !r < n do
              let last = min n (!r + rows) in
              Sampling_rows.band plan i tr ~first:!r ~last;
              for _ = !r to last - 1 do
                incr finished;
                let w = Gc.minor_words () in
                progress ~rows:!finished ~total ~rays:(Render_work.rays tr);
                progress_words.(0) <- progress_words.(0) +. (Gc.minor_words () -. w)
              done;
              r := last
            done
          done
      with
      | exception Limits.Work_exceeded n -> Error (`Msg (Limits.work_exceeded limits n))
      | () ->
          Render_work.save ints 0 tr (Gc.minor_words () -. before -. progress_words.(0));
          let t2 = clock () in
          Ok
            ( img,
              Render_work.stats ints ~slots:1 ~pixels:(Region.pixels region) ~jobs:1 ~prepare_s:(t1 -. t0)
                ~trace_s:(t2 -. t1) ))

