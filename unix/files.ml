(* A mesh file, 64 KiB at a time: the text is never held whole. *)
let read_mesh path =
  match open_in_bin path with
  | exception Sys_error m -> Error (`Msg (Printf.sprintf "cannot read mesh file: %s" m))
  | ic ->
      Fun.protect
        ~finally:(fun () -> close_in_noerr ic)
        (fun () ->
          let p = Obj_file.create ~name:path ~max_vertices:Limits.max_triangles ~max_triangles:Limits.max_triangles in
          let chunk = Bytes.create 65536 in
          let rec go () =
            match input ic chunk 0 (Bytes.length chunk) with
            | 0 -> Obj_file.finish p
            | n -> ( match Obj_file.feed_bytes p chunk 0 n with Ok () -> go () | Error e -> Error e)
            | exception Sys_error m -> Error (`Msg (Printf.sprintf "cannot read mesh file: %s" m))
          in
          go ())

let split_bytes = 4 lsl 20

(* The first line start at or after the middle of the [n] bytes of file
   [path], if one comes within 64 KiB. *)
let middle_line path n =
  match open_in_bin path with
  | exception Sys_error _ -> None
  | ic ->
      Fun.protect
        ~finally:(fun () -> close_in_noerr ic)
        (fun () ->
          match
            seek_in ic (n / 2);
            let buf = Bytes.create 65536 in
            let k = input ic buf 0 (Bytes.length buf) in
            Bytes.index_opt (Bytes.sub buf 0 k) '\n'
          with
          | Some j -> Some ((n / 2) + j + 1)
          | None | (exception (Sys_error _ | End_of_file)) -> None)

(* The second half of a big file, read by a child process
   (Parallel.beside) from a line start near the middle while the caller
   reads the first; [ic] is the caller's channel, which skips past what
   the child read. A child that fails, or whose part is not what the
   sequential read would have read, costs only its time. *)
let beside ~limits ~on_part path ic n =
  match middle_line path n with
  | None -> None
  | Some split when split >= n -> None
  | Some split ->
      let read () =
        let ic = open_in_bin path in
        Fun.protect
          ~finally:(fun () -> close_in_noerr ic)
          (fun () ->
            seek_in ic split;
            Scene_file.read_part ~limits { Scene_file.read = input ic; close = ignore } ~from:split)
      in
      let wait = Parallel.beside read in
      let wait () =
        match wait () with
        | Ok part ->
            on_part (Scene_file.part_length part);
            Some part
        | Error _ -> None
      in
      Some { Scene_file.split; wait; seek = seek_in ic }

(* A regular file is read a window at a time (Scene_file.of_source): the
   text of a million spheres (88 MB) is never held whole. Other files
   (pipes, /proc files), whose text cannot be read a second time to
   locate an error, are read whole. The errors are File_io.read's. *)
let read_scene ?(limits = Limits.default) ?(jobs = 1) ?(split_bytes = split_bytes) ?(on_part = ignore) path =
  let whole () =
    match File_io.read ~check_size:(Limits.check_scene_bytes limits) path with
    | Error e -> Error e
    | Ok text -> Scene_file.of_string ~limits ~load_mesh:read_mesh ~file:path text
  in
  match open_in_bin path with
  | exception Sys_error e -> Error (`Msg e)
  | ic -> (
      match Unix.fstat (Unix.descr_of_in_channel ic) with
      | exception Unix.Unix_error _ ->
          close_in_noerr ic;
          whole ()
      | { st_kind = S_REG; st_size = n; _ } when n > 0 -> (
          match Limits.check_scene_bytes limits n with
          | Error (`Msg m) ->
              close_in_noerr ic;
              Error (`Msg (Printf.sprintf "%s: %s" path m))
          | Ok _ -> (
              (* The first pass reads the channel opened here; an error's
                 pass opens the file again. *)
              let first = ref (Some ic) in
              let source () =
                let ic = match !first with Some ic -> first := None; ic | None -> open_in_bin path in
                { Scene_file.read = input ic; close = (fun () -> close_in_noerr ic) }
              in
              let beside = if jobs > 1 && n >= split_bytes then beside ~limits ~on_part path ic n else None in
              match Scene_file.of_source ~limits ~load_mesh:read_mesh ~file:path ?beside source with
              | r ->
                  Option.iter close_in_noerr !first;
                  r
              | exception Sys_error e ->
                  Option.iter close_in_noerr !first;
                  Error (`Msg (Printf.sprintf "%s: %s" path e))))
      | _ ->
          close_in_noerr ic;
          whole ())

let read_ppm ?(limits = Limits.default) path =
  match File_io.read ~check_size:(Ppm.check_file_size ~limits) path with
  | Error (`Msg e) -> Error (`Msg e)
  | Ok s -> (
      match Ppm.of_string ~limits s with Ok img -> Ok img | Error (`Msg m) -> Error (`Msg (path ^ ": " ^ m)))

let write_ppm ?comments path img = File_io.write_atomic path (fun oc -> Ppm.output ?comments oc img)

let render_file ?limits ?jobs path =
  match read_scene ?limits path with
  | Error _ as e -> e
  | Ok scene -> ( match Render_jobs.image ?limits ?jobs scene with Ok (img, _) -> Ok img | Error _ as e -> e)
