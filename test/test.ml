(* Alcotest prints its summary and exits (its [test] command exits even
   with [~and_exit:false]); the skips' summary comes after it, at exit, and
   under CI=true a skip fails the run even if every test passed. *)
let () =
  at_exit (fun () -> if Helpers.report_skips () <> 0 then exit 1);
  (* The farm's daemons (munged, slurmctld, slurmd, sshd) live in the sbin
     directories, which an environment without a login shell (env -i, some
     CI runners) may leave off PATH: the tests would skip them. *)
  let path = Option.value (Sys.getenv_opt "PATH") ~default:"/usr/bin:/bin" in
  let dirs = String.split_on_char ':' path in
  let extra = List.filter (fun d -> not (List.mem d dirs)) [ "/usr/local/sbin"; "/usr/sbin"; "/sbin" ] in
  if extra <> [] then Unix.putenv "PATH" (String.concat ":" (path :: extra));
  (* The command-line tests exercise the workers of --jobs N on small images
     and on machines whose cores other work holds, where the render would
     trace in one process: RAYTRACE_SPLIT=always forks them (docs/usage.md).
     The tests of that rule unset it. *)
  Unix.putenv "RAYTRACE_SPLIT" "always";
  Alcotest.run "raytrace"
    [
      ("vec3", Test_vec3.tests);
      ("sample-key", Test_sample_key.tests);
      ("color", Test_color.tests);
      ("canvas", Test_canvas.tests);
      ("viewport", Test_viewport.tests);
      ("camera", Test_camera.tests);
      ("lens", Test_lens.tests);
      ("sphere", Test_sphere.tests);
      ("spheres", Test_spheres.tests);
      ("light", Test_light.tests);
      ("soft-light", Test_soft_light.tests);
      ("shading", Test_shading.tests);
      ("literal", Test_literal.tests);
      ("pattern", Test_pattern.tests);
      ("scene", Test_scene.tests);
      ("scene_file", Test_scene_file.tests);
      ("sexp_scan", Test_sexp_scan.tests);
      ("sphere_scan", Test_sphere_scan.tests);
      ("scene_split", Test_scene_split.tests);
      ("ppm", Test_ppm.tests);
      ("image_diff", Test_image_diff.tests);
      ("render", Test_render.tests);
      ("fast_oracle", Test_fast_oracle.tests);
      ("kernel", Test_kernel.tests);
      ("sampling", Test_sampling.tests);
      ("numerics", Test_numerics.tests);
      ("shapes", Test_shapes.tests);
      ("cylinder", Test_cylinder.tests);
      ("csg", Test_csg.tests);
      ("cone", Test_cone.tests);
      ("edges", Test_edges.tests);
      ("torus", Test_torus.tests);
      ("transform", Test_transform.tests);
      ("operand", Test_operand.tests);
      ("bvh", Test_bvh.tests);
      ("prepared", Test_prepared.tests);
      ("antialias", Test_antialias.tests);
      ("progressive", Test_progressive.tests);
      ("view", Test_view.tests);
      ("golden", Test_golden.tests);
      ("cli", Test_cli.tests);
      ("progress", Test_progress.tests);
      ("region", Test_region.tests);
      ("part", Test_part.tests);
      ("camera_path", Test_camera_path.tests);
      ("png", Test_png.tests);
      ("cli_parts", Test_cli_parts.tests);
      ("new_scenes", Test_new_scenes.tests);
      ("recipes", Test_recipes.tests);
      ("window", Test_window.tests);
      ("web_session", Test_web_session.tests);
      ("web", Test_web.tests);
      ("example", Test_example.tests);
      ("pixel", Test_pixel.tests);
      ("library", Test_library.tests);
      ("hostile", Test_hostile.tests);
      ("work", Test_work.tests);
      ("faults", Test_faults.tests);
      ("outputs", Test_outputs.tests);
      ("cli_fuzz", Test_cli_fuzz.tests);
      ("skips", Test_skips.tests);
      ("memory", Test_memory.tests);
      ("float_scan", Test_float_scan.tests);
      ("obj_file", Test_obj_file.tests);
      ("texture", Test_texture.tests);
      ("texdraw", Test_texdraw.tests);
      ("obj_split", Test_obj_split.tests);
      ("mesh_gen", Test_mesh_gen.tests);
      ("embree", Test_embree.tests);
      ("optics", Test_optics.tests);
      ("promises", Test_promises.tests @ Test_promises_values.tests);
    ]
