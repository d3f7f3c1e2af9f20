(* Memory is bounded before it is allocated: frame ranges, big forms of a
   scene file, image headers and parts are checked against the documented
   limits first, and an allocation that fails anyway is one line saying it
   is memory. *)
open Raytrace

let write path text =
  let oc = open_out_bin path in
  output_string oc text;
  close_out oc

(* [args] run with at most [kb] KiB of address space (ulimit -v). *)
let run_limited ?(env = []) ~kb args =
  let env = Array.append (Array.of_list env) (Unix.environment ()) in
  Helpers.run ~env "/bin/sh"
    ([ "-c"; Printf.sprintf "ulimit -v %d; exec \"$0\" \"$@\"" kb; Helpers.raytrace () ] @ args)

let check_one_line what ~code ~expected (c, out, err) =
  Alcotest.(check int) (what ^ ": exit status: " ^ err) code c;
  Alcotest.(check string) (what ^ ": stdout") "" out;
  Alcotest.(check string) (what ^ ": stderr") expected err

(* A PNG file whose header says [w x h] RGB pixels, and whose data is
   missing: only the header can be read. *)
let png_header w h =
  let be32 n = String.init 4 (fun i -> Char.chr ((n lsr (8 * (3 - i))) land 255)) in
  Raytrace_png.Png_file.signature ^ be32 13 ^ "IHDR" ^ be32 w ^ be32 h ^ "\008\002\000\000\000" ^ be32 0
  ^ be32 0 ^ "IEND" ^ be32 0

(* Runs [f] with the limits that RAYTRACE_MAX_FORM_BYTES=[value] sets, read
   as the command line reads them. *)
let with_env_form_bytes value f =
  Unix.putenv "RAYTRACE_MAX_FORM_BYTES" value;
  Fun.protect
    ~finally:(fun () -> Unix.putenv "RAYTRACE_MAX_FORM_BYTES" "")
    (fun () -> match Limits_env.read () with Ok limits -> f limits | Error (`Msg m) -> Alcotest.fail m)

(* Whether [render ~progress valid] has let the spheres of the scene it
   was given go by the time it reports its first row: a collection then
   finds them unreachable. The scene is made in a function of its own, so
   that nothing here holds it but [valid], which is not used after the
   call. *)
let spheres_gone_while_tracing render =
  let weak = Weak.create 1 in
  let valid =
    (fun [@inline never] () ->
      let s = Scene.with_overrides ~width:16 ~height:16 (Scene.grid 5000) in
      Weak.set weak 0 (Some (Scene.spheres s));
      match Scene.validate s with Ok v -> v | Error (`Msg m) -> Alcotest.fail m)
      ()
  in
  let gone = ref None in
  let progress ~rows:_ ~total:_ ~rays:_ =
    if !gone = None then begin
      Gc.full_major ();
      gone := Some (not (Weak.check weak 0))
    end
  in
  render ~progress valid;
  !gone

(* A torus knot of [2 * segments * 16] triangles, smooth, on a plane, as
   the scene [Scene.cgfs] lights: the million-triangle case of
   docs/performance.md, smaller. *)
let knot_obj segments = Mesh.Gen.torus_knot ~p:2 ~q:3 ~radius:2. ~tube:0.3 ~segments ~sides:16

