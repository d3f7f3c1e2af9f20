open Cmdliner

let exits =
  Cmd.Exit.info Commands.exit_input
    ~doc:"on bad input: an unreadable or invalid scene or image, an unwritable output, a failed render."
  :: Cmd.Exit.info Commands.exit_no_display ~doc:"when no window can be opened (no X display)."
  :: Cmd.Exit.defaults

(* The environment variables of Raytrace.Limits, for the ENVIRONMENT
   section of the manuals. *)
let limit_envs =
  let open Raytrace in
  let env name what =
    Cmd.Env.info (Limits.variable name)
      ~doc:
        (Printf.sprintf "Raise (or lower) the limit on %s; default %s. Inputs beyond a limit are refused before any work, with a message that names the variable."
           what (Printf.sprintf "%.0f" (Limits.bound Limits.default name)))
  in
  [
    env `Pixels "canvas and image pixels (width x height)";
    env `Depth "the recursion depth";
    env `Samples "rays per pixel (--samples N traces N x N)";
    env `Spheres "objects in a scene (spheres, planes, triangles, boxes, meshes and CSG solids, each counted once)";
    env `Triangles "the triangles of a scene's meshes, over all its mesh forms (a file named twice counts twice), counted before they are made";
    env `Lights "lights in a scene";
    env `Scene_bytes "the size of a scene file, in bytes";
    env `Form_bytes "the size of one top-level form of a scene file (such as a camera-path), in bytes: the parser holds a form whole, in about 50 times its size";
    env `Mesh_bytes "the size of a mesh (OBJ) file, in bytes: it is read 64 KiB at a time, so the bound stops a file that would never end";
    env `Work "the intersection tests that a render may need (pixels x samples x rays per sample x objects met per ray x (1 + lights), rays per sample a tree of 2^(depth+1) - 1 when glass both reflects and refracts); and, as they are counted during the render, the tests it does; 1e12 is a few hours of one core";
  ]

let scene_options =
  let scene =
    Arg.(
      value
      & pos 0 (some string) None
      & info [] ~docv:"SCENE"
          ~doc:"Scene file (S-expressions). Without it, the built-in CGFS reference scene.")
  in
  let dim name =
    Arg.(
      value
      & opt (some int) None
      & info [ name ] ~docv:"PIXELS" ~doc:(Printf.sprintf "Override the canvas %s." name))
  in
  let depth =
    Arg.(
      value
      & opt (some int) None
      & info [ "depth"; "d" ] ~docv:"N" ~doc:"Override the recursion depth: how many times a ray is followed after its first hit, reflected or refracted.")
  in
  let make scene width height depth = Commands.{ scene; width; height; depth } in
  Term.(const make $ scene $ dim "width" $ dim "height" $ depth)

let jobs =
  Arg.(
    value
    & opt (some int) None
    & info [ "jobs"; "j" ] ~docv:"N"
        ~doc:"Trace with $(docv) processes (default: the number of cores). The image is the same for every $(docv).")

let sampling =
  let samples =
    Arg.(
      value
      & opt (some int) None
      & info [ "samples" ] ~docv:"N"
          ~doc:
            "Antialiasing: trace a regular $(docv) x $(docv) grid of rays in every pixel and \
             average them (each clamped to 0-255 first). 1, the default, is the document's \
             image. With $(b,--adaptive), the largest grid. Under a camera with a lens \
             (aperture), each ray leaves its own point of the lens: this is how to get a smooth \
             depth of field instead of a grainy one.")
  in
  let adaptive =
    Arg.(
      value
      & opt (some int) None
      & info [ "adaptive" ] ~docv:"T"
          ~doc:
            "Adaptive supersampling: trace one ray per pixel, through its centre, then the rest \
             of the $(b,--samples) grid (an odd N: 3, 5, 7...; under a lens any N >= 2) only in pixels whose ray hit \
             another object than a neighbour's, or whose colour differs from a neighbour's by \
             more than $(docv) (0-255) in some channel; under a camera with a lens, also in \
             blurred pixels where one of four probe rays from the lens's rim sees another \
             object or colour. Without a lens, never traces more rays than full sampling.")
  in
  let subsample =
    Arg.(
      value & flag
      & info [ "subsample" ]
          ~doc:
            "CGFS's subsampling, approximate: where the pixels on either side of a pixel hit \
             the same sphere, assume its ray hits that sphere too and skip the search for it.")
  in
  let make samples adaptive subsample = Commands.{ samples; adaptive; subsample } in
  Term.(const make $ samples $ adaptive $ subsample)

