open Raytrace

let exit_ok = 0
let exit_input = 1
let exit_no_display = 3

type scene_options = {
  scene : string option;
  width : int option;
  height : int option;
  depth : int option;
}

type sampling_options = { samples : int option; adaptive : int option; subsample : bool }

let ( let* ) = Result.bind
let msg fmt = Printf.ksprintf (fun m -> Error (`Msg m)) fmt

(* A line on stderr. A closed or full stderr loses it, as it would lose
   any message: the exit status still tells. *)
let say line =
  (* A name with a newline in it (a file name, an argument) must not make
     two lines of one: control characters are written escaped. *)
  let b = Buffer.create (String.length line + 16) in
  String.iter
    (fun c ->
      match c with
      | '\n' -> Buffer.add_string b "\\n"
      | '\r' -> Buffer.add_string b "\\r"
      | '\t' -> Buffer.add_string b "\\t"
      | c when Char.code c < 0x20 || Char.code c = 0x7f -> Printf.bprintf b "\\x%02x" (Char.code c)
      | c -> Buffer.add_char b c)
    line;
  try
    prerr_string ("raytrace: " ^ Buffer.contents b ^ "\n");
    flush stderr
  with Sys_error _ -> ()

(* A reader gone from a pipeline (`raytrace render -o - | head -c 10`)
   is no error: the process ends as Unix tools do there, killed by
   SIGPIPE (status 141 in the shell), quietly. By the signal, not by
   status 0: the output was not all delivered, which a script with
   [set -o pipefail] may want to know. SIGPIPE itself is ignored (see
   bin/main.ml), so that the write fails and this runs: nothing is left
   to clean up by then. *)
let broken_pipe = Unix.error_message Unix.EPIPE

let is_broken_pipe m =
  let n = String.length m and k = String.length broken_pipe in
  n >= k && String.sub m (n - k) k = broken_pipe && (n = k || (n >= k + 2 && String.sub m (n - k - 2) 2 = ": "))

let end_as_reader_gone () =
  (try flush stderr with Sys_error _ -> ());
  Sys.set_signal Sys.sigpipe Sys.Signal_default;
  Unix.kill (Unix.getpid ()) Sys.sigpipe;
  (* Where SIGPIPE is blocked: the status a shell shows for it. *)
  Unix._exit 141

(* The one place where an error becomes a message and an exit status. *)
let report = function
  | Ok code -> code
  | Error (`Msg m) when is_broken_pipe m -> end_as_reader_gone ()
  | Error (`Msg m) ->
      say m;
      exit_input

(* The one scene validation of a command: a file's, or the built-in
   scene's. Overrides come from the command line: checked like a file's
   values, and only they. *)
let load_with_inputs ~limits ~jobs opts =
  let* scene, inputs =
    match opts.scene with
    | None ->
        let* s = Scene.validate ~limits Scene.cgfs in
        Ok (s, [])
    | Some path ->
        let* l = Files.load_scene ~limits ~jobs ~read_texture:(Image_file.read_texture ~limits) path in
        Ok (l.scene, l.inputs)
  in
  let* scene = Scene.override ~limits ?width:opts.width ?height:opts.height ?depth:opts.depth scene in
  Ok (scene, inputs)

let load ~limits ~jobs opts = Result.map fst (load_with_inputs ~limits ~jobs opts)

let scene_name opts =
  match opts.scene with None -> "cgfs (built-in)" | Some p -> Filename.basename p

(* --jobs, or all cores; checked like any other input. *)
let jobs_or_cores = function
  | None -> Ok (Parallel.cores ())
  | Some j -> Limits.check_jobs j

let sampling_of (o : sampling_options) =
  Render.Sampling.v ?samples:o.samples ?adaptive:o.adaptive ~subsample:o.subsample ()

(* The meter's hook into the renderer; none when there is nothing to
   show, so that a render without a terminal does no more than before. *)
let progress meter = match meter with None -> None | Some m -> Some (Meter.update m)

(* RAYTRACE_SPLIT=always: the workers of --jobs N are forked whatever the
   image and the host (the tests, which exercise them on small images and
   loaded machines); anything else, or nothing, lets the render judge
   ({!Render_jobs.split_work}). *)
let split = match Sys.getenv_opt "RAYTRACE_SPLIT" with Some "always" -> `Always | _ -> `Auto

(* The image, its statistics (none for the oracle) and its tracing time. *)
let render_image ?rows_done ~limits ~sampling ~literal ~jobs ~meter valid =
  let scene = Scene.of_valid valid in
  if literal then
    if not (Render.Sampling.is_one sampling) then
      msg "--literal traces one ray per pixel: it cannot be combined with --samples or --subsample"
    else
      (* Render.image checks these itself; the oracle does not. *)
      let* () = Scene.check_work ~limits valid in
      let t0 = Unix.gettimeofday () in
      match Private.Literal.render ~limits valid with
      | exception Out_of_memory -> msg "not enough memory for a %dx%d image" (Scene.width scene) (Scene.height scene)
      | exception Limits.Work_exceeded n -> Error (`Msg (Limits.work_exceeded limits n))
      | img -> Ok (img, None, Unix.gettimeofday () -. t0)
  else
    let* img, stats =
      Render_jobs.image ~limits ~jobs ~split ~samples:sampling.samples ?adaptive:sampling.adaptive
        ~subsample:sampling.subsample ?progress:(progress meter) ?rows_done valid
    in
    Ok (img, Some stats, stats.trace_s)

let view opts ~jobs =
  report
    (let* limits = Limits_env.read () in
     let* jobs = jobs_or_cores jobs in
     let* scene = load ~limits ~jobs opts in
     (* As [render] does: a frame that cannot finish is refused before the
        window opens. *)
     let* () = Scene.check_work ~limits scene in
     match Window.run ~limits ~name:(scene_name opts) ~scene_file:opts.scene ~jobs scene with
     | Ok () -> Ok exit_ok
     | Error (`Msg _ as e) -> Error e
     | Error (`No_display reason) ->
         say
           (Printf.sprintf
              "cannot open a window (%s); to render without a display, use: raytrace render%s -o out.ppm"
              reason
              (match opts.scene with Some p -> " " ^ Filename.quote p | None -> ""));
         Ok exit_no_display)

let default_output opts =
  match opts.scene with
  | None -> "cgfs.ppm"
  | Some p -> Filename.remove_extension (Filename.basename p) ^ ".ppm"

(* A full disk, a closed stdout or a reader gone (SIGPIPE is ignored, see
   bin/main.ml) is one line. *)
let to_stdout data =
  match
    set_binary_mode_out stdout true;
    print_string data;
    flush stdout
  with
  | () -> Ok ()
  | exception Sys_error e -> msg "standard output: %s" e

(* PPM to stdout; a file in the format its name says. *)
let write output img =
  if output = "-" then to_stdout (Image.Ppm.to_string img) else Image_file.write_file output img

type part_spec = Tile of int * int | Corners of int * int * int * int

(* The rectangle to render, [None] for the whole image. *)
let part_region (scene : Scene.t) = function
  | None -> Ok None
  | Some (Tile (index, count)) ->
      Result.map Option.some (Render.Region.tile ~width:(Scene.width scene) ~height:(Scene.height scene) ~index ~count)
  | Some (Corners (x0, y0, x1, y1)) ->
      Result.map Option.some (Render.Region.of_corners ~width:(Scene.width scene) ~height:(Scene.height scene) x0 y0 x1 y1)

let parse_frames s =
  let frame t =
    if t <> "" && String.length t <= 9 && String.for_all (fun c -> c >= '0' && c <= '9') t then
      Some (int_of_string t)
    else None
  in
  match List.map frame (String.split_on_char ':' s) with
  | [ Some a ] -> Ok (a, a)
  | [ Some a; Some b ] when a <= b -> Ok (a, b)
  | [ Some a; Some b ] -> msg "frames %s: the first frame %d comes after the last %d" s a b
  | _ -> msg "frames %S: expected A:B (frames A to B, both included) or A, e.g. 0:47" s

(* The frame number in an output path: the first %d or %0Nd, as printf
   would write it. [None] when there is none. *)
let frame_placeholder path =
  let n = String.length path in
  let rec from i =
    match String.index_from_opt path i '%' with
    | None -> None
    | Some p ->
        let j = ref (p + 1) in
        while !j < n && path.[!j] >= '0' && path.[!j] <= '9' do incr j done;
        let digits = String.sub path (p + 1) (!j - p - 1) in
        if !j < n && path.[!j] = 'd' && (digits = "" || (digits.[0] = '0' && String.length digits <= 3)) then
          Some (p, !j + 1, if digits = "" then 0 else int_of_string digits)
        else from (p + 1)
  in
  from 0

let frame_path path f =
  match frame_placeholder path with
  | None -> path
  | Some (start, stop, width) ->
      String.sub path 0 start ^ Printf.sprintf "%0*d" width f ^ String.sub path stop (String.length path - stop)

let default_render_output opts ~frames ~spec =
  let base = Filename.remove_extension (default_output opts) in
  let frame = match frames with Some _ -> "-%04d" | None -> "" in
  let part =
    match spec with
    | None -> ""
    | Some (Tile (i, n)) -> Printf.sprintf "-tile-%d-of-%d" i n
    | Some (Corners (x0, y0, x1, y1)) -> Printf.sprintf "-region-%d-%d-%d-%d" x0 y0 x1 y1
  in
  base ^ frame ^ part ^ ".ppm"

let scene_input opts = match opts.scene with Some p -> [ ("scene", p) ] | None -> []

(* The output plan ({!Io_plan}): no output is an input or another output.
   Frames without a number in their name collide, unless they go to a
   stream. *)
(* RAYTRACE_PROGRESS_AFTER: the seconds of work before the progress line
   appears (default 1); the tests set 0, so that they need no long render.
   Read once, when a line is made. *)
let progress_after =
  match Option.map float_of_string_opt (Sys.getenv_opt "RAYTRACE_PROGRESS_AFTER") with
  | Some (Some s) when Float.is_finite s && s >= 0. -> Some s
  | _ -> None

let outputs ~frames output =
  match frames with
  | None -> [ ("output", output) ]
  | Some (a, b) -> List.init (b - a + 1) (fun i -> (Printf.sprintf "frame %d" (a + i), frame_path output (a + i)))

let check_output opts ~frames ~part output =
  (* No camera path has frames outside [0, Camera.Path.max_frame]: a range
     beyond it is refused before its list of outputs is made. *)
  let* () =
    match frames with
    | Some (a, b) when a < 0 || b > Camera.Path.max_frame ->
        msg "frame %d is outside every camera path, whose frames lie in [0, %d]" (if a < 0 then a else b)
          Camera.Path.max_frame
    | _ -> Ok ()
  in
  let* () =
    match (Io_plan.check ~inputs:(scene_input opts) ~outputs:(outputs ~frames output), frames, frame_placeholder output) with
    | Error _, Some (a, b), None when a < b ->
        msg "%s: with --frames %d:%d, the output needs the frame number, e.g. anim-%%04d.ppm" output a b
    | r, _, _ -> r
  in
  match (part, Image_file.format_of_path output) with
  | true, Image_file.Png when output <> "-" ->
      msg "%s: a part of an image is written as PPM, whose header records what raytrace merge checks; name it .ppm"
        output
  | _ -> Ok ()

(* The peak resident size of this process in kB, if known. *)
let peak_kb () = Proc_self.kb "status" "VmHWM"

(* One picture (a frame, a part, or both) rendered and written. *)
let render_one ~limits ~literal ~jobs ~stats ~quiet ~meter ~load_s ~files ~frame ~region ~output ~sampling valid =
  let scene = Scene.of_valid valid in
  (* A whole image to a PPM file is written while the workers trace
     (Ppm_stream): little of the writing is left when the last row is done.
     One job has no idle parent to write meanwhile. *)
  let streamed =
    jobs > 1 && region = None && (not literal) && output <> "-" && Image_file.format_of_path output = Ppm
  in
  (* What the report needs, taken now: a whole picture's render holds the
     scene no longer than preparing it needs (Prepared.prepare lets the
     spheres go as it builds the hierarchy). *)
  let width = (Scene.width scene) and height = (Scene.height scene) in
  let meshes =
    List.filter_map
      (function Shape.Mesh (m : Mesh.t) -> Some (m.source, Mesh.triangle_count m, m.skipped) | _ -> None)
      (Scene.shapes scene)
  in
  (* A part's header, taken now too: nothing below reads [scene] (one job
     held a million spheres through the render, 324 MB instead of 232). *)
  let part_settings =
    match region with
    | None -> []
    | Some _ ->
        let renderer = if literal then "literal" else "fast" in
        Part.settings ?frame ~samples:sampling.Render.Sampling.samples ?adaptive:sampling.adaptive ~subsample:sampling.subsample
          ~renderer ~files scene
  in
  let* (st, seconds), write_s =
    if streamed then begin
      (* The closure uses nothing of its own after the render. *)
      let r =
        Ppm_stream.render_to output (fun ~rows_done ->
            let* _, st, seconds = render_image ~rows_done ~limits ~sampling ~literal ~jobs ~meter valid in
            Ok (st, seconds))
      in
      Option.iter Meter.clear meter;
      r
    end
    else
      let* img, st, seconds =
        match region with
        | None -> render_image ~limits ~sampling ~literal ~jobs ~meter valid
        | Some (r : Render.Region.t) when literal ->
            let* img, st, seconds = render_image ~limits ~sampling ~literal ~jobs ~meter valid in
            Ok (Image.sub img ~x:r.x ~y:r.y ~w:r.w ~h:r.h, st, seconds)
        | Some r ->
            let* img, st =
              Render_jobs.region_image ~limits ~jobs ~split ~samples:sampling.samples ?adaptive:sampling.adaptive
                ~subsample:sampling.subsample ?progress:(progress meter) valid r
            in
            Ok (img, Some st, st.trace_s)
      in
      Option.iter Meter.clear meter;
      let t2 = Unix.gettimeofday () in
      let* () =
        match region with
        | None -> write output img
        | Some region ->
            let part = Part.v ~canvas_width:width ~canvas_height:height ~region ~settings:part_settings img in
            if output = "-" then to_stdout (Part.to_string part) else Part.write_file output part
      in
      Ok ((st, seconds), Unix.gettimeofday () -. t2)
  in
  if stats then begin
    (match st with
    | Some st -> Format.eprintf "%-24s %s@\n%a@?" "sampling" (Render.Sampling.to_string sampling) Render.Stats.pp_table st
    | None -> Format.eprintf "%-24s %.4f@." "time, literal oracle (s)" seconds);
    Format.eprintf "%-24s %.4f@.%-24s %.4f@." "time, load (s)" load_s "time, write (s)" write_s;
    List.iter
      (fun (source, triangles, skipped) ->
        Format.eprintf "%-24s %s: %d triangles, %d OBJ statements skipped@." "mesh" source triangles skipped)
      meshes;
    Option.iter (fun kb -> Format.eprintf "%-24s %.1f@." "peak memory (MB)" (Float.of_int kb /. 1024.)) (peak_kb ())
  end;
  if output <> "-" && not quiet then begin
    let what =
      match region with
      | None -> Printf.sprintf "%dx%d" width height
      | Some r -> Format.asprintf "region %a of %dx%d" Render.Region.pp_corners r width height
    in
    say (Printf.sprintf "wrote %s (%s, %.3f s)" output what seconds)
  end;
  Ok ()

