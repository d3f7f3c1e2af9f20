(* Raytrace's side of make bench-embree (issue 28): reads a scene (a mesh,
   an ambient light, recursion depth 0: bench/embree/compare.sh writes it),
   prepares it, casts the camera ray of every pixel with the pixel's
   shading (Trace.pixel) and without it (Trace.camera_hit), then, given a
   light, the shadow rays from the hits toward it (Trace.shadow_blocked),
   and builds the hierarchy once more alone, timed; it prints one row of
   the table and writes the rays (for embree_rays) and the hit masks.

   raytrace_rays.exe SCENE RAYS MASK [SHADOW_RAYS SHADOW_MASK X Y Z]

   The row: tracer, read s, prepare s, the hierarchy's build s, ns per
   camera ray with the pixel's shading, ns per camera ray alone, the share
   of camera rays that hit, peak bytes per triangle, differ ("-"), ns per
   shadow ray, the share of shadow rays blocked, differ ("-"). *)

open Raytrace.Private

let or_exit = function Ok x -> x | Error (`Msg m) -> prerr_endline m; exit 1
let ns (r : Mesh_rays.result) = r.cpu_s *. 1e9 /. Float.of_int (max 1 r.rays)
let share hits rays = 100. *. Float.of_int hits /. Float.of_int (max 1 rays)

let write_mask path m =
  let oc = open_out_bin path in
  output_bytes oc m;
  close_out oc

let () =
  let scene, rays, mask, shadows =
    match Sys.argv with
    | [| _; s; r; m |] -> (s, r, m, None)
    | [| _; s; r; m; sr; sm; x; y; z |] -> (s, r, m, Some (sr, sm, Raytrace.Vec3.v (float_of_string x) (float_of_string y) (float_of_string z)))
    | _ -> prerr_endline "usage: raytrace_rays SCENE RAYS MASK [SHADOW_RAYS SHADOW_MASK X Y Z]"; exit 2
  in
  let limits = or_exit (Raytrace_unix.Limits_env.read ()) in
  let t0 = Sys.time () in
  let scene = or_exit (Raytrace_unix.Files.read_scene ~limits scene) in
  let t1 = Sys.time () in
  (* RAYTRACE_CUT_LEAVES=1: the hierarchy's leaves cut by planes
     (Prepared.prepare ~cut), for the benchmark's rows of that option. *)
  let cut = Sys.getenv_opt "RAYTRACE_CUT_LEAVES" = Some "1" in
  let p = Prepared.prepare ~cut scene in
  let t2 = Sys.time () in
  let m = Bytes.create (p.width * p.height) and m2 = Bytes.create (p.width * p.height) in
  let r = Mesh_rays.cast p m in
  let c = Mesh_rays.cast_camera p m2 in
  if not (Bytes.equal m m2) then (prerr_endline "raytrace_rays: Trace.camera_hit and Trace.pixel disagree"; exit 1);
  (* Before the shadow rays, the rays' buffers and the second build: the
     peak of reading, preparing, tracing. *)
  let peak_kb = match Raytrace_unix.Proc_self.kb "status" "VmHWM" with Some kb -> kb | None -> 0 in
  let shadow =
    match shadows with
    | None -> None
    | Some (path, smask, light) ->
        let s = Mesh_rays.shadow_rays p ~light in
        let n = Array.length s / 6 in
        let sm = Bytes.create n in
        let rounds = Mesh_rays.rounds ~camera:(p.width * p.height) ~shadow:n in
        let sr = Mesh_rays.cast_shadows p s ~rounds sm in
        Some (path, smask, s, sm, sr, n)
  in
  let bvh_s = Mesh_rays.build_alone p in
  let shadow_cols =
    match shadow with
    | None -> Printf.sprintf "%8s %8s %8s" "-" "-" "-"
    | Some (_, _, _, _, sr, n) -> Printf.sprintf "%8.0f %7.2f%% %8s" (ns sr) (share sr.hits n) "-"
  in
  Printf.printf "%-16s %8.3f %8.3f %8.3f %8.0f %8.0f %7.2f%% %7.0f %8s %s\n%!" "raytrace" (t1 -. t0) (t2 -. t1) bvh_s (ns r) (ns c)
    (share r.hits r.rays)
    (Float.of_int peak_kb *. 1024. /. Float.of_int p.n_scene_objects)
    "-" shadow_cols;
  Mesh_rays.write_rays p rays;
  write_mask mask m;
  match shadow with
  | None -> ()
  | Some (path, smask, s, sm, _, _) ->
      Mesh_rays.write_floats s path;
      write_mask smask sm
