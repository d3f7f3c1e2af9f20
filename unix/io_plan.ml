type file = Inode of int * int | Path of string

let msg fmt = Printf.ksprintf (fun m -> Error (`Msg m)) fmt

(* The file a path reaches, and whether it is a stream: written to in
   turn, never replaced, so that several outputs may share it. *)
let output_file path =
  match if path = "-" then Unix.fstat Unix.stdout else Unix.stat path with
  | st ->
      let stream =
        match st.st_kind with
        | S_CHR | S_FIFO | S_SOCK | S_BLK -> true
        | S_REG -> path = "-" || File_io.standard_channel path <> None
        | S_DIR | S_LNK -> false
      in
      (Some st.st_kind, Inode (st.st_dev, st.st_ino), stream)
  | exception Unix.Unix_error _ -> (
      (* Not there yet: the name it will have once its directory's links
         and [..] are resolved. *)
      match Unix.realpath (Filename.dirname path) with
      | dir -> (None, Path (Filename.concat dir (Filename.basename path)), false)
      | exception Unix.Unix_error _ -> (None, Path path, false))

let check ~inputs ~outputs =
  (* Only regular files can be both read and destroyed: a terminal or a
     pipe given as input and output is no collision. *)
  let inputs =
    List.filter_map
      (fun (what, path) ->
        match Unix.stat path with
        | { st_kind = S_REG; st_dev; st_ino; _ } -> Some (Inode (st_dev, st_ino), what)
        | _ -> None
        | exception Unix.Unix_error _ -> None)
      inputs
  in
  let seen = Hashtbl.create 16 in
  let rec go = function
    | [] -> Ok ()
    | (what, path) :: rest -> (
        let kind, file, stream = output_file path in
        let name = if path = "-" then "standard output" else path in
        match (List.assoc_opt file inputs, Hashtbl.find_opt seen file) with
        | Some input, _ when kind = Some Unix.S_REG ->
            msg "%s: the output file is the input %s; choose another output path" name input
        | _, Some (other, other_path) when not stream ->
            msg "%s: %s and %s would be written to the same file%s; give each its own file" path other what
              (if other_path = path then "" else " (" ^ other_path ^ ")")
        | _ ->
            Hashtbl.replace seen file (what, path);
            go rest)
  in
  go outputs
