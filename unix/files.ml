let split_bytes = 4 lsl 20

(* The first line start at or after byte [at] of file [path], if one
   comes within 64 KiB. *)
let line_after path at =
  match File_io.open_read ~regular:true path with
  | Error _ -> None
  | Ok { channel = ic; _ } ->
      Fun.protect
        ~finally:(fun () -> close_in_noerr ic)
        (fun () ->
          match
            seek_in ic at;
            let buf = Bytes.create 65536 in
            let k = input ic buf 0 (Bytes.length buf) in
            Bytes.index_opt (Bytes.sub buf 0 k) '\n'
          with
          | Some j -> Some (at + j + 1)
          | None | (exception (Sys_error _ | End_of_file)) -> None)

(* A temporary file for a child's result, in memory where /dev/shm is,
   unlinked as soon as it is made; [None] where none can be made. *)
let temporary () =
  let dir = if Sys.file_exists "/dev/shm" then "/dev/shm" else Filename.get_temp_dir_name () in
  match Filename.temp_file ~temp_dir:dir "raytrace" ".part" with
  | exception Sys_error _ -> None
  | name -> (
      match Unix.openfile name [ O_RDWR; O_CLOEXEC ] 0o600 with
      | fd ->
          Sys.remove name;
          Some fd
      | exception Unix.Unix_error _ ->
          (try Sys.remove name with Sys_error _ -> ());
          None)

let rec write_all fd buf off len =
  if len > 0 then
    let k = Unix.write fd buf off len in
    write_all fd buf (off + k) (len - k)

let rec read_all fd buf off len =
  if len > 0 then
    match Unix.read fd buf off len with
    | 0 -> raise End_of_file
    | k -> read_all fd buf (off + k) (len - k)

(* Feeds [p] the bytes of [ic] until [stop] bytes were read from [start]
   (or the end). [check at] is called on the offset reached after each
   chunk: a file that grows as it is read stops at the bound. *)
let feed_mesh ~check ~path p ic ~start ~stop =
  let chunk = Bytes.create 65536 in
  let rec go at =
    if at >= stop then Ok ()
    else
      match input ic chunk 0 (min (Bytes.length chunk) (stop - at)) with
      | 0 -> Ok ()
      | n -> (
          match check (at + n) with
          | Error (`Msg m) -> Error (`Msg m)
          | Ok _ -> ( match Mesh.Obj.feed_bytes p chunk 0 n with Ok () -> go (at + n) | Error e -> Error e))
      | exception Sys_error m -> Error (`Msg (Printf.sprintf "cannot read mesh file: %s: %s" path m))
  in
  go start

(* The mesh from line start [split] of file [path] to its end, read in a
   child process (Parallel.beside); [wait ()] is the part, the id of the
   process that read it and the temporary file that holds its arrays
   (Obj_parts.join reads them), or [None] where the child failed, whatever
   the reason: the caller then reads that part itself. The child writes
   its arrays to the file as it reads (a block at a time: it holds a few
   blocks, never the part, and its collector has little to do) and sends
   the part's counts through the pipe. A file rather than the pipe: there
   each 64 KiB would need the other process to run, and on a busy machine
   the two would wait for each other some 400 times. *)
let mesh_part ~check path split =
  match temporary () with
  | None -> fun () -> None
  | Some fd ->
      let read () =
        match File_io.open_read ~regular:true path with
        | Error _ -> None
        | Ok { channel = ic; _ } ->
        Fun.protect
          ~finally:(fun () -> close_in_noerr ic)
          (fun () ->
            seek_in ic split;
            let p =
              Obj_parts.create_part ~output:(write_all fd) ~name:path ~max_vertices:Limits.max_triangles
                ~max_triangles:Limits.max_triangles
            in
            match Result.bind (feed_mesh ~check ~path p ic ~start:split ~stop:max_int) (fun () -> Obj_parts.finish_part p) with
            | Error _ -> None
            | Ok part -> Some (Unix.getpid (), part))
      in
      let wait = Parallel.beside read in
      fun () ->
        match wait () with
        | Ok (Some (pid, part)) -> (
            match
              ignore (Unix.lseek fd 0 SEEK_SET);
              (Unix.fstat fd).st_size = Obj_parts.part_bytes part
            with
            | true -> Some (pid, part, fd)
            | false | (exception Unix.Unix_error _) ->
                (try Unix.close fd with Unix.Unix_error _ -> ());
                None)
        | Ok None | Error _ ->
            (try Unix.close fd with Unix.Unix_error _ -> ());
            None

(* Where the child's part of a mesh file starts, in percent of the file:
   where the two readings cost about the same, since the join comes after
   both. The knot's file has its [v] and [vn] lines first, which cost
   about as much per byte as its [f] lines. On the knot of 100,000
   triangles (callgrind, bench/obj_load.exe --jobs 2, the reading loop of
   each process, the child's sending of its blocks included): 52% gives
   120.1 M in the parent and 136.5 M in the child, 54% 125.4 M and
   131.0 M; the child's sending also costs system time (its temporary
   file's pages), which callgrind does not count: 55%. *)
let mesh_split_percent = 55

(* A mesh file is a regular file (never a FIFO, whose open could wait for
   ever, nor a device, which could be read for ever), within the
   [`Mesh_bytes] bound, checked before it is read and as it is read. *)
