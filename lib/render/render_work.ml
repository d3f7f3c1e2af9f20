let ( let* ) = Result.bind

let inside fn scene (region : Region.t) =
  let s = Scene.view (Scene.of_valid scene) in
  if not (Region.contains region ~width:s.width ~height:s.height) then
    invalid_arg (fn ^ ": region outside the canvas")

(* Refused before anything is allocated: a render that cannot finish
   should fail now, not after hours or with the machine out of memory. At
   most [samples x samples] rays a pixel (adaptive sampling traces fewer,
   subsampling about half a ray), and under a lens adaptive sampling's
   four probes of a pixel besides: counted in the work, not in the
   samples. *)
let check ~limits scene (region : Region.t) (sampling : Sampling.t) =
  let rays_per_pixel = sampling.samples * sampling.samples in
  let* _ = Limits.check_samples limits rays_per_pixel in
  let lens = Camera.has_lens (Scene.view (Scene.of_valid scene)).camera in
  (* An even adaptive grid has no centre sample for the first ray: under a
     lens, where the first ray is noise anyway, it is traced whole;
     without one it would waste or bias the first ray (Sampling). *)
  let* () =
    if sampling.adaptive <> None && sampling.samples land 1 = 0 && not lens then
      Error (`Msg (Sampling.even_message sampling.samples))
    else Ok ()
  in
  let probes = if sampling.adaptive <> None && lens then 4 else 0 in
  Scene.check_work ~limits ~samples:(rays_per_pixel + probes) ~pixels:(Region.pixels region) scene

let out_of_memory (region : Region.t) =
  let mib = Float.of_int (3 * Region.pixels region) /. 1048576. in
  Error (`Msg (Printf.sprintf "not enough memory for a %dx%d image (%.0f MiB)" region.w region.h mib))

let counter_fields = 12

type counters = (int64, Bigarray.int64_elt, Bigarray.c_layout) Bigarray.Array1.t

(* Slot [w]'s counters are at [w * counter_fields ...]. *)
let save ints w tr words =
  let c = Trace.counters tr in
  let k = w * counter_fields in
  let set i v = Bigarray.Array1.set ints (k + i) (Int64.of_int v) in
  set 0 c.primary;
  set 1 c.shadow;
  set 2 c.reflection;
  set 3 c.tests;
  set 4 c.early_stops;
  set 5 (truncate words);
  set 6 c.box_tests;
  set 8 c.decided;
  set 9 c.penumbra;
  set 10 c.umbra;
  set 11 c.whole

let save_work ?(base = 0) ints w tr =
  let c = Trace.counters tr in
  let k = w * counter_fields in
  Bigarray.Array1.set ints (k + 3) (Int64.of_int (c.tests - base));
  Bigarray.Array1.set ints (k + 6) (Int64.of_int c.box_tests)

let field ints w i = Int64.to_int (Bigarray.Array1.get ints ((w * counter_fields) + i))

(* Each worker reserves its slice in its slot before it works through it:
   a worker takes a [jobs]th of what nobody has done or reserved, so that
   even workers that refill at the same moment reserve at most what is
   left between them (and at least a 64th of a [jobs]th of the whole:
   slices that shrank to nothing would make workers refill at every
   pixel). Once all is reserved, a worker waits for the others to do or
   give back what they hold; once all is done, it takes a last small
   slice, past which the render stops. *)
let refill ?(base = 0) ?(wait = ignore) ints ~slots ~slot ~budget ~jobs tr =
  save_work ~base ints slot tr;
  let own = Trace.work tr - base and least = max 1 (budget / (64 * jobs)) in
  let rec next () =
    let total = ref 0 and others = ref 0 and unused = ref 0 in
    for w = 0 to slots - 1 do
      let d = field ints w 3 + field ints w 6 in
      total := !total + d;
      if w <> slot then begin
        let r = field ints w 7 in
        others := !others + max d r;
        unused := !unused + max 0 (r - d)
      end
    done;
    if !total > budget then raise (Limits.Work_exceeded (base + !total));
    let free = budget - !others - own in
    if free > 0 then max least (free / jobs)
    else if !unused > 0 then begin
      wait ();
      next ()
    end
    else least
  in
  let slice = next () in
  let reserved = if own > max_int - slice then max_int else own + slice in
  Bigarray.Array1.set ints ((slot * counter_fields) + 7) (Int64.of_int reserved);
  if reserved > max_int - base then max_int else base + reserved

let release ?(base = 0) ints slot tr =
  Bigarray.Array1.set ints ((slot * counter_fields) + 7) (Int64.of_int (Trace.work tr - base))

let stats ints ~slots ~pixels ~jobs ~prepare_s ~trace_s =
  let sum i = List.init slots (fun w -> Int64.to_int ints.{(w * counter_fields) + i}) |> List.fold_left ( + ) 0 in
  Stats.
    {
      pixels;
      primary = sum 0;
      shadow = sum 1;
      reflection = sum 2;
      tests = sum 3;
      box_tests = sum 6;
      early_stops = sum 4;
      decided = sum 8;
      penumbra = sum 9;
      umbra = sum 10;
      whole = sum 11;
      jobs;
      prepare_s;
      trace_s;
      minor_words = Float.of_int (sum 5);
    }

let rays tr =
  let c = Trace.counters tr in
  c.primary + c.shadow + c.reflection

let total_rows plan =
  let t = ref 0 in
  for i = 0 to Sampling_rows.passes plan - 1 do
    t := !t + Sampling_rows.pass_rows plan i
  done;
  !t
