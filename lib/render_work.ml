let ( let* ) = Result.bind

let inside fn scene (region : Region.t) =
  let s = Scene.of_valid scene in
  if not (Region.contains region ~width:s.width ~height:s.height) then
    invalid_arg (fn ^ ": region outside the canvas")

(* Refused before anything is allocated: a render that cannot finish
   should fail now, not after hours or with the machine out of memory. At
   most [samples x samples] rays a pixel (adaptive sampling traces fewer,
   subsampling about half a ray). *)
let check ~limits scene (region : Region.t) (sampling : Sampling.t) =
  let rays_per_pixel = sampling.samples * sampling.samples in
  let* _ = Limits.check_samples limits rays_per_pixel in
  Scene.check_work ~limits ~samples:rays_per_pixel ~pixels:(Region.pixels region) scene

let out_of_memory (region : Region.t) =
  let mib = Float.of_int (3 * Region.pixels region) /. 1048576. in
  Error (`Msg (Printf.sprintf "not enough memory for a %dx%d image (%.0f MiB)" region.w region.h mib))

let counter_fields = 7

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
  set 6 c.box_tests

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
  for i = 0 to Sampling.passes plan - 1 do
    t := !t + Sampling.pass_rows plan i
  done;
  !t
