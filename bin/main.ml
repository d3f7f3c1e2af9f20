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
           what (Printf.sprintf "%.0f" (Limits.default name)))
  in
  [
    env `Pixels "canvas and image pixels (width x height)";
    env `Depth "the recursion depth";
    env `Samples "samples per pixel";
    env `Spheres "spheres in a scene";
    env `Lights "lights in a scene";
    env `Scene_bytes "the size of a scene file, in bytes";
    env `Work "the ray-sphere intersection tests that a render may need (pixels x samples x rays per sample x spheres x (1 + lights)); 1e12 is a few hours of one core";
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
      & info [ "depth"; "d" ] ~docv:"N" ~doc:"Override the recursion depth of mirror reflection.")
  in
  let make scene width height depth = Commands.{ scene; width; height; depth } in
  Term.(const make $ scene $ dim "width" $ dim "height" $ depth)

let jobs =
  Arg.(
    value
    & opt (some int) None
    & info [ "jobs"; "j" ] ~docv:"N"
        ~doc:"Trace with $(docv) processes (default: the number of cores). The image is the same for every $(docv).")

let scene_format =
  `Blocks
    [
      `S "SCENE FILES";
      `P
        "A scene is a file of S-expressions, for instance $(b,scenes/cgfs.scene). See the \
         README for every form; errors name the file, line and column.";
    ]

let view_info =
  Cmd.info "view" ~exits ~envs:limit_envs ~doc:"show a scene in a window"
    ~man:
      [
        `S Manpage.s_description;
        `P
          "Renders $(i,SCENE) (default: the built-in CGFS scene) and shows it in a Graphics \
           window of the canvas size, drawn through the document's centered-origin $(b,plotc). \
           Press $(b,q) or Escape to quit.";
        `P "Without a display it exits with status 3 and suggests $(b,raytrace render).";
        scene_format;
        `S Manpage.s_examples;
        `Pre "raytrace\nraytrace view scenes/cgfs-camera.scene\nraytrace view --depth 0 scenes/cgfs.scene";
      ]

let view_term =
  Term.(const (fun opts jobs -> Commands.view opts ~jobs) $ scene_options $ jobs)

let render_cmd =
  let output =
    Arg.(
      value
      & opt (some string) None
      & info [ "output"; "o" ] ~docv:"FILE"
          ~doc:
            "Write the image to $(docv), a binary PPM (P6). $(b,-) writes to standard output. \
             Default: the scene's base name with $(b,.ppm), in the current directory.")
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
            "Renders $(i,SCENE) (default: the built-in CGFS scene) to a binary PPM file. The \
             file is written atomically: a failed or interrupted render leaves no file, and an \
             existing file keeps its contents.";
          `P
            "Interrupted (Ctrl-C, SIGTERM, SIGHUP), it stops its worker processes, removes its \
             temporary file and ends with the signal. A worker that dies (killed, out of memory) \
             fails the render with a message instead of leaving a hole in the image. A scene or \
             an override beyond a limit (see ENVIRONMENT) is refused before any work.";
          scene_format;
          `S Manpage.s_examples;
          `Pre
            "raytrace render scenes/cgfs.scene -o cgfs.ppm\n\
             raytrace render --width 1920 --height 1920 --stats scenes/cgfs.scene -o big.ppm\n\
             raytrace render scenes/cgfs.scene -o - | convert ppm:- cgfs.png";
        ]
  in
  Cmd.v info
    Term.(
      const (fun opts output jobs stats literal -> Commands.render opts ~output ~jobs ~stats ~literal)
      $ scene_options $ output $ jobs $ stats $ literal)

let diff_cmd =
  let image n =
    Arg.(required & pos n (some string) None & info [] ~docv:(if n = 0 then "A" else "B") ~doc:"A PPM image.")
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
    Cmd.info "raytrace" ~version:"%%VERSION%%" ~exits ~doc:"a very basic ray tracer, faithful and fast"
      ~man:
        [
          `S Manpage.s_description;
          `P
            "Renders spheres lit by ambient, point and directional lights, with diffuse and \
             specular shading, shadows and mirror reflection, as the document \"Very Basic \
             Raytracer\" describes. Without a command, shows the built-in scene in a window \
             (as $(b,raytrace view)).";
          `S Manpage.s_examples;
          `Pre "raytrace\nraytrace render scenes/cgfs.scene -o cgfs.ppm\nraytrace diff a.ppm b.ppm";
        ]
  in
  Cmd.group ~default:view_term info [ Cmd.v view_info view_term; render_cmd; diff_cmd ]

let () = exit (Cmd.eval' main)
