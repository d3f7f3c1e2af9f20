module Sexp = Sexplib0.Sexp

exception Unusual

let is_atom_char c =
  match c with 'a' .. 'z' | 'A' .. 'Z' | '0' .. '9' | '.' | '+' | '-' | '_' -> true | _ -> false

(* [is_atom_char] as a table: one load a character where the scanner
   spends most of its time. *)
let atom_table = String.init 256 (fun i -> if is_atom_char (Char.chr i) then '\001' else '\000')
let[@inline] is_atom_byte c = String.unsafe_get atom_table (Char.code c) = '\001'

(* parsexp refuses a carriage return that no newline follows, in a comment
   too: such text goes to parsexp for its error. *)
let skip_blank s i =
  let n = String.length s in
  (* Most calls skip one space, or none. *)
  let i = if i < n && String.unsafe_get s i = ' ' then i + 1 else i in
  if i < n && (String.unsafe_get s i > ' ' && String.unsafe_get s i <> ';') then i
  else
  let i = ref i in
  let continue = ref true in
  while !continue && !i < n do
    match String.unsafe_get s !i with
    | ' ' | '\t' | '\n' | '\012' -> incr i
    | '\r' -> if !i + 1 < n && String.unsafe_get s (!i + 1) = '\n' then i := !i + 2 else raise Unusual
    | ';' ->
        while !i < n && String.unsafe_get s !i <> '\n' do
          if String.unsafe_get s !i = '\r' && not (!i + 1 < n && String.unsafe_get s (!i + 1) = '\n') then
            raise Unusual;
          incr i
        done
    | _ -> continue := false
  done;
  !i

let atom_end s i =
  let n = String.length s in
  let i = ref i in
  while !i < n && is_atom_byte (String.unsafe_get s !i) do
    incr i
  done;
  !i

let max_depth = 64

let form s i ~max_bytes =
  let n = String.length s in
  let limit = if max_bytes < n - i then i + max_bytes else n in
  (* Elements in reverse order; [i] is just past the opening parenthesis. *)
  let rec list depth i acc =
    let i = skip_blank s i in
    if i >= limit then raise Unusual;
    match String.unsafe_get s i with
    | ')' -> (Sexp.List (List.rev acc), i + 1)
    | '(' ->
        if depth >= max_depth then raise Unusual;
        let x, j = list (depth + 1) (i + 1) [] in
        list depth j (x :: acc)
    | c when is_atom_byte c ->
        let j = atom_end s i in
        if j >= limit then raise Unusual;
        list depth j (Sexp.Atom (String.sub s i (j - i)) :: acc)
    | _ -> raise Unusual
  in
  if i >= n || String.unsafe_get s i <> '(' then raise Unusual;
  list 1 (i + 1) []
