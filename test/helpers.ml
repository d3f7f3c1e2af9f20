open Raytrace

let vec3 = Alcotest.testable Vec3.pp Vec3.equal

let vec3_near eps =
  Alcotest.testable Vec3.pp (Vec3.equal_f (fun a b -> Float.abs (a -. b) <= eps))

let color = Alcotest.testable Color.pp Color.equal
let float_near eps = Alcotest.float eps

let check_images ?(max_abs = 0) ?min_share what ~expected actual =
  match Image.Diff.compare expected actual with
  | Error (`Msg m) -> Alcotest.failf "%s: %s" what m
  | Ok d ->
      let ok =
        match min_share with
        | Some share -> Image.Diff.share_within d >= share
        | None -> d.max_abs <= max_abs
      in
      if not ok then
        Alcotest.failf "%s: %d of %d pixels differ (%d by more than 1), by up to %d per channel, mean %.4f, PSNR %.2f dB"
          what d.differing d.pixels d.differing_gt1 d.max_abs d.mean_abs d.psnr

let scenes_dir = "../scenes"
let scene_path name = Filename.concat scenes_dir name

let scene_names () =
  Sys.readdir scenes_dir |> Array.to_list
  |> List.filter (fun f -> Filename.check_suffix f ".scene")
  |> List.sort String.compare

let load_scene name =
  match Raytrace_unix.Files.read_scene (scene_path name) with
  | Ok s -> Scene.of_valid s
  | Error (`Msg m) -> Alcotest.failf "cannot load %s: %s" name m

(* The seed is pinned so that CI sees the same cases every run;
   RAYTRACE_QCHECK_SEED draws others, to survey what the pinned cases do
   not reach (docs/testing.md). *)
let qcheck_seed =
  match Sys.getenv_opt "RAYTRACE_QCHECK_SEED" with
  | None -> 20261121
  | Some s -> (
      match int_of_string_opt s with
      | Some n -> n
      | None -> failwith ("RAYTRACE_QCHECK_SEED is not an integer: " ^ s))

let qcheck ?(count = 200) name arb prop =
  let test = QCheck.Test.make ~count ~name arb prop in
  Alcotest.test_case name `Quick (fun () ->
      let rand = Random.State.make [| qcheck_seed |] in
      QCheck.Test.check_exn ~rand test)

let read_all fd =
  let b = Buffer.create 4096 and chunk = Bytes.create 4096 in
  let rec go () =
    match Unix.read fd chunk 0 4096 with
    | 0 -> ()
    | n ->
        Buffer.add_subbytes b chunk 0 n;
        go ()
    | exception Unix.Unix_error (EINTR, _, _) -> go ()
  in
  go ();
  Buffer.contents b

let run ?env exe args =
  let out = Filename.temp_file "rt" ".out" and err = Filename.temp_file "rt" ".err" in
  let fd_out = Unix.openfile out [ O_WRONLY; O_TRUNC ] 0o600 in
  let fd_err = Unix.openfile err [ O_WRONLY; O_TRUNC ] 0o600 in
  let argv = Array.of_list (exe :: args) in
  let pid =
    match env with
    | None -> Unix.create_process exe argv Unix.stdin fd_out fd_err
    | Some env -> Unix.create_process_env exe argv env Unix.stdin fd_out fd_err
  in
  Unix.close fd_out;
  Unix.close fd_err;
  let _, status = Unix.waitpid [] pid in
  let slurp f =
    let fd = Unix.openfile f [ O_RDONLY ] 0 in
    let s = read_all fd in
    Unix.close fd;
    Sys.remove f;
    s
  in
  let code = match status with Unix.WEXITED c -> c | WSIGNALED s | WSTOPPED s -> 128 + s in
  (code, slurp out, slurp err)

let raytrace () =
  match Sys.getenv_opt "RAYTRACE_EXE" with
  | Some p when Filename.is_relative p -> Filename.concat (Sys.getcwd ()) p
  | Some p -> p
  | None -> Alcotest.fail "RAYTRACE_EXE is not set (run the tests with dune test)"

let temp_dir () =
  let d = Filename.temp_file "raytrace-test" "" in
  Sys.remove d;
  Unix.mkdir d 0o755;
  d

let valid s = match Scene.validate s with Ok v -> v | Error (`Msg m) -> Alcotest.failf "invalid scene: %s" m

