(* The farm (tiles, regions, merge, frames, docs/farm.md) on the scenes
   with planes, boxes, meshes, patterns, CSG and glass (New_scenes): the same bytes as
   a plain render. (The window's test takes the same table.) *)

(* Run in separate processes at the same time, as on a farm. *)
let concurrently = Test_cli_parts.concurrently
let succeed = Test_cli_parts.succeed
let read = Test_cli_parts.read

let size = [ "--width"; "53"; "--height"; "41" ]

let same what a b =
  if not (String.equal (read a) (read b)) then Alcotest.failf "%s: %s and %s differ" what a b

(* A copy of the scene [name] with a camera path of 3 frames around the
   point (0, 0, 4), in [dir]. *)
let animated dir name =
  let path = Filename.concat dir ("animated-" ^ name) in
  New_scenes.copy_models dir;
  let oc = open_out_bin path in
  output_string oc (read (Helpers.scene_path name));
  output_string oc
    "\n(camera-path (key (frame 0) (position 0 1.5 -2) (look-at 0 0 4)) (key (frame 2) (position 2.5 2 -1) (look-at 0 0 4)))\n";
  close_out oc;
  path

let for_each f () =
  List.iter
    (fun (name, what) ->
      let dir = Helpers.temp_dir () in
      f (Printf.sprintf "%s (%s)" name what) (Helpers.scene_path name) (Filename.concat dir) dir name)
    New_scenes.all

let tests =
  [
    Alcotest.test_case "tiles in separate processes and regions merge into the bytes of one render" `Quick
      (for_each (fun what scene f _ _ ->
           succeed what ([ "render"; scene; "-o"; f "whole.ppm" ] @ size);
           concurrently
             (List.init 5 (fun i ->
                  [ "render"; scene; "--jobs"; "1"; "--tile"; Printf.sprintf "%d/5" (i + 1); "-o"; f (Printf.sprintf "t%d.ppm" i) ]
                  @ size));
           succeed what ([ "merge"; "-o"; f "tiles.ppm" ] @ List.map (fun i -> f (Printf.sprintf "t%d.ppm" i)) [ 3; 0; 4; 2; 1 ]);
           same (what ^ ", tiles") (f "whole.ppm") (f "tiles.ppm");
           (* An L of regions, with anti-aliasing, into PNG. *)
           let aa = [ "--samples"; "2" ] in
           succeed what ([ "render"; scene; "-o"; f "whole.png" ] @ size @ aa);
           List.iter
             (fun (n, r) -> succeed what ([ "render"; scene; "--region"; r; "-o"; f (n ^ ".ppm") ] @ size @ aa))
             [ ("a", "0,0,53,17"); ("b", "0,17,20,41"); ("c", "20,17,53,41") ];
           succeed what [ "merge"; f "c.ppm"; f "a.ppm"; f "b.ppm"; "-o"; f "regions.png" ];
           same (what ^ ", regions") (f "whole.png") (f "regions.png")));
    Alcotest.test_case "frames together, one per process, or in tiles are the same files" `Quick
      (for_each (fun what _ f dir name ->
           let scene = animated dir name in
           succeed what ([ "render"; scene; "--frames"; "0:2"; "-o"; f "all-%d.ppm" ] @ size);
           concurrently (List.map (fun i -> [ "render"; scene; "--frames"; string_of_int i; "-o"; f "one-%d.ppm" ] @ size) [ 0; 1; 2 ]);
           List.iter
             (fun i -> same (Printf.sprintf "%s, frame %d" what i) (f (Printf.sprintf "all-%d.ppm" i)) (f (Printf.sprintf "one-%d.ppm" i)))
             [ 0; 1; 2 ];
           if String.equal (read (f "all-0.ppm")) (read (f "all-1.ppm")) then Alcotest.failf "%s: the camera did not move" what;
           List.iter
             (fun i -> succeed what ([ "render"; scene; "--frames"; "1"; "--tile"; i ^ "/2"; "-o"; f ("f" ^ i ^ ".ppm") ] @ size))
             [ "1"; "2" ];
           succeed what [ "merge"; f "f2.ppm"; f "f1.ppm"; "-o"; f "merged-1.ppm" ];
           same (what ^ ", tiles of frame 1") (f "all-1.ppm") (f "merged-1.ppm")));
  ]
