let check_memory (region : Render.Region.t) =
  let bytes = 3 * Render.Region.pixels region in
  match Parallel.available_memory () with
  | Some available when bytes > available ->
      let gib n = Float.of_int n /. 1073741824. in
      Error
        (`Msg
          (Printf.sprintf "a %dx%d image needs %.2f GiB of memory, but only %.2f GiB are available" region.w region.h
             (gib bytes) (gib available)))
  | _ -> Ok ()

let shared_memory =
  {
    Sampling_rows.bytes = Parallel.shared_bytes;
    floats = Parallel.shared_floats;
    ints = Parallel.shared_ints;
    at_row = Parallel.exit_if_orphaned;
  }

type progress_slots = (int64, Bigarray.int64_elt, Bigarray.c_layout) Bigarray.Array1.t

(* Worker [w] of [jobs] counts the rows it has finished, over every pass,
   in slot [w] and its rays in slot [jobs + w]: writes of its own, read by
   the parent between them. The type is known here, so that a write
   allocates nothing. *)
let count_row (slots : progress_slots) ~jobs w ~rays =
  Bigarray.Array1.set slots w (Int64.succ (Bigarray.Array1.get slots w));
  Bigarray.Array1.set slots (jobs + w) (Int64.of_int rays)

let sum_slots (slots : progress_slots) lo n =
  let s = ref 0 in
  for k = lo to lo + n - 1 do
    s := !s + Int64.to_int (Bigarray.Array1.get slots k)
  done;
  !s

(* Guided scheduling: bands of consecutive rows, each an eighth of the
   rows still to hand out per job, down to [least] rows. The first bands are
   large (few tasks), the last ones a row: the workers finish within about
   a row of each other, whatever the rows cost. *)
let bands_from ~least ~jobs n =
  let rec go acc r =
    if r >= n then Array.of_list (List.rev (n :: acc)) else go (r :: acc) (r + max least ((n - r) / (8 * jobs)))
  in
  go [] 0

let bands ~jobs n =
  let rec fit least =
    let b = bands_from ~least ~jobs n in
    if Array.length b - 1 <= Parallel.max_tasks then b else fit (2 * least)
  in
  fit 1

(* A pass starts once the previous one has finished in every worker. Its
   rows are cut into {!bands} that the workers take from a queue in order
   as they go: they finish together even if a core is slowed or some rows
   cost more, and the image is complete from the top down as the bands
   come back (the parent is told of each on {!Parallel.reports}), so that
   [rows_done] can write it while the workers still trace. *)
let bvh_beside ?(min_objects = 1 lsl 16) ?(idle = Parallel.idle_core) ?(take_over = true) () =
  (* The floats in memory shared with the child: its part's leaves' boxes
     come back in order, no permutation followed through them here. The
     child reserves what it sends, once it knows how much: nothing is
     written before the fork (28 MB of zeros for a million objects, in
     /dev/shm). Their descriptors are let go once the child is waited
     for. *)
  let pending = ref [] in
  let floats n =
    let r = Parallel.shared_floats_later n in
    pending := r :: !pending;
    (r.floats, r.reserve)
  in
  (* A child that has had too little of a core to finish before this
     process could do its part again is killed and its part built here
     ([take_over]): a core taken after the fork costs about the fork. *)
  let beside f =
    let wait = Parallel.beside ~take_over f in
    fun () ->
      let r = wait () in
      List.iter (fun (r : Parallel.reserved_later) -> r.release ()) !pending;
      pending := [];
      Result.to_option r
  in
  (* [idle] is asked at each fork (the twins' child, the hierarchy's
     half), where the other core's state is known best: with it busy,
     the part is computed here, as with one job. *)
  { Bvh.beside; min_objects; floats; idle }

(* Every piece of shared memory is taken before the scene is prepared:
   where one cannot be had (a full /dev/shm, a file-size limit), the
   render is [one_process scene], the same picture traced in this process,
   which needs none. Nothing here holds the scene past
   [Prepared.prepare], which lets its spheres go as it builds the
   hierarchy ([one_process] does not hold it either). *)
let in_workers ~limits ~jobs ~split ~one_process ?skips ?progress ?rows_done sampling scene (region : Render.Region.t) =
  let canvas = (let s = Scene.of_valid scene in (Scene.width s, Scene.height s)) in
  match Image.of_buffer region.w region.h (Parallel.shared_bytes (3 * Render.Region.pixels region)) with
  | exception Out_of_memory -> Render_work.out_of_memory region
  | exception Failure _ -> one_process scene
  | img -> (
      match Sampling_rows.plan ~memory:shared_memory sampling img ~canvas ~at:(region.x, region.y) with
      | exception Failure _ -> one_process scene
      | plan ->
      let passes = Sampling_rows.passes plan in
      match Parallel.shared_ints (passes * jobs * Render_work.counter_fields) with
      | exception Out_of_memory -> Render_work.out_of_memory region
      | exception Failure _ -> one_process scene
      | ints -> (
          match Option.map (fun _ -> Parallel.shared_ints (2 * jobs)) progress with
          | exception Out_of_memory -> Render_work.out_of_memory region
          | exception Failure _ -> one_process scene
          | slots ->
          let t0 = Unix.gettimeofday () in
          (* A part of a big hierarchy is built by a child process meanwhile,
             where a core is idle when it would be forked: on a machine
             whose cores are all busy the child waits for one, and preparing
             takes longer (docs/performance.md, issue 31). A child that
             falls behind after the fork is taken over ([bvh_beside]).
             [`Always] forks it whatever the host (the tests). *)
          let idle = match split with `Always -> fun () -> true | `Auto -> Parallel.idle_core in
          let beside = if jobs > 1 then Some (bvh_beside ~idle ()) else None in
          let p = Prepared.prepare ?skips ?beside scene in
          let t1 = Unix.gettimeofday () in
          let total = Render_work.total_rows plan in
          let report () =
            match (progress, slots) with
            | Some progress, Some slots ->
                progress ~rows:(sum_slots slots 0 jobs) ~total ~rays:(sum_slots slots jobs jobs)
            | _ -> ()
          in
          let averaging = Render.Sampling.averaging sampling in
          let budget = Limits.work_budget limits in
          (* Tests and box tests of every slot; a loop, since workers call it
             between bands and their allocation is measured. *)
          let work_done (ints : Render_work.counters) =
            let n = ref 0 in
            for w = 0 to (passes * jobs) - 1 do
              let k = w * Render_work.counter_fields in
              n := !n + Int64.to_int ints.{k + 3} + Int64.to_int ints.{k + 6}
            done;
            !n
          in
          let wait () = Unix.sleepf 0.001 in
          let over_budget n = Error (`Msg (Limits.work_exceeded limits n)) in
          let rec run i =
            if i = passes then
              let () = report () in
              let t2 = Unix.gettimeofday () in
              Ok
                ( img,
                  Render_work.stats ints ~slots:(passes * jobs) ~pixels:(Render.Region.pixels region) ~jobs
                    ~prepare_s:(t1 -. t0) ~trace_s:(t2 -. t1) )
            else
              let n = Sampling_rows.pass_rows plan i in
              let bands = bands ~jobs n in
              let count = Array.length bands - 1 in
              let queue = Parallel.queue count in
              let reports = Parallel.reports () in
              (* Rows of the image are final as their bands come back only
                 in a single pass, whose rows are the image's. *)
              let streamed = passes = 1 && n = region.h in
              let finished = Array.make count false and complete = ref 0 in
              let band_done b =
                finished.(b) <- true;
                let before = !complete in
                while !complete < count && finished.(!complete) do incr complete done;
                if streamed && !complete > before then Option.iter (fun f -> f img bands.(!complete)) rows_done
              in
              let work w =
                let tr = Trace.create ~averaging p in
                let slot = (i * jobs) + w in
                let before = Gc.minor_words () in
                let publish () = Render_work.save ints slot tr (Gc.minor_words () -. before) in
                (* The work budget is shared: a worker reserves a slice of
                   what is left, and once it has done that, publishes its
                   count and reserves the next (Render_work.refill). *)
                let refill _ = Render_work.refill ~wait ints ~slots:(passes * jobs) ~slot ~budget ~jobs tr in
                let rec loop () =
                  let b = Parallel.take queue in
                  if b >= 0 then begin
                    publish ();
                    (* Rays of the earlier passes, whose tracers are gone. *)
                    let earlier =
                      match slots with
                      | Some slots -> Int64.to_int (Bigarray.Array1.get slots (jobs + w)) - Render_work.rays tr
                      | None -> 0
                    in
                    (* Square by square where the pass allows
                       ([Sampling_rows.band]), the rows counted for the
                       progress after each band of them. *)
                    let r = ref bands.(b) and stop = bands.(b + 1) and rows = Sampling_rows.band_rows plan tr in
                    while !r < stop do
                      let last = min stop (!r + rows) in
                      Sampling_rows.band plan i tr ~first:!r ~last;
                      (match slots with
                      | Some slots ->
                          for _ = !r to last - 1 do
                            count_row slots ~jobs w ~rays:(earlier + Render_work.rays tr)
                          done
                      | None -> ());
                      r := last
                    done;
                    Parallel.report reports b;
                    loop ()
                  end
                in
                (try
                   Trace.set_budget ~refill tr (refill 0);
                   loop ()
                 with Limits.Work_exceeded _ -> ());
                Render_work.release ints slot tr;
                publish ()
              in
              let tick = Option.map (fun _ -> report) progress in
              let result = Parallel.run ?tick ~reports:(reports, band_done) jobs work in
              Parallel.close_queue queue;
              Parallel.close_reports reports;
              match result with
              | Error e -> Error e
              | Ok () ->
                  if work_done ints > budget then over_budget (work_done ints)
                  else begin
                    if i = passes - 1 && not streamed then Option.iter (fun f -> f img region.h) rows_done;
                    run (i + 1)
                  end
          in
          run 0))

type split = [ `Auto | `Always ]

let least_split_work = 1 lsl 20

(* The objects of the hierarchy that a ray descends (each mesh triangle
   one, a CSG solid or an instance one), counted from the scene's lists:
   nothing is prepared yet. *)
let hierarchy_objects scene =
  let s = Scene.view (Scene.of_valid scene) in
  List.fold_left
    (fun n (_, sh) -> match (sh : Shape.t) with Mesh m -> n + Mesh.objects m | _ -> n + 1)
    (Spheres.length s.spheres) s.placed

(* Splitting the trace costs the workers' fork and the shared memory, paid
   whatever the image: it pays only where the trace is long enough to
   halve that cost and more, and where a worker finds a core of its own
   (with the other core busy, two workers share one and finish no sooner).
   The trace's length is guessed before anything is prepared, from its
   primary rays times the levels of a hierarchy of the scene's objects
   (a ray's walk grows with their logarithm): the threshold is where the
   reference scene's trace, measured, starts to gain from two workers
   (about 600 x 600), and a million-triangle mesh splits at 200 x 250
   (docs/performance.md, "Issue 31, round 3"). *)
let split_work scene (region : Render.Region.t) ~samples =
  let levels = 1. +. Float.log2 (1. +. Float.of_int (hierarchy_objects scene)) in
  Float.of_int (Render.Region.pixels region * samples * samples) *. levels

let splits ~split ~jobs scene region (sampling : Render.Sampling.t) =
  jobs > 1
  &&
  match split with
  | `Always -> true
  | `Auto ->
      split_work scene region ~samples:sampling.samples >= Float.of_int least_split_work && Parallel.idle_core ()

let region_image ?(limits = Limits.default) ?(jobs = 1) ?(split = `Auto) ?skips ?samples ?adaptive ?subsample
    ?progress ?rows_done scene (region : Render.Region.t) =
  if jobs < 1 then invalid_arg "Render_jobs.region_image: jobs < 1";
  Render_work.inside "Render_jobs.region_image" scene region;
  (* Matches, not [let*]: a closure would hold [scene] through the render
     with [rows_done] (see [Render.region_image]). *)
  match Render.Sampling.v ?samples ?adaptive ?subsample () with
  | Error _ as e -> e
  | Ok sampling -> (
      match Render_work.check ~limits scene region sampling with
      | Error _ as e -> e
      | Ok () -> (
          match check_memory region with
          | Error _ as e -> e
          | Ok () -> (
              let jobs = min jobs region.h in
              (* A function of the scene, not a closure over it: passed to
                 [in_workers], it would hold the scene through the render. *)
              let one_process ?beside scene =
                match
                  Render_region.region_image ~limits ~clock:Unix.gettimeofday ?skips ?beside ?samples ?adaptive ?subsample
                    ?progress scene region
                with
                | Error _ as e -> e
                | Ok (img, stats) ->
                    Option.iter (fun f -> f img region.h) rows_done;
                    Ok (img, stats)
              in
              if splits ~split ~jobs scene region sampling then
                in_workers ~limits ~jobs ~split ~one_process:(fun s -> one_process s) ?skips ?progress ?rows_done
                  sampling scene region
              else if jobs > 1 then
                (* A trace too short to split may follow a big build: its
                   child is still forked where a core is idle. *)
                one_process ~beside:(bvh_beside ()) scene
              else one_process scene)))

let image ?limits ?jobs ?split ?skips ?samples ?adaptive ?subsample ?progress ?rows_done scene =
  if Option.value jobs ~default:1 < 1 then invalid_arg "Render_jobs.image: jobs < 1";
  let s = Scene.of_valid scene in
  region_image ?limits ?jobs ?split ?skips ?samples ?adaptive ?subsample ?progress ?rows_done scene
    (Render.Region.full ~width:(Scene.width s) ~height:(Scene.height s))
