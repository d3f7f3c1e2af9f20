(* Raytrace's side of make bench-embree (issue 28): reads a scene (a mesh,
   an ambient light, recursion depth 0: bench/embree/compare.sh writes it),
   prepares it, casts the camera ray of every pixel, and prints one row of
   the table, then writes the rays (for embree_rays) and the hit mask.

   raytrace_rays.exe SCENE RAYS MASK *)

open Raytrace.Private

let or_exit = function Ok x -> x | Error (`Msg m) -> prerr_endline m; exit 1

let () =
  let scene, rays, mask =
    match Sys.argv with
    | [| _; s; r; m |] -> (s, r, m)
    | _ -> prerr_endline "usage: raytrace_rays SCENE RAYS MASK"; exit 2
  in
  let limits = or_exit (Raytrace_unix.Limits_env.read ()) in
  let t0 = Sys.time () in
  let scene = or_exit (Raytrace_unix.Files.read_scene ~limits scene) in
  let t1 = Sys.time () in
  let p = Prepared.prepare scene in
  let t2 = Sys.time () in
  let m = Bytes.create (p.width * p.height) in
  let r = Mesh_rays.cast p m in
  (* Before the rays' buffer below: the peak of reading, preparing, tracing. *)
  let peak_kb = match Raytrace_unix.Proc_self.kb "status" "VmHWM" with Some kb -> kb | None -> 0 in
  Printf.printf "%-16s %8.3f %8.3f %8.0f %7.2f%% %7.0f %8s\n%!" "raytrace" (t1 -. t0) (t2 -. t1)
    (r.cpu_s *. 1e9 /. Float.of_int r.rays)
    (100. *. Float.of_int r.hits /. Float.of_int r.rays)
    (Float.of_int peak_kb *. 1024. /. Float.of_int p.n_scene_objects)
    "-";
  Mesh_rays.write_rays p rays;
  let oc = open_out_bin mask in
  output_bytes oc m;
  close_out oc
