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

let ( let* ) = Result.bind
let msg fmt = Printf.ksprintf (fun m -> Error (`Msg m)) fmt

(* The one place where an error becomes a message and an exit status. *)
let report = function
  | Ok code -> code
  | Error (`Msg m) ->
      prerr_endline ("raytrace: " ^ m);
      exit_input

let load opts =
  let* scene =
    match opts.scene with None -> Ok Scene.cgfs | Some path -> Scene_file.read path
  in
  (* Overrides come from the command line: checked like a file's values. *)
  Scene.validate (Scene.with_overrides ?width:opts.width ?height:opts.height ?depth:opts.depth scene)

let scene_name opts =
  match opts.scene with None -> "cgfs (built-in)" | Some p -> Filename.basename p

let jobs_or_cores = function Some j -> j | None -> Parallel.cores ()

(* The image, its statistics (none for the oracle) and its tracing time. *)
let render_image ~literal ~jobs scene =
  if literal then
    (* Render.image checks these itself; the oracle does not. *)
    let* () = Scene.check_work scene in
    let t0 = Unix.gettimeofday () in
    match Literal.render scene with
    | exception Out_of_memory -> msg "not enough memory for a %dx%d image" scene.width scene.height
    | img -> Ok (img, None, Unix.gettimeofday () -. t0)
  else
    let* img, stats = Render.image ~jobs scene in
    Ok (img, Some stats, stats.trace_s)

let view opts ~jobs =
  report
    (let* scene = load opts in
     let* img, _, _ = render_image ~literal:false ~jobs:(jobs_or_cores jobs) scene in
     match Window.show ~title:("raytrace: " ^ scene_name opts) img with
     | Ok () -> Ok exit_ok
     | Error (`Msg _ as e) -> Error e
     | Error (`No_display reason) ->
         Printf.eprintf
           "raytrace: cannot open a window (%s); to render without a display, use: raytrace \
            render%s -o out.ppm\n"
           reason
           (match opts.scene with Some p -> " " ^ Filename.quote p | None -> "");
         Ok exit_no_display)

let default_output opts =
  match opts.scene with
  | None -> "cgfs.ppm"
  | Some p -> Filename.remove_extension (Filename.basename p) ^ ".ppm"

let same_file a b =
  match (Unix.stat a, Unix.stat b) with
  | sa, sb -> sa.st_dev = sb.st_dev && sa.st_ino = sb.st_ino
  | exception Unix.Unix_error _ -> false

let write output img =
  if output = "-" then begin
    set_binary_mode_out stdout true;
    Ppm.output stdout img;
    flush stdout;
    Ok ()
  end
  else Ppm.write_file output img

let render opts ~output ~jobs ~stats ~literal =
  let output = Option.value output ~default:(default_output opts) in
  report
    (let* () =
       match opts.scene with
       | Some input when output <> "-" && same_file input output ->
           msg "%s: the output file is the input scene; choose another output path" output
       | _ -> Ok ()
     in
     let* scene = load opts in
     let* img, st, seconds = render_image ~literal ~jobs:(jobs_or_cores jobs) scene in
     let* () = write output img in
     (match (stats, st) with
     | true, Some st -> Format.eprintf "%a@?" Stats.pp_table st
     | true, None -> Format.eprintf "literal oracle: %.3f s@." seconds
     | false, _ -> ());
     if output <> "-" then
       Printf.eprintf "raytrace: wrote %s (%dx%d, %.3f s)\n%!" output scene.width scene.height
         seconds;
     Ok exit_ok)

let diff a b ~max_diff =
  report
    (let* ia = Ppm.read_file a in
     let* ib = Ppm.read_file b in
     let* d = Image_diff.compare ia ib in
     Format.printf "%a@." Image_diff.pp_summary d;
     match max_diff with
     | Some m when d.max_abs > m ->
         msg "images differ by up to %d per channel, more than --max-diff %d" d.max_abs m
     | _ -> Ok exit_ok)
