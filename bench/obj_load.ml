(* How fast Obj_file reads a large OBJ file, and in how much memory: the
   file read 64 KiB at a time, never whole, as a renderer would
   (Files.read_mesh); with --jobs 2, its second half by a child process.

   dune build --profile release bench/gen.exe bench/obj_load.exe
   ./_build/default/bench/gen.exe knot --segments 31250 --sides 16 -o /tmp/knot.obj
   ./_build/default/bench/obj_load.exe /tmp/knot.obj [--jobs 2] *)

open Raytrace

let () =
  let file, jobs =
    match Sys.argv with
    | [| _; f |] -> (f, 1)
    | [| _; f; "--jobs"; j |] -> (f, int_of_string j)
    | _ -> prerr_endline "usage: obj_load FILE.obj [--jobs N]"; exit 2
  in
  let size = (Unix.stat file).st_size in
  let t0 = Unix.gettimeofday () and cpu0 = Sys.time () in
  let on_part ~pid k = Printf.printf "the child process %d read %d triangles\n" pid k in
  let m = match Files.read_mesh ~jobs ~on_part file with Ok m -> m | Error (`Msg e) -> prerr_endline e; exit 1 in
  let t = Unix.gettimeofday () -. t0 and cpu = Sys.time () -. cpu0 in
  let child = (Unix.times ()).tms_cutime in
  let tris = Mesh.Obj.triangle_count m in
  let top_heap = Float.of_int ((Gc.quick_stat ()).top_heap_words * (Sys.word_size / 8)) /. 1048576. in
  (* What the mesh holds: its normal numbers may be its vertex numbers. *)
  let result_mb = Float.of_int (Obj.reachable_words (Obj.repr m) * (Sys.word_size / 8)) /. 1048576. in
  Printf.printf "%s: %.1f MB, %d vertices, %d normals, %d triangles\n" file (Float.of_int size /. 1048576.)
    (Mesh.Obj.vertex_count m) (Array.length m.normals / 3) tris;
  Printf.printf "cpu s: this process %.3f, its child %.3f\n" cpu child;
  Printf.printf "load %.3f s (%.0f MB/s), minor words %.0f (%.1f per line)\n" t (Float.of_int size /. 1048576. /. t)
    (Gc.minor_words ())
    (Gc.minor_words () /. Float.of_int (Mesh.Obj.vertex_count m + (Array.length m.normals / 3) + tris));
  Printf.printf "mesh %.1f MB (%.1f bytes per triangle), peak heap %.1f MB, peak RSS %.1f MB\n" result_mb
    (result_mb *. 1048576. /. Float.of_int (max 1 tris)) top_heap (Peak_rss.mb ())
