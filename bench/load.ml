(* Where the time of loading a big scene goes, in CPU seconds (steady on a
   shared machine, unlike wall time): reading and converting the file
   (Files.read_scene, a window of text at a time, as the render command
   does), preparing it for the tracer (Prepared), then the peak resident
   memory.

   dune build --profile release bench/load.exe
   ./_build/default/bench/load.exe SCENE [REPEATS] [--sizes] [--jobs N]

   --sizes also prints the bytes the scene and the prepared scene hold;
   --jobs 2 reads the scene on two cores (Files.read_scene ~jobs) and
   builds a part of the hierarchy in a child process, as the render
   command does with two jobs or more, where a core is idle when it
   would fork (Parallel.idle_core). *)


let or_exit = function Ok x -> x | Error (`Msg m) -> prerr_endline m; exit 1

let () =
  let sizes = Array.mem "--sizes" Sys.argv in
  let rec options jobs = function
    | "--sizes" :: rest -> options jobs rest
    | "--jobs" :: j :: rest -> options (int_of_string j) rest
    | a :: rest -> let j, l = options jobs rest in (j, a :: l)
    | [] -> (jobs, [])
  in
  let jobs, args = options 1 (List.tl (Array.to_list Sys.argv)) in
  let beside = if jobs > 1 then Some (Render_jobs.bvh_beside ()) else None in
  let file, repeats =
    match args with
    | [ f ] -> (f, 1)
    | [ f; r ] -> (f, int_of_string r)
    | _ -> prerr_endline "usage: load SCENE [REPEATS] [--sizes] [--jobs N]"; exit 2
  in
  let limits = or_exit (Limits_env.read ()) in
  for _ = 1 to repeats do
    let t0 = Sys.time () and wall = Unix.gettimeofday () in
    let scene = or_exit (Files.read_scene ~limits ~jobs file) in
    let t2 = Sys.time () and w2 = Unix.gettimeofday () in
    (* With --jobs 2 a child reads half the file: its CPU time is not this
       process's, the wall time shows the gain. *)
    Printf.printf "load wall %.3f s (%d jobs)\n" (Unix.gettimeofday () -. wall) jobs;
    let mb x = Float.of_int (Obj.reachable_words (Obj.repr x) * (Sys.word_size / 8)) /. 1048576. in
    (* Measured before: the scene not held past [prepare], as the
       renderers hold it (a flat mesh's normals go with it). *)
    let scene_mb = if sizes then mb scene else 0. in
    let p = Prepared.prepare ?beside scene in
    let t3 = Sys.time () and w3 = Unix.gettimeofday () in
    if sizes then
      Printf.printf "scene %.1f MB, prepared %.1f MB (what it shares with the scene included)\n" scene_mb (mb p);
    let nodes, depth = match p.bvh with Some b -> (b.n_nodes, b.depth) | None -> (0, 0) in
    (* With a child process, this one's CPU time is not the wall's. *)
    Printf.printf "%s: %d objects, %d nodes of depth %d; cpu s: load %.3f, prepare %.3f (wall %.3f), total %.3f\n%!"
      file p.n_scene_objects nodes depth (t2 -. t0) (t3 -. t2) (w3 -. w2) (t3 -. t0)
  done;
  Printf.printf "peak RSS %.1f MB\n" (Peak_rss.mb ())