let render opts ~output ~jobs ~stats ~quiet ~literal ~part ~frames ~sampling =
  let output =
    match output with Some o -> o | None -> default_render_output opts ~frames ~spec:part
  in
  report
    (let* () = check_output opts ~frames ~part:(Option.is_some part) output in
     let* sampling = sampling_of sampling in
     let* limits = Limits_env.read () in
     let t0 = Unix.gettimeofday () in
     (* The reader uses the jobs too; a bad --jobs is reported after the
        scene's errors, as before. *)
     let* scene, inputs = load_with_inputs ~limits ~jobs:(Result.value (jobs_or_cores jobs) ~default:1) opts in
     let load_s = Unix.gettimeofday () -. t0 in
     (* The files the scene read (its meshes) are inputs too, known only
        now: no output may replace one. *)
     let* () =
       match inputs with
       | [] -> Ok ()
       | _ ->
           let inputs = List.map (fun (i : Files.input) -> (i.what, i.path)) inputs in
           Io_plan.check ~inputs:(scene_input opts @ inputs) ~outputs:(outputs ~frames output)
     in
     let* region = part_region (Scene.of_valid scene) part in
     (* A part's digest covers what the files the scene read held when they
        were read: parts rendered before and after a mesh changed do not
        merge. *)
     let* files = match part with None -> Ok "" | Some _ -> Files.inputs_digest inputs in
     let* jobs = jobs_or_cores jobs in
     let count = match frames with None -> 1 | Some (a, b) -> b - a + 1 in
     let meter =
       if Meter.wanted ~quiet && not literal then Some (Meter.create ?after:progress_after ~frames:count ())
       else None
     in
     (* An error's message, or an interrupt, finds the line erased. *)
     Fun.protect ~finally:(fun () -> Option.iter Meter.clear meter) @@ fun () ->
     let render_one = render_one ~limits ~literal ~jobs ~stats ~quiet ~meter ~load_s ~files ~region ~sampling in
     match frames with
     | None ->
         let* () = render_one ~frame:None ~output scene in
         Ok exit_ok
     | Some (a, b) ->
         (* Both ends are checked before the first frame is rendered, and
            the path has checked every frame between its keys: a bad range
            fails at once. Frames are then made one by one, never all held:
            memory is that of one frame, whatever the range. *)
         let* _ = Scene.at_frame scene a in
         let* _ = Scene.at_frame scene b in
         let rec frames f =
           if f > b then Ok exit_ok
           else
             let* s = Scene.at_frame scene f in
             let* () = render_one ~frame:(Some f) ~output:(frame_path output f) s in
             Option.iter Meter.next_frame meter;
             frames (f + 1)
         in
         frames a)

let merge parts ~output ~quiet =
  report
    (let* () =
       Io_plan.check ~inputs:(List.map (fun p -> ("part " ^ p, p)) parts) ~outputs:[ ("output", output) ]
     in
     let* limits = Limits_env.read () in
     let* parts, _, _ =
       List.fold_left
         (fun acc path ->
           let* acc, canvas, pixels = acc in
           let* p = Part.read_file ~limits path in
           (* Parts that fit together cover their canvas once: more pixels
              on the first part's canvas than it has means an overlap,
              refused before more parts fill the memory. (A part of another
              canvas is left to [Part.merge], which says so.) *)
           let canvas = Option.value canvas ~default:(p.canvas_width, p.canvas_height) in
           let pixels = if canvas = (p.canvas_width, p.canvas_height) then pixels + Render.Region.pixels p.region else pixels in
           if pixels > fst canvas * snd canvas then
             msg "%s: the parts up to this one hold %d pixels, more than their %dx%d canvas: they overlap" path
               pixels (fst canvas) (snd canvas)
           else Ok ((path, p) :: acc, Some canvas, pixels))
         (Ok ([], None, 0)) parts
     in
     let parts = List.rev parts in
     let* img = Part.merge parts in
     let* () = write output img in
     if output <> "-" && not quiet then
       say
         (Printf.sprintf "wrote %s (%dx%d, from %d parts)" output (Image.width img) (Image.height img)
            (List.length parts));
     Ok exit_ok)

let diff a b ~max_diff =
  report
    (let* () = Io_plan.check ~inputs:[ ("image " ^ a, a); ("image " ^ b, b) ] ~outputs:[ ("output", "-") ] in
     let* limits = Limits_env.read () in
     let* ia = Image_file.read_file ~limits a in
     let* ib = Image_file.read_file ~limits b in
     let* d = Image.Diff.compare ia ib in
     let* () = to_stdout (Format.asprintf "%a\n" Image.Diff.pp_summary d) in
     match max_diff with
     | Some m when d.max_abs > m ->
         msg "images differ by up to %d per channel, more than --max-diff %d" d.max_abs m
     | _ -> Ok exit_ok)
