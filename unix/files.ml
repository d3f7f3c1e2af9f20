let read_scene ?(limits = Limits.default) path =
  match File_io.read ~check_size:(Limits.check_scene_bytes limits) path with
  | Error e -> Error e
  | Ok text -> Scene_file.of_string ~limits ~file:path text

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
