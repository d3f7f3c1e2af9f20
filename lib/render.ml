let check_size tr img fn =
  let p = Trace.prepared tr in
  if Image.width img <> p.width || Image.height img <> p.height then
    invalid_arg (Printf.sprintf "Render.%s: image size differs from the canvas" fn)

(* One image row: canvas G_y from the row (the one flip, Canvas.y_of_row),
   then each column's G_x. *)
let row tr buffer ~width ~height ~x0 ~x1 r =
  let gy = Canvas.y_of_row ~height r in
  for x = x0 to x1 - 1 do
    Trace.pixel tr (Canvas.x_of_column ~width x) gy;
    Trace.store tr buffer (3 * ((r * width) + x))
  done

let rows tr img ~first ~step =
  check_size tr img "rows";
  if step < 1 then invalid_arg "Render.rows: step < 1";
  let width = Image.width img and height = Image.height img in
  let buffer = Image.buffer img in
  let r = ref first in
  while !r < height do
    (* A worker whose parent was killed stops here, within one row. *)
    Parallel.exit_if_orphaned ();
    row tr buffer ~width ~height ~x0:0 ~x1:width !r;
    r := !r + step
  done

let region tr img ~x ~y ~w ~h =
  check_size tr img "region";
  let width = Image.width img and height = Image.height img in
  if x < 0 || y < 0 || w < 0 || h < 0 || x + w > width || y + h > height then
    invalid_arg "Render.region: region outside the canvas";
  let buffer = Image.buffer img in
  for r = y to y + h - 1 do
    row tr buffer ~width ~height ~x0:x ~x1:(x + w) r
  done

let counter_fields = 6

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
  set 5 (truncate words)

(* Refused before anything is allocated: a render that cannot finish
   should fail now, not after hours or with the machine out of memory. *)
let check_resources (scene : Scene.t) =
  match Scene.check_work scene with
  | Error e -> Error e
  | Ok () -> (
      let bytes = 3 * scene.width * scene.height in
      match Parallel.available_memory () with
      | Some available when bytes > available ->
          let gib n = Float.of_int n /. 1073741824. in
          Error
            (`Msg
              (Printf.sprintf "a %dx%d image needs %.2f GiB of memory, but only %.2f GiB are available"
                 scene.width scene.height (gib bytes) (gib available)))
      | _ -> Ok ())

let out_of_memory (scene : Scene.t) =
  let mib = Float.of_int (3 * scene.width * scene.height) /. 1048576. in
  Error (`Msg (Printf.sprintf "not enough memory for a %dx%d image (%.0f MiB)" scene.width scene.height mib))

let image ?(jobs = 1) ?skips (scene : Scene.t) =
  if jobs < 1 then invalid_arg "Render.image: jobs < 1";
  match check_resources scene with
  | Error e -> Error e
  | Ok () ->
  let t0 = Unix.gettimeofday () in
  let p = Prepared.prepare ?skips scene in
  let t1 = Unix.gettimeofday () in
  let jobs = min jobs scene.height in
  let sum ints i = List.init jobs (fun w -> Int64.to_int ints.{(w * counter_fields) + i}) |> List.fold_left ( + ) 0 in
  let finish img ints =
    let t2 = Unix.gettimeofday () in
    let stats =
      Stats.
        {
          pixels = scene.width * scene.height;
          primary = sum ints 0;
          shadow = sum ints 1;
          reflection = sum ints 2;
          tests = sum ints 3;
          early_stops = sum ints 4;
          jobs;
          prepare_s = t1 -. t0;
          trace_s = t2 -. t1;
          minor_words = Float.of_int (sum ints 5);
        }
    in
    Ok (img, stats)
  in
  let work img ints w =
    let tr = Trace.create p in
    let before = Gc.minor_words () in
    rows tr img ~first:w ~step:jobs;
    save_counters ints w tr (Gc.minor_words () -. before)
  in
  if jobs = 1 then
    match Image.create scene.width scene.height with
    | exception Out_of_memory -> out_of_memory scene
    | img ->
        let ints = Bigarray.Array1.create Bigarray.int64 Bigarray.c_layout counter_fields in
        work img ints 0;
        finish img ints
  else
    match
      ( Image.of_buffer scene.width scene.height (Parallel.shared_bytes (3 * scene.width * scene.height)),
        Parallel.shared_ints (jobs * counter_fields) )
    with
    | exception Out_of_memory -> out_of_memory scene
    | exception Failure m -> Error (`Msg m)
    | img, ints -> (
        match Parallel.run jobs (work img ints) with
        | Ok () -> finish img ints
        | Error e -> Error e)

let image_exn ?jobs ?skips scene =
  match image ?jobs ?skips scene with Ok (img, _) -> img | Error (`Msg m) -> failwith m
