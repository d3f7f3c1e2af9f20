let ( let* ) = Result.bind

let check_memory (region : Region.t) =
  let bytes = 3 * Region.pixels region in
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
    Sampling.bytes = Parallel.shared_bytes;
    floats = Parallel.shared_floats;
    ints = Parallel.shared_ints;
    at_row = Parallel.exit_if_orphaned;
  }

(* A pass starts once the previous one has finished in every worker. Its
   rows are dealt into [classes] interleaved classes (rows c, c + classes,
   ...), all about as costly, that the workers take from a queue as they
   go: they finish together even if a core is slowed. *)
let in_workers ~jobs ?skips sampling scene (region : Region.t) =
  let s = Scene.of_valid scene in
  match Image.of_buffer region.w region.h (Parallel.shared_bytes (3 * Region.pixels region)) with
  | exception Out_of_memory -> Render_work.out_of_memory region
  | exception Failure m -> Error (`Msg m)
  | img -> (
      let t0 = Unix.gettimeofday () in
      let p = Prepared.prepare ?skips scene in
      let t1 = Unix.gettimeofday () in
      let plan =
        Sampling.plan ~memory:shared_memory sampling img ~canvas:(s.width, s.height) ~at:(region.x, region.y)
      in
      let passes = Sampling.passes plan in
      match Parallel.shared_ints (passes * jobs * Render_work.counter_fields) with
      | exception Out_of_memory -> Render_work.out_of_memory region
      | exception Failure m -> Error (`Msg m)
      | ints ->
          let averaging = Sampling.averaging sampling in
          let classes = min Parallel.max_tasks (min region.h (32 * jobs)) in
          let rec run i =
            if i = passes then
              let t2 = Unix.gettimeofday () in
              Ok
                ( img,
                  Render_work.stats ints ~slots:(passes * jobs) ~pixels:(Region.pixels region) ~jobs
                    ~prepare_s:(t1 -. t0) ~trace_s:(t2 -. t1) )
            else
              let queue = Parallel.queue classes in
              let work w =
                let tr = Trace.create ~averaging p in
                let before = Gc.minor_words () in
                let rec loop () =
                  let c = Parallel.take queue in
                  if c >= 0 then begin
                    Sampling.rows plan i tr ~first:c ~step:classes;
                    loop ()
                  end
                in
                loop ();
                Render_work.save ints ((i * jobs) + w) tr (Gc.minor_words () -. before)
              in
              let result = Parallel.run jobs work in
              Parallel.close_queue queue;
              match result with Ok () -> run (i + 1) | Error e -> Error e
          in
          run 0)

let region_image ?(limits = Limits.default) ?(jobs = 1) ?skips ?samples ?adaptive ?subsample scene
    (region : Region.t) =
  if jobs < 1 then invalid_arg "Render_jobs.region_image: jobs < 1";
  Render_work.inside "Render_jobs.region_image" scene region;
  let* sampling = Sampling.v ?samples ?adaptive ?subsample () in
  let* () = Render_work.check ~limits scene region sampling in
  let* () = check_memory region in
  let jobs = min jobs region.h in
  if jobs = 1 then
    Render.region_image ~limits ~clock:Unix.gettimeofday ?skips ?samples ?adaptive ?subsample scene region
  else in_workers ~jobs ?skips sampling scene region

let image ?limits ?jobs ?skips ?samples ?adaptive ?subsample scene =
  if Option.value jobs ~default:1 < 1 then invalid_arg "Render_jobs.image: jobs < 1";
  let s = Scene.of_valid scene in
  region_image ?limits ?jobs ?skips ?samples ?adaptive ?subsample scene (Region.full ~width:s.width ~height:s.height)
