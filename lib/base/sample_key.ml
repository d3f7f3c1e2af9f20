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

(* A keyed permutation by cycle walking (Kensler, "Correlated
   multi-jittered sampling", 2013): bijective steps on the [b] low bits
   (xor with a constant, multiplication by an odd constant, xor with a
   right shift of the masked value), repeated until the value falls in
   [\[0, n)]. Every product is masked to [b <= 31] bits before the next
   step, so native code and js_of_ocaml keep the same bits. *)
let mask n =
  let w = ref 0 in
  while !w < n - 1 do
    w := (!w lsl 1) lor 1
  done;
  !w

let walk ~p ~w ~n k =
  let i = ref k and walking = ref true in
  while !walking do
    let x = !i in
    let x = x lxor p land w in
    let x = (x * 0x6935_FA69) land w in
    let x = x lxor (x lsr 4) lxor ((p lsr 8) land w) in
    let x = (x * (0x0929_EB3F lor ((p lsr 27) lsl 1))) land w in
    let x = x lxor (x lsr 1) lxor ((p lsr 16) land w) in
    let x = (x * 0x74DC_B303) land w in
    let x = x lxor (x lsr 2) in
    let x = (x * 0x4C60_A3DF) land w in
    let x = x lxor (x lsr 5) in
    i := x;
    walking := x >= n
  done;
  (* [p mod n] first: [p + i] could pass [2^31 - 1], JavaScript's largest int. *)
  ((p mod n) + !i) mod n

let fill t ~at ~shift ~p ~n =
  let w = mask n in
  for k = 0 to n - 1 do
    t.(at + k) <- shift + walk ~p ~w ~n k
  done

let permute h ~n k =
  if n < 1 || k < 0 || k >= n then invalid_arg "Sample_key.permute: k outside [0, n)";
  walk ~p:(mix h) ~w:(mask n) ~n k
