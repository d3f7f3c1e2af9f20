exception Render_failed of string

(* Flushed to disk every so many bytes while the workers trace: what the
   final [fsync] of the atomic write then waits for is at most this much,
   whatever the size of the image. *)
let sync_bytes = 1 lsl 20

let render_to path render =
  if not (File_io.replaces path) then begin
    let image = ref None in
    match render ~rows_done:(fun img _ -> image := Some img) with
    | Error (`Msg m) -> Error (`Msg m)
    | Ok x -> (
        let t = Unix.gettimeofday () in
        match !image with
        | None -> invalid_arg "Ppm_stream.render_to: rows_done was not called"
        | Some img -> (
            match Files.write_ppm path img with Ok () -> Ok (x, Unix.gettimeofday () -. t) | Error e -> Error e))
  end
  else
    let result = ref None in
    let write oc =
      let fd = Unix.descr_of_out_channel oc in
      let written = ref (-1) and unsynced = ref 0 and failure = ref None in
      (* Called by the parent between the workers' reports: it must not
         raise, so that the workers are always waited for; a failure is
         kept and raised once the render is over. *)
      let rows_done img r =
        if !failure = None then
          try
            if !written < 0 then begin
              output_string oc (Ppm.header img);
              written := 0
            end;
            if r > !written then begin
              Ppm.output_rows oc img ~first:!written ~stop:r;
              unsynced := !unsynced + (3 * Image.width img * (r - !written));
              written := r;
              if !unsynced >= sync_bytes && r < Image.height img then begin
                flush oc;
                Unix.fsync fd;
                unsynced := 0
              end
            end
          with
          | Sys_error e -> failure := Some e
          | Unix.Unix_error (e, _, _) -> failure := Some (Unix.error_message e)
      in
      match render ~rows_done with
      | Error (`Msg m) -> raise (Render_failed m)
      | Ok x -> (
          match !failure with
          | Some e -> raise (Sys_error e)
          | None ->
              if !written < 0 then invalid_arg "Ppm_stream.render_to: rows_done was not called";
              result := Some (x, Unix.gettimeofday ()))
    in
    match File_io.write_atomic path write with
    | exception Render_failed m -> Error (`Msg m)
    | Error e -> Error e
    | Ok () -> (
        match !result with Some (x, t) -> Ok (x, Unix.gettimeofday () -. t) | None -> assert false)