let quality_section =
  `Blocks
    [
      `S "RUN TIME AGAINST ERROR";
      `P
        "$(b,--depth) (reflections and refractions), $(b,--samples) (rays per pixel), $(b,--adaptive) \
         and $(b,--subsample) trade time for accuracy; docs/run-time-against-error.md shows the \
         trade-off measured on four scenes ($(b,make bench-quality)). Recommended: the default (one ray per \
         pixel) or $(b,--subsample) for previews; $(b,--samples 5 --adaptive 2 --depth 5) for \
         final renders; full sampling ($(b,--samples 4)) where objects are smaller than a \
         pixel, which adaptive sampling cannot see.";
    ]

(* The window forks its workers anew for every band of rows (each about
   0.1 s of tracing), which pays only where cores are idle: by default it
   traces in its own process (docs/window.md). *)
let view_jobs =
  Arg.(
    value
    & opt (some int) (Some 1)
    & info [ "jobs"; "j" ] ~docv:"N"
        ~doc:
          "Trace the full-resolution passes with $(docv) processes (default: 1, this process). \
           The picture is the same for every $(docv).")

let scene_format =
  `Blocks
    [
      `S "SCENE FILES";
      `P
        "A scene is a file of S-expressions, for instance $(b,scenes/cgfs.scene). See the \
         $(b,docs/scene-format.md) for every form; errors name the file, line and column.";
    ]

let view_info =
  Cmd.info "view" ~exits ~envs:limit_envs ~doc:"show a scene in a window"
    ~man:
      [
        `S Manpage.s_description;
        `P
          "Renders $(i,SCENE) (default: the built-in CGFS scene) in a Graphics window of the \
           canvas size: a coarse picture at once, refined to the full image, which is drawn \
           through the document's centered-origin $(b,plotc) and is exactly what $(b,raytrace \
           render) writes. The window answers keys while it renders. After each full frame, \
           its title and a line on stderr give the time and the rays per second.";
        `P "Without a display it exits with status 3 and suggests $(b,raytrace render).";
        `S "KEYS";
        `I ("arrows, $(b,W) $(b,A) $(b,S) $(b,D)", "Move the camera forward, left, back, right, by half the viewport distance. Letters that move or turn are upper case (Shift), as lower-case $(b,a) and $(b,s) are commands.");
        `I ("$(b,Q) $(b,E), $(b,<) $(b,>), drag", "Turn left or right by 5 degrees; dragging with a button held turns so that the picture follows the pointer.");
        `I ("$(b,+) $(b,-)", "Recursion depth (reflections and refractions) up or down by one.");
        `I ("$(b,a)", "Antialiasing on or off: each pixel the mean of 3 x 3 samples.");
        `I ("$(b,r)", "Render again.");
        `I ("$(b,s)", "Save the picture as a PPM next to the scene file ($(i,NAME)-$(i,N).ppm, written atomically), with the scene of the current view ($(i,NAME)-$(i,N).scene), and print their names.");
        `I ("$(b,h)", "Show or hide the help.");
        `I ("$(b,q), Escape", "Quit.");
        `P "Resizing the window renders at the new size; pixels stay square and the scene's own view stays in sight.";
        scene_format;
        `S Manpage.s_examples;
        `Pre "raytrace\nraytrace view scenes/cgfs-camera.scene\nraytrace view --depth 0 scenes/cgfs.scene";
      ]

let view_term =
  Term.(const (fun opts jobs -> Commands.view opts ~jobs) $ scene_options $ view_jobs)

(* A cmdliner converter from a parser of ours. *)
let parsed parse docv =
  Arg.conv ~docv ((fun s -> (parse s :> (_, [ `Msg of string ]) result)), fun ppf _ -> Format.pp_print_string ppf docv)

let part =
  let tile =
    Arg.(
      value
      & opt (some (parsed Raytrace.Render.Region.parse_tile "I/N")) None
      & info [ "tile" ] ~docv:"I/N"
          ~doc:
            "Render only tile $(i,I) of $(i,N) (from 1 to $(i,N)): a band of full rows, the $(i,N) \
             tiles top to bottom. The output is a part file for $(b,raytrace merge).")
  in
  let region =
    Arg.(
      value
      & opt (some (parsed Raytrace.Render.Region.parse_corners "X0,Y0,X1,Y1")) None
      & info [ "region" ] ~docv:"X0,Y0,X1,Y1"
          ~doc:
            "Render only columns $(i,X0) to $(i,X1)-1 and rows $(i,Y0) to $(i,Y1)-1 (rows from the \
             top, as in the image file). The output is a part file for $(b,raytrace merge).")
  in
  let make tile region =
    match (tile, region) with
    | Some _, Some _ -> `Error (true, "--tile and --region exclude each other: give one")
    | Some (i, n), None -> `Ok (Some (Commands.Tile (i, n)))
    | None, Some (x0, y0, x1, y1) -> `Ok (Some (Commands.Corners (x0, y0, x1, y1)))
    | None, None -> `Ok None
  in
  Term.(ret (const make $ tile $ region))

