(* check_refs ROOT: the code that README.md and docs/*.md cite exists.
   In the prose (outside fenced blocks), every backquoted file path under
   one of the project's folders names a file or folder, and every
   backquoted [Module.name] whose module is one of the project's names
   something that module's .mli or .ml defines (a value, type, field,
   constructor or module; [Raytrace.], [Raytrace_unix.], [Private.] and the
   nested modules of [Raytrace], e.g. [Render.Pixel], resolved as the
   entry module resolves them). A module name that is neither the
   project's nor a library's we know is reported too, so a module that was
   renamed or removed is caught. And the README's program is
   examples/hello_scene.ml, byte for byte (the tests build and run that
   file). Prints one line per stale reference, "FILE:LINE: ...", and exits
   1 if there is any. *)

open Pages

(* The backquoted spans of a line. *)
let spans line =
  let rec go i acc =
    match String.index_from_opt line i '`' with
    | None -> List.rev acc
    | Some a -> (
        match String.index_from_opt line (a + 1) '`' with
        | None -> List.rev acc
        | Some b -> go (b + 1) (String.sub line (a + 1) (b - a - 1) :: acc))
  in
  go 0 []

(* The project's modules: each capitalised file name of a .ml or .mli in
   these folders, with the text of both files. *)
let folders = [ "lib"; "unix"; "view"; "png"; "bin"; "web"; "test"; "bench"; "examples"; "tools"; "scenes"; "fuzz" ]

let rec walk dir acc =
  if not (Sys.file_exists dir && Sys.is_directory dir) then acc
  else
    Array.fold_left
      (fun acc name ->
        let path = Filename.concat dir name in
        if name = "node_modules" || name = "_build" || (String.length name > 0 && name.[0] = '.') then acc
        else if Sys.is_directory path then walk path acc
        else path :: acc)
      acc (Sys.readdir dir)

let modules root =
  let table = Hashtbl.create 256 in
  List.iter
    (fun folder ->
      List.iter
        (fun path ->
          if Filename.check_suffix path ".ml" || Filename.check_suffix path ".mli" then begin
            let m = String.capitalize_ascii (Filename.remove_extension (Filename.basename path)) in
            let old = Option.value (Hashtbl.find_opt table m) ~default:"" in
            Hashtbl.replace table m (old ^ "\n" ^ read path)
          end)
        (walk (Filename.concat root folder) []))
    folders;
  table

(* The nested modules of the entry module: [module Path = Camera_path]
   inside [module Camera : sig], read from lib/raytrace.mli. *)
let nested root =
  let outer = ref None and table = Hashtbl.create 16 in
  let module_eq = Str.regexp "^ *module \\([A-Z][A-Za-z0-9_]*\\) = \\([A-Z][A-Za-z0-9_]*\\)" in
  let module_sig = Str.regexp "^module \\([A-Z][A-Za-z0-9_]*\\) : sig" in
  List.iter
    (fun l ->
      if Str.string_match module_sig l 0 then outer := Some (Str.matched_group 1 l)
      else if l = "end" then outer := None
      else if Str.string_match module_eq l 0 then
        match !outer with
        | Some o when o <> "Private" -> Hashtbl.replace table (o, Str.matched_group 1 l) (Str.matched_group 2 l)
        | _ -> ())
    (lines (Filename.concat root "lib/raytrace.mli"));
  table

(* Modules of OCaml's and other libraries that the pages may cite. *)
let foreign =
  [ "Array"; "Bigarray"; "Buffer"; "Bytes"; "Char"; "Domain"; "Filename"; "Float"; "Format"; "Fun"; "Gc"; "Graphics";
    "Hashtbl"; "In_channel"; "Int"; "Int32"; "Int64"; "List"; "Marshal"; "Math"; "Obj"; "Option"; "Printexc"; "Printf";
    "Random"; "Result"; "Seq"; "Stdlib"; "String"; "Sys"; "Unix"; "Alcotest"; "QCheck"; "Crowbar"; "Cmdliner"; "Cmd";
    "Term"; "Arg"; "Parsexp"; "Sexplib0"; "Sexp"; "Zarith"; "Z"; "Q"; "Js"; "Js_of_ocaml"; "Dom_html"; "Camlimages";
    "Png"; "Images"; "Rgb24"; "Lazy"; "Atomic"; "Mutex"; "Thread"; "Condition"; "Ephemeron"; "Weak"; "Queue"; "Stack";
    "Map"; "Set"; "Complex"; "Lexing"; "Parsing"; "Scanf"; "Str"; "Callback"; "Oo"; "Bool"; "Unit"; "Either"; "Uchar";
    "Digest"; "Positions" ]

(* Files that hold a page's ident in a defining position: [let f], [val f],
   a field [f :], a constructor [| F], a module [module F], ... *)
let defines text name =
  let q = Str.quote name in
  let re =
    if name.[0] >= 'A' && name.[0] <= 'Z' then
      Str.regexp ("\\(module\\|module type\\|exception\\||\\|\\[\\|(\\|=\\|`\\) *" ^ q ^ "\\b")
    else
      Str.regexp
        ("\\(\\b\\(let\\|and\\|val\\|external\\|type\\|mutable\\|method\\|~\\|?\\)\\(\\[@[^]]*\\]\\)?\\( rec\\)?[ ('a-z_,)]*" ^ q ^ "\\b\\)\\|\\(\\b" ^ q
       ^ " *:[^=]\\)")
  in
  try
    ignore (Str.search_forward re text 0);
    true
  with Not_found -> false

let strip_prefix = [ "Raytrace"; "Raytrace_unix"; "Raytrace_view"; "Raytrace_png"; "Private" ]

(* What is wrong with the reference [parts] (a dotted path), if anything. *)
let check_ident mods nested parts =
  let rec drop = function
    | p :: (_ :: _ as rest) when List.mem p strip_prefix -> drop rest
    | l -> l
  in
  match drop parts with
  | [] | [ _ ] -> None
  | m :: _ when List.mem m foreign || String.uppercase_ascii m = m -> None
  | m :: _ when not (Hashtbl.mem mods m) -> Some (Printf.sprintf "no module %s in the project" m)
  | m :: rest ->
      let rec go m text = function
        | [] -> None
        | x :: rest -> (
            match Hashtbl.find_opt nested (m, x) with
            | Some target -> go target (Hashtbl.find mods target) rest
            | None ->
                if defines text x then if x.[0] >= 'A' && x.[0] <= 'Z' then go x text rest else None
                else Some (Printf.sprintf "%s defines no %s" m x))
      in
      go m (Hashtbl.find mods m) rest

let all_matches re group s =
  let rec go i acc =
    match Str.search_forward re s i with
    | exception Not_found -> List.rev acc
    | j -> go (max (j + 1) (Str.match_end ())) (Str.matched_group group s :: acc)
  in
  go 0 []

(* The labels [~x] of a span that cites one function: each must be one of
   the function's module's labels ([x:], [?x:], [~x]). *)
let label_re = Str.regexp "[~?]\\([a-z_][A-Za-z0-9_']*\\)"

let check_labels mods nested span id =
  let parts = String.split_on_char '.' id in
  let rec last_module m = function
    | [] | [ _ ] -> Some m
    | x :: rest -> (
        match Hashtbl.find_opt nested (m, x) with
        | Some t -> last_module t rest
        | None -> if Hashtbl.mem mods x then last_module x rest else None)
  in
  let rec drop = function p :: (_ :: _ as rest) when List.mem p strip_prefix -> drop rest | l -> l in
  match drop parts with
  | m :: rest when Hashtbl.mem mods m -> (
      match last_module m rest with
      | None -> []
      | Some m ->
          let text = Hashtbl.find mods m in
          (* The function's signature, from [val f :] to its comment. *)
          let f = List.nth parts (List.length parts - 1) in
          let text =
            match Str.search_forward (Str.regexp ("val " ^ Str.quote f ^ " *:")) text 0 with
            | i -> (
                match Str.search_forward (Str.regexp_string "(**") text i with
                | j -> String.sub text i (j - i)
                | exception Not_found -> text)
            | exception Not_found -> text
          in
          List.filter_map
            (fun l ->
              let has s = try ignore (Str.search_forward (Str.regexp_string s) text 0); true with Not_found -> false in
              if has (l ^ ":") || has ("~" ^ l) || has ("?" ^ l) then None
              else Some (Printf.sprintf "%s takes no label ~%s" id l))
            (all_matches label_re 1 span))
  | _ -> []

let ident = Str.regexp "\\b\\([A-Z][A-Za-z0-9_]*\\(\\.[A-Za-z_][A-Za-z0-9_']*\\)+\\)"

let path_re = Str.regexp "\\(^\\|[^A-Za-z0-9_/.]\\)\\(\\(lib\\|unix\\|view\\|png\\|bin\\|web\\|test\\|scenes\\|examples\\|bench\\|tools\\)/[A-Za-z0-9_./-]*\\)"

let file_suffixes = [ ".ml"; ".mli"; ".md"; ".ppm"; ".png"; ".scene"; ".obj"; ".js"; ".sh"; ".txt"; ".html"; ".c"; ".exe"; ".json" ]

let check_page root mods nested file =
  List.concat_map
    (fun (n, line) ->
      List.concat_map
        (fun span ->
          let where = Printf.sprintf "%s:%d: `%s`" file n span in
          let paths =
            if String.contains span '*' || String.contains span '%' || String.contains span '<' || String.contains span '$'
            then []
            else
              List.filter_map
                (fun p ->
                  let p = if String.length p > 1 && p.[String.length p - 1] = '.' then String.sub p 0 (String.length p - 1) else p in
                  (* A built program is named by its source. *)
                  let base = Filename.remove_extension (Filename.basename p) in
                  if base <> "" && String.uppercase_ascii base = base then None
                  else
                  let source = if Filename.check_suffix p ".exe" then Filename.chop_suffix p ".exe" ^ ".ml" else p in
                  if Sys.file_exists (Filename.concat root source) then None else Some (where ^ ": no such file " ^ p))
                (all_matches path_re 2 span)
          in
          let idents =
            (* performance.md is a dated log: its names are the code's as it
               was measured. *)
            if String.contains span '/' || file = "docs/performance.md" then []
            else
              let ids =
                List.filter
                  (fun id -> not (List.exists (fun s -> Filename.check_suffix id s) file_suffixes))
                  (all_matches ident 1 span)
              in
              let stale =
                List.filter_map
                  (fun id -> Option.map (fun e -> where ^ ": " ^ e) (check_ident mods nested (String.split_on_char '.' id)))
                  ids
              in
              match (stale, ids) with
              | [], [ id ] -> List.map (fun e -> where ^ ": " ^ e) (check_labels mods nested span id)
              | _ -> stale
          in
          paths @ idents)
        (spans line))
    (prose (Filename.concat root file))

(* The README's program, its first OCaml block, is examples/hello_scene.ml
   after that file's opening comment. *)
let check_example root =
  let rec block acc inside = function
    | [] -> List.rev acc
    | l :: rest when not inside -> block acc (String.trim l = "```ocaml") rest
    | l :: _ when is_fence l -> List.rev acc
    | l :: rest -> block (l :: acc) true rest
  in
  let readme = String.concat "\n" (block [] false (lines (Filename.concat root "README.md"))) in
  let example = read (Filename.concat root "examples/hello_scene.ml") in
  let body =
    match Str.search_forward (Str.regexp_string "*)\n") example 0 with
    | i when String.length example > 1 && String.sub example 0 2 = "(*" -> String.sub example (i + 3) (String.length example - i - 3)
    | _ -> example
    | exception Not_found -> example
  in
  if String.trim body = String.trim readme then []
  else [ "README.md: its OCaml program is not examples/hello_scene.ml (after the file's opening comment)" ]

let () =
  let root = if Array.length Sys.argv > 1 then Sys.argv.(1) else "." in
  let pages = Pages.all root in
  let mods = modules root and nested = nested root in
  match check_example root @ List.concat_map (check_page root mods nested) pages with
  | [] -> ()
  | stale ->
      List.iter prerr_endline stale;
      exit 1