let knot_mesh segments =
  let o = knot_obj segments in
  match
    Mesh.v ~smooth:true ~translate:(Vec3.v 0. 1.45 3.) ~positions:o.positions ~triangles:o.triangles ~normals:o.normals
      ~triangle_normals:o.triangle_normals (Material.v ~specular:300. (Color.v 230. 150. 40.))
  with
  | Ok m -> m
  | Error (`Msg m) -> Alcotest.fail m

(* The words reachable from [p] (and not from the mesh [m]'s placed
   positions, where [p] shares them: a scene without a hierarchy), per
   triangle of [m]. *)
let prepared_bytes_per_triangle (p : Prepared.t) (m : Mesh.t) =
  let shared = if p.vertex == m.positions then Obj.reachable_words (Obj.repr m.positions) else 0 in
  let words = Obj.reachable_words (Obj.repr p) - shared in
  Float.of_int (8 * words) /. Float.of_int (Mesh.triangle_count m)

let peak_mb err =
  List.find_map
    (fun line ->
      match Scanf.sscanf line "peak memory (MB) %f" Fun.id with
      | mb -> Some mb
      | exception (Scanf.Scan_failure _ | Failure _ | End_of_file) -> None)
    (String.split_on_char '\n' err)

let tests =
  [
    Alcotest.test_case "a render lets the scene's spheres go once it has prepared them" `Quick (fun () ->
        (* A million spheres take 232 MB to render, not 324 MB, because
           no caller holds the scene through the render. *)
        let check what render =
          Alcotest.(check (option bool)) (what ^ ": spheres collected when the first row is done") (Some true)
            (spheres_gone_while_tracing render)
        in
        let ok = function Ok _ -> () | Error (`Msg m) -> Alcotest.fail m in
        check "Render.image" (fun ~progress v -> ok (Render.image ~progress v));
        check "Render_jobs.image, one job" (fun ~progress v -> ok (Raytrace_unix.Render_jobs.image ~jobs:1 ~progress v));
        check "Render_jobs.image, two jobs" (fun ~progress v -> ok (Raytrace_unix.Render_jobs.image ~jobs:2 ~split:`Always ~progress v)));
    Alcotest.test_case "a huge frame range is refused before any memory is taken" `Quick (fun () ->
        (* A list of the 10^9 frames' scenes (or of their file names) was
           built first: with 300 MB of address space, an uncaught
           Out_of_memory (status 125). No path has such a frame: refused
           before the scene is read. *)
        let dir = Helpers.temp_dir () in
        check_one_line "--frames 0:999999999" ~code:1
          ~expected:"raytrace: frame 999999999 is outside every camera path, whose frames lie in [0, 1000000]\n"
          (run_limited ~kb:300_000
             [ "render"; Helpers.scene_path "orbit.scene"; "--frames"; "0:999999999"; "-o"; Filename.concat dir "o-%d.ppm" ]);
        Alcotest.(check (array string)) "no frame written" [||] (Sys.readdir dir));
    Alcotest.test_case "a PNG header is held to the pixel bound in force before libpng sees it" `Quick (fun () ->
        (* 10000 x 10000 is within the default bound (2^28 pixels), which
           was the only one checked: the file went to the decoder, and came
           back as "corrupt or truncated data". *)
        let dir = Helpers.temp_dir () in
        let png = Filename.concat dir "big.png" in
        write png (png_header 10000 10000);
        let small = Filename.concat dir "small.ppm" in
        write small "P6 1 1 255\n\000\000\000";
        check_one_line "diff" ~code:1
          ~expected:
            (Printf.sprintf
               "raytrace: %s: image 10000x10000 has 100000000 pixels, more than the limit of 1000000 (set \
                RAYTRACE_MAX_PIXELS to raise it)\n"
               png)
          (Helpers.run
             ~env:(Array.append [| "RAYTRACE_MAX_PIXELS=1000000" |] (Unix.environment ()))
             (Helpers.raytrace ()) [ "diff"; png; small ]));
    Alcotest.test_case "one enormous form of a scene file is refused as it grows" `Quick (fun () ->
        (* 400 KB of numbers in one form: held whole, it would take about
           30 bytes of memory per byte. With the form bound at 100000
           bytes, the parser stops within a chunk of 64 KiB past it. *)
        with_env_form_bytes "100000" (fun limits ->
            let text = "(canvas (width 10) (height 10))\n; a comment\n  (sphere (center " ^ String.concat "" (List.init 200_000 (fun _ -> "0 ")) ^ "))\n" in
            let before = Gc.allocated_bytes () in
            (match Scene_file.of_string ~limits ~file:"big.scene" text with
            | Ok _ -> Alcotest.fail "loaded"
            | Error (`Msg m) ->
                Alcotest.(check string) __LOC__
                  (* Two chunks of 65536 bytes, less the 31 of the canvas form. *)
                  "big.scene:3:3: a form of the scene is more than 131041 bytes long, more than the limit of 100000 \
                   (set RAYTRACE_MAX_FORM_BYTES to raise it)"
                  m);
            let mb = (Gc.allocated_bytes () -. before) /. 1e6 in
            Alcotest.(check bool) (Printf.sprintf "%.1f MB allocated, under 8" mb) true (mb < 8.)));
    Alcotest.test_case "parts with more pixels than their canvas are refused as they are read" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let part i =
          let p = Filename.concat dir (Printf.sprintf "p%d.ppm" i) in
          let code, _, err =
            Helpers.run (Helpers.raytrace ())
              [ "render"; "--width"; "8"; "--height"; "8"; "--region"; "0,0,8,8"; "-o"; p ]
          in
          if code <> 0 then Alcotest.failf "render: %s" err;
          p
        in
        let p1 = part 1 in
        let p2 = Filename.concat dir "p2.ppm" and p3 = Filename.concat dir "p3.ppm" in
        write p2 (In_channel_free.read p1);
        write p3 (In_channel_free.read p1);
        check_one_line "merge" ~code:1
          ~expected:
            (Printf.sprintf
               "raytrace: %s: the parts up to this one hold 128 pixels, more than their 8x8 canvas: they overlap\n" p2)
          (Helpers.run (Helpers.raytrace ()) [ "merge"; p1; p2; p3; "-o"; Filename.concat dir "whole.ppm" ]);
        Alcotest.(check bool) "no merged image" false (Sys.file_exists (Filename.concat dir "whole.ppm")));
    Alcotest.test_case "an allocation that fails anyway is one line saying it is memory" `Quick (fun () ->
        (* 10 MB of numbers in one form, the form bound raised: the parser
           needs about 300 MB, beyond 150 MB of address space. The runtime
           said "Fatal error: out of memory" and aborted (status 134). *)
        let dir = Helpers.temp_dir () in
        let scene = Filename.concat dir "big.scene" in
        write scene ("(sphere (center " ^ String.concat "" (List.init 5_000_000 (fun _ -> "0 ")) ^ "))\n");
        let code, out, err =
          run_limited ~env:[ "RAYTRACE_MAX_FORM_BYTES=1e9" ] ~kb:150_000
            [ "render"; scene; "-o"; Filename.concat dir "out.ppm" ]
        in
        Alcotest.(check int) ("exit status: " ^ err) 1 code;
        Alcotest.(check string) "stdout" "" out;
        let prefix = "raytrace: out of memory: " in
        Alcotest.(check bool) ("one line about memory: " ^ err) true
          (String.length err > String.length prefix
          && String.sub err 0 (String.length prefix) = prefix
          && List.length (String.split_on_char '\n' err) = 2);
        Alcotest.(check bool) "no output" false (Sys.file_exists (Filename.concat dir "out.ppm")));
    Alcotest.test_case "a mesh's prepared scene holds each vertex once, in the order its leaves read them" `Quick (fun () ->
        (* 100,000 triangles. The tracer reads a triangle's corners by
           three offsets a slot in one copy of the mesh's placed
           positions, each vertex once, and a smooth corner's normal where
           its vertex is: no 9 floats of geometry, 3 normal offsets and an
           extent per triangle (104 bytes); 24 bytes of offsets, and 16 of
           the copy and its map to the normals (a vertex for two
           triangles), instead. *)
        let m = knot_mesh 3125 in
        let floor = Shape.Plane (Plane.v ~point:Vec3.zero ~normal:Vec3.oy (Material.v (Color.v 120. 120. 130.))) in
        let s = Scene.with_overrides ~width:8 ~height:8 ~objects:[ floor; Shape.Mesh m ] Scene.cgfs in
        let p = Helpers.prepare s in
        let n = Mesh.triangle_count m in
        Alcotest.(check int) "triangles" 100_000 n;
        (* The tracer's vertices: the mesh's positions copied once, in the
           order the slots (leaf after leaf) first name them
           (Vertex_order), each slot's corners where its triangle's are;
           each smooth corner's normal where its vertex was, found by
           [vsource]. *)
        let next = ref 0 and wrong = ref 0 and unordered = ref 0 and normal = Array.make 3 0. in
        for i = 0 to n do
          if p.kind.(i) = Private.Kind.Smooth_triangle then begin
            (* Object 0 is the plane, the mesh's triangles follow. *)
            let t = p.index.(i) - 1 in
            List.iteri
              (fun c o ->
                if o = !next then next := o + 3 else if o > !next then incr unordered;
                let v = Mesh.vertex m t c in
                if p.vertex.(o) <> v.x || p.vertex.(o + 1) <> v.y || p.vertex.(o + 2) <> v.z then incr wrong;
                (* Its normal where its vertex was: the vertex's number in
                   the mesh, times 3 (the mesh's base is 0). *)
                let j = m.triangles.((3 * t) + c) in
                if p.vsource.(o / 3) <> 3 * j then incr wrong;
                ignore (Mesh.unit_normal m j normal 0);
                let n = 3 * j in
                if p.vnormal.(n) <> normal.(0) || p.vnormal.(n + 1) <> normal.(1) || p.vnormal.(n + 2) <> normal.(2) then
                  incr wrong)
              [ p.at0.(i); p.at1.(i); p.at2.(i) ]
          end
        done;
        Alcotest.(check int) "corners whose position or normal is not their triangle's" 0 !wrong;
        Alcotest.(check int) "vertices placed out of the order of first use" 0 !unordered;
        Alcotest.(check int) "every vertex copied once" (Array.length m.positions) !next;
        Alcotest.(check int) "no other vertex" (Array.length m.positions) (Array.length p.vertex);
        Alcotest.(check int) "geometry: the plane's alone" Private.Kind.stride (Array.length p.geom);
        Alcotest.(check int) "extents: the plane's alone" 1 (Array.length p.extent);
        Alcotest.(check int) "an offset a slot, in each of three arrays" (n + 1) (Array.length p.at0);
        Alcotest.(check int) "no table of the corners' normals" 0 (Array.length p.vcorner);
        (* What is left a triangle: its offsets (24), kind, material, index
           and slot (32), a share of the hierarchy (about 40 with its
           order), of the vertices and of the unit normals (12 each a
           triangle here) and of the vertices' map to the normals (4). Main had
           geom, vcorner and extent besides: 104 bytes more. *)
        let bytes = prepared_bytes_per_triangle p m in
        Alcotest.(check bool) (Printf.sprintf "%.1f bytes a triangle, at most 150" bytes) true (bytes <= 150.));
    Alcotest.test_case "a 500,000-triangle mesh renders within 150 MB, with one job and two" `Slow (fun () ->
        (* Its OBJ text is 42 MB; main before this round peaked at 198 MB
           with either, now 124 MB. The 1M-triangle knot: 382 -> 235 MB. *)
        let dir = Helpers.temp_dir () in
        write (Filename.concat dir "knot.obj") (Mesh.Obj.to_string (knot_obj 15625));
        let scene = Filename.concat dir "knot.scene" in
        write scene
          "(canvas (width 40) (height 30)) (camera (position 0 2.2 -4.5) (look-at 0 0.9 3))\n\
           (plane (point 0 0 0) (normal 0 1 0) (color 120 120 130) (reflective 0.35))\n\
           (mesh (file \"knot.obj\") (color 230 150 40) (specular 300) (translate 0 1.45 3) (smooth true))\n\
           (light ambient (intensity 0.2)) (light point (intensity 0.6) (position -2 4 0))\n";
        List.iter
          (fun jobs ->
            let code, _, err =
              Helpers.run (Helpers.raytrace ())
                [ "render"; scene; "--stats"; "--jobs"; jobs; "-o"; Filename.concat dir "knot.ppm" ]
            in
            Alcotest.(check int) ("exit status: " ^ err) 0 code;
            match peak_mb err with
            | None -> Helpers.skip "the peak of a 500,000-triangle render" ~why:"no peak memory in --stats (not Linux)"
            | Some mb ->
                Alcotest.(check bool) (Printf.sprintf "--jobs %s: peak %.1f MB, at most 150" jobs mb) true (mb <= 150.))
          [ "1"; "2" ]);
  ]
