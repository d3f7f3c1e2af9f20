(* Run time against error: every speed/quality setting of the renderer on a
   set of scenes, timed, and compared with a high-quality reference render
   of the same scene. Writes a CSV, a gnuplot PNG plot with the Pareto
   front of each scene marked, and a Markdown summary.

   Run from the repository root, built in release mode (the dev profile
   stops cross-module inlining):

     make bench-quality

   With --soft (make bench-soft) it measures the integrals of soft
   shadows and depth of field instead: uniform, stratified and adaptive
   sampling against a reference of 64 times the samples (see "Soft
   shadows and depth of field" below).

   Times are the CPU seconds (user + system) of [Render.image] in one
   process (jobs 1), the median of several runs: on a machine shared with
   other work they vary far less than wall-clock seconds, which the CSV
   gives too and which equal them on an idle machine. Rays per pixel are
   exact. Benchmarks print tables; no test runs this program. *)

open Raytrace

let reference_samples = 16
let reference_depth = 10

(* The documented set: name and file, one line per scene (the plot makes
   a panel for each). Each is rendered at its own canvas size (600 x 600,
   600 x 600, 480 x 360, 600 x 600, then 320 x 240 for the shapes' scenes,
   240 x 180 for the checker and the glass lens, 320 x 240 for the glass
   ball, 200 x 200 for the die), or half of it with --half. The glass
   mesh (scenes/glass-knot.scene) is not in the set: its reference render
   (16 x 16 samples at depth 10, where each glass hit spawns two rays)
   would take 10 to 20 minutes (docs/run-time-against-error.md). *)
let scenes =
  [
    ("cgfs", "scenes/cgfs.scene");
    ("cgfs-camera", "scenes/cgfs-camera.scene");
    ("sphere-grid", "scenes/sphere-grid.scene");
    ("tiny-spheres", "scenes/tiny-spheres.scene");
    ("room", "scenes/room.scene");
    ("boxes", "scenes/boxes.scene");
    ("checker", "scenes/checker.scene");
    ("glass", "scenes/glass.scene");
    ("glass-lens", "scenes/glass-lens.scene");
    ("die", "scenes/die.scene");
  ]

(* The depths of the table of error against depth, each against one ray
   per pixel at [reference_depth]: the error that the depth alone
   causes, with the aliasing of one ray per pixel on both sides. *)
let table_depths = [ 0; 1; 2; 3; 4; 5; 6; 8 ]

type setting = {
  family : string;  (** depth, full, adaptive, subsample *)
  depth : int;
  samples : int;
  adaptive : int option;
  subsample : bool;
}

(* For the plot's labels. *)
let short s =
  let base =
    match s.adaptive with
    | Some th -> Printf.sprintf "a%d t%d" s.samples th
    | None -> if s.subsample then "sub" else Printf.sprintf "%dx%d" s.samples s.samples
  in
  Printf.sprintf "%s d%d" base s.depth

let label s =
  let base =
    match s.adaptive with
    | Some th -> Printf.sprintf "adaptive %dx%d t%d" s.samples s.samples th
    | None -> if s.subsample then "subsample" else Printf.sprintf "%dx%d" s.samples s.samples
  in
  Printf.sprintf "%s d%d" base s.depth

(* The command-line options of the setting, for the summary. *)
let options s =
  String.concat " "
    (List.concat
       [
         [ Printf.sprintf "--depth %d" s.depth ];
         (if s.samples > 1 then [ Printf.sprintf "--samples %d" s.samples ] else []);
         (match s.adaptive with Some th -> [ Printf.sprintf "--adaptive %d" th ] | None -> []);
         (if s.subsample then [ "--subsample" ] else []);
       ])

(* Depth 0-6 and 8 with one ray per pixel; full N x N, N = 2-8, adaptive N = 3, 5,
   7 with thresholds 1-32, all at the scene's depth; then the same deeper;
   subsampling at depth 0-5. *)
let settings ~depth =
  let one = { family = "depth"; depth; samples = 1; adaptive = None; subsample = false } in
  let adaptive ?(depth = depth) n th = { one with family = "adaptive"; depth; samples = n; adaptive = Some th } in
  List.map (fun d -> { one with depth = d }) table_depths
  @ List.init 7 (fun i -> { one with family = "full"; samples = i + 2 })
  @ List.concat_map (fun n -> List.map (adaptive n) [ 2; 3; 4; 8; 32 ]) [ 3; 5; 7 ]
  @ (if depth >= 5 then []
     else
       [
         { one with family = "full"; depth = 5; samples = 4 };
         adaptive ~depth:5 5 2;
         adaptive ~depth:5 7 2;
       ])
  @ List.init 6 (fun d -> { one with family = "subsample"; depth = d; subsample = true })

type row = {
  scene : string;
  setting : setting;
  times : float list;  (** CPU seconds, sorted. *)
  wall : float;  (** Median wall-clock seconds. *)
  primary_pp : float;  (** Primary rays per pixel. *)
  rays_pp : float;  (** All rays per pixel. *)
  diff : Image.Diff.t;
  depth_diff : Image.Diff.t option;
      (** One ray per pixel: against one ray per pixel at [reference_depth]. *)
  mutable pareto : bool;
}

let median l =
  let a = Array.of_list (List.sort Float.compare l) in
  let n = Array.length a in
  if n mod 2 = 1 then a.(n / 2) else (a.((n / 2) - 1) +. a.(n / 2)) /. 2.

let time_of r = median r.times

let cpu () =
  let t = Unix.times () in
  t.tms_utime +. t.tms_stime

(* The image, its statistics, its CPU and wall-clock seconds. *)
let render (scene : Scene.t) s =
  let scene = Scene.with_overrides ~depth:s.depth scene in
  let c0 = cpu () and t0 = Unix.gettimeofday () in
  match Result.bind (Scene.validate scene) (Render.image ~samples:s.samples ?adaptive:s.adaptive ~subsample:s.subsample) with
  | Ok (img, stats) -> (img, stats, cpu () -. c0, Unix.gettimeofday () -. t0)
  | Error (`Msg m) -> failwith m

(* At least [runs] runs, more for fast settings (up to about half a second
   of them, at most 15): the median of few short runs is noisy. *)
let measure ~runs scene s =
  let img, stats, t, w = render scene s in
  let extra = if t > 0. then min 14 (max (runs - 1) (truncate (0.5 /. t))) else 14 in
  let more = List.init extra (fun _ -> let _, _, t, w = render scene s in (t, w)) in
  (img, stats, List.sort Float.compare (t :: List.map fst more), median (w :: List.map snd more))

(* A row is on the Pareto front if no other row of its scene is at least as
   fast and at least as accurate, and better in one of the two. *)
let mark_pareto rows =
  List.iter
    (fun r ->
      let dominated =
        List.exists
          (fun o ->
            o.scene = r.scene
            && time_of o <= time_of r
            && o.diff.mean_abs <= r.diff.mean_abs
            && (time_of o < time_of r || o.diff.mean_abs < r.diff.mean_abs))
          rows
      in
      r.pareto <- not dominated)
    rows

let psnr_text p = if p = Float.infinity then "inf" else Printf.sprintf "%.2f" p

let csv_header =
  "scene,setting,family,depth,samples,adaptive,subsample,cpu_s,cpu_min_s,cpu_max_s,wall_s,runs,primary_per_pixel,rays_per_pixel,mean_abs,max_abs,psnr_db,share_gt1,pareto,depth_mean_abs"

let csv_line r =
  let s = r.setting in
  Printf.sprintf "%s,%s,%s,%d,%d,%s,%b,%.6f,%.6f,%.6f,%.6f,%d,%.4f,%.4f,%.6f,%d,%s,%.6f,%b,%s" r.scene (label s) s.family
    s.depth s.samples
    (match s.adaptive with Some th -> string_of_int th | None -> "")
    s.subsample (time_of r) (List.hd r.times)
    (List.nth r.times (List.length r.times - 1))
    r.wall (List.length r.times) r.primary_pp r.rays_pp r.diff.mean_abs r.diff.max_abs (psnr_text r.diff.psnr)
    (Float.of_int r.diff.differing_gt1 /. Float.of_int r.diff.pixels)
    r.pareto
    (match r.depth_diff with Some d -> Printf.sprintf "%.6f" d.mean_abs | None -> "")

let write path f =
  match File_io.write_atomic path f with Ok () -> print_endline ("wrote " ^ path) | Error (`Msg m) -> failwith m

let families =
  [
    ("depth", "depth 0-6 and 8, 1 ray per pixel", "7", "#1f77b4");
    ("full", "full N x N, N = 2-8", "5", "#2ca02c");
    ("adaptive", "adaptive (a) N = 3,5,7; t = 2-32", "9", "#d62728");
    ("subsample", "subsampling (sub), depth 0-5", "13", "#9467bd");
  ]

(* The plot: one panel per scene, time against mean absolute error, both
   logarithmic, each family of settings in its own colour, the Pareto front
   as a line through its labelled points. The data is inlined in the
   script. *)
let gnuplot_script ~png ~runs scenes rows =
  let b = Buffer.create 65536 in
  let pr fmt = Printf.bprintf b fmt in
  let floor_err e = Float.max e 1e-3 in
  List.iteri
    (fun i (name, _, _, _) ->
      List.iter
        (fun (fam, _, _, _) ->
          pr "$d%d_%s << EOD\n" i fam;
          List.iter
            (fun r ->
              if r.scene = name && r.setting.family = fam then pr "%.6f %.6f\n" (time_of r) (floor_err r.diff.mean_abs))
            rows;
          pr "EOD\n")
        families;
      pr "$p%d << EOD\n" i;
      rows
      |> List.filter (fun r -> r.scene = name && r.pareto)
      |> List.sort (fun a b -> Float.compare (time_of a) (time_of b))
      |> List.iter (fun r -> pr "%.6f %.6f \"%s\"\n" (time_of r) (floor_err r.diff.mean_abs) (short r.setting));
      pr "EOD\n")
    scenes;
  (* Three panels a row. *)
  let rows = (List.length scenes + 2) / 3 in
  pr "set terminal pngcairo size 1800,%d font 'sans,11' background rgb 'white'\n" (560 * rows);
  pr "set output '%s'\n" png;
  pr "set multiplot layout %d,%d title" rows (min 3 (List.length scenes));
  pr " 'raytrace: run time against error (median CPU time of >= %d runs, 1 process; error against %dx%d samples, depth %d)'\n"
    runs reference_samples reference_samples reference_depth;
  pr "set logscale xy\nset grid\nset xlabel 'CPU time (s)'\nset ylabel 'mean absolute error (0-255 per channel)'\n";
  pr "set key top right font ',10'\n";
  List.iteri
    (fun i (name, _, w, h) ->
      pr "set title '%s (%dx%d)'\n" name w h;
      pr "plot ";
      List.iter
        (fun (fam, title, pt, color) ->
          pr "$d%d_%s using 1:2 with points pt %s ps 1.2 lc rgb '%s' title '%s', \\\n  " i fam pt color title)
        families;
      pr "$p%d using 1:2 with steps lw 1.5 lc rgb 'black' title 'Pareto front', \\\n  " i;
      pr "$p%d using 1:2 with points pt 6 ps 2 lc rgb 'black' notitle, \\\n  " i;
      pr "$p%d using 1:2:3 with labels left offset 0.8,0.6 rotate by 20 font ',8' notitle\n" i)
    scenes;
  pr "unset multiplot\n";
  Buffer.contents b

let find rows scene pred = List.find_opt (fun r -> r.scene = scene && pred r.setting) rows

let summary_line r =
  Printf.sprintf "| %s | `%s` | %.4f | %.2f | %.1f | %.3f | %d | %s | %.2f%% |%s" r.scene (label r.setting) (time_of r)
    r.primary_pp r.rays_pp r.diff.mean_abs r.diff.max_abs (psnr_text r.diff.psnr)
    (100. *. Float.of_int r.diff.differing_gt1 /. Float.of_int r.diff.pixels)
    (if r.pareto then " yes |" else " |")

let summary ~runs scenes rows =
  let b = Buffer.create 4096 in
  let pr fmt = Printf.bprintf b fmt in
  pr "<!-- Generated by bench/quality.ml (make bench-quality); do not edit. -->\n\n";
  pr "Median CPU time of `Render.image` in one process over >= %d runs (wall-clock in `quality.csv`); error against %dx%d samples at depth %d.\n\n"
    runs reference_samples reference_samples reference_depth;
  pr "| scene | setting | CPU time (s) | primary rays/px | rays/px | mean abs err | max err | PSNR (dB) | pixels off by > 1 | Pareto |\n";
  pr "|---|---|---|---|---|---|---|---|---|---|\n";
  let key s = (s.family = "depth" && s.depth = 3) || (s.family = "full" && s.samples = 4) in
  List.iter
    (fun (name, _, _, _) ->
      let scene_rows = List.filter (fun r -> r.scene = name) rows in
      List.iter (fun r -> if key r.setting || r.pareto then pr "%s\n" (summary_line r)) scene_rows)
    scenes;
  (* Depth alone: one ray per pixel at each depth against one ray per
     pixel at the reference depth. *)
  pr "\nError against depth: mean absolute error of one ray per pixel at each depth against one ray per pixel at depth %d (the error that the depth alone causes), and CPU time (s).\n\n"
    reference_depth;
  pr "| scene |%s\n|---|%s\n"
    (String.concat "" (List.map (fun d -> Printf.sprintf " depth %d |" d) table_depths))
    (String.concat "" (List.map (fun _ -> "---|") table_depths));
  List.iter
    (fun (name, _, _, _) ->
      pr "| %s |" name;
      List.iter
        (fun d ->
          match find rows name (fun s -> s.family = "depth" && s.depth = d) with
          | Some ({ depth_diff = Some dd; _ } as r) -> pr " %.3f (%.3f s) |" dd.mean_abs (time_of r)
          | _ -> pr " |")
        table_depths;
      pr "\n")
    scenes;
  (* The issue's criterion: adaptive sampling reaching the error of full
     4 x 4 sampling on the reference scene in at most half its time. *)
  (match find rows "cgfs" (fun s -> s.family = "full" && s.samples = 4) with
  | None -> ()
  | Some full4 ->
      let candidates =
        List.filter
          (fun r -> r.scene = "cgfs" && r.setting.family = "adaptive" && r.diff.mean_abs <= full4.diff.mean_abs)
          rows
        |> List.sort (fun a b -> Float.compare (time_of a) (time_of b))
      in
      pr "\nOn `cgfs`, full 4x4 sampling: %.4f s, mean abs error %.3f, PSNR %s dB.\n" (time_of full4)
        full4.diff.mean_abs (psnr_text full4.diff.psnr);
      match candidates with
      | [] -> pr "No adaptive setting reaches its error.\n"
      | best :: _ ->
          pr "The fastest adaptive setting at or below that error: `%s` (`%s`), %.4f s (%.0f%% of the time), mean abs error %.3f, PSNR %s dB.\n"
            (label best.setting) (options best.setting) (time_of best)
            (100. *. time_of best /. time_of full4)
            best.diff.mean_abs (psnr_text best.diff.psnr));
  Buffer.contents b

(* Writes the script [script ~png] to [path ".gp"] and runs gnuplot on it;
   the plot replaces [path ".png"] only once it is whole. *)
let plot ~path script =
  let png = path ".png" in
  let tmp = png ^ ".tmp" in
  write (path ".gp") (fun oc -> output_string oc (script ~png:tmp));
  match Sys.command (Printf.sprintf "gnuplot %s" (Filename.quote (path ".gp"))) with
  | 0 ->
      Sys.rename tmp png;
      print_endline ("wrote " ^ png)
  | n ->
      prerr_endline (Printf.sprintf "quality: gnuplot failed (status %d); is gnuplot-nox installed?" n);
      exit 1

(* {1 Soft shadows and depth of field (--soft)}

   The integrals of issue 27: an area light's soft shadows and a thin
   lens's blur, each a ladder of sample counts per variant, timed as
   above and compared with a reference of 64 times the samples of the
   ladder's top rung. Writes docs/soft.{csv,md,gp,png}. *)

(* Soft shadows: the area light's [(samples n n)] for each [n] here,
   drawn [(sampling uniform)], stratified (the default) or stratified and
   [(adaptive true)] (corners first, the samples only in the penumbra);
   the reference is stratified at 64 x 64, 64 times the 8 x 8 top. The
   scene's other lights are kept: their samples are keyed by the pixel
   alone (one camera sample), the same in every render, so they add no
   error. *)
let soft_sides = [ 1; 2; 3; 4; 5; 6; 8 ]
let soft_reference_side = 64

(* Depth of field: the pixel's N x N grid, one lens point per camera
   sample, drawn independently over the lens disc ([(lens-sampling
   uniform)]: "uniform") or stratified (the default: "stratified"), for
   N = 1-6; and stratified under [--adaptive T] for N = 3-7 and 9 (an
   even N only under a lens: its refined pixels trace the whole grid),
   which refines to the full grid the pixels that differ from a
   neighbour, and those that lie in a first ray's circle of confusion
   where a probe from the lens's rim sees another object or colour. The
   reference: stratified 48 x 48, 64 times the 6 x 6 top. *)
let lens_sides = [ 1; 2; 3; 4; 5; 6 ]

let lens_adaptive =
  [ (3, 8); (3, 2); (4, 8); (4, 2); (5, 8); (5, 2); (6, 8); (6, 2); (7, 8); (7, 2); (9, 8); (9, 2) ]
let lens_reference_side = 48

(* A ball over a floor under a 2 x 2 panel (the soft-light tests'
   scene, larger): most of the floor in view is penumbra. *)
let ball_scene =
  {|(canvas (width 160) (height 120))
(camera (position 0 2 -3) (look-at 0 0 2))
(plane (point 0 -1 0) (normal 0 1 0) (color 200 200 200) (specular 20))
(sphere (center 0 0 2) (radius 0.7) (color 255 80 80) (specular 300))
(box (min 0.9 -1 2.5) (max 1.5 -0.2 3.1) (color 80 80 255))
(light ambient (intensity 0.1))
(light area (intensity 0.8) (corner -1 3 1) (edge1 2 0 0) (edge2 0 0 2) (samples 4 4))|}

(* Name, scene, canvas, kind. *)
let soft_scenes =
  [
    ("area-room", `File "scenes/area-room.scene", (160, 120), `Shadow);
    ("ball", `Text ball_scene, (160, 120), `Shadow);
    ("focus", `File "scenes/focus.scene", (160, 90), `Lens);
  ]

type soft_row = {
  s_scene : string;
  variant : string;  (** uniform, stratified, adaptive *)
  side : int;  (** Area light samples per side, or the pixel grid's N. *)
  threshold : int option;  (** [--adaptive T] of the lens runs. *)
  s_times : float list;
  s_wall : float;
  shadow_pp : float;
  primary_pp : float;
  s_diff : Image.Diff.t;
}

let soft_label r =
  match r.threshold with
  | Some t -> Printf.sprintf "a%d t%d" r.side t
  | None -> Printf.sprintf "%dx%d" r.side r.side

(* The scene with its area lights at [n x n] samples, drawn as
   [variant] says. *)
let with_area scene variant n =
  let lights =
    List.map
      (fun (l : Light.t) ->
        match l with
        | Area { intensity; corner; edge1; edge2; _ } ->
            Light.area ~adaptive:(variant = "adaptive")
              ~sampling:(if variant = "uniform" then Light.Uniform else Light.Stratified)
              intensity ~corner ~edge1 ~edge2 ~samples:(n, n)
        | l -> l)
      (Scene.lights scene)
  in
  Scene.with_overrides ~lights scene

(* The scene with its lens sampled as [variant] says. *)
let with_lens scene variant =
  let c = Scene.camera scene in
  let lens_sampling = if variant = "uniform" then Camera.Uniform else Camera.Stratified in
  let camera =
    Camera.v ~rotation:c.rotation ~aperture:c.aperture ~focal_distance:c.focal_distance ~lens_sampling c.position
  in
  Scene.with_overrides ~camera scene

let soft_load source (w, h) =
  let valid =
    match source with `File path -> Files.read_scene path | `Text text -> Scene_file.of_string ~file:"ball" text
  in
  match Result.map Scene.of_valid valid with
  | Ok s -> Scene.with_overrides ~width:w ~height:h s
  | Error (`Msg m) -> failwith m

(* Every rung of one scene, against its reference. *)
let soft_rows ~runs (name, source, size, kind) =
  let scene = soft_load source size in
  let setting samples adaptive = { family = "soft"; depth = Scene.depth scene; samples; adaptive; subsample = false } in
  let reference_scene, reference_setting =
    match kind with
    | `Shadow -> (with_area scene "stratified" soft_reference_side, setting 1 None)
    | `Lens -> (with_lens scene "stratified", setting lens_reference_side None)
  in
  Printf.printf "%s (%dx%d): reference...%!" name (fst size) (snd size);
  let reference, _, t, _ = render reference_scene reference_setting in
  Printf.printf " %.1f s\n%!" t;
  let rung variant side threshold scene s =
    let img, (stats : Render.Stats.t), times, wall = measure ~runs scene s in
    let diff = match Image.Diff.compare reference img with Ok d -> d | Error (`Msg m) -> failwith m in
    let px = Float.of_int stats.pixels in
    let r =
      {
        s_scene = name;
        variant;
        side;
        threshold;
        s_times = times;
        s_wall = wall;
        shadow_pp = Float.of_int stats.shadow /. px;
        primary_pp = Float.of_int stats.primary /. px;
        s_diff = diff;
      }
    in
    Printf.printf "  %-10s %-8s %8.4f s  %7.1f shadow/px  mean %.4f  max %3d\n%!" variant (soft_label r) (median times)
      r.shadow_pp diff.mean_abs diff.max_abs;
    r
  in
  match kind with
  | `Shadow ->
      List.concat_map
        (fun variant -> List.map (fun n -> rung variant n None (with_area scene variant n) (setting 1 None)) soft_sides)
        [ "uniform"; "stratified"; "adaptive" ]
  | `Lens ->
      List.concat_map
        (fun variant -> List.map (fun n -> rung variant n None (with_lens scene variant) (setting n None)) lens_sides)
        [ "uniform"; "stratified" ]
      @ List.map
          (fun (n, t) -> rung "adaptive" n (Some t) (with_lens scene "stratified") (setting n (Some t)))
          lens_adaptive

let soft_time r = median r.s_times

(* The claim: for each uniform rung, the fastest adaptive rung of the
   same scene at or below its error, and the share of its time. *)
let soft_claim rows =
  List.filter_map
    (fun u ->
      if u.variant <> "uniform" then None
      else
        let best =
          List.filter (fun a -> a.s_scene = u.s_scene && a.variant = "adaptive" && a.s_diff.mean_abs <= u.s_diff.mean_abs) rows
          |> List.sort (fun a b -> Float.compare (soft_time a) (soft_time b))
        in
        Some (u, match best with [] -> None | a :: _ -> Some a))
    rows

(* The time at which the adaptive rungs reach error [e]: on their front
   (each rung more accurate than every faster one), interpolated
   linearly in log time against log error between the two rungs around
   [e]; the first rung's own time if it is already below; [None] if no
   rung reaches it. The ladder's rungs are coarse (from 3 x 3 to 4 x 4 the
   samples almost double): this is the time a rung in between would
   take, if time and error vary smoothly. *)
let interpolated_time rows scene e =
  let front =
    rows
    |> List.filter (fun a -> a.s_scene = scene && a.variant = "adaptive")
    |> List.sort (fun a b -> Float.compare (soft_time a) (soft_time b))
    |> List.fold_left
         (fun acc a -> match acc with b :: _ when b.s_diff.mean_abs <= a.s_diff.mean_abs -> acc | _ -> a :: acc)
         []
    |> List.rev
  in
  let rec go = function
    | a :: _ when a.s_diff.mean_abs <= e -> Some (soft_time a)
    | a :: (b :: _ as rest) ->
        if b.s_diff.mean_abs <= e then
          let la = log a.s_diff.mean_abs and lb = log b.s_diff.mean_abs in
          let f = (log e -. la) /. (lb -. la) in
          Some (exp (log (soft_time a) +. (f *. (log (soft_time b) -. log (soft_time a)))))
        else go rest
    | _ -> None
  in
  go front

let soft_variants =
  [ ("uniform", "uniform", "7", "#1f77b4"); ("stratified", "stratified", "5", "#2ca02c"); ("adaptive", "adaptive", "9", "#d62728") ]

let soft_gnuplot ~png ~runs scenes rows =
  let b = Buffer.create 16384 in
  let pr fmt = Printf.bprintf b fmt in
  List.iteri
    (fun i (name, _, _, _) ->
      List.iter
        (fun (v, _, _, _) ->
          pr "$d%d_%s << EOD\n" i v;
          rows
          |> List.filter (fun r -> r.s_scene = name && r.variant = v)
          |> List.sort (fun a b -> Float.compare (soft_time a) (soft_time b))
          |> List.iter (fun r -> pr "%.6f %.6f \"%s\"\n" (soft_time r) (Float.max r.s_diff.mean_abs 1e-3) (soft_label r));
          pr "EOD\n")
        soft_variants)
    scenes;
  pr "set terminal pngcairo size 1800,600 font 'sans,11' background rgb 'white'\n";
  pr "set output '%s'\n" png;
  pr "set multiplot layout 1,%d title" (List.length scenes);
  pr " 'raytrace: soft shadows and depth of field, run time against error (median CPU time of >= %d runs; error against 64x the top rung''s samples)'\n" runs;
  pr "set logscale xy\nset grid\nset xlabel 'CPU time (s)'\nset ylabel 'mean absolute error (0-255 per channel)'\n";
  pr "set key top right font ',10'\n";
  List.iteri
    (fun i (name, _, (w, h), kind) ->
      pr "set title '%s (%dx%d, %s)'\n" name w h
        (match kind with `Shadow -> "area light n x n samples" | `Lens -> "N x N pixel grid, a lens point each; aN tT: --adaptive");
      pr "plot ";
      let parts =
        List.filter_map
          (fun (v, title, pt, color) ->
            if List.exists (fun r -> r.s_scene = name && r.variant = v) rows then
              Some
                (Printf.sprintf
                   "$d%d_%s using 1:2 with linespoints pt %s ps 1.3 lc rgb '%s' title '%s', $d%d_%s using 1:2:3 with labels left offset 0.6,0.5 font ',8' tc rgb '%s' notitle"
                   i v pt color title i v color)
            else None)
          soft_variants
      in
      pr "%s\n" (String.concat ", \\\n  " parts))
    scenes;
  pr "unset multiplot\n";
  Buffer.contents b

let soft_csv rows oc =
  output_string oc
    "scene,variant,samples_side,adaptive_threshold,cpu_s,cpu_min_s,cpu_max_s,wall_s,runs,primary_per_pixel,shadow_per_pixel,mean_abs,max_abs,psnr_db,share_gt1\n";
  List.iter
    (fun r ->
      Printf.fprintf oc "%s,%s,%d,%s,%.6f,%.6f,%.6f,%.6f,%d,%.4f,%.4f,%.6f,%d,%s,%.6f\n" r.s_scene r.variant r.side
        (match r.threshold with Some t -> string_of_int t | None -> "")
        (soft_time r) (List.hd r.s_times)
        (List.nth r.s_times (List.length r.s_times - 1))
        r.s_wall (List.length r.s_times) r.primary_pp r.shadow_pp r.s_diff.mean_abs r.s_diff.max_abs
        (psnr_text r.s_diff.psnr)
        (Float.of_int r.s_diff.differing_gt1 /. Float.of_int r.s_diff.pixels))
    rows

let soft_summary ~runs rows =
  let b = Buffer.create 8192 in
  let pr fmt = Printf.bprintf b fmt in
  pr "<!-- Generated by bench/quality.ml --soft (make bench-soft); do not edit. -->\n\n";
  pr "Median CPU time of `Render.image` in one process over >= %d runs (wall-clock in `soft.csv`); error against %d x %d area light samples (soft shadows) or %d x %d pixel samples (depth of field).\n\n"
    runs soft_reference_side soft_reference_side lens_reference_side lens_reference_side;
  pr "| scene | variant | samples | CPU time (s) | primary rays/px | shadow rays/px | mean abs err | max err | PSNR (dB) | pixels off by > 1 |\n";
  pr "|---|---|---|---|---|---|---|---|---|---|\n";
  List.iter
    (fun r ->
      pr "| %s | %s | %s | %.4f | %.2f | %.1f | %.3f | %d | %s | %.2f%% |\n" r.s_scene r.variant (soft_label r) (soft_time r)
        r.primary_pp r.shadow_pp r.s_diff.mean_abs r.s_diff.max_abs (psnr_text r.s_diff.psnr)
        (100. *. Float.of_int r.s_diff.differing_gt1 /. Float.of_int r.s_diff.pixels))
    rows;
  pr "\nThe claim, per uniform rung: the fastest adaptive rung at or below its mean error and its share of the uniform rung's time; then the time at which the adaptive rungs reach that error, interpolated between the two around it (log time against log error), and its share. Met: at most 50%%.\n\n";
  pr "| scene | uniform | its time (s) | its error | fastest adaptive at or below | its time (s) | its error | share of time | interpolated time (s) | share | met |\n";
  pr "|---|---|---|---|---|---|---|---|---|---|---|\n";
  List.iter
    (fun (u, a) ->
      let interpolated =
        match interpolated_time rows u.s_scene u.s_diff.mean_abs with
        | None -> ("", "", "no")
        | Some t ->
            let share = t /. soft_time u in
            (Printf.sprintf "%.4f" t, Printf.sprintf "%.0f%%" (100. *. share), if share <= 0.5 then "yes" else "no")
      in
      let it, is, met = interpolated in
      match a with
      | None -> pr "| %s | %s | %.4f | %.3f | none | | | | %s | %s | %s |\n" u.s_scene (soft_label u) (soft_time u) u.s_diff.mean_abs it is met
      | Some a ->
          pr "| %s | %s | %.4f | %.3f | %s | %.4f | %.3f | %.0f%% | %s | %s | %s |\n" u.s_scene (soft_label u) (soft_time u)
            u.s_diff.mean_abs (soft_label a) (soft_time a) a.s_diff.mean_abs
            (100. *. soft_time a /. soft_time u)
            it is met)
    (soft_claim rows);
  Buffer.contents b

let soft_main ~out ~runs ~only =
  let scenes = List.filter (fun (n, _, _, _) -> only = [] || List.mem n only) soft_scenes in
  let rows = List.concat_map (soft_rows ~runs) scenes in
  let path ext = Filename.concat out ("soft" ^ ext) in
  write (path ".csv") (soft_csv rows);
  write (path ".md") (fun oc -> output_string oc (soft_summary ~runs rows));
  plot ~path (soft_gnuplot ~runs scenes rows)

(* {1 A sphere light's samples (--sphere-light)}

   A ball and a box under a sphere light alone: the error of [n] samples
   against [64 n] (4096 at most, the most a light takes), the same
   sampler, one camera ray a pixel. Printed, not written: the numbers are
   quoted in docs/run-time-against-error.md. *)
let sphere_light_scene =
  {|(canvas (width 160) (height 120))
(viewport (width 1.3333333333333333) (height 1) (distance 1))
(camera (position 0 2.2 -1.5) (look-at 0 0 4))
(plane (point 0 -1 0) (normal 0 1 0) (color 220 220 220))
(sphere (center -0.8 -0.3 4) (radius 0.6) (color 200 80 60))
(box (min 0.5 -1 3.4) (max 1.4 0.2 4.3) (color 60 120 200))
(light ambient (intensity 0.15))
(light sphere (intensity 0.85) (position 0.2 1.6 3.6) (radius 0.6) (samples 1))|}

let with_sphere_samples scene n =
  let lights =
    List.map
      (fun (l : Light.t) ->
        match l with Sphere { intensity; position; radius; _ } -> Light.sphere intensity ~position ~radius ~samples:n | l -> l)
      (Scene.lights scene)
  in
  Scene.with_overrides ~lights scene

let sphere_light_main ~runs =
  let scene = soft_load (`Text sphere_light_scene) (160, 120) in
  let setting = { family = "soft"; depth = Scene.depth scene; samples = 1; adaptive = None; subsample = false } in
  Printf.printf "%4s %6s %10s %10s %8s %5s %8s\n" "n" "ref" "time s" "shadow/px" "mean" "max" "rmse";
  List.iter
    (fun n ->
      let r = min Light.max_samples (64 * n) in
      let reference, _, _, _ = render (with_sphere_samples scene r) setting in
      let img, (stats : Render.Stats.t), times, _ = measure ~runs (with_sphere_samples scene n) setting in
      let d = match Image.Diff.compare reference img with Ok d -> d | Error (`Msg m) -> failwith m in
      (* PSNR = 20 log10 (255 / rmse). *)
      let rmse = 255. /. (10. ** (d.psnr /. 20.)) in
      Printf.printf "%4d %6d %10.4f %10.1f %8.4f %5d %8.4f\n%!" n r (median times)
        (Float.of_int stats.shadow /. Float.of_int stats.pixels)
        d.mean_abs d.max_abs rmse)
    [ 4; 9; 16; 36; 64 ]

let () =
  let out = ref "docs" and name = ref "quality" and runs = ref 5 and only = ref [] and half = ref false
  and soft = ref false and sphere_light = ref false in
  Arg.parse
    [
      ("--out", Arg.Set_string out, "DIR  where to write quality.csv, quality.png, quality.md (default docs)");
      ("--name", Arg.Set_string name, "NAME  the files' name: NAME.csv, NAME.png, NAME.md, NAME.gp (default quality)");
      ("--runs", Arg.Set_int runs, "R  at least R timed runs per setting (default 5)");
      ("--scene", Arg.String (fun s -> only := s :: !only), "NAME  only this scene (repeatable)");
      ("--half", Arg.Set half, " at half the scene files' canvas sizes (4 times quicker)");
      ("--soft", Arg.Set soft, " soft shadows and depth of field instead: writes soft.{csv,png,md,gp}");
      ("--sphere-light", Arg.Set sphere_light, " a sphere light's error against 64 times its samples, printed");
    ]
    (fun a -> raise (Arg.Bad ("unexpected argument " ^ a)))
    "quality [--out DIR] [--name NAME] [--runs R] [--scene NAME] [--half] [--soft] [--sphere-light]: run time against error";
  if !sphere_light then begin
    sphere_light_main ~runs:!runs;
    exit 0
  end;
  if !soft then begin
    soft_main ~out:!out ~runs:!runs ~only:!only;
    exit 0
  end;
  let selected =
    List.filter_map
      (fun (n, path) ->
        if !only <> [] && not (List.mem n !only) then None
        else
          match Result.map Scene.of_valid (Files.read_scene path) with
          | Ok s -> Some (n, path, (if !half then (Scene.width s) / 2 else (Scene.width s)), if !half then (Scene.height s) / 2 else (Scene.height s))
          | Error (`Msg m) -> failwith m)
      scenes
  in
  let rows =
    List.concat_map
      (fun (name, path, w, h) ->
        let scene =
          match Result.map Scene.of_valid (Files.read_scene path) with
          | Ok s -> Scene.with_overrides ~width:w ~height:h s
          | Error (`Msg m) -> failwith m
        in
        Printf.printf "%s (%dx%d): reference %dx%d depth %d...%!" name w h reference_samples reference_samples
          reference_depth;
        let reference, _, t, _ =
          render scene { family = "ref"; depth = reference_depth; samples = reference_samples; adaptive = None; subsample = false }
        in
        Printf.printf " %.1f s\n%!" t;
        let depth_reference, _, _, _ =
          render scene { family = "ref"; depth = reference_depth; samples = 1; adaptive = None; subsample = false }
        in
        List.map
          (fun s ->
            let img, (stats : Render.Stats.t), times, wall = measure ~runs:!runs scene s in
            let compare a = match Image.Diff.compare a img with Ok d -> d | Error (`Msg m) -> failwith m in
            let diff = compare reference in
            let depth_diff = if s.family = "depth" then Some (compare depth_reference) else None in
            let px = Float.of_int stats.pixels in
            let r =
              {
                scene = name;
                setting = s;
                times;
                wall;
                primary_pp = Float.of_int stats.primary /. px;
                rays_pp = Float.of_int (Render.Stats.rays stats) /. px;
                diff;
                depth_diff;
                pareto = false;
              }
            in
            Printf.printf "  %-24s %8.4f s  %6.2f rays/px  mean %.4f  max %3d  psnr %s\n%!" (label s) (time_of r)
              r.rays_pp diff.mean_abs diff.max_abs (psnr_text diff.psnr);
            r)
          (settings ~depth:(Scene.depth scene)))
      selected
  in
  mark_pareto rows;
  let path ext = Filename.concat !out (!name ^ ext) in
  write (path ".csv") (fun oc ->
      output_string oc (csv_header ^ "\n");
      List.iter (fun r -> output_string oc (csv_line r ^ "\n")) rows);
  write (path ".md") (fun oc -> output_string oc (summary ~runs:!runs selected rows));
  plot ~path (gnuplot_script ~runs:!runs selected rows)
