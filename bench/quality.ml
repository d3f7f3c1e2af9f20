(* Run time against error: every speed/quality setting of the renderer on a
   set of scenes, timed, and compared with a high-quality reference render
   of the same scene. Writes a CSV, a gnuplot PNG plot with the Pareto
   front of each scene marked, and a Markdown summary.

   Run from the repository root, built in release mode (the dev profile
   stops cross-module inlining):

     make bench-quality

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

let () =
  let out = ref "docs" and name = ref "quality" and runs = ref 5 and only = ref [] and half = ref false in
  Arg.parse
    [
      ("--out", Arg.Set_string out, "DIR  where to write quality.csv, quality.png, quality.md (default docs)");
      ("--name", Arg.Set_string name, "NAME  the files' name: NAME.csv, NAME.png, NAME.md, NAME.gp (default quality)");
      ("--runs", Arg.Set_int runs, "R  at least R timed runs per setting (default 5)");
      ("--scene", Arg.String (fun s -> only := s :: !only), "NAME  only this scene (repeatable)");
      ("--half", Arg.Set half, " at half the scene files' canvas sizes (4 times quicker)");
    ]
    (fun a -> raise (Arg.Bad ("unexpected argument " ^ a)))
    "quality [--out DIR] [--name NAME] [--runs R] [--scene NAME] [--half]: run time against error";
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
  let png = path ".png" in
  let tmp = png ^ ".tmp" in
  write (path ".gp") (fun oc -> output_string oc (gnuplot_script ~png:tmp ~runs:!runs selected rows));
  match Sys.command (Printf.sprintf "gnuplot %s" (Filename.quote (path ".gp"))) with
  | 0 ->
      Sys.rename tmp png;
      print_endline ("wrote " ^ png)
  | n ->
      prerr_endline (Printf.sprintf "quality: gnuplot failed (status %d); is gnuplot-nox installed?" n);
      exit 1
