(* check_links ROOT: checks the relative links of ROOT/README.md and
   ROOT/docs/*.md. Prints one line per broken link, "FILE:LINE: ...", and
   exits 1 if there is any. *)

open Pages

(* GitHub's anchor of a heading: lower case, letters, digits, spaces,
   hyphens and underscores kept, spaces made hyphens. *)
let slug heading =
  let b = Buffer.create (String.length heading) in
  String.iter
    (fun c ->
      match Char.lowercase_ascii c with
      | ('a' .. 'z' | '0' .. '9' | '-' | '_') as c -> Buffer.add_char b c
      | ' ' -> Buffer.add_char b '-'
      | c when Char.code c >= 128 -> Buffer.add_char b c
      | _ -> ())
    (String.trim heading);
  Buffer.contents b


let anchors path =
  List.filter_map
    (fun (_, l) ->
      if String.length l > 0 && l.[0] = '#' then
        let i = ref 0 in
        while !i < String.length l && l.[!i] = '#' do incr i done;
        Some (slug (String.sub l !i (String.length l - !i)))
      else None)
    (prose path)

(* The targets of the inline links and images of [line]: what is between
   "](" and the next ")" or space. *)
let targets line =
  let n = String.length line in
  let rec from i acc =
    if i + 1 >= n then List.rev acc
    else if line.[i] = ']' && line.[i + 1] = '(' then begin
      let j = ref (i + 2) in
      while !j < n && line.[!j] <> ')' && line.[!j] <> ' ' do incr j done;
      from !j (String.sub line (i + 2) (!j - i - 2) :: acc)
    end
    else from (i + 1) acc
  in
  from 0 []

let starts_with p s = String.length s >= String.length p && String.sub s 0 (String.length p) = p

let check root file =
  let path = Filename.concat root file in
  List.concat_map
    (fun (n, line) ->
      List.filter_map
        (fun target ->
          let where = Printf.sprintf "%s:%d: link %S" file n target in
          if starts_with "http://" target || starts_with "https://" target || starts_with "mailto:" target then None
          else
            let file_part, anchor =
              match String.index_opt target '#' with
              | Some k -> (String.sub target 0 k, Some (String.sub target (k + 1) (String.length target - k - 1)))
              | None -> (target, None)
            in
            if file_part <> "" && not (Filename.is_relative file_part) then Some (where ^ ": an absolute path")
            else
              let dest = if file_part = "" then path else Filename.concat (Filename.dirname path) file_part in
              if not (Sys.file_exists dest) then Some (where ^ ": no such file")
              else
                match anchor with
                | Some a when Filename.check_suffix dest ".md" && not (List.mem a (anchors dest)) ->
                    Some (where ^ ": no such heading")
                | _ -> None)
        (targets line))
    (prose path)

let () =
  let root = if Array.length Sys.argv > 1 then Sys.argv.(1) else "." in
  let pages = Pages.all root in
  match List.concat_map (check root) pages with
  | [] -> ()
  | broken ->
      List.iter prerr_endline broken;
      exit 1
