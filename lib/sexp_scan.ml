module Sexp = Sexplib0.Sexp

exception Unusual

let[@inline] is_atom_char c =
  match c with 'a' .. 'z' | 'A' .. 'Z' | '0' .. '9' | '.' | '+' | '-' | '_' -> true | _ -> false

(* parsexp refuses a carriage return that no newline follows, in a comment
   too: such text goes to parsexp for its error. *)
let skip_blank s i =
  let n = String.length s in
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
  while !i < n && is_atom_char (String.unsafe_get s !i) do
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
    | c when is_atom_char c ->
        let j = atom_end s i in
        if j >= limit then raise Unusual;
        list depth j (Sexp.Atom (String.sub s i (j - i)) :: acc)
    | _ -> raise Unusual
  in
  if i >= n || String.unsafe_get s i <> '(' then raise Unusual;
  list 1 (i + 1) []
