type t = { values : float array; mutable seen : int }

let create () = { values = Array.make 9 0.; seen = 0 }

(* Per field (center, radius, color, specular, reflective): how many
   numbers, and the index of the first in [values]. *)
let arity = [| 3; 1; 3; 1; 1 |]
let first_value = [| 0; 3; 4; 7; 8 |]

(* Is [s.[i] .. s.[j - 1]] the word [w]? *)
let is_word s i j w =
  j - i = String.length w
  &&
  let k = ref 0 in
  while !k < j - i && String.unsafe_get s (i + !k) = String.unsafe_get w !k do
    incr k
  done;
  !k = j - i

(* The field named [s.[a] .. s.[e - 1]], numbered as in [arity]; [-1] if
   none. *)
let field s a e =
  match e - a with
  | 6 -> if is_word s a e "center" then 0 else if is_word s a e "radius" then 1 else -1
  | 5 -> if is_word s a e "color" then 2 else -1
  | 8 -> if is_word s a e "specular" then 3 else -1
  | 10 -> if is_word s a e "reflective" then 4 else -1
  | _ -> -1

(* The fields from [s.[p]] on, to the form's closing parenthesis: a
   function of its own, not a closure made per sphere. *)
let rec fields f s p =
  let open Sexp_scan in
  let p = skip_blank s p in
  if p >= String.length s then raise Unusual;
  match String.unsafe_get s p with
  | ')' -> p + 1
  | '(' ->
      let a = skip_blank s (p + 1) in
      let e = atom_end s a in
      let c = field s a e in
      if c < 0 || f.seen land (1 lsl c) <> 0 then raise Unusual;
      f.seen <- f.seen lor (1 lsl c);
      let q = ref e in
      for v = 0 to arity.(c) - 1 do
        let a = skip_blank s !q in
        let e = atom_end s a in
        let d = first_value.(c) + v in
        if e = a then raise Unusual;
        (* Stored, not returned: a returned float would be boxed. *)
        Float_scan.into (Bytes.unsafe_of_string s) a e f.values d;
        if not (Float.is_finite f.values.(d)) then raise Unusual;
        q := e
      done;
      let q = skip_blank s !q in
      if q >= String.length s || String.unsafe_get s q <> ')' then raise Unusual;
      fields f s (q + 1)
  | _ -> raise Unusual

let general f s i =
  let open Sexp_scan in
  if i >= String.length s || String.unsafe_get s i <> '(' then raise Unusual;
  let j = skip_blank s (i + 1) in
  let k = atom_end s j in
  if not (is_word s j k "sphere") then raise Unusual;
  f.seen <- 0;
  fields f s k

(* The layout's literals, compared 8 bytes at a time: a word is the 8
   bytes at an index, little-endian, and a literal of [n] bytes is
   compared under the mask of the word's [n] low bytes. *)
external get64 : string -> int -> int64 = "%caml_string_get64u"

(* Equality of int64 words as one comparison: [Int64.equal] goes through
   [compare]. *)
let[@inline] eq64 (x : int64) (y : int64) = x = y


let literal w =
  let b = Bytes.make 8 '\000' in
  Bytes.blit_string w 0 b 0 (String.length w);
  Bytes.get_int64_le b 0

let low_bytes n = Int64.(sub (shift_left 1L (8 * n)) 1L)
let mask6 = low_bytes 6
let mask7 = low_bytes 7
let open_sphere = literal "(sphere"
let center = literal "center "
let radius = literal "radius "
let color = literal "color "
let specular = literal "specular"
let reflecti = literal "reflecti"

(* The margin that [layout] leaves at the end of [s]: every literal it
   compares lies within 16 bytes of a point before [n - margin]. *)
let margin = 16

let layout f s i =
  let n = String.length s in
  let limit = n - margin in
  if i < 0 || i >= limit || not (eq64 (Int64.logand (get64 s i) mask7) open_sphere) then -1
  else begin
    let b = Bytes.unsafe_of_string s in
    f.seen <- 0;
    (* [!stop]: [-2] while reading, then the result. *)
    let p = ref (i + 7) and stop = ref (-2) in
    while !stop = -2 do
      let q = !p in
      if q >= limit then stop := -1
      else if String.unsafe_get s q = ')' then stop := q + 1
      else if String.unsafe_get s q <> ' ' || String.unsafe_get s (q + 1) <> '(' then stop := -1
      else begin
        (* The field, and where its first number starts. *)
        let w = get64 s (q + 2) in
        let c = ref (-1) and at = ref 0 in
        if eq64 (Int64.logand w mask7) center then (c := 0; at := q + 9)
        else if eq64 (Int64.logand w mask7) radius then (c := 1; at := q + 9)
        else if eq64 (Int64.logand w mask6) color then (c := 2; at := q + 8)
        else if eq64 w specular && String.unsafe_get s (q + 10) = ' ' then (c := 3; at := q + 11)
        else if
          eq64 w reflecti
          && String.unsafe_get s (q + 10) = 'v'
          && String.unsafe_get s (q + 11) = 'e'
          && String.unsafe_get s (q + 12) = ' '
        then (c := 4; at := q + 13);
        let c = !c in
        if c < 0 || f.seen land (1 lsl c) <> 0 then stop := -1
        else begin
          f.seen <- f.seen lor (1 lsl c);
          let last = Array.unsafe_get first_value c + Array.unsafe_get arity c - 1 in
          let d = ref (Array.unsafe_get first_value c) and k = ref !at in
          while !d <= last do
            let a = !k in
            let e = Float_scan.scan b a n f.values !d in
            (* A space before the next number, a parenthesis after the
               last: then the number is the whole atom. *)
            let ends = if !d < last then ' ' else ')' in
            if e > a && e < limit && String.unsafe_get s e = ends && Float.is_finite (Array.unsafe_get f.values !d)
            then begin
              k := e + 1;
              incr d
            end
            else begin
              stop := -1;
              d := last + 1
            end
          done;
          if !stop = -2 then p := !k
        end
      end
    done;
    !stop
  end

let read f s i = match layout f s i with -1 -> general f s i | e -> e