let read_mesh_paced ~limits ~jobs ~split_bytes ~on_part path (o : File_io.opened) =
  let ic = o.channel in
  Fun.protect
    ~finally:(fun () -> close_in_noerr ic)
    (fun () ->
      let check n = Limits.check_mesh_bytes limits path n in
      match check o.stats.st_size with
      | Error _ as e -> e
      | Ok n ->
          let p = Mesh.Obj.create ~name:path ~max_vertices:Limits.max_triangles ~max_triangles:Limits.max_triangles in
          let split =
            if jobs <= 1 || n < split_bytes || n = 0 then None
            else
              match line_after path (n / 100 * mesh_split_percent) with Some split when split < n -> Some split | Some _ | None -> None
          in
          let rest at = match feed_mesh ~check ~path p ic ~start:at ~stop:max_int with Ok () -> Mesh.Obj.finish p | Error e -> Error e in
          match split with
          | None -> rest 0
          | Some split -> (
              let wait = mesh_part ~check path split in
              let first = feed_mesh ~check ~path p ic ~start:0 ~stop:split in
              (* Waited for even after an error, so that no child is left. *)
              let part = wait () in
              match first with
              | Error e -> Error e
              | Ok () -> (
                  match part with
                  | None -> rest split
                  | Some (pid, part, fd) -> (
                      let joined =
                        match Obj_parts.join p part ~input:(read_all fd) with
                        | m -> m
                        | exception (Unix.Unix_error _ | End_of_file | Failure _) -> None
                      in
                      (try Unix.close fd with Unix.Unix_error _ -> ());
                      match joined with
                      | Some m ->
                          on_part ~pid (Obj_parts.part_triangle_count part);
                          Ok m
                      | None -> rest split))))

(* While a mesh is read, the major collector is paced for a heap 10 times
   its live data (space_overhead 1000, then restored): what the read
   allocates is nearly all kept (blocks of 65536 numbers, straight into
   the major heap), and every cycle marks the numbers of every block,
   field by field. The knot of 1M triangles with one job (callgrind,
   Files.read_scene): 3,785 M instructions at the default 120, 3,514 M so;
   its garbage (the blocks, once concatenated) waits for the next cycle,
   or for the compaction that preparing a big mesh makes. *)
let mesh_space_overhead = 1000

(* A mesh file, 64 KiB at a time: the text is never held whole. With two
   jobs, a child reads the second half of a big regular file meanwhile. *)
let read_mesh_opened ~limits ~jobs ~split_bytes ~on_part path o =
  let gc = Gc.get () in
  Gc.set { gc with space_overhead = max gc.space_overhead mesh_space_overhead };
  Fun.protect
    ~finally:(fun () -> Gc.set { (Gc.get ()) with space_overhead = gc.space_overhead })
    (fun () -> read_mesh_paced ~limits ~jobs ~split_bytes ~on_part path o)

