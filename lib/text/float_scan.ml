(* Powers of ten that are exact floats: 10^22 < 2^53 * 2^22 is the last
   whose odd part 5^22 fits in 53 bits. *)
let pow10 =
  [| 1e0; 1e1; 1e2; 1e3; 1e4; 1e5; 1e6; 1e7; 1e8; 1e9; 1e10; 1e11; 1e12; 1e13; 1e14; 1e15;
     1e16; 1e17; 1e18; 1e19; 1e20; 1e21; 1e22 |]

let two_53 = 1 lsl 53
let two_57 = 1 lsl 57

(* A mantissa beyond 2^53 leaves the fast path, so accumulation stops
   there: no overflow of the 63-bit int. An exponent beyond this bound is
   far outside the float range whatever the mantissa's length (below the
   line-length bound of any caller), and only saturates. *)
let exponent_cap = 1_000_000

let[@inline] is_digit c = c >= '0' && c <= '9'

(* The correctly rounded [main + corr], given that [corr] is within
   [2^-40 ulp(main)] of the exact correction; [nan] when that error could
   change the rounding (the sum lies within [2^-30 ulp] of a rounding
   boundary, or at a power of two, where the boundaries are not
   symmetric). [err] is the exact error of [main +. corr] (Knuth's
   TwoSum). A safety net rather than a path the tests reach: exact ties
   come with an exact correction, and a 17-digit decimal that is not a
   tie lies much further than 2^-30 ulp from every tie (the numerator of
   the difference is a non-zero multiple of a large power of two). *)
let decide main corr =
  let r = main +. corr in
  let bb = r -. main in
  let err = (main -. (r -. bb)) +. (corr -. bb) in
  let up = Float.succ r -. r and down = r -. Float.pred r in
  if up = down && Float.abs err < up *. (0.5 -. 0x1p-30) then r else Float.nan

(* [m 10^e] for [2^53 < m < 2^57] (17 digits, those of doubles printed
   exactly) and [|e| <= 22], correctly rounded, or [nan] if undecided.
   [m = a + b] exactly, [a] of 53 bits, [b < 16]. With [e >= 0]: [a p] is
   exactly [p1 + e1] and [b p] is [p2 + e2] (fma), and the correction
   [e1 + p2 + e2], below [2^5 ulp(p1)], is summed with an error below
   [2^-47 ulp(p1)]. With [e < 0]: [q = a / p] leaves the exact remainder
   [a - q p] (fma; the remainder of a correctly rounded division is a
   float), and the correction [(rem + b) / p], below [2^5 ulp(q)], is
   computed with an error below [2^-47 ulp(q)]. *)
let seventeen_digits m e =
  let a = Float.of_int (m land lnot 15) and b = Float.of_int (m land 15) in
  if e >= 0 then begin
    let p = Array.unsafe_get pow10 e in
    let p1 = a *. p in
    let e1 = Float.fma a p (-.p1) in
    let p2 = b *. p in
    let e2 = Float.fma b p (-.p2) in
    decide p1 ((e1 +. p2) +. e2)
  end
  else begin
    let p = Array.unsafe_get pow10 (-e) in
    let q = a /. p in
    let rem = Float.fma (-.q) p a in
    decide q ((rem +. b) /. p)
  end

(* The decimal [b.[i] .. b.[j-1]] (or NaN if it is not one) into
   [dst.(d)], for any length: [scan]'s path for numbers of more than 18
   digits or beyond the exact powers of ten. *)
let[@inline never] slow b i j (dst : float array) d =
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
  (* Each branch stores its own result: a float returned from a function
     that is not inlined is boxed, two words a number. *)
  if not !ok || !k <> j then Array.unsafe_set dst d Float.nan
  else if !exact && !m <= two_53 && !e >= -22 && !e <= 22 then begin
    let f = Float.of_int !m in
    let r = if !e >= 0 then f *. Array.unsafe_get pow10 !e else f /. Array.unsafe_get pow10 (- !e) in
    Array.unsafe_set dst d (if neg then -.r else r)
  end
  else
    let r = if !exact && !e >= -22 && !e <= 22 then seventeen_digits !m !e else Float.nan in
    if Float.is_nan r then Array.unsafe_set dst d (float_of_string (Bytes.sub_string b i (j - i)))
    else Array.unsafe_set dst d (if neg then -.r else r)

(* Digits that [scan] reads into an integer: 10^18 < 2^62 fits in 63
   bits, 10^9 < 2^30 in the 32 bits of JavaScript's integers (the web
   page reads scenes with this too). *)
let max_digits = if Sys.int_size >= 63 then 18 else 9

(* Eight digits at a time where eight follow: the 8 bytes at [k] as a
   little-endian word (the first digit in the low byte) are all digits
   iff each byte's high nibble is 3, and still 3 once 6 is added (no
   byte carries into the next unless the first test fails). Their value
   is summed in lanes: pairs [10 d0 + d1] in the even bytes, then
   quadruples in 16-bit lanes, then the eight in the low 32 bits; no lane
   overflows into the next. The fractions of a mesh's coordinates have 8
   to 10 digits, where a byte loop pays a test and a multiply a digit; integer
   parts are short (a scene's fractions too, but the test costs them a
   few instructions only). *)
external get64 : Bytes.t -> int -> int64 = "%caml_bytes_get64u"

(* Equality of int64 words as one comparison: [Int64.equal] goes through
   [compare]. *)
let[@inline] eq64 (x : int64) (y : int64) = x = y


