(* Build a scene in code and render it to a PPM file, with the core
   library alone: dune exec examples/hello_scene.exe -- hello.ppm *)
open Raytrace

let scene =
  Scene.v ~width:128 ~height:96
    ~objects:
      [
        Shape.Sphere
          (Sphere.v ~center:(Vec3.v 0. (-0.5) 3.) ~radius:1.
             (Material.v ~specular:500. ~reflective:0.3 (Color.v 255. 0. 0.)));
        Shape.Sphere
          (Sphere.v ~center:(Vec3.v 1.5 0. 5.) ~radius:1. (Material.v ~specular:10. (Color.v 0. 0. 255.)));
        (* A huge sphere makes the ground. *)
        Shape.Sphere
          (Sphere.v ~center:(Vec3.v 0. (-5001.) 0.) ~radius:5000.
             (Material.v ~reflective:0.2 (Color.v 255. 255. 0.)));
      ]
    ~lights:
      [
        Light.ambient 0.2;
        Light.point 0.6 (Vec3.v 2. 1. 0.);
        Light.directional 0.2 (Vec3.v 1. 4. 4.);
      ]
    ()

let () =
  let output = if Array.length Sys.argv > 1 then Sys.argv.(1) else "hello.ppm" in
  match Result.bind (Scene.validate scene) Render.image with
  | Ok (image, _stats) ->
      let oc = open_out_bin output in
      output_string oc (Image.Ppm.to_string image);
      close_out oc;
      print_endline ("wrote " ^ output)
  | Error (`Msg m) ->
      prerr_endline m;
      exit 1