let frames =
  Arg.(
    value
    & opt (some (parsed Commands.parse_frames "A:B")) None
    & info [ "frames" ] ~docv:"A:B"
        ~doc:
          "Render frames $(i,A) to $(i,B) (both included; $(i,A) alone is one frame) of the scene's \
           $(b,camera-path), each to the output name with its $(b,%d) or $(b,%04d) replaced by the \
           frame number (default: the scene's base name with $(b,-%04d.ppm)).")

let quiet =
  Arg.(
    value & flag
    & info [ "quiet"; "q" ]
        ~doc:"Print nothing on stderr but errors (and $(b,--stats) when asked): no progress line, no line naming the file written.")

let render_cmd =
  let output =
    Arg.(
      value
      & opt (some string) None
      & info [ "output"; "o" ] ~docv:"FILE"
          ~doc:
            "Write the image to $(docv): PNG if its name ends in $(b,.png), otherwise a binary PPM \
             (P6). $(b,-) writes PPM to standard output. Default: the scene's base name with \
             $(b,.ppm), in the current directory.")
  in
  let stats =
    Arg.(value & flag & info [ "stats" ] ~doc:"Print rays by kind, intersection tests, time and allocation to stderr.")
  in
  let literal =
    Arg.(
      value & flag
      & info [ "literal" ]
          ~doc:"Render with the literal transcription of the document (slow; the oracle the fast renderer is tested against).")
  in
  let info =
    Cmd.info "render" ~exits ~envs:limit_envs ~doc:"render a scene to an image file"
      ~man:
        [
          `S Manpage.s_description;
          `P
            "Renders $(i,SCENE) (default: the built-in CGFS scene) to a binary PPM or a PNG file. \
             The file is written atomically: a failed or interrupted render leaves no file, and an \
             existing file keeps its contents.";
          `P
            "$(b,--tile) and $(b,--region) render one part of the image, to a PPM file whose header \
             records the canvas, the region and every setting that changes pixels; $(b,raytrace \
             merge) assembles the parts, from any processes or machines, into exactly the image a \
             single render gives. $(b,--frames) renders the frames of an animated scene; each \
             frame is an independent job.";
          `P
            "Interrupted (Ctrl-C, SIGTERM, SIGHUP), it stops its worker processes, removes its \
             temporary file and ends with the signal. A worker that dies (killed, out of memory) \
             fails the render with a message instead of leaving a hole in the image. A scene or \
             an override beyond a limit (see ENVIRONMENT) is refused before any work. A reader of \
             standard output that goes away ($(b,| head)) ends it quietly, by SIGPIPE, as other \
             tools in a pipeline.";
          `P
            "On a terminal, a render that takes more than a second shows its progress on stderr, \
             on one line rewritten in place: the share done, the rays per second and the time \
             left. Nothing of it is written when stderr is not a terminal; $(b,--quiet) hides it \
             too.";
          scene_format;
          quality_section;
          `S Manpage.s_examples;
          `Pre
            "raytrace render scenes/cgfs.scene -o cgfs.ppm\n\
             raytrace render scenes/cgfs.scene -o cgfs.png\n\
             raytrace render --width 1920 --height 1920 --stats scenes/cgfs.scene -o big.ppm\n\
             raytrace render --samples 4 scenes/cgfs.scene -o smooth.ppm\n\
             raytrace render --samples 5 --adaptive 2 --depth 5 scenes/cgfs.scene -o final.ppm\n\
             raytrace render scenes/cgfs.scene --tile 3/16 -o part-3.ppm\n\
             raytrace render scenes/cgfs.scene --region 0,0,300,300 -o corner.ppm\n\
             raytrace render scenes/orbit.scene --frames 0:47 -o 'orbit-%04d.png'\n\
             raytrace render scenes/cgfs.scene -o - | convert ppm:- cgfs.jpg";
        ]
  in
  Cmd.v info
    Term.(
      const (fun opts output jobs stats quiet literal part frames sampling ->
          Commands.render opts ~output ~jobs ~stats ~quiet ~literal ~part ~frames ~sampling)
      $ scene_options $ output $ jobs $ stats $ quiet $ literal $ part $ frames $ sampling)

let merge_cmd =
  let parts =
    Arg.(non_empty & pos_all string [] & info [] ~docv:"PART" ~doc:"A part file written by $(b,raytrace render --tile) or $(b,--region).")
  in
  let output =
    Arg.(
      required
      & opt (some string) None
      & info [ "output"; "o" ] ~docv:"FILE"
          ~doc:"Write the whole image to $(docv): PNG if its name ends in $(b,.png), otherwise PPM; $(b,-) writes PPM to standard output.")
  in
  let info =
    Cmd.info "merge" ~exits ~doc:"assemble the parts of an image"
      ~man:
        [
          `S Manpage.s_description;
          `P
            "Assembles parts rendered with $(b,raytrace render --tile) or $(b,--region) (in any \
             order, by any processes on any machines) into the whole image: byte for byte the \
             image that one $(b,raytrace render) gives.";
          `P
            "Refuses, naming the files, parts that do not fit together: of different canvas \
             sizes, rendered with a different depth, sampling, renderer or frame, or \
             from a different scene (a digest of the scene is in every part's header); parts \
             that overlap; and parts that leave pixels uncovered.";
          `S Manpage.s_examples;
          `Pre
            "raytrace merge part-*.ppm -o cgfs.png\n\
             parallel raytrace render scenes/cgfs.scene --tile {}/16 -o part-{}.ppm ::: \\$(seq 16)\n\
             raytrace merge part-*.ppm -o cgfs.ppm";
        ]
  in
  Cmd.v info Term.(const (fun parts output quiet -> Commands.merge parts ~output ~quiet) $ parts $ output $ quiet)