let open_mesh path =
  match File_io.open_read ~regular:true path with
  | Ok o -> Ok o
  | Error (`Msg m) -> Error (`Msg ("cannot read mesh file: " ^ m))

let read_mesh ?(limits = Limits.default) ?(jobs = 1) ?(split_bytes = split_bytes) ?(on_part = fun ~pid:_ _ -> ()) path =
  match open_mesh path with
  | Error _ as e -> e
  | Ok o -> read_mesh_opened ~limits ~jobs ~split_bytes ~on_part path o

(* The fields of the child's spheres (40 bytes each: center, radius as
   floats, the material as an integer) travel through a temporary file,
   unlinked as soon as it is made, a block of spheres at a time: sent by
   Marshal they took the parent a buffer and a copy of their size (18 MB
   for grid:1000000), which raised the render's peak by 9 MB. *)
let block = 16384
let sphere_bytes = 40

(* Top-level and inlined, so that the floats are not boxed. *)
let[@inline] put_float buf at x = Bytes.set_int64_le buf at (Int64.bits_of_float x)
let[@inline] get_float buf at = Int64.float_of_bits (Bytes.get_int64_le buf at)

(* Block after block: the [len] x, then y, z, radius and material. *)
let write_spheres fd s =
  let n = Private.Spheres.length s in
  let buf = Bytes.create (block * sphere_bytes) in
  let at = ref 0 in
  while !at < n do
    let len = min block (n - !at) in
    for i = 0 to len - 1 do
      let k = !at + i in
      put_float buf (8 * i) (Private.Spheres.center_x s k);
      put_float buf (8 * (len + i)) (Private.Spheres.center_y s k);
      put_float buf (8 * ((2 * len) + i)) (Private.Spheres.center_z s k);
      put_float buf (8 * ((3 * len) + i)) (Private.Spheres.radius s k);
      Bytes.set_int64_le buf (8 * ((4 * len) + i)) (Int64.of_int (Private.Spheres.material_index s k))
    done;
    write_all fd buf 0 (sphere_bytes * len);
    at := !at + len
  done

(* The part's spheres, read back into [b] with its materials mapped to
   [b]'s table. Its size was checked: a failure here is the system's. *)
let append_spheres fd b part =
  let n = Private.Scene_text.part_length part in
  let index = Array.map (Private.Spheres.material b) (Private.Scene_text.part_materials part) in
  let buf = Bytes.create (block * sphere_bytes) in
  let x = Array.make block 0. and y = Array.make block 0. and z = Array.make block 0. in
  let r = Array.make block 0. and m = Array.make block 0 in
  match
    ignore (Unix.lseek fd 0 SEEK_SET);
    let at = ref 0 in
    while !at < n do
      let len = min block (n - !at) in
      read_all fd buf 0 (sphere_bytes * len);
      for i = 0 to len - 1 do
        x.(i) <- get_float buf (8 * i);
        y.(i) <- get_float buf (8 * (len + i));
        z.(i) <- get_float buf (8 * ((2 * len) + i));
        r.(i) <- get_float buf (8 * ((3 * len) + i));
        let k = Int64.to_int (Bytes.get_int64_le buf (8 * ((4 * len) + i))) in
        m.(i) <- (if k >= 0 && k < Array.length index then index.(k) else -1)
      done;
      Private.Spheres.append_fields b ~x ~y ~z ~radius:r ~material:m len;
      at := !at + len
    done
  with
  | () -> ()
  | exception Unix.Unix_error (e, _, _) -> raise (Sys_error (Unix.error_message e))
  | exception End_of_file -> raise (Sys_error "a temporary file was cut short")

(* The second half of a big file, read by a child process
   (Parallel.beside) from a line start near the middle while the caller
   reads the first; [ic] is the caller's channel, which skips past what
   the child read. A child that fails, or whose part is not what the
   sequential read would have read, costs only its time. [None], and
   nothing to close, where no temporary file can be made. *)