(* With several jobs the workers are forked ([`Always]) unless a test asks
   otherwise: the suites compare their images with one process's on small
   images and on loaded machines, where [`Auto] would trace in one. *)
let render ?limits ?jobs ?(split = `Always) ?skips ?samples ?adaptive ?subsample ?progress s =
  Result.bind (Scene.validate ?limits s)
    (Raytrace_unix.Render_jobs.image ?limits ?jobs ~split ?skips ?samples ?adaptive ?subsample ?progress)

let render_region ?limits ?jobs ?(split = `Always) ?skips ?samples ?adaptive ?subsample ?progress s r =
  Result.bind (Scene.validate ?limits s) (fun v ->
      Raytrace_unix.Render_jobs.region_image ?limits ?jobs ~split ?skips ?samples ?adaptive ?subsample ?progress v r)

let image_exn ?jobs ?skips ?samples ?adaptive ?subsample s =
  match render ?jobs ?skips ?samples ?adaptive ?subsample s with Ok (img, _) -> img | Error (`Msg m) -> Alcotest.fail m

let prepare ?skips s = Raytrace.Private.Prepared.prepare ?skips (valid s)
let read_scene path = Result.map Scene.of_valid (Raytrace_unix.Files.read_scene path)
let of_string ?limits ?file text = Result.map Scene.of_valid (Scene_file.of_string ?limits ?file text)

let parse_ok text =
  match of_string ~file:"t.scene" text with Ok s -> s | Error (`Msg m) -> Alcotest.failf "unexpected error: %s" m

let parse_error text =
  match of_string ~file:"t.scene" text with Ok _ -> Alcotest.failf "expected an error for %S" text | Error (`Msg m) -> m

(* Alcotest sends what a test prints to stdout and stderr into the test's
   output file; a skip must reach the console, so it writes to a copy of
   stderr taken before any test runs. *)
let console = Unix.dup ~cloexec:true Unix.stderr
let skipped = ref []

let say text =
  (* What Alcotest has buffered goes first, so that the console reads in order. *)
  Format.pp_print_flush Format.std_formatter ();
  Format.pp_print_flush Format.err_formatter ();
  flush stdout;
  flush stderr;
  let b = Bytes.of_string text in
  let rec go off = if off < Bytes.length b then go (off + Unix.write console b off (Bytes.length b - off)) in
  try go 0 with Unix.Unix_error _ -> ()

let in_ci () = Sys.getenv_opt "CI" = Some "true"

let skip what ~why =
  skipped := (what, why) :: !skipped;
  say (Printf.sprintf "SKIPPED %s: %s\n" what why);
  if in_ci () then Alcotest.failf "SKIPPED %s: %s (a skip is a failure under CI=true)" what why

let skips () = List.rev !skipped

let report_skips () =
  match skips () with
  | [] -> 0
  | l ->
      say
        (Printf.sprintf "\n%d check%s SKIPPED, so not everything was tested:\n%s" (List.length l)
           (if List.length l = 1 then "" else "s")
           (String.concat "" (List.map (fun (what, why) -> Printf.sprintf "  SKIPPED %s: %s\n" what why) l)));
      if in_ci () then 1 else 0

let on_path prog =
  List.exists
    (fun dir -> dir <> "" && Sys.file_exists (Filename.concat dir prog))
    (String.split_on_char ':' (Option.value (Sys.getenv_opt "PATH") ~default:""))

let missing progs = List.filter (fun p -> not (on_path p)) progs

let mask_errors mask exact =
  let wrong = ref 0 and inside = ref 0 in
  Array.iteri
    (fun row line ->
      Array.iteri
        (fun col hit ->
          match exact.(row).(col) with
          | `In ->
              incr inside;
              if not hit then incr wrong
          | `Out -> if hit then incr wrong
          | `Edge -> ())
        line)
    mask;
  (!wrong, !inside)

let oracle_floats (s : Scene.t) =
  let tr = Trace.create (prepare ~skips:false s) in
  let ok = ref true in
  for gx = Canvas.min_x (Scene.width s) to Canvas.max_x (Scene.width s) do
    for gy = Canvas.min_y (Scene.height s) to Canvas.max_y (Scene.height s) do
      Trace.pixel tr gx gy;
      let c = Private.Literal.pixel s gx gy in
      let same a b = Float.abs (a -. b) <= 1e-9 *. Float.max 1. (Float.max (Float.abs a) (Float.abs b)) in
      if not (same c.r (Trace.red tr) && same c.g (Trace.green tr) && same c.b (Trace.blue tr)) then begin
        if !ok then
          Printf.printf "pixel (%d, %d): literal %h %h %h, fast %h %h %h\n" gx gy c.r c.g c.b (Trace.red tr)
            (Trace.green tr) (Trace.blue tr);
        ok := false
      end
    done
  done;
  !ok