let diff_cmd =
  let image n =
    Arg.(required & pos n (some string) None & info [] ~docv:(if n = 0 then "A" else "B") ~doc:"A PPM or PNG image.")
  in
  let max_diff =
    Arg.(
      value
      & opt (some int) None
      & info [ "max-diff" ] ~docv:"N" ~doc:"Exit with status 1 if any channel differs by more than $(docv).")
  in
  let info =
    Cmd.info "diff" ~exits ~envs:[ List.hd limit_envs ] ~doc:"compare two images"
      ~man:
        [
          `S Manpage.s_description;
          `P
            "Prints, on one line: the number of pixels, how many differ at all and by more than \
             1 in some channel, the largest and the mean channel difference, and the PSNR in \
             decibels ($(b,inf) for identical images).";
          `S Manpage.s_examples;
          `Pre "raytrace diff cgfs.ppm reference.ppm\nraytrace diff --max-diff 1 a.ppm b.ppm";
        ]
  in
  Cmd.v info Term.(const (fun a b max_diff -> Commands.diff a b ~max_diff) $ image 0 $ image 1 $ max_diff)

let main =
  let info =
    Cmd.info "raytrace" ~version:Raytrace.version ~exits ~doc:"a very basic ray tracer, faithful and fast"
      ~man:
        [
          `S Manpage.s_description;
          `P
            "Renders spheres lit by ambient, point and directional lights, with diffuse and \
             specular shading, shadows and mirror reflection, as the document \"Very Basic \
             Raytracer\" describes, and beyond it planes, triangles, boxes, OBJ meshes, \
             constructive solid geometry, glass and checker patterns. Without a command, shows the built-in scene in a window \
             (as $(b,raytrace view)).";
          `S Manpage.s_examples;
          `Pre "raytrace\nraytrace render scenes/cgfs.scene -o cgfs.ppm\nraytrace diff a.ppm b.ppm";
        ]
  in
  Cmd.group ~default:view_term info [ Cmd.v view_info view_term; render_cmd; merge_cmd; diff_cmd ]

(* A descriptor 0, 1 or 2 closed by the caller ([>&-]) would be reused by
   the next file opened, and the image or a message would land in it: each
   is held by /dev/null. Read-only for stdin and stdout, so that writing
   the image to a closed stdout fails ("Bad file descriptor"); write-only
   for stderr, whose messages the caller chose not to see. *)
let hold_closed_descriptors () =
  List.iter
    (fun (fd, flag) ->
      match Unix.fstat fd with
      | _ -> ()
      | exception Unix.Unix_error (EBADF, _, _) -> (
          match Unix.openfile "/dev/null" [ flag; O_CLOEXEC ] 0 with
          | null ->
              if null <> fd then begin
                Unix.dup2 ~cloexec:false null fd;
                Unix.close null
              end
          | exception Unix.Unix_error _ -> ())
      | exception Unix.Unix_error _ -> ())
    [ (Unix.stdin, Unix.O_RDONLY); (Unix.stdout, Unix.O_RDONLY); (Unix.stderr, Unix.O_WRONLY) ]