let beside ~limits ~on_part path ic n =
  match line_after path (n / 2) with
  | None -> None
  | Some split when split >= n -> None
  | Some split -> (
      match temporary () with
      | None -> None
      | Some fd ->
          let read () =
            let ic = open_in_bin path in
            let part =
              Fun.protect
                ~finally:(fun () -> close_in_noerr ic)
                (fun () ->
                  seek_in ic split;
                  Private.Scene_text.read_part ~limits { Private.Scene_text.read = input ic; close = ignore } ~from:split)
            in
            write_spheres fd (Private.Scene_text.part_spheres part);
            Private.Scene_text.part_header part
          in
          let wait = Parallel.beside read in
          let wait () =
            match wait () with
            | Ok part when (Unix.fstat fd).st_size = sphere_bytes * Private.Scene_text.part_length part ->
                on_part (Private.Scene_text.part_length part);
                Some part
            | Ok _ | Error _ -> None
            | exception Unix.Unix_error _ -> None
          in
          Some ({ Private.Scene_text.split; wait; append = append_spheres fd; seek = seek_in ic }, fd))

type input = { what : string; path : string; stats : Unix.stats }

(* A texture as this library reads it: PPM only, PNG being raytrace-png's
   (its [Image_file.read_texture] is the reader to pass), read without the
   file's text and an image beside it (Image.Ppm.texture_of_channel): a
   texture's reading peaks near its size, not three times it. *)
let read_ppm_texture ?(limits = Limits.default) path =
  match File_io.open_read ~regular:true path with
  | Error e -> Error e
  | Ok o ->
      Fun.protect
        ~finally:(fun () -> close_in_noerr o.channel)
        (fun () ->
          let length = o.stats.st_size in
          match Image.Ppm.check_file_size ~limits length with
          | Error (`Msg m) -> Error (`Msg (path ^ ": " ^ m))
          | Ok _ -> (
              match Image.Ppm.texture_of_channel ~limits o.channel ~length with
              | Ok t -> Ok t
              | Error (`Msg m) -> Error (`Msg (path ^ ": " ^ m))
              | exception Sys_error m -> Error (`Msg m)))

type loaded = { scene : Scene.valid; inputs : input list }

(* A regular file is read a window at a time (Private.Scene_text.of_source): the
   text of a million spheres (88 MB) is never held whole. Other files
   (pipes, /proc files), whose text cannot be read a second time to
   locate an error, are read whole, from the descriptor opened here (a
   FIFO closed and opened again would lose what its writer wrote
   meanwhile). The errors are File_io.read's. *)
let load_scene ?(limits = Limits.default) ?(jobs = 1) ?(split_bytes = split_bytes) ?(on_part = ignore) ?read_image
    ?read_texture path =
  (* Every file the scene reads, as it reads it (Scene_file reads each
     path once). *)
  let inputs = ref [] in
  let read_texture =
    match (read_texture, read_image) with
    | Some r, _ -> r
    | None, Some r -> fun file -> Result.map Image.Texture.of_image (r file)
    | None, None -> read_ppm_texture ~limits
  in
  let load_texture file =
    match File_io.open_read ~regular:true file with
    | Error (`Msg m) -> Error (`Msg ("cannot read texture file: " ^ m))
    | Ok o -> (
        close_in_noerr o.channel;
        match read_texture file with
        | Error (`Msg m) -> Error (`Msg ("cannot read texture file: " ^ m))
        | Ok texture ->
            inputs := { what = "texture"; path = file; stats = o.stats } :: !inputs;
            Ok texture)
  in
  let load_mesh mesh =
    match open_mesh mesh with
    | Error _ as e -> e
    | Ok o ->
        inputs := { what = "mesh"; path = mesh; stats = o.stats } :: !inputs;
        read_mesh_opened ~limits ~jobs ~split_bytes ~on_part:(fun ~pid:_ _ -> ()) mesh o
  in
  let loaded r = Result.map (fun scene -> { scene; inputs = List.rev !inputs }) r in
  match File_io.open_read path with
  | Error _ as e -> e
  | Ok ({ stats = { st_kind = S_REG; st_size = n; _ }; channel = ic; _ }) when n > 0 -> (
      match Limits.check_scene_bytes limits n with
      | Error (`Msg m) ->
          close_in_noerr ic;
          Error (`Msg (Printf.sprintf "%s: %s" path m))
      | Ok _ -> (
          (* The first pass reads the channel opened here; an error's
             pass opens the file again. *)
          let first = ref (Some ic) in
          let source () =
            let ic =
              match !first with
              | Some ic ->
                  first := None;
                  ic
              | None -> ( match File_io.open_read ~regular:true path with Ok o -> o.channel | Error (`Msg m) -> raise (Sys_error m))
            in
            { Private.Scene_text.read = input ic; close = (fun () -> close_in_noerr ic) }
          in
          let beside = if jobs > 1 && n >= split_bytes then beside ~limits ~on_part path ic n else None in
          let close () =
            Option.iter close_in_noerr !first;
            Option.iter (fun (_, fd) -> try Unix.close fd with Unix.Unix_error _ -> ()) beside
          in
          match Private.Scene_text.of_source ~limits ~load_mesh ~load_texture ~file:path ?beside:(Option.map fst beside) source with
          | r ->
              close ();
              loaded r
          | exception Sys_error e ->
              close ();
              Error (`Msg (Printf.sprintf "%s: %s" path e))))
  | Ok o -> (
      match File_io.read_opened ~check_size:(Limits.check_scene_bytes limits) path o with
      | Error e -> Error e
      | Ok text -> loaded (Scene_file.of_string ~limits ~load_mesh ~load_texture ~file:path text))

let read_scene ?limits ?jobs ?split_bytes ?on_part ?read_image ?read_texture path =
  Result.map (fun l -> l.scene) (load_scene ?limits ?jobs ?split_bytes ?on_part ?read_image ?read_texture path)

(* The identity and version of a file: another file, or the same one
   written to, differs in one of them. *)
let same_version (a : Unix.stats) (b : Unix.stats) =
  a.st_dev = b.st_dev && a.st_ino = b.st_ino && a.st_size = b.st_size
  && Float.equal a.st_mtime b.st_mtime && Float.equal a.st_ctime b.st_ctime

let inputs_digest inputs =
  let digest i =
    let changed () =
      Error
        (`Msg
          (Printf.sprintf "%s: the %s changed after it was read (written to or replaced); render again" i.path i.what))
    in
    match File_io.open_read ~regular:true i.path with
    | Error _ -> changed ()
    | Ok o ->
        Fun.protect
          ~finally:(fun () -> close_in_noerr o.channel)
          (fun () ->
            if not (same_version o.stats i.stats) then changed ()
            else
              match Digest.channel o.channel (-1) with
              | exception (Sys_error _ | End_of_file) -> changed ()
              | d -> (
                  match Unix.fstat (Unix.descr_of_in_channel o.channel) with
                  | st when same_version st i.stats -> Ok (i.what ^ " " ^ Digest.to_hex d)
                  | _ | (exception Unix.Unix_error _) -> changed ()))
  in
  let rec all acc = function
    | [] -> Ok (List.rev acc)
    | i :: rest -> ( match digest i with Ok d -> all (d :: acc) rest | Error _ as e -> e)
  in
  match inputs with
  | [] -> Ok ""
  | _ -> Result.map (fun ds -> Digest.to_hex (Digest.string (String.concat "\n" ds))) (all [] inputs)

let read_ppm ?(limits = Limits.default) path =
  match File_io.read ~check_size:(Image.Ppm.check_file_size ~limits) path with
  | Error (`Msg e) -> Error (`Msg e)
  | Ok s -> (
      match Image.Ppm.of_string ~limits s with Ok img -> Ok img | Error (`Msg m) -> Error (`Msg (path ^ ": " ^ m)))

let write_ppm ?comments path img = File_io.write_atomic path (fun oc -> Image.Ppm.output ?comments oc img)

let render_file ?limits ?jobs path =
  match read_scene ?limits ?jobs path with
  | Error _ as e -> e
  | Ok scene -> ( match Render_jobs.image ?limits ?jobs scene with Ok (img, _) -> Ok img | Error _ as e -> e)
