type t = {
  pixels : int;
  primary : int;
  shadow : int;
  reflection : int;
  tests : int;
  box_tests : int;
  early_stops : int;
  decided : int;
  penumbra : int;
  umbra : int;
  whole : int;
  jobs : int;
  prepare_s : float;
  trace_s : float;
  minor_words : float;
}
[@@deriving show]

let rays s = s.primary + s.shadow + s.reflection

let pp_table ppf s =
  let per_pixel x = if s.pixels = 0 then 0. else x /. Float.of_int s.pixels in
  let row label value = Format.fprintf ppf "%-24s %s@\n" label value in
  let int n = Printf.sprintf "%d" n in
  row "pixels" (int s.pixels);
  row "rays, primary" (int s.primary);
  row "rays, shadow" (int s.shadow);
  row "rays, reflection" (int s.reflection);
  row "rays, total" (int (rays s));
  row "intersection tests" (int s.tests);
  row "tests per ray" (Printf.sprintf "%.2f" (Float.of_int s.tests /. Float.of_int (max 1 (rays s))));
  row "box tests" (int s.box_tests);
  row "reflections cut short" (int s.early_stops);
  if s.decided + s.penumbra > 0 then begin
    row "soft light, by corners" (int s.decided);
    row "soft light, penumbra" (int s.penumbra)
  end;
  if s.umbra > 0 then row "soft light, umbra" (int s.umbra);
  if s.whole > 0 then row "soft light, whole" (int s.whole);
  row "jobs" (int s.jobs);
  row "time, prepare (s)" (Printf.sprintf "%.4f" s.prepare_s);
  row "time, trace (s)" (Printf.sprintf "%.4f" s.trace_s);
  row "rays per second"
    (if s.trace_s > 0. then Printf.sprintf "%.3g" (Float.of_int (rays s) /. s.trace_s) else "-");
  row "minor words per pixel" (Printf.sprintf "%.3f" (per_pixel s.minor_words))
