(* 31 bits, not 32 or 63: see the .mli. The steps are those of a
   multiply-xorshift hash (Wang, "lowbias32"), with constants below 2^31 so
   that js_of_ocaml reads the same numbers. *)
let low = 0x7FFF_FFFF

let[@inline] mix h =
  let h = h land low in
  let h = ((h lxor (h lsr 16)) * 0x7FEB_352D) land low in
  let h = ((h lxor (h lsr 15)) * 0x46CA_68B3) land low in
  h lxor (h lsr 16)

(* The constant keeps 0 from being a fixed point: [key 0 0] is not 0. *)
let[@inline] key h v = mix ((mix h * 0x2C92_77B5) land low lxor (v land low) lxor 0x5BD1_E995)
let pixel ~col ~row ~sample = key (key (key 0 col) row) sample
let camera ~gx ~gy ~di ~dj = key (key (pixel ~col:gx ~row:gy ~sample:0) di) dj
let[@inline] unit h = Float.of_int (mix h) *. 0x1p-31

let[@inline] stratum h ~n i =
  let x = (Float.of_int i +. unit (key h i)) /. Float.of_int n in
  (* The division may round (i + u)/n up to 1 when u is near 1. *)
  if x < 1. then x else Float.pred 1.
