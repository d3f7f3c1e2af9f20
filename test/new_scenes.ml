let all =
  [
    ("room.scene", "planes");
    ("boxes.scene", "boxes, a triangle, a plane");
    ("mesh.scene", "an OBJ mesh, smooth shading");
    ("checker.scene", "checker patterns on a plane, spheres and a box");
  ]

let names = List.map fst all

let copy_models dir =
  Array.iter
    (fun name ->
      if Filename.check_suffix name ".obj" then
        match Raytrace_unix.File_io.read (Helpers.scene_path name) with
        | Ok text ->
            let oc = open_out_bin (Filename.concat dir name) in
            output_string oc text;
            close_out oc
        | Error (`Msg m) -> Alcotest.fail m)
    (Sys.readdir (Filename.dirname (Helpers.scene_path "cgfs.scene")))
