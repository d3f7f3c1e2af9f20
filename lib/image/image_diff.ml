type t = {
  pixels : int;
  differing : int;
  differing_gt1 : int;
  max_abs : int;
  mean_abs : float;
  psnr : float;
}
[@@deriving show]

let compare a b =
  let w = Image.width a and h = Image.height a in
  if w <> Image.width b || h <> Image.height b then
    Error
      (`Msg
        (Printf.sprintf "image sizes differ: %dx%d and %dx%d" w h (Image.width b) (Image.height b)))
  else
    let da = Image.buffer a and db = Image.buffer b in
    let differing = ref 0 and differing_gt1 = ref 0 and max_abs = ref 0 in
    let sum = ref 0 and sum_sq = ref 0 in
    for p = 0 to (w * h) - 1 do
      let worst = ref 0 in
      for c = 0 to 2 do
        let k = (3 * p) + c in
        let d = abs (Bigarray.Array1.unsafe_get da k - Bigarray.Array1.unsafe_get db k) in
        sum := !sum + d;
        sum_sq := !sum_sq + (d * d);
        if d > !worst then worst := d
      done;
      if !worst > 0 then incr differing;
      if !worst > 1 then incr differing_gt1;
      if !worst > !max_abs then max_abs := !worst
    done;
    let channels = Float.of_int (3 * w * h) in
    let mse = Float.of_int !sum_sq /. channels in
    Ok
      {
        pixels = w * h;
        differing = !differing;
        differing_gt1 = !differing_gt1;
        max_abs = !max_abs;
        mean_abs = Float.of_int !sum /. channels;
        psnr = (if mse = 0. then infinity else 10. *. Float.log10 (255. *. 255. /. mse));
      }

let share_within d = 1. -. (Float.of_int d.differing_gt1 /. Float.of_int d.pixels)

let pp_summary ppf d =
  Format.fprintf ppf "pixels=%d differing=%d differing_gt1=%d max_abs=%d mean_abs=%.6f psnr=%s"
    d.pixels d.differing d.differing_gt1 d.max_abs d.mean_abs
    (if d.psnr = infinity then "inf" else Printf.sprintf "%.2f" d.psnr)
