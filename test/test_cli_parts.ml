(* The raytrace command for render farms: tiles and regions in separate
   processes, merge, frames of an animation, PNG output. *)

let run = Helpers.run
let exe () = Helpers.raytrace ()

let read path =
  match Raytrace_unix.File_io.read path with Ok s -> s | Error (`Msg m) -> Alcotest.fail m

let succeed what args =
  let code, _, err = run (exe ()) args in
  if code <> 0 then Alcotest.failf "%s: raytrace %s exited with %d: %s" what (String.concat " " args) code err

(* One line on stderr, status 1, no output file. *)
let refused what ~out ~expected args =
  let code, _, err = run (exe ()) args in
  Alcotest.(check int) (what ^ ": status") 1 code;
  Alcotest.(check string) what ("raytrace: " ^ expected ^ "\n") err;
  Alcotest.(check bool) (what ^ ": no output file") false (Sys.file_exists out)

(* The processes run at the same time, as on a farm. *)
let concurrently commands =
  let null = Unix.openfile "/dev/null" [ O_WRONLY ] 0 in
  let pids =
    List.map (fun args -> Unix.create_process (exe ()) (Array.of_list (exe () :: args)) Unix.stdin null null) commands
  in
  Unix.close null;
  List.iter
    (fun pid ->
      match Unix.waitpid [] pid with
      | _, WEXITED 0 -> ()
      | _ -> Alcotest.fail "a tile process failed")
    pids

let size = [ "--width"; "97"; "--height"; "61" ]
let small = [ "--width"; "24"; "--height"; "18" ]
let orbit = Helpers.scene_path "orbit.scene"

(* A fresh directory, and the path of a name in it. *)
let fresh () =
  let dir = Helpers.temp_dir () in
  (dir, Filename.concat dir)

let tests =
  [
    Alcotest.test_case "7 tiles in separate processes merge into the bytes of one render" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let scene = Helpers.scene_path "mirrors.scene" in
        let whole = Filename.concat dir "whole.ppm" and merged = Filename.concat dir "merged.ppm" in
        let part i = Filename.concat dir (Printf.sprintf "part-%d.ppm" i) in
        succeed __LOC__ ([ "render"; scene; "-o"; whole ] @ size);
        concurrently (List.init 7 (fun i -> [ "render"; scene; "--jobs"; "1"; "--tile"; Printf.sprintf "%d/7" (i + 1); "-o"; part (i + 1) ] @ size));
        (* In a shuffled order: merge does not care. *)
        succeed __LOC__ ([ "merge"; "-o"; merged ] @ List.map part [ 4; 2; 7; 1; 6; 3; 5 ]);
        Alcotest.(check bool) "merged bytes = whole bytes" true (String.equal (read whole) (read merged)));
    Alcotest.test_case "regions of any shape merge too, into PNG as into PPM" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let scene = Helpers.scene_path "cgfs-camera.scene" in
        let f name = Filename.concat dir name in
        succeed __LOC__ ([ "render"; scene; "-o"; f "whole.png" ] @ size);
        (* An L of two regions and a corner, with uneven splits. *)
        let regions = [ ("a", "0,0,97,20"); ("b", "0,20,30,61"); ("c", "30,20,97,61") ] in
        List.iter (fun (n, r) -> succeed __LOC__ ([ "render"; scene; "--region"; r; "-o"; f (n ^ ".ppm") ] @ size)) regions;
        succeed __LOC__ [ "merge"; f "c.ppm"; f "a.ppm"; f "b.ppm"; "-o"; f "merged.png" ];
        Alcotest.(check bool) "merged PNG = whole PNG" true (String.equal (read (f "whole.png")) (read (f "merged.png"))));
    Alcotest.test_case "merge refuses parts of another scene, size or depth" `Quick (fun () ->
        let _, f = fresh () in
        let scene = Helpers.scene_path "cgfs.scene" in
        let tile ?(scene = scene) ?(extra = []) ?(size = size) i name =
          succeed __LOC__ ([ "render"; scene; "--tile"; Printf.sprintf "%d/2" i; "-o"; f name ] @ size @ extra)
        in
        tile 1 "t1.ppm";
        tile 2 "t2.ppm";
        tile ~extra:[ "--depth"; "1" ] 2 "depth.ppm";
        tile ~size:[ "--width"; "98"; "--height"; "61" ] 2 "wide.ppm";
        tile ~scene:(Helpers.scene_path "cgfs-camera.scene") 2 "other.ppm";
        let out = f "out.ppm" in
        let merge what second expected = refused what ~out ~expected [ "merge"; f "t1.ppm"; f second; "-o"; out ] in
        merge "depth" "depth.ppm" (Printf.sprintf "%s was rendered with depth 1, %s with depth 3: they do not fit together" (f "depth.ppm") (f "t1.ppm"));
        merge "size" "wide.ppm" (Printf.sprintf "%s is a part of a 98x61 image, %s of a 97x61 one: they do not fit together" (f "wide.ppm") (f "t1.ppm"));
        let code, _, err = run (exe ()) [ "merge"; f "t1.ppm"; f "other.ppm"; "-o"; out ] in
        Alcotest.(check int) __LOC__ 1 code;
        if not (Astring_free.contains err "was rendered from a different scene than") then Alcotest.failf "scene: %s" err;
        (* Tile 2 of 2 is rows 61 / 2 = 30 to 60: 31 rows of 97 pixels. *)
        refused "a missing tile" ~out
          ~expected:"the parts leave 3007 of 5917 pixels uncovered, the first at (0, 30) (column, row): a part is missing"
          [ "merge"; f "t1.ppm"; "-o"; out ];
        refused "a whole image" ~out
          ~expected:
            (f "whole.ppm"
            ^ ": not a part of a raytrace render (its header has no \"# raytrace-part 1\" line); render parts with raytrace render --tile or --region")
          (succeed __LOC__ ([ "render"; scene; "-o"; f "whole.ppm" ] @ size);
           [ "merge"; f "t1.ppm"; f "whole.ppm"; "-o"; out ]));
    Alcotest.test_case "tiles rendered before and after the mesh file changed do not merge, nor do frames" `Quick
      (fun () ->
        let _, f = fresh () in
        let write name text =
          let oc = open_out_bin (f name) in
          output_string oc text;
          close_out oc
        in
        let triangle x = Printf.sprintf "v -1 -1 0\nv %s -1 0\nv 0 1 0\nf 1 2 3\n" x in
        write "m.obj" (triangle "1");
        write "s.scene"
          "(canvas (width 8) (height 8))\n(mesh (file \"m.obj\") (color 255 0 0) (translate 0 0 3))\n(light ambient (intensity 1))\n";
        let tile i name = succeed __LOC__ [ "render"; f "s.scene"; "--tile"; Printf.sprintf "%d/2" i; "-o"; f name ] in
        tile 1 "t1.ppm";
        tile 2 "t2.ppm";
        succeed __LOC__ [ "merge"; f "t1.ppm"; f "t2.ppm"; "-o"; f "same.ppm" ];
        (* The scene's text is the same; the mesh it reads is not. *)
        write "m.obj" (triangle "1.5");
        tile 2 "t2-new.ppm";
        let out = f "torn.ppm" in
        let code, _, err = run (exe ()) [ "merge"; f "t1.ppm"; f "t2-new.ppm"; "-o"; out ] in
        Alcotest.(check int) __LOC__ 1 code;
        if not (Astring_free.contains err (f "t2-new.ppm" ^ " was rendered from a different scene than " ^ f "t1.ppm"))
        then Alcotest.failf "torn picture: %s" err;
        Alcotest.(check bool) __LOC__ false (Sys.file_exists out);
        (* The same bytes again: the digest is of the contents, not of the
           file's time. *)
        write "m.obj" (triangle "1");
        tile 2 "t2-again.ppm";
        succeed __LOC__ [ "merge"; f "t1.ppm"; f "t2-again.ppm"; "-o"; f "again.ppm" ];
        Alcotest.(check bool) __LOC__ true (String.equal (read (f "same.ppm")) (read (f "again.ppm"))));
    Alcotest.test_case "bad tiles and regions are one line, no file" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let out = Filename.concat dir "p.ppm" in
        refused "tile 8 of 7" ~out ~expected:"tile 8/7: the tile number must lie in [1, 7]" [ "render"; "--tile"; "8/7"; "-o"; out ];
        refused "more tiles than rows" ~out ~expected:"tile 1/9: the canvas has only 8 rows, fewer than 9 tiles"
          [ "render"; "--height"; "8"; "--tile"; "1/9"; "-o"; out ];
        refused "region outside" ~out ~expected:"region columns 0 to 601: need 0 <= x0 < x1 <= 600 (the canvas width)"
          [ "render"; "--region"; "0,0,601,10"; "-o"; out ];
        let png = Filename.concat dir "p.png" in
        refused "part as PNG" ~out:png
          ~expected:(png ^ ": a part of an image is written as PPM, whose header records what raytrace merge checks; name it .ppm")
          [ "render"; "--tile"; "1/2"; "-o"; png ];
        let code, _, err = run (exe ()) [ "render"; "--tile"; "1/2"; "--region"; "0,0,1,1"; "-o"; out ] in
        Alcotest.(check int) __LOC__ 124 code;
        if not (Astring_free.contains err "--tile and --region exclude each other") then Alcotest.failf "%s" err);
    Alcotest.test_case "a tile to stdout is the part file" `Quick (fun () ->
        let code, out, _ = run (exe ()) [ "render"; "--tile"; "2/3"; "--width"; "4"; "--height"; "6"; "-o"; "-" ] in
        Alcotest.(check int) __LOC__ 0 code;
        match Part.of_string out with
        | Ok p -> Alcotest.(check (list int)) __LOC__ [ 0; 2; 4; 2 ] [ p.region.x; p.region.y; p.region.w; p.region.h ]
        | Error (`Msg m) -> Alcotest.fail m);
    Alcotest.test_case "render writes PNG for .png names, and diff reads it" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let png = Filename.concat dir "x.png" and ppm = Filename.concat dir "x.ppm" in
        succeed __LOC__ [ "render"; "--width"; "30"; "--height"; "20"; "-o"; png ];
        succeed __LOC__ [ "render"; "--width"; "30"; "--height"; "20"; "-o"; ppm ];
        Alcotest.(check string) __LOC__ "\137PNG" (String.sub (read png) 0 4);
        let code, out, _ = run (exe ()) [ "diff"; "--max-diff"; "0"; png; ppm ] in
        Alcotest.(check int) __LOC__ 0 code;
        Alcotest.(check string) __LOC__ "pixels=600 differing=0 differing_gt1=0 max_abs=0 mean_abs=0.000000 psnr=inf\n" out);
    Alcotest.test_case "frames rendered together or one per process are the same files" `Quick (fun () ->
        let dir, f = fresh () in
        succeed __LOC__ ([ "render"; orbit; "--frames"; "10:13"; "-o"; f "all-%03d.ppm" ] @ small);
        Alcotest.(check (list string)) __LOC__ [ "all-010.ppm"; "all-011.ppm"; "all-012.ppm"; "all-013.ppm" ]
          (List.sort String.compare (Array.to_list (Sys.readdir dir)));
        concurrently (List.map (fun i -> [ "render"; orbit; "--frames"; string_of_int i; "-o"; f "one-%d.ppm" ] @ small) [ 10; 11; 12; 13 ]);
        List.iter
          (fun i ->
            Alcotest.(check bool) (string_of_int i) true
              (String.equal (read (f (Printf.sprintf "all-%03d.ppm" i))) (read (f (Printf.sprintf "one-%d.ppm" i)))))
          [ 10; 11; 12; 13 ];
        (* Frame 12 is a key: the camera at (4.5, 1, 3.5) looking at (0, 0, 3.5). *)
        let still = f "still.scene" in
        let text = read orbit in
        let rec find i = if String.sub text i 8 = "(epsilon" then i else find (i + 1) in
        let cut = find 0 in
        let oc = open_out still in
        output_string oc ("(camera (position 4.5 1 3.5) (look-at 0 0 3.5))\n" ^ String.sub text cut (String.length text - cut));
        close_out oc;
        succeed __LOC__ ([ "render"; still; "-o"; f "still.ppm" ] @ small);
        Alcotest.(check bool) "frame 12 = the still" true (String.equal (read (f "still.ppm")) (read (f "all-012.ppm"))));
    Alcotest.test_case "a frame's still is frame 0, which here is the reference view" `Quick (fun () ->
        let _, f = fresh () in
        succeed __LOC__ [ "render"; Helpers.scene_path "orbit.scene"; "--frames"; "0"; "--width"; "30"; "--height"; "30"; "-o"; f "o.ppm" ];
        succeed __LOC__ [ "render"; Helpers.scene_path "cgfs.scene"; "--width"; "30"; "--height"; "30"; "-o"; f "c.ppm" ];
        Alcotest.(check bool) __LOC__ true (String.equal (read (f "o.ppm")) (read (f "c.ppm"))));
    Alcotest.test_case "tiles of a frame merge into that frame" `Quick (fun () ->
        let _, f = fresh () in
        succeed __LOC__ ([ "render"; orbit; "--frames"; "5"; "-o"; f "whole.ppm" ] @ small);
        List.iter (fun i -> succeed __LOC__ ([ "render"; orbit; "--frames"; "5"; "--tile"; i ^ "/2"; "-o"; f ("t" ^ i ^ ".ppm") ] @ small)) [ "1"; "2" ];
        succeed __LOC__ [ "merge"; f "t1.ppm"; f "t2.ppm"; "-o"; f "m.ppm" ];
        Alcotest.(check bool) __LOC__ true (String.equal (read (f "whole.ppm")) (read (f "m.ppm")));
        succeed __LOC__ ([ "render"; orbit; "--frames"; "6"; "--tile"; "2/2"; "-o"; f "t6.ppm" ] @ small);
        refused "frames differ" ~out:(f "x.ppm")
          ~expected:(Printf.sprintf "%s was rendered with frame 6, %s with frame 5: they do not fit together" (f "t6.ppm") (f "t1.ppm"))
          [ "merge"; f "t1.ppm"; f "t6.ppm"; "-o"; f "x.ppm" ]);
    Alcotest.test_case "bad frames are one line, no file" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let out = Filename.concat dir "f-%d.ppm" in
        refused "beyond the path" ~out:(Filename.concat dir "f-49.ppm")
          ~expected:"frame 49 is outside the camera path, which runs from frame 0 to 48"
          [ "render"; orbit; "--frames"; "47:49"; "-o"; out ];
        Alcotest.(check (array string)) "not even the frames in range" [||] (Sys.readdir dir);
        refused "a still scene" ~out:(Filename.concat dir "f-0.ppm")
          ~expected:"the scene has no camera-path, so it has no frames to render" [ "render"; "--frames"; "0"; "-o"; out ];
        let plain = Filename.concat dir "plain.ppm" in
        refused "no frame number in the name" ~out:plain
          ~expected:(plain ^ ": with --frames 0:2, the output needs the frame number, e.g. anim-%04d.ppm")
          [ "render"; orbit; "--frames"; "0:2"; "-o"; plain ];
        let code, _, err = run (exe ()) [ "render"; orbit; "--frames"; "3:1"; "-o"; out ] in
        Alcotest.(check int) __LOC__ 124 code;
        if not (Astring_free.contains err "the first frame 3 comes after") then Alcotest.failf "%s" err);
    Alcotest.test_case "frame numbers fill the first %d or %0Nd of the name, as printf does" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        List.iter
          (fun pattern ->
            succeed __LOC__ [ "render"; orbit; "--frames"; "7"; "--width"; "4"; "--height"; "4"; "-o"; Filename.concat dir pattern ])
          [ "a-%04d.ppm"; "b-%d.png"; "50%-%03d-%d.ppm"; "still.ppm" ];
        Alcotest.(check (list string)) __LOC__ [ "50%-007-%d.ppm"; "a-0007.ppm"; "b-7.png"; "still.ppm" ]
          (List.sort String.compare (Array.to_list (Sys.readdir dir))));
    Alcotest.test_case "merge has a manual with examples" `Quick (fun () ->
        let code, out, _ = run (exe ()) [ "merge"; "--help=plain" ] in
        Alcotest.(check int) __LOC__ 0 code;
        if not (Astring_free.contains out "EXAMPLES") then Alcotest.fail "no EXAMPLES");
  ]
