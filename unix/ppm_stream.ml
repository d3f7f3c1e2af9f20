(* Flushed to disk every so many bytes while the workers trace: what the
   final [fsync] of the atomic write then waits for is at most this much,
   whatever the size of the image. *)
let sync_bytes = 1 lsl 20

let after_render path render =
  let image = ref None in
  match render ~rows_done:(fun img _ -> image := Some img) with
  | Error (`Msg m) -> Error (`Msg m)
  | Ok x -> (
      let t = Unix.gettimeofday () in
      match !image with
      | None -> invalid_arg "Ppm_stream.render_to: rows_done was not called"
      | Some img -> (
          match Files.write_ppm path img with Ok () -> Ok (x, Unix.gettimeofday () -. t) | Error e -> Error e))

let while_rendering path render a =
  let oc = File_io.channel a in
  let fd = Unix.descr_of_out_channel oc in
  let written = ref (-1) and unsynced = ref 0 and failure = ref None in
  (* Called by the parent between the workers' reports: it must not raise,
     so that the workers are always waited for; a failure is kept and
     reported once the render is over. A file-size limit is an error of
     the write (EFBIG), not a signal, only while writing, as for
     File_io.write_atomic. *)
  let rows_done img r =
    if !failure = None then
      try
        Signals.without_sigxfsz (fun () ->
            if !written < 0 then begin
              output_string oc (Image.Ppm.header img);
              written := 0
            end;
            if r > !written then begin
              Image.Ppm.output_rows oc img ~first:!written ~stop:r;
              unsynced := !unsynced + (3 * Image.width img * (r - !written));
              written := r;
              if !unsynced >= sync_bytes && r < Image.height img then begin
                flush oc;
                Unix.fsync fd;
                unsynced := 0
              end
            end)
      with
      | Sys_error e -> failure := Some e
      | Unix.Unix_error (e, _, _) -> failure := Some (Unix.error_message e)
  in
  match render ~rows_done with
  | exception e ->
      File_io.discard a;
      raise e
  | Error (`Msg m) ->
      File_io.discard a;
      Error (`Msg m)
  | Ok x -> (
      match !failure with
      | Some e ->
          File_io.discard a;
          Error (`Msg (path ^ ": " ^ e))
      | None -> (
          if !written < 0 then invalid_arg "Ppm_stream.render_to: rows_done was not called";
          let t = Unix.gettimeofday () in
          match Signals.without_sigxfsz (fun () -> File_io.commit a) with
          | Ok () -> Ok (x, Unix.gettimeofday () -. t)
          | Error e -> Error e))

let render_to path render =
  if not (File_io.replaces path) then after_render path render
  else
    (* A signal during the render removes the temporary file (after the
       workers are stopped); a parent killed outright leaves it to its
       workers (Parallel.exit_if_orphaned). *)
    Signals.protect ~cleanup:File_io.remove_temporaries (fun () ->
        match File_io.open_atomic path with Error e -> Error e | Ok a -> while_rendering path render a)