(* Cmdliner's error on the command line is three lines (the error, the
   usage, where to find help): one line here, the error and where to find
   help. *)
let one_line_usage text =
  let lines = List.filter (fun l -> String.trim l <> "") (String.split_on_char '\n' text) in
  let strip prefix l =
    let n = String.length prefix in
    if String.length l >= n && String.sub l 0 n = prefix then String.sub l n (String.length l - n) else l
  in
  let help =
    List.find_map
      (fun l ->
        match String.split_on_char '\'' l with
        | "Try " :: command :: _ -> Some (Printf.sprintf "; see '%s'" command)
        | _ -> None)
      lines
  in
  match lines with
  | [] -> ""
  | first :: _ -> strip "raytrace: " first ^ Option.value help ~default:""

(* The single exit point. Every output channel may fail, cmdliner's help
   and version included (a full disk, a closed stdout): one line, status
   1. A reader gone ends the process quietly, by SIGPIPE, as Unix tools
   end in a pipeline (Commands.end_as_reader_gone). SIGPIPE is ignored
   until then on purpose, so that a write to a broken pipe fails where it
   can be told from other failures, with nothing left to clean up (no
   worker, no temporary file) when the process ends; a stray SIGPIPE from
   [kill] does nothing. What the channels still buffer after a
   failure is dropped by leaving with [_exit], as the standard library's
   own flush at exit would raise again. *)
(* An allocation that fails despite the bounds checked before (the
   machine's memory is shared, or limited by ulimit) may end in the
   runtime's fatal error rather than [Out_of_memory]: the hook makes that
   one line that says it is memory too. *)
external install_fatal_hook : unit -> unit = "raytrace_install_fatal_hook"

let () =
  install_fatal_hook ();
  hold_closed_descriptors ();
  Sys.set_signal Sys.sigpipe Sys.Signal_ignore;
  (* Cmdliner pages its help through [less] whenever TERM is set, and
     ignores what becomes of the pager: into a file or a pipe, it prints
     the help itself, whose write errors reach us. *)
  if not (Unix.isatty Unix.stdout) then Unix.putenv "TERM" "dumb";
  (* A failed flush keeps the bytes, and the standard library's flush at
     exit would fail again and abort: then the process leaves with
     [_exit]. *)
  let flush_error flush = match flush () with () -> None | exception Sys_error e -> Some e in
  let stdout_error () =
    match flush_error (fun () -> Format.pp_print_flush Format.std_formatter ()) with
    | None -> flush_error (fun () -> flush stdout)
    | e -> e
  in
  let leave code =
    let out = stdout_error () in
    let err = flush_error (fun () -> Format.pp_print_flush Format.err_formatter ()) in
    let err = match err with None -> flush_error (fun () -> flush stderr) | e -> e in
    if out = None && err = None then exit code else Unix._exit code
  in
  let failed ?(code = Commands.exit_input) line =
    Commands.say line;
    leave code
  in
  let usage = Buffer.create 256 in
  let err = Format.formatter_of_buffer usage in
  (* Cmdliner wraps its messages at the formatter's margin: a wrapped
     message would lose its end to [one_line_usage]. *)
  Format.pp_set_margin err 1_000_000;
  match Cmd.eval' ~catch:false ~err main with
  | code -> (
      Format.pp_print_flush err ();
      if Buffer.length usage > 0 then Commands.say (one_line_usage (Buffer.contents usage));
      (* A write that failed in a command was reported already; stderr's
         failures lose only messages. *)
      match stdout_error () with
      | Some e when Commands.is_broken_pipe e -> Commands.end_as_reader_gone ()
      | Some e when code = Commands.exit_ok -> failed ("standard output: " ^ e)
      | _ -> leave code)
  | exception Sys_error e when Commands.is_broken_pipe e -> Commands.end_as_reader_gone ()
  | exception Sys_error e -> failed ("standard output: " ^ e)
  | exception Out_of_memory ->
      failed "out of memory: an allocation failed (see the limits in raytrace render --help, ENVIRONMENT)"
  | exception Stack_overflow -> failed "stack overflow"
  | exception e -> failed ~code:Cmd.Exit.internal_error ("internal error: " ^ Printexc.to_string e)
