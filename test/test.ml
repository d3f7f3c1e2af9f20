let () =
  Alcotest.run "raytrace"
    [
      ("vec3", Test_vec3.tests);
      ("color", Test_color.tests);
      ("canvas", Test_canvas.tests);
      ("viewport", Test_viewport.tests);
      ("camera", Test_camera.tests);
      ("sphere", Test_sphere.tests);
      ("light", Test_light.tests);
      ("shading", Test_shading.tests);
      ("literal", Test_literal.tests);
      ("scene_file", Test_scene_file.tests);
      ("ppm", Test_ppm.tests);
      ("image_diff", Test_image_diff.tests);
      ("render", Test_render.tests);
      ("golden", Test_golden.tests);
      ("cli", Test_cli.tests);
      ("window", Test_window.tests);
      ("example", Test_example.tests);
      ("hostile", Test_hostile.tests);
      ("faults", Test_faults.tests);
    ]
