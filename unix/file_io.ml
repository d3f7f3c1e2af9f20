let error path reason = Error (`Msg (Printf.sprintf "%s: %s" path reason))

(* Files whose length is unknown (/proc files, pipes, devices): read in
   chunks, checking the size so far. *)
let read_to_end ~first ~check_size ic =
  let b = Buffer.create 4096 and chunk = Bytes.create 65536 in
  let rec go () =
    match check_size (Buffer.length b) with
    | Error (`Msg m) -> Error m
    | Ok _ -> (
        match input ic chunk 0 (Bytes.length chunk) with
        | 0 -> Ok (Buffer.contents b)
        | k ->
            Buffer.add_subbytes b chunk 0 k;
            go ())
  in
  Buffer.add_string b first;
  go ()

type opened = { channel : in_channel; stats : Unix.stats; first : string }

let fifo_wait = 5.

let kind_name = function
  | Unix.S_DIR -> "a directory"
  | S_FIFO -> "a FIFO"
  | S_CHR -> "a character device"
  | S_BLK -> "a block device"
  | S_SOCK -> "a socket"
  | S_LNK -> "a symbolic link"
  | S_REG -> "a regular file"

(* A FIFO opened without blocking: [0] from a read means that no program
   has it open for writing (or one did and wrote nothing), [EAGAIN] that
   one has and has not written yet. The first bytes, where some came, are
   the text's: they are given back. *)
let wait_for_writer path fd =
  let buf = Bytes.create 65536 in
  let deadline = Unix.gettimeofday () +. fifo_wait in
  let rec go () =
    match Unix.read fd buf 0 (Bytes.length buf) with
    | 0 when Unix.gettimeofday () < deadline ->
        Unix.sleepf 0.02;
        go ()
    | 0 ->
        error path
          (Printf.sprintf
             "is a FIFO that no program wrote to within %.0f s; start the program that writes it first, or pipe its data to /dev/stdin"
             fifo_wait)
    | n -> Ok (Bytes.sub_string buf 0 n)
    | exception Unix.Unix_error ((EAGAIN | EWOULDBLOCK), _, _) -> Ok ""
    | exception Unix.Unix_error (EINTR, _, _) -> go ()
    | exception Unix.Unix_error (e, _, _) -> error path (Unix.error_message e)
  in
  go ()

let open_read ?(regular = false) path =
  (* O_NONBLOCK: opening a FIFO for reading would otherwise wait, without
     end, for a program to open it for writing. *)
  match Unix.openfile path [ O_RDONLY; O_NONBLOCK; O_CLOEXEC ] 0 with
  | exception Unix.Unix_error (e, _, _) -> error path (Unix.error_message e)
  | fd -> (
      let fail m =
        (try Unix.close fd with Unix.Unix_error _ -> ());
        error path m
      in
      match Unix.fstat fd with
      | exception Unix.Unix_error (e, _, _) -> fail (Unix.error_message e)
      | { st_kind = S_DIR; _ } -> fail "is a directory"
      | { st_kind = S_REG; _ } as stats ->
          Unix.clear_nonblock fd;
          Ok { channel = Unix.in_channel_of_descr fd; stats; first = "" }
      | { st_kind; _ } when regular -> fail ("is " ^ kind_name st_kind ^ ", not a regular file")
      | { st_kind = S_FIFO; _ } as stats -> (
          match wait_for_writer path fd with
          | Error _ as e ->
              (try Unix.close fd with Unix.Unix_error _ -> ());
              e
          | Ok first ->
              Unix.clear_nonblock fd;
              Ok { channel = Unix.in_channel_of_descr fd; stats; first })
      | stats ->
          Unix.clear_nonblock fd;
          Ok { channel = Unix.in_channel_of_descr fd; stats; first = "" })

let read_opened ?(check_size = fun n -> Ok n) path o =
  let ic = o.channel in
  set_binary_mode_in ic true;
  match
    Fun.protect
      ~finally:(fun () -> close_in_noerr ic)
      (fun () ->
        (* The size is checked before a byte is read or allocated. *)
        match o.stats with
        | { st_kind = S_REG; st_size = n; _ } when n > 0 -> (
            match check_size n with Error (`Msg m) -> Error m | Ok _ -> Ok (really_input_string ic n))
        | _ -> read_to_end ~first:o.first ~check_size ic)
  with
      | Ok s -> Ok s
      | Error m -> error path m
      | exception Sys_error e -> error path e
      | exception Unix.Unix_error (e, _, _) -> error path (Unix.error_message e)
      | exception Out_of_memory -> error path "not enough memory to read the file"
      | exception End_of_file -> error path "file changed while it was read"

let read ?check_size path =
  match open_read path with Error _ as e -> e | Ok o -> read_opened ?check_size path o

(* Temporary files of writes in progress, for [remove_temporaries]. *)
let temporaries : (string, unit) Hashtbl.t = Hashtbl.create 4

let remove_temporaries () =
  Hashtbl.iter (fun tmp () -> try Sys.remove tmp with Sys_error _ -> ()) temporaries;
  Hashtbl.reset temporaries

let is_special path =
  match Unix.stat path with
  | { Unix.st_kind = S_CHR | S_FIFO | S_SOCK | S_BLK; _ } -> true
  | _ -> false
  | exception Unix.Unix_error _ -> false

let write_direct path f =
  match open_out_gen [ Open_wronly; Open_binary ] 0o666 path with
  | exception Sys_error e -> Error (`Msg e)
  | oc -> (
      match
        f oc;
        close_out oc
      with
      | () -> Ok ()
      | exception Sys_error e ->
          close_out_noerr oc;
          error path e)

(* A fresh name beside [path]; O_EXCL makes a collision an error, retried. *)
let rec open_temporary path attempt =
  let dir = Filename.dirname path and base = Filename.basename path in
  let tmp =
    Filename.concat dir
      (Printf.sprintf ".%s.%d.%d.tmp" base (Unix.getpid ()) (Random.State.bits (Random.State.make_self_init ())))
  in
  match Unix.openfile tmp [ O_WRONLY; O_CREAT; O_EXCL; O_CLOEXEC ] 0o666 with
  | fd -> (tmp, fd)
  | exception Unix.Unix_error (EEXIST, _, _) when attempt < 100 -> open_temporary path (attempt + 1)

(* A symbolic link is written through, as [cp] does: the link stays and
   its target gets the new contents. A dangling link is an error. *)
let resolve path =
  match Unix.lstat path with
  | { st_kind = S_LNK; _ } -> (
      match Unix.realpath path with
      | real -> Ok real
      | exception Unix.Unix_error (e, _, _) ->
          error path ("is a symbolic link that cannot be followed: " ^ Unix.error_message e))
  | _ -> Ok path
  | exception Unix.Unix_error _ -> Ok path

(* An existing file that this process may not write stays as it is, even
   though its directory would let a rename replace it. (For root, as in
   [cp], permission bits do not make a file read-only.) *)
let check_writable path =
  match Unix.access path [ W_OK ] with
  | () -> Ok ()
  | exception Unix.Unix_error (ENOENT, _, _) -> Ok ()
  | exception Unix.Unix_error (e, _, _) -> error path ("cannot be replaced: " ^ Unix.error_message e)

(* Best effort: the rename is durable once the directory is on disk. *)
let sync_directory dir =
  match Unix.openfile dir [ O_RDONLY; O_CLOEXEC ] 0 with
  | fd ->
      (try Unix.fsync fd with Unix.Unix_error _ -> ());
      Unix.close fd
  | exception Unix.Unix_error _ -> ()

type atomic = { target : string; tmp : string; channel : out_channel }

let channel a = a.channel

let discard a =
  close_out_noerr a.channel;
  (try Sys.remove a.tmp with Sys_error _ -> ());
  Hashtbl.remove temporaries a.tmp

(* The temporary file beside [path], registered for [remove_temporaries]. *)
let open_temporary_channel path =
  match open_temporary path 0 with
  | exception Unix.Unix_error (e, _, _) ->
      error path ("cannot create a file in its directory: " ^ Unix.error_message e)
  | tmp, fd -> (
      Hashtbl.replace temporaries tmp ();
      let oc = Unix.out_channel_of_descr fd in
      set_binary_mode_out oc true;
      let a = { target = path; tmp; channel = oc } in
      (* The replaced file's permissions carry over to the new one. *)
      match Unix.stat path with
      | st -> (
          match Unix.fchmod fd (st.st_perm land 0o7777) with
          | () -> Ok a
          | exception Unix.Unix_error (e, _, _) ->
              discard a;
              error path (Unix.error_message e))
      | exception Unix.Unix_error _ -> Ok a)

let commit a =
  match
    flush a.channel;
    Unix.fsync (Unix.descr_of_out_channel a.channel);
    close_out a.channel;
    Unix.rename a.tmp a.target
  with
  | () ->
      Hashtbl.remove temporaries a.tmp;
      sync_directory (Filename.dirname a.target);
      Ok ()
  | exception Sys_error e ->
      discard a;
      error a.target e
  | exception Unix.Unix_error (e, _, _) ->
      discard a;
      error a.target (Unix.error_message e)

let write_temporary path f =
  match open_temporary_channel path with
  | Error e -> Error e
  | Ok a -> (
      match f a.channel with
      | () -> commit a
      | exception Sys_error e ->
          discard a;
          error path e
      | exception Unix.Unix_error (e, _, _) ->
          discard a;
          error path (Unix.error_message e)
      | exception ex ->
          discard a;
          raise ex)

(* Standard output or error, when [path] names the very file it writes to
   ([/dev/stdout], [/proc/self/fd/2], the file of a redirection): written
   through the open descriptor, at its offset and with its flags (a [>>]
   redirection appends), never reopened from the start or replaced. *)
let standard_channel path =
  match Unix.stat path with
  | exception Unix.Unix_error _ -> None
  | st ->
      let same fd =
        match Unix.fstat fd with
        | s -> s.st_dev = st.st_dev && s.st_ino = st.st_ino
        | exception Unix.Unix_error _ -> false
      in
      if same Unix.stdout then Some stdout else if same Unix.stderr then Some stderr else None

let write_channel path oc f =
  match
    set_binary_mode_out oc true;
    f oc;
    flush oc
  with
  | () -> Ok ()
  | exception Sys_error e -> error path e

let replaces path =
  standard_channel path = None
  && match resolve path with Ok path -> not (is_special path) | Error _ -> true

(* The checks of [write_atomic] before it writes a temporary file. *)
let replaceable path k =
  match resolve path with
  | Error e -> Error e
  | Ok path -> (
      if Sys.file_exists path && Sys.is_directory path then error path "is a directory"
      else match check_writable path with Error e -> Error e | Ok () -> k path)

let open_atomic path =
  if not (replaces path) then invalid_arg "File_io.open_atomic: not a file that a rename replaces";
  replaceable path (fun path -> Signals.without_sigxfsz (fun () -> open_temporary_channel path))

let write_atomic path f =
  match (standard_channel path, resolve path) with
  | Some oc, _ -> write_channel path oc f
  | None, Error e -> Error e
  | None, Ok path ->
      if Sys.file_exists path && Sys.is_directory path then error path "is a directory"
      else if is_special path then write_direct path f
      else
        match check_writable path with
        | Error e -> Error e
        | Ok () ->
            Signals.protect ~cleanup:remove_temporaries (fun () ->
                Signals.without_sigxfsz (fun () -> write_temporary path f))
