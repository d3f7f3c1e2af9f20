open Cmdliner

let exits =
  Cmd.Exit.info Commands.exit_input
    ~doc:"on bad input: an unreadable or invalid scene or image, an unwritable output, a failed render."
  :: Cmd.Exit.info Commands.exit_no_display ~doc:"when no window can be opened (no X display)."
  :: Cmd.Exit.defaults

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

let sampling =
  let samples =
    Arg.(
      value
      & opt (some int) None
      & info [ "samples" ] ~docv:"N"
          ~doc:
            "Antialiasing: trace a regular $(docv) x $(docv) grid of rays in every pixel and \
             average them (each clamped to 0-255 first). 1, the default, is the document's \
             image. With $(b,--adaptive), the largest grid.")
  in
  let adaptive =
    Arg.(
      value
      & opt (some int) None
      & info [ "adaptive" ] ~docv:"T"
          ~doc:
            "Adaptive supersampling: trace one ray per pixel, through its centre, then the rest \
             of the $(b,--samples) grid (an odd N: 3, 5, 7...) only in pixels whose ray hit \
             another sphere than a neighbour's, or whose colour differs from a neighbour's by \
             more than $(docv) (0-255) in some channel. Never traces more rays than full \
             sampling.")
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
        "$(b,--depth) (mirror reflections), $(b,--samples) (rays per pixel), $(b,--adaptive) \
         and $(b,--subsample) trade time for accuracy; the README shows the trade-off measured \
         on four scenes ($(b,make bench-quality)). Recommended: the default (one ray per \
         pixel) or $(b,--subsample) for previews; $(b,--samples 5 --adaptive 2 --depth 5) for \
         final renders; full sampling ($(b,--samples 4)) where spheres are smaller than a \
         pixel, which adaptive sampling cannot see.";
    ]

let scene_format =
  `Blocks
    [
      `S "SCENE FILES";
      `P
        "A scene is a file of S-expressions, for instance $(b,scenes/cgfs.scene). See the \
         README for every form; errors name the file, line and column.";
    ]

let view_info =
  Cmd.info "view" ~exits ~doc:"show a scene in a window"
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
  Term.(
    const (fun opts jobs sampling -> Commands.view opts ~jobs ~sampling) $ scene_options $ jobs $ sampling)

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
    Cmd.info "render" ~exits ~doc:"render a scene to an image file"
      ~man:
        [
          `S Manpage.s_description;
          `P
            "Renders $(i,SCENE) (default: the built-in CGFS scene) to a binary PPM file. The \
             file is written atomically: a failed or interrupted render leaves no file, and an \
             existing file keeps its contents.";
          scene_format;
          quality_section;
          `S Manpage.s_examples;
          `Pre
            "raytrace render scenes/cgfs.scene -o cgfs.ppm\n\
             raytrace render --width 1920 --height 1920 --stats scenes/cgfs.scene -o big.ppm\n\
             raytrace render --samples 4 scenes/cgfs.scene -o smooth.ppm\n\
             raytrace render --samples 5 --adaptive 2 --depth 5 scenes/cgfs.scene -o final.ppm\n\
             raytrace render scenes/cgfs.scene -o - | convert ppm:- cgfs.png";
        ]
  in
  Cmd.v info
    Term.(
      const (fun opts output jobs stats literal sampling ->
          Commands.render opts ~output ~jobs ~stats ~literal ~sampling)
      $ scene_options $ output $ jobs $ stats $ literal $ sampling)

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
    Cmd.info "diff" ~exits ~doc:"compare two images"
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