let obj_part_joined p ~name ~max_vertices ~max_triangles s off len =
  let sent = Buffer.create 4096 in
  let q = Raytrace.Private.Obj_parts.create_part ~output:(Buffer.add_subbytes sent) ~name ~max_vertices ~max_triangles in
  match Result.bind (Raytrace.Mesh.Obj.feed q s off len) (fun () -> Raytrace.Private.Obj_parts.finish_part q) with
  | Error _ -> None
  | Ok part ->
      let bytes = Buffer.to_bytes sent and at = ref 0 in
      if Raytrace.Private.Obj_parts.part_bytes part <> Bytes.length bytes then Alcotest.fail "the part's bytes are not those sent";
      let input b off len =
        Bytes.blit bytes !at b off len;
        at := !at + len
      in
      let m = Raytrace.Private.Obj_parts.join p part ~input in
      if Option.is_some m && !at <> Bytes.length bytes then Alcotest.failf "the join read %d of %d bytes" !at (Bytes.length bytes);
      m

let csg_spiral n =
  let b = Buffer.create (n * 64) in
  let rec tree lo hi =
    if hi - lo = 1 then
      let a = Float.of_int lo *. 0.01 and r = 0.2 +. (Float.of_int lo *. 1e-4) in
      Printf.bprintf b "(sphere (center %.4f %.4f 4) (radius 0.05) (color 255 0 0))" (r *. cos a) (r *. sin a)
    else begin
      Buffer.add_string b "(csg union ";
      tree lo ((lo + hi) / 2);
      Buffer.add_char b ' ';
      tree ((lo + hi) / 2) hi;
      Buffer.add_char b ')'
    end
  in
  Buffer.add_string b
    "(canvas (width 16) (height 16))\n(camera (position 0 0 -3))\n(light ambient (intensity 0.3))\n\
     (light point (intensity 0.7) (position 2 3 -4))\n";
  tree 0 n;
  Buffer.add_char b '\n';
  Buffer.contents b

let glass_planes ~width ~height ~depth =
  let plane z =
    Printf.sprintf
      "(plane (point 0 0 %d) (normal 0 0 -1) (color 200 200 255) (transparency 0.5) (reflective 0.5) \
       (refractive-index 1.5))"
      z
  in
  String.concat "\n"
    ([ Printf.sprintf "(canvas (width %d) (height %d))" width height; Printf.sprintf "(recursion-depth %d)" depth;
       "(light ambient (intensity 0.5))" ]
    @ List.map plane [ 2; 3; 4; 5 ])
  ^ "\n"

let sphere ?specular ?reflective ?transparency ?refractive_index ?fresnel ?pattern ~center ~radius color =
  Sphere.v ~center ~radius (Material.v ?specular ?reflective ?transparency ?refractive_index ?fresnel ?pattern color)

let scene ?width ?height ?viewport ?camera ?background ?depth ?epsilon ?camera_path ?(shapes = []) ~spheres ~lights () =
  Scene.v ?width ?height ?viewport ?camera ?background ?depth ?epsilon ?camera_path
    ~objects:(List.map (fun s -> Shape.Sphere s) spheres @ shapes)
    ~lights ()

let with_sphere_material (s : Sphere.t) f = Sphere.v ~center:s.center ~radius:s.radius (f s.material)
let scene_spheres s = Private.Spheres.to_list (Scene.spheres s)

let with_objects ?spheres ?shapes s =
  let spheres = match spheres with Some l -> l | None -> scene_spheres s in
  let shapes = match shapes with Some l -> l | None -> Scene.shapes s in
  Scene.with_overrides ~objects:(List.map (fun sp -> Shape.Sphere sp) spheres @ shapes) s

(* The image that tracer [tr] makes a pixel at a time, in columns (tiles
   are entered in another order than by rows). *)
let by_pixels (tr : Raytrace.Private.Trace.t) =
  let p = Raytrace.Private.Trace.prepared tr in
  let img = Image.create p.width p.height in
  let buf = Image.buffer img in
  for c = 0 to p.width - 1 do
    for r = 0 to p.height - 1 do
      Raytrace.Private.Trace.pixel tr (Canvas.x_of_column ~width:p.width c) (Canvas.y_of_row ~height:p.height r);
      Raytrace.Private.Trace.store tr buf (3 * ((r * p.width) + c))
    done
  done;
  img
