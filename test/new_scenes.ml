let all =
  [
    ("room.scene", "planes");
    ("boxes.scene", "boxes, a triangle, a plane");
    ("mesh.scene", "an OBJ mesh, smooth shading");
    ("checker.scene", "checker patterns on a plane, spheres and a box");
    ("lens.scene", "a CSG intersection of two spheres");
    ("die.scene", "a CSG difference of a cube and spheres");
    ("glass.scene", "a glass ball over a checkered floor");
    ("glass-lens.scene", "a glass CSG lens over a checkered floor");
    ("glass-knot.scene", "a glass mesh");
    ("cylinder.scene", "capped and open cylinders, a glass one, a checker, a CSG drill");
    ("disk.scene", "disks seen from both sides, a mirror, glass, an open tube with a lid");
    ("focus.scene", "a thin lens, focused on the middle of a row of balls");
    ("area-room.scene", "a room under an area light, a sphere light and a spotlight");
    ("globe.scene", "a textured globe on a tiled floor");
  ]

let names = List.map fst all

let copy_models dir =
  Array.iter
    (fun name ->
      if Filename.check_suffix name ".obj" || Filename.check_suffix name ".ppm" then
        match Raytrace_unix.File_io.read (Helpers.scene_path name) with
        | Ok text ->
            let oc = open_out_bin (Filename.concat dir name) in
            output_string oc text;
            close_out oc
        | Error (`Msg m) -> Alcotest.fail m)
    (Sys.readdir (Filename.dirname (Helpers.scene_path "cgfs.scene")))
