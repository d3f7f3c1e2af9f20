(* The benchmark against Embree (issue 28, make bench-embree) is not a test,
   but its instrument is: the C driver bench/embree/embree_rays.c builds
   against Debian's libembree-dev, and on a small mesh it finds the same
   hit mask as raytrace on raytrace's own camera rays (Mesh_rays), and the
   same blocked shadow rays from their hits toward a light, in both of
   Embree's modes. Without Embree the check is skipped (a failure under
   CI=true, where make deps installs it). *)

open Raytrace

let header = "/usr/include/embree3/rtcore.h"
let source = "../bench/embree/embree_rays.c"

let write path text =
  let oc = open_out_bin path in
  output_string oc text;
  close_out oc

let read path =
  let ic = open_in_bin path in
  let s = really_input_string ic (in_channel_length ic) in
  close_in ic;
  s

(* The driver, built once per run in a fresh directory; [None] if Embree's
   header is not here. *)
let driver =
  lazy
    (if not (Sys.file_exists header) then None
     else
       let exe = Filename.concat (Helpers.temp_dir ()) "embree_rays" in
       let cmd = Printf.sprintf "cc -O2 -Wall -o %s %s -lembree3" (Filename.quote exe) (Filename.quote source) in
       if Sys.command cmd <> 0 then Alcotest.failf "the Embree driver does not build: %s" cmd;
       Some exe)

let differ a b =
  let n = ref 0 in
  String.iteri (fun k c -> if (c <> '\000') <> (Bytes.get b k <> '\000') then incr n) a;
  !n

(* Raytrace's mask of [mesh] at 64 x 64 from [camera], and Embree's in each
   mode, on the same rays: they must agree on every pixel; so must their
   masks of the shadow rays from the hits toward [light]. *)
let same_masks name (mesh : Mesh.Obj.t) camera light () =
  match Lazy.force driver with
  | None -> Helpers.skip ("embree " ^ name) ~why:("no " ^ header ^ " (apt-get install libembree-dev)")
  | Some exe ->
      let dir = Helpers.temp_dir () in
      let obj = Filename.concat dir "mesh.obj" and scene = Filename.concat dir "mesh.scene" in
      let b = Buffer.create 65536 in
      Mesh.Obj.to_buffer b mesh;
      write obj (Buffer.contents b);
      write scene
        (Printf.sprintf
           "(canvas (width 64) (height 64)) (viewport (width 1) (height 1) (distance 1))\n%s\n\
            (recursion-depth 0) (mesh (file \"mesh.obj\") (color 230 150 40)) (light ambient (intensity 1))\n"
           camera);
      let s = match Files.read_scene scene with Ok s -> s | Error (`Msg m) -> Alcotest.fail m in
      let p = Prepared.prepare s in
      let ours = Bytes.create (64 * 64) in
      let r = Mesh_rays.cast p ours in
      (* A mask worth comparing: neither all hits nor all misses. *)
      if r.hits < 200 || r.hits > (64 * 64) - 200 then Alcotest.failf "%d hits of %d: move the camera" r.hits r.rays;
      let alone = Bytes.create (64 * 64) in
      ignore (Mesh_rays.cast_camera p alone);
      Alcotest.(check int) "the camera rays' search alone finds the pixels' hits" 0 (differ (Bytes.to_string alone) ours);
      let rays = Filename.concat dir "rays" and mask = Filename.concat dir "ours.mask" in
      Mesh_rays.write_rays p rays;
      write mask (Bytes.to_string ours);
      let shadow_rays = Mesh_rays.shadow_rays p ~light in
      let n = Array.length shadow_rays / 6 in
      Alcotest.(check int) "a shadow ray per hit" r.hits n;
      let blocked = Bytes.create n in
      let b = Mesh_rays.cast_shadows p shadow_rays ~rounds:1 blocked in
      if b.hits < 50 || b.hits > n - 50 then Alcotest.failf "%d of %d shadow rays blocked: move the light" b.hits n;
      let shadows = Filename.concat dir "shadows" and smask = Filename.concat dir "ours.smask" in
      Mesh_rays.write_floats shadow_rays shadows;
      write smask (Bytes.to_string blocked);
      List.iter
        (fun mode ->
          let theirs = Filename.concat dir "embree.mask" and their_shadows = Filename.concat dir "embree.smask" in
          let cmd =
            String.concat " "
              (List.map Filename.quote
                 ([ exe ] @ mode
                 @ [ "--compare"; mask; "--shadows"; shadows; their_shadows; "--compare-shadows"; smask; obj; rays; theirs ]))
            ^ " > " ^ Filename.quote (Filename.concat dir "row")
          in
          if Sys.command cmd <> 0 then Alcotest.failf "%s failed" cmd;
          let theirs = read theirs in
          Alcotest.(check int) "one byte per pixel" (64 * 64) (String.length theirs);
          Alcotest.(check int) (String.concat " " ("pixels that differ, embree" :: mode)) 0 (differ theirs ours);
          let their_shadows = read their_shadows in
          Alcotest.(check int) "one byte per shadow ray" n (String.length their_shadows);
          Alcotest.(check int) (String.concat " " ("shadow rays that differ, embree" :: mode)) 0 (differ their_shadows blocked);
          (* The driver's own counts, the columns make bench-embree prints:
             differ (the 9th) and the shadow rays' (the 12th, the last). *)
          let row = List.filter (( <> ) "") (String.split_on_char ' ' (String.trim (read (Filename.concat dir "row")))) in
          Alcotest.(check int) "the driver's columns" 12 (List.length row);
          Alcotest.(check string) "the driver's count" "0" (List.nth row 8);
          Alcotest.(check string) "the driver's count of shadow rays" "0" (List.nth row 11))
        [ []; [ "--robust" ] ]

let tests =
  [
    Alcotest.test_case "Embree's two modes find raytrace's hit masks of camera and shadow rays on a 2048-triangle knot" `Quick
      (same_masks "knot"
         (Mesh.Gen.torus_knot ~p:2 ~q:3 ~radius:2. ~tube:0.35 ~segments:128 ~sides:8)
         "(camera (position 0 0.8333333333333334 -8.333333333333334) (look-at 0 -0.6111111111111112 0))"
         (Vec3.v (-3.) 5. (-5.)));
    Alcotest.test_case "Embree's two modes find raytrace's hit masks of camera and shadow rays on a 2048-triangle terrain" `Quick
      (same_masks "terrain"
         (Mesh.Gen.terrain ~seed:1 ~nx:32 ~nz:32 ~size:10. ~height:1.)
         "(camera (position 0 3 -7) (look-at 0 0 0))" (Vec3.v 8. 1.5 2.));
  ]
