type workers = {
  jobs : int;
  image : Image.t;
  run : int -> (int -> int array) -> (int array array, [ `Msg of string ]) result;
  budget : Render_work.counters;
}

type t = {
  tr : Trace.t;
  img : Image.t;
  samples : int;
  workers : workers option;
  passes : (int * int) array;  (** Block size and samples per pixel of each pass. *)
  mutable pass : int;  (** Index of the current pass; [Array.length passes] once finished. *)
  mutable top : int;  (** First row of the next band. *)
  mutable failure : string option;
  mutable stopped : string option;  (** Why the render stopped before its end. *)
  limits : Limits.t;
}

type band = { size : int; top : int; rows : int }

let coarsest = 16

(* 2 x 2 blocks would cost as much to draw as single pixels (one request
   per block), for little preview: the pass after 4 is the full one. *)
let passes samples =
  let plain = [ (coarsest, 1); (8, 1); (4, 1); (1, 1) ] in
  Array.of_list (if samples = 1 then plain else plain @ [ (1, samples) ])

let create ?(limits = Limits.default) ?(samples = 1) ?workers valid =
  if samples < 1 then invalid_arg "Progressive.create: samples < 1";
  let scene = Scene.of_valid valid in
  (* An averaging tracer, for the antialiased pass, stops reflections
     exactly for single-sample pixels too. *)
  let tr = Trace.create ~averaging:(samples > 1) (Prepared.prepare valid) in
  Trace.set_budget tr (Limits.work_budget limits);
  let img =
    match workers with
    | None -> Image.create scene.width scene.height
    | Some w ->
        if Image.width w.image <> scene.width || Image.height w.image <> scene.height then
          invalid_arg "Progressive.create: the workers' image is not of the canvas size";
        w.image
  in
  { tr; img; samples; workers; passes = passes samples; pass = 0; top = 0; failure = None; stopped = None; limits }

let finished (r : t) = r.pass >= Array.length r.passes
let image r = r.img
let samples r = r.samples
let tracer r = r.tr
let failure r = r.failure
let stopped r = r.stopped

(* Row [row] of pass [pass], traced by [tr] into [r]'s image. *)
let trace_row (r : t) tr pass row =
  let width = Image.width r.img and height = Image.height r.img in
  let buffer = Image.buffer r.img in
  let size, n = r.passes.(pass) in
  let gy = Canvas.y_of_row ~height row in
  if n > 1 then
    for col = 0 to width - 1 do
      Antialias.store tr buffer (Canvas.x_of_column ~width col) gy ~n (3 * ((row * width) + col))
    done
  else
    (* The grid of the previous one-sample pass holds every pixel traced
       so far: the block sizes divide each other. *)
    let prev = if pass = 0 then 0 else fst r.passes.(pass - 1) in
    let row_done = prev > 0 && row mod prev = 0 in
    let col = ref 0 in
    while !col < width do
      if not (row_done && !col mod prev = 0) then begin
        Trace.pixel tr (Canvas.x_of_column ~width !col) gy;
        Trace.store tr buffer (3 * ((row * width) + !col))
      end;
      col := !col + size
    done;
  Trace.check_budget tr

(* Rows [top .. top + rows - 1] of a full-resolution pass, interleaved over
   the workers; each worker's tracer is its own copy of [r.tr], whose
   counts it returns. *)
let trace_rows_in_workers (r : t) (ws : workers) pass ~top ~rows =
  let jobs = min ws.jobs rows in
  let counts () =
    let c = Trace.counters r.tr in
    [| c.primary; c.shadow; c.reflection; c.tests; c.box_tests; c.early_stops |]
  in
  (* The workers share what is left of the budget, each reserving slices
     of it (Render_work.refill): together they pass it by little. *)
  let base = Trace.work r.tr in
  let budget = Limits.work_budget r.limits - base in
  Bigarray.Array1.fill ws.budget 0L;
  let work w =
    let before = counts () in
    let row = ref (top + w) in
    (* Over its budget, a worker stops; the parent sees the sum. *)
    (try
       Trace.set_budget r.tr (base - 1)
         ~refill:(fun _ -> Render_work.refill ~base ws.budget ~slots:jobs ~slot:w ~budget ~jobs r.tr);
       while !row < top + rows do
         trace_row r r.tr pass !row;
         row := !row + jobs
       done
     with Limits.Work_exceeded _ -> ());
    Render_work.release ~base ws.budget w r.tr;
    Array.map2 ( - ) (counts ()) before
  in
  match ws.run jobs work with
  | Error _ as e -> e
  | Ok deltas ->
      let c = Trace.counters r.tr in
      let sum i = Array.fold_left (fun acc d -> acc + d.(i)) 0 deltas in
      c.primary <- c.primary + sum 0;
      c.shadow <- c.shadow + sum 1;
      c.reflection <- c.reflection + sum 2;
      c.tests <- c.tests + sum 3;
      c.box_tests <- c.box_tests + sum 4;
      c.early_stops <- c.early_stops + sum 5;
      Trace.check_budget r.tr;
      Ok ()

let step ?(rows = 1) (r : t) =
  if rows < 1 then invalid_arg "Progressive.step: rows < 1";
  if finished r then None
  else begin
    let height = Image.height r.img in
    let size = fst r.passes.(r.pass) in
    let rows = if size = 1 then min rows (height - r.top) else min size (height - r.top) in
    (match
       match r.workers with
    | Some s when size = 1 && rows > 1 && r.failure = None -> (
        match trace_rows_in_workers r s r.pass ~top:r.top ~rows with
        | Ok () -> ()
        | Error (`Msg m) ->
            (* Every pixel stands alone: trace the band again here, and go
               on in this process. *)
            r.failure <- Some m;
            for row = r.top to r.top + rows - 1 do
              trace_row r r.tr r.pass row
            done)
    | _ ->
        if size = 1 then
          for row = r.top to r.top + rows - 1 do
            trace_row r r.tr r.pass row
          done
        else trace_row r r.tr r.pass r.top
     with
    | () -> ()
    | exception Limits.Work_exceeded n ->
        (* The band is incomplete: the render ends here. *)
        r.stopped <- Some (Limits.work_exceeded r.limits n);
        r.pass <- Array.length r.passes);
    let band = { size; top = r.top; rows } in
    r.top <- r.top + (if size = 1 then rows else size);
    if r.top >= height then begin
      r.pass <- r.pass + 1;
      r.top <- 0
    end;
    Some band
  end