let[@inline] eight_digits b k =
  let x = get64 b k in
  eq64 (Int64.logand x 0xF0F0F0F0F0F0F0F0L) 0x3030303030303030L
  && eq64 (Int64.logand (Int64.add x 0x0606060606060606L) 0xF0F0F0F0F0F0F0F0L) 0x3030303030303030L

let[@inline] eight_value b k =
  let v = Int64.sub (get64 b k) 0x3030303030303030L in
  let v = Int64.logand (Int64.add (Int64.mul v 10L) (Int64.shift_right_logical v 8)) 0x00FF00FF00FF00FFL in
  let v = Int64.logand (Int64.add (Int64.mul v 100L) (Int64.shift_right_logical v 16)) 0x0000FFFF0000FFFFL in
  Int64.to_int (Int64.logand (Int64.add (Int64.mul v 10000L) (Int64.shift_right_logical v 32)) 0xFFFFFFFFL)

(* The longest decimal at [i] (see the interface), its value stored in
   [dst.(d)]: one pass over the bytes, which the callers need not have
   delimited first. Decimals of at most 18 digits whose integer is at
   most 2^53 and power of ten at most 10^22 (Clinger's fast path: nearly
   every number of a scene or mesh) make no call, which would spill the
   registers of the loops, and allocate nothing; the others are read
   again by [slow]. *)
let[@inline never] unsafe_scan b i j (dst : float array) d =
  let k = ref i in
  let neg =
    if !k < j && Bytes.unsafe_get b !k = '-' then (incr k; true)
    else (if !k < j && Bytes.unsafe_get b !k = '+' then incr k; false)
  in
  let start = !k in
  let m = ref 0 in
  while !k < j && is_digit (Bytes.unsafe_get b !k) do
    m := (!m * 10) + (Char.code (Bytes.unsafe_get b !k) - 48);
    incr k
  done;
  let n = ref (!k - start) and e = ref 0 in
  if !k < j && Bytes.unsafe_get b !k = '.' && !n <= max_digits then begin
    incr k;
    let frac = !k in
    while !k + 8 <= j && eight_digits b !k do
      m := (!m * 100_000_000) + eight_value b !k;
      k := !k + 8
    done;
    while !k < j && is_digit (Bytes.unsafe_get b !k) do
      m := (!m * 10) + (Char.code (Bytes.unsafe_get b !k) - 48);
      incr k
    done;
    e := frac - !k;
    n := !n + (!k - frac)
  end
  else if !k < j && Bytes.unsafe_get b !k = '.' then begin
    incr k;
    let frac = !k in
    while !k < j && is_digit (Bytes.unsafe_get b !k) do incr k done;
    n := !n + (!k - frac)
  end;
  if !n = 0 then begin
    Array.unsafe_set dst d Float.nan;
    i
  end
  else begin
    (* An exponent marker without digits is not part of the number. *)
    if !k + 1 < j && (Bytes.unsafe_get b !k = 'e' || Bytes.unsafe_get b !k = 'E') then begin
      let s = if Bytes.unsafe_get b (!k + 1) = '-' || Bytes.unsafe_get b (!k + 1) = '+' then !k + 2 else !k + 1 in
      if s < j && is_digit (Bytes.unsafe_get b s) then begin
        let eneg = Bytes.unsafe_get b (!k + 1) = '-' in
        k := s;
        let x = ref 0 in
        while !k < j && is_digit (Bytes.unsafe_get b !k) do
          if !x < exponent_cap then x := (!x * 10) + (Char.code (Bytes.unsafe_get b !k) - 48);
          incr k
        done;
        e := if eneg then !e - !x else !e + !x
      end
    end;
    (* Each branch stores its own result: a float returned from a function
       that is not inlined is boxed, two words a number. *)
    if !n <= max_digits && !m <= two_53 && !e >= -22 && !e <= 22 then begin
      let f = Float.of_int !m in
      let r = if !e >= 0 then f *. Array.unsafe_get pow10 !e else f /. Array.unsafe_get pow10 (- !e) in
      Array.unsafe_set dst d (if neg then -.r else r)
    end
    else begin
      (* 17 digits, a double printed exactly: [m] holds them all. *)
      let r =
        if Sys.int_size >= 63 && !n <= max_digits && !m < two_57 && !e >= -22 && !e <= 22 then seventeen_digits !m !e
        else Float.nan
      in
      if Float.is_nan r then slow b i !k dst d else Array.unsafe_set dst d (if neg then -.r else r)
    end;
    !k
  end

(* The checks inlined where [scan] is called, so that a caller that
   knows them true ({!unsafe_scan}) does not pay them per number. *)
let[@inline] scan b i j (dst : float array) d =
  if i < 0 || j > Bytes.length b || i > j || d < 0 || d >= Array.length dst then
    raise (Invalid_argument "Float_scan.scan");
  unsafe_scan b i j dst d

let into b i j (dst : float array) d =
  if i < 0 || j > Bytes.length b || i > j || d < 0 || d >= Array.length dst then invalid_arg "Float_scan.into";
  if unsafe_scan b i j dst d <> j then Array.unsafe_set dst d Float.nan

let to_float b i j =
  if i < 0 || j > Bytes.length b || i > j then invalid_arg "Float_scan.to_float";
  let r = [| 0. |] in
  into b i j r 0;
  r.(0)

let of_string s = to_float (Bytes.unsafe_of_string s) 0 (String.length s)
