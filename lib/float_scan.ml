(* Powers of ten that are exact floats: 10^22 < 2^53 * 2^22 is the last
   whose odd part 5^22 fits in 53 bits. *)
let pow10 =
  [| 1e0; 1e1; 1e2; 1e3; 1e4; 1e5; 1e6; 1e7; 1e8; 1e9; 1e10; 1e11; 1e12; 1e13; 1e14; 1e15;
     1e16; 1e17; 1e18; 1e19; 1e20; 1e21; 1e22 |]

let two_53 = 1 lsl 53

(* A mantissa beyond 2^53 leaves the fast path, so accumulation stops
   there: no overflow of the 63-bit int. An exponent beyond this bound is
   far outside the float range whatever the mantissa's length (below the
   line-length bound of any caller), and only saturates. *)
let exponent_cap = 1_000_000

let[@inline] is_digit c = c >= '0' && c <= '9'

let to_float b i j =
  if i < 0 || j > Bytes.length b || i > j then invalid_arg "Float_scan.to_float";
  let k = ref i in
  let neg =
    if !k < j && Bytes.unsafe_get b !k = '-' then (incr k; true)
    else (if !k < j && Bytes.unsafe_get b !k = '+' then incr k; false)
  in
  let m = ref 0 and e = ref 0 and digits = ref false and exact = ref true in
  while !k < j && is_digit (Bytes.unsafe_get b !k) do
    digits := true;
    if !m <= two_53 then m := (!m * 10) + (Char.code (Bytes.unsafe_get b !k) - 48)
    else exact := false;
    incr k
  done;
  if !k < j && Bytes.unsafe_get b !k = '.' then begin
    incr k;
    while !k < j && is_digit (Bytes.unsafe_get b !k) do
      digits := true;
      if !m <= two_53 then begin
        m := (!m * 10) + (Char.code (Bytes.unsafe_get b !k) - 48);
        decr e
      end
      else exact := false;
      incr k
    done
  end;
  let ok = ref !digits in
  if !ok && !k < j && (Bytes.unsafe_get b !k = 'e' || Bytes.unsafe_get b !k = 'E') then begin
    incr k;
    let eneg =
      if !k < j && Bytes.unsafe_get b !k = '-' then (incr k; true)
      else (if !k < j && Bytes.unsafe_get b !k = '+' then incr k; false)
    in
    let x = ref 0 in
    if not (!k < j && is_digit (Bytes.unsafe_get b !k)) then ok := false;
    while !k < j && is_digit (Bytes.unsafe_get b !k) do
      if !x < exponent_cap then x := (!x * 10) + (Char.code (Bytes.unsafe_get b !k) - 48);
      incr k
    done;
    e := if eneg then !e - !x else !e + !x
  end;
  if not !ok || !k <> j then Float.nan
  else if !exact && !m <= two_53 && !e >= -22 && !e <= 22 then begin
    let f = Float.of_int !m in
    let r = if !e >= 0 then f *. Array.unsafe_get pow10 !e else f /. Array.unsafe_get pow10 (- !e) in
    if neg then -.r else r
  end
  else float_of_string (Bytes.sub_string b i (j - i))

let of_string s = to_float (Bytes.unsafe_of_string s) 0 (String.length s)
