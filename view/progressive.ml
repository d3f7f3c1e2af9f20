type band = { size : int; top : int; rows : int }

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
  mutable band_rows : int;  (** Rows of the band begun and not finished; [0] between bands. *)
  mutable row : int;  (** In that band: the row... *)
  mutable col : int;  (** ...and the column of the next pixel to trace. *)
  mutable failure : string option;
  mutable stopped : string option;  (** Why the render stopped before its end. *)
  limits : Limits.t;
}

type poll = Between_pixels | Inside_pixel
type outcome = Band of band | Paused | Done


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
    | None -> Image.create (Scene.width scene) (Scene.height scene)
    | Some w ->
        if Image.width w.image <> (Scene.width scene) || Image.height w.image <> (Scene.height scene) then
          invalid_arg "Progressive.create: the workers' image is not of the canvas size";
        w.image
  in
  { tr; img; samples; workers; passes = passes samples; pass = 0; top = 0; band_rows = 0; row = 0; col = 0; failure = None; stopped = None; limits }

let finished (r : t) = r.pass >= Array.length r.passes
let image r = r.img
let samples r = r.samples
let tracer r = r.tr
let failure r = r.failure
let stopped r = r.stopped

(* Raised by the poll hook (see [arm]): the front end wants its thread
   back. The pixel being traced, if any, is traced again later. *)
exception Pause

(* Tests between two looks of the front end: a few milliseconds of
   tracing, natively or in a browser. *)
let poll_tests = 1 lsl 16

(* Where the tracer of a render is: [between] pixels, [inside] one, or
   inside one where the front end was asked and said to go on. *)
let between = 0
let inside = 1
let looked = 2

(* Makes [r]'s tracer call [poll] about every [poll_tests] tests, inside
   pixels (at each hit of a ray tree) and between them, and raise [Pause]
   when it says so; without [poll], the budget alone, as {!create} set it.
   The next look is [w + poll_tests], or the budget if that is nearer: an
   int of 32 bits (in a browser) may wrap there, and then the hook is
   only called more often until the count wraps too. [where] is set by
   [trace_row]. Is what to do at a pixel's end: a pixel in which the
   front end was asked gets a look at its end too, where pausing loses
   nothing (the look of a clock that said "not yet, inside a pixel" may
   say "now" there). *)
let arm (r : t) poll ~where =
  let budget = Limits.work_budget r.limits in
  match poll with
  | None ->
      Trace.set_budget r.tr budget;
      fun () -> ()
  | Some poll ->
      let next w = if w + poll_tests > budget then budget else w + poll_tests in
      (* The next look is set before [poll], which may raise [Pause]. *)
      let rec look w =
        if w > budget then raise (Limits.Work_exceeded w);
        Trace.set_budget r.tr ~refill:look (next w);
        if !where = between then (if poll Between_pixels then raise Pause)
        else begin
          where := looked;
          if poll Inside_pixel then raise Pause
        end;
        next w
      in
      Trace.set_budget r.tr ~refill:look (next (Trace.work r.tr));
      fun () -> if poll Between_pixels then raise Pause

(* Row [row] of pass [pass], traced by [tr] into [r]'s image from column
   [from] on; [r.col] is the next column to trace, kept when [Pause]
   interrupts. [where] and [pixel_end]: see [arm]. *)
let trace_row (r : t) tr ?(where = ref between) ?(pixel_end = ignore) ?(from = 0) pass row =
  let width = Image.width r.img and height = Image.height r.img in
  let buffer = Image.buffer r.img in
  let size, n = r.passes.(pass) in
  let gy = Canvas.y_of_row ~height row in
  (* The grid of the previous one-sample pass holds every pixel traced
     so far: the block sizes divide each other. *)
  let prev = if pass = 0 || n > 1 then 0 else fst r.passes.(pass - 1) in
  let row_done = prev > 0 && row mod prev = 0 in
  let col = ref from in
  while !col < width do
    r.col <- !col;
    if not (row_done && !col mod prev = 0) then begin
      where := inside;
      let k = 3 * ((row * width) + !col) in
      if n > 1 then Antialias.store tr buffer (Canvas.x_of_column ~width !col) gy ~n k
      else begin
        Trace.pixel tr (Canvas.x_of_column ~width !col) gy;
        Trace.store tr buffer k
      end;
      r.col <- !col + size;
      let was = !where in
      where := between;
      if was = looked then pixel_end ();
      (* Between pixels: the budget, or a look of the front end. *)
      Trace.check_budget tr
    end;
    col := !col + size
  done;
  r.col <- width;
  Trace.check_budget tr

(* Rows [top .. top + rows - 1] of a full-resolution pass, interleaved over
   the workers; each worker's tracer is its own copy of [r.tr], whose
   counts it returns. Workers do not look at the front end: its poll
   reads the parent's windows and clocks. *)
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

(* The rows of the band begun, from [r.row], [r.col] on, in this process. *)
let trace_here (r : t) ~where ~pixel_end =
  while r.row < r.top + r.band_rows do
    trace_row r r.tr ~where ~pixel_end ~from:r.col r.pass r.row;
    r.row <- r.row + 1;
    r.col <- 0
  done

(* The band begun, traced to its end: by the workers if it is a band of
   several full-resolution rows not begun yet. *)
let trace_band (r : t) ~where ~pixel_end =
  let size = fst r.passes.(r.pass) in
  match r.workers with
  | Some s when size = 1 && r.band_rows > 1 && r.failure = None && r.row = r.top && r.col = 0 -> (
      let (_ : unit -> unit) = arm r None ~where in
      match trace_rows_in_workers r s r.pass ~top:r.top ~rows:r.band_rows with
      | Ok () -> r.row <- r.top + r.band_rows
      | Error (`Msg m) ->
          (* Every pixel stands alone: trace the band again here, and go
             on in this process. *)
          r.failure <- Some m;
          trace_here r ~where ~pixel_end:ignore)
  | _ -> trace_here r ~where ~pixel_end

let advance ?(rows = 1) ?poll (r : t) =
  if rows < 1 then invalid_arg "Progressive.advance: rows < 1";
  if finished r then Done
  else begin
    let height = Image.height r.img in
    let size = fst r.passes.(r.pass) in
    if r.band_rows = 0 then begin
      (* A coarse band traces one row, its first. *)
      r.band_rows <- (if size = 1 then min rows (height - r.top) else 1);
      r.row <- r.top;
      r.col <- 0
    end;
    let where = ref between in
    let pixel_end = arm r poll ~where in
    let band_done ~stopped =
      let band = { size; top = r.top; rows = (if size = 1 then r.band_rows else min size (height - r.top)) } in
      r.band_rows <- 0;
      r.top <- r.top + (if size = 1 then band.rows else size);
      if stopped then r.pass <- Array.length r.passes
      else if r.top >= height then begin
        r.pass <- r.pass + 1;
        r.top <- 0
      end;
      Band band
    in
    match trace_band r ~where ~pixel_end with
    | () -> band_done ~stopped:false
    | exception Pause -> Paused
    | exception Limits.Work_exceeded n ->
        (* The band is incomplete: the render ends here. *)
        r.stopped <- Some (Limits.work_exceeded r.limits n);
        band_done ~stopped:true
  end

let step ?(rows = 1) (r : t) =
  if rows < 1 then invalid_arg "Progressive.step: rows < 1";
  match advance ~rows r with Band b -> Some b | Done -> None | Paused -> assert false
