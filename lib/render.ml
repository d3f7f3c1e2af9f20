let counter_fields = 7

(* Worker [w]'s counters go to slots [w * counter_fields ...]. *)
let save_counters ints w tr words =
  let c = Trace.counters tr in
  let k = w * counter_fields in
  let set i v = Bigarray.Array1.set ints (k + i) (Int64.of_int v) in
  set 0 c.primary;
  set 1 c.shadow;
  set 2 c.reflection;
  set 3 c.tests;
  set 4 c.early_stops;
  set 5 (truncate words);
  set 6 c.box_tests

(* Refused before anything is allocated: a render that cannot finish
   should fail now, not after hours or with the machine out of memory. *)
let check_resources (scene : Scene.t) (region : Region.t) ~rays_per_pixel =
  let ( let* ) = Result.bind in
  let* _ = Result.map_error (fun m -> `Msg m) (Limits.check_samples rays_per_pixel) in
  let* () = Scene.check_work ~samples:rays_per_pixel ~pixels:(Region.pixels region) scene in
  let bytes = 3 * Region.pixels region in
  match Parallel.available_memory () with
  | Some available when bytes > available ->
      let gib n = Float.of_int n /. 1073741824. in
      Error
        (`Msg
          (Printf.sprintf "a %dx%d image needs %.2f GiB of memory, but only %.2f GiB are available"
             region.w region.h (gib bytes) (gib available)))
  | _ -> Ok ()

let out_of_memory (region : Region.t) =
  let mib = Float.of_int (3 * Region.pixels region) /. 1048576. in
  Error (`Msg (Printf.sprintf "not enough memory for a %dx%d image (%.0f MiB)" region.w region.h mib))

(* Rays cast so far by [tr]. *)
let rays tr =
  let c = Trace.counters tr in
  c.primary + c.shadow + c.reflection

let total_rows plan =
  let t = ref 0 in
  for i = 0 to Sampling.passes plan - 1 do
    t := !t + Sampling.pass_rows plan i
  done;
  !t

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

let region_image ?(jobs = 1) ?skips ?samples ?adaptive ?subsample ?progress (scene : Scene.t) (region : Region.t) =
  if jobs < 1 then invalid_arg "Render.region_image: jobs < 1";
  if not (Region.contains region ~width:scene.width ~height:scene.height) then
    invalid_arg "Render.region_image: region outside the canvas";
  let sampling =
    match Sampling.v ?samples ?adaptive ?subsample () with
    | Ok s -> s
    | Error (`Msg m) -> invalid_arg ("Render.region_image: " ^ m)
  in
  (* At most [samples x samples] rays a pixel (adaptive sampling traces
     fewer, subsampling about half a ray). *)
  let rays_per_pixel = sampling.samples * sampling.samples in
  match check_resources scene region ~rays_per_pixel with
  | Error e -> Error e
  | Ok () ->
  let t0 = Unix.gettimeofday () in
  let p = Prepared.prepare ?skips scene in
  let t1 = Unix.gettimeofday () in
  let jobs = min jobs region.h in
  (* Counter slots: one per worker and pass. *)
  let slots = ref jobs in
  let sum ints i = List.init !slots (fun w -> Int64.to_int ints.{(w * counter_fields) + i}) |> List.fold_left ( + ) 0 in
  let finish img ints =
    let t2 = Unix.gettimeofday () in
    let stats =
      Stats.
        {
          pixels = Region.pixels region;
          primary = sum ints 0;
          shadow = sum ints 1;
          reflection = sum ints 2;
          tests = sum ints 3;
          box_tests = sum ints 6;
          early_stops = sum ints 4;
          jobs;
          prepare_s = t1 -. t0;
          trace_s = t2 -. t1;
          minor_words = Float.of_int (sum ints 5);
        }
    in
    Ok (img, stats)
  in
  let averaging = Sampling.averaging sampling in
  let budget = Limits.work_budget () in
  (* Tests and box tests of every slot; a loop, since workers call it
     between classes of rows and their allocation is measured. *)
  let work_done (ints : (int64, Bigarray.int64_elt, Bigarray.c_layout) Bigarray.Array1.t) =
    let n = ref 0 in
    for w = 0 to !slots - 1 do
      let k = w * counter_fields in
      n := !n + Int64.to_int ints.{k + 3} + Int64.to_int ints.{k + 6}
    done;
    !n
  in
  let over_budget n = Error (`Msg (Limits.work_exceeded n)) in
  if jobs = 1 then begin
    (* One tracer for every pass. *)
    match Image.create region.w region.h with
    | exception Out_of_memory -> out_of_memory region
    | img ->
    let plan = Sampling.plan sampling img ~canvas:(scene.width, scene.height) ~at:(region.x, region.y) ~shared:false in
    let ints = Bigarray.Array1.create Bigarray.int64 Bigarray.c_layout counter_fields in
    let tr = Trace.create ~averaging p in
    (* What the caller's [progress] allocates is not the tracer's. *)
    let progress_words = Array.make 1 0. in
    let before = Gc.minor_words () in
    match
      match progress with
      | None ->
          for i = 0 to Sampling.passes plan - 1 do
            Sampling.rows plan i tr ~first:0 ~step:1
          done
      | Some progress ->
          let total = total_rows plan in
          let finished = ref 0 in
          for i = 0 to Sampling.passes plan - 1 do
            let n = Sampling.pass_rows plan i in
            for r = 0 to n - 1 do
              Sampling.rows plan i tr ~first:r ~step:n;
              incr finished;
              let w = Gc.minor_words () in
              progress ~rows:!finished ~total ~rays:(rays tr);
              progress_words.(0) <- progress_words.(0) +. (Gc.minor_words () -. w)
            done
          done
    with
    | exception Limits.Work_exceeded n -> over_budget n
    | () ->
        save_counters ints 0 tr (Gc.minor_words () -. before -. progress_words.(0));
        finish img ints
  end
  else
    match Image.of_buffer region.w region.h (Parallel.shared_bytes (3 * Region.pixels region)) with
    | exception Out_of_memory -> out_of_memory region
    | exception Failure m -> Error (`Msg m)
    | img ->
    let plan = Sampling.plan sampling img ~canvas:(scene.width, scene.height) ~at:(region.x, region.y) ~shared:true in
    let passes = Sampling.passes plan in
    slots := passes * jobs;
    match Parallel.shared_ints (passes * jobs * counter_fields) with
    | exception Out_of_memory -> out_of_memory region
    | exception Failure m -> Error (`Msg m)
    | ints ->
    match Option.map (fun _ -> Parallel.shared_ints (2 * jobs)) progress with
    | exception Out_of_memory -> out_of_memory region
    | exception Failure m -> Error (`Msg m)
    | progress_slots ->
    let total = total_rows plan in
    let report () =
      match (progress, progress_slots) with
      | Some progress, Some slots ->
          progress ~rows:(sum_slots slots 0 jobs) ~total ~rays:(sum_slots slots jobs jobs)
      | _ -> ()
    in
    (* A pass starts once the previous one has finished in every worker.
       Its rows are dealt into [classes] interleaved classes (rows c,
       c + classes, ...), all about as costly, that the workers take from a
       queue as they go: they finish together even if a core is slowed. *)
    let classes = min Parallel.max_tasks (min region.h (32 * jobs)) in
    let rec run i =
      if i = passes then begin
        report ();
        finish img ints
      end
      else
        let queue = Parallel.queue classes in
        let n = Sampling.pass_rows plan i in
        let work w =
          let tr = Trace.create ~averaging p in
          let slot = (i * jobs) + w in
          let before = Gc.minor_words () in
          let publish () = save_counters ints slot tr (Gc.minor_words () -. before) in
          (* The work budget is shared: before each class of rows, a
             worker publishes its count and keeps for itself what the
             others (as last published) have left. *)
          let rec loop () =
            let c = Parallel.take queue in
            if c >= 0 then begin
              publish ();
              Trace.set_budget tr (budget - (work_done ints - Trace.work tr));
              (match progress_slots with
              | None -> Sampling.rows plan i tr ~first:c ~step:classes
              | Some slots ->
                  (* Rays of the earlier passes, whose tracers are gone. *)
                  let earlier = Int64.to_int (Bigarray.Array1.get slots (jobs + w)) - rays tr in
                  let r = ref c in
                  while !r < n do
                    Sampling.rows plan i tr ~first:!r ~step:n;
                    count_row slots ~jobs w ~rays:(earlier + rays tr);
                    r := !r + classes
                  done);
              loop ()
            end
          in
          (try loop () with Limits.Work_exceeded _ -> ());
          publish ()
        in
        let tick = Option.map (fun _ -> report) progress in
        let result = Parallel.run ?tick jobs work in
        Parallel.close_queue queue;
        match result with
        | Error e -> Error e
        | Ok () -> if work_done ints > budget then over_budget (work_done ints) else run (i + 1)
    in
    run 0

let image ?jobs ?skips ?samples ?adaptive ?subsample ?progress (scene : Scene.t) =
  region_image ?jobs ?skips ?samples ?adaptive ?subsample ?progress scene (Region.full ~width:scene.width ~height:scene.height)

let image_exn ?jobs ?skips ?samples ?adaptive ?subsample scene =
  match image ?jobs ?skips ?samples ?adaptive ?subsample scene with
  | Ok (img, _) -> img
  | Error (`Msg m) -> failwith m
