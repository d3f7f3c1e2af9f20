(* An OBJ text read on two cores: the part after a line start read apart
   (Obj_parts.create_part) and joined to the reader of the text before
   (Obj_parts.join), as Files.read_mesh does with a child process. The
   mesh, its skipped counts and its errors must be one reader's. *)
open Raytrace

let name = "t.obj"

let one ?(max_vertices = 1000) ?(max_triangles = 1000) text =
  Mesh.Obj.of_string ~name ~max_vertices ~max_triangles text

(* [text] cut at line start [split]: the part after it read apart, then
   joined, or read by the first reader where it cannot be joined (the
   steps of Files.read_mesh, without the fork); and whether it was
   joined. *)
let two ?(max_vertices = 1000) ?(max_triangles = 1000) text split =
  let n = String.length text in
  let p = Mesh.Obj.create ~name ~max_vertices ~max_triangles in
  let rest () = match Mesh.Obj.feed p text split (n - split) with Error _ as e -> e | Ok () -> Mesh.Obj.finish p in
  match Mesh.Obj.feed p text 0 split with
  | Error _ as e -> (e, false)
  | Ok () -> (
      match Helpers.obj_part_joined p ~name ~max_vertices ~max_triangles text split (n - split) with
      | Some m -> (Ok m, true)
      | None -> (rest (), false))

(* Equal meshes that share their two numberings alike (48 bytes a
   triangle rather than 72), or equal errors. *)
let same what a b =
  match (a, b) with
  | Ok (a : Mesh.Obj.t), Ok (b : Mesh.Obj.t) ->
      if not (Mesh.Obj.equal a b) then Alcotest.failf "%s: the meshes differ" what;
      if (a.triangle_normals == a.triangles) <> (b.triangle_normals == b.triangles) then
        Alcotest.failf "%s: the numberings are shared by one read only" what
  | Error (`Msg a), Error (`Msg b) -> if a <> b then Alcotest.failf "%s: error %S, not %S" what b a
  | Ok _, Error (`Msg e) -> Alcotest.failf "%s: refused on two cores (%s)" what e
  | Error (`Msg e), Ok _ -> Alcotest.failf "%s: read on two cores, but one refuses it: %s" what e

let line_starts text =
  0 :: List.filter_map (fun k -> if text.[k] = '\n' then Some (k + 1) else None) (List.init (String.length text) Fun.id)

(* Every line start of [text] as the cut; the number of cuts joined. *)
let every_split ?max_vertices ?max_triangles what text =
  let expected = one ?max_vertices ?max_triangles text in
  List.fold_left
    (fun joined split ->
      let r, j = two ?max_vertices ?max_triangles text split in
      same (Printf.sprintf "%s cut at byte %d" what split) expected r;
      if j then joined + 1 else joined)
    0 (line_starts text)

let crlf text = String.concat "\r\n" (String.split_on_char '\n' text)
let unended text = if text <> "" && text.[String.length text - 1] = '\n' then String.sub text 0 (String.length text - 1) else text

(* Skipped statements between all lines. *)
let noisy text =
  String.concat "\n# a comment\no part\ng group\nvt 0.5 0.5\ns 1\n" (String.split_on_char '\n' text)

let square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"

(* Every vertex form, polygons, negative indices of all three kinds,
   normals numbered as vertices but relative ones that resolve apart. *)
let valid =
  [
    ("squares", square ^ "f 1 2 3 4\nv 0.5 2 0\nf 5 4 3 2 1\nf -1 -2 -3\nf 1 2 -1 -2\n");
    ("every form", square ^ "vt 0 0\nvt 1 0\nvn 0 0 1\nvn 0 1 0\n"
      ^ "f 1 2 3\nf 1/1 2/2 3/1\nf 1//1 2//2 3//1\nf 1/1/1 2/2/2 3/1/1 4/2/2\nf 4/-1/-2 3/-2 2//-1\n");
    ("negative indices", square ^ "f -4 -3 -1\nvn 0 0 1\nv 9 9 9\nf -1//-1 -2//1 -5//-1\nvn 1 0 0\nv 8 8 8\nf -1//-1 -2//-2 -3//-1\n");
    ("numbered alike, then not", square ^ "vn 0 0 1\nvn 0 1 0\nvn 1 0 0\nvn 1 1 0\nf 1//1 2//2 3//3\nf 4//4 -2//-2 -1//-1\nv 5 5 5\nf -1//-1 1//1 2//2\n");
    ("many lines", String.concat "" (List.init 30 (fun k -> Printf.sprintf "v %d 0.%d -%d\nvn 0 %d 1\n" k k k k))
      ^ String.concat "" (List.init 28 (fun k -> Printf.sprintf "f %d//%d %d//-1 -1//%d\n" (k + 1) (k + 1) (k + 2) (k + 3))));
    ("rich", Test_obj_file.rich);
  ]

let knot = Mesh.Obj.to_string (Mesh.Gen.torus_knot ~p:2 ~q:3 ~radius:1. ~tube:0.2 ~segments:9 ~sides:4)
let terrain = Mesh.Obj.to_string (Mesh.Gen.terrain ~seed:3 ~nx:5 ~nz:4 ~size:2. ~height:0.5)

(* Errors that only the text before tells: each is one reader's, at its
   line and column, wherever the cut. *)
let v3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nf 1/1/1 2/1/1 3/1/1\n"
let errors =
  [
    ("a bad number", v3 ^ v3 ^ "v 1 2 x\n" ^ v3);
    ("a vertex index out of range", v3 ^ v3 ^ "f 1 2 7\n" ^ v3);
    ("a vertex index in range only given the text before", v3 ^ v3 ^ "f 1 2 6\nf 1 2 99\n");
    ("a negative index out of range", v3 ^ v3 ^ "f -1 -2 -7\n");
    ("a normal index out of range", v3 ^ "vn 0 1 0\n" ^ v3 ^ "f 1//1 2//4 3//1\n");
    ("a negative normal index out of range", v3 ^ "f 1//1 2//-1 3//-2\nvn 1 0 0\nf 1//-3 2//1 3//1\n");
    ("a texture index out of range", v3 ^ v3 ^ "f 1/2 2/2 3/3\n");
    ("a negative texture index out of range", v3 ^ v3 ^ "f 1/-2 2/2 3/1\nf 1/-3 2/2 3/1\n");
    ("an index 0", v3 ^ v3 ^ "f 0 1 2\n");
    ("an index of 19 digits", v3 ^ v3 ^ "f 1 2 1000000000000000000\n");
    ("a face of 2 vertices", v3 ^ v3 ^ "f 1 2\n");
  ]

let tests =
  [
    Alcotest.test_case "a text cut at any line start and read in two parts is the text read whole" `Quick (fun () ->
        let texts =
          valid @ [ ("a knot of Mesh_gen", knot); ("a terrain of Mesh_gen", terrain) ]
          |> List.concat_map (fun (what, t) ->
                 [ (what, t); (what ^ ", CRLF", crlf t); (what ^ ", no last line end", unended t);
                   (what ^ ", comments, vt, o, g and s between lines", noisy t); (what ^ ", both", unended (crlf (noisy t))) ])
        in
        List.iter
          (fun (what, text) ->
            let starts = List.length (line_starts text) in
            let joined = every_split what text in
            (* A valid text's part is always joined: the two cores are used. *)
            if joined <> starts then Alcotest.failf "%s: joined at %d of %d cuts" what joined starts)
          texts);
    Alcotest.test_case "the knot's numberings are one array, read in one part or two" `Quick (fun () ->
        let middle = String.index_from knot (String.length knot / 2) '\n' + 1 in
        match (one knot, two knot middle) with
        | Ok a, (Ok b, true) ->
            Alcotest.(check bool) __LOC__ true (a.triangle_normals == a.triangles);
            Alcotest.(check bool) __LOC__ true (b.triangle_normals == b.triangles)
        | _ -> Alcotest.fail "the knot was not read in two parts");
    Alcotest.test_case "a part of several blocks, its normals numbered as its vertices, relatively or apart, joins as one read" `Quick
      (fun () ->
        (* A part sends its arrays a block of 65536 numbers at a time,
           and a block of normal numbers equal to its vertex numbers, with
           no relative index, as a mark only: 70,000 vertices are 4 blocks
           of positions; 52,000 triangles are 3 blocks of numbers, the
           middle faces alike but relative ([-1//-1]: equal once re-based,
           since the text has as many normals as vertices) or apart. *)
        let vertices = String.concat "" (List.init 70_000 (fun k -> Printf.sprintf "v %d %d.5 -%d\nvn 0 %d 1\n" (k mod 97) (k mod 89) k k)) in
        let alike k = Printf.sprintf "f %d//%d %d//%d %d//%d\n" (k + 1) (k + 1) (k + 2) (k + 2) (k + 3) (k + 3) in
        let faces middle = String.concat "" (List.init 52_000 (fun k -> if k >= 24_000 && k < 26_000 then middle k else alike k)) in
        let texts =
          [ ("alike", vertices ^ faces alike); ("relative", vertices ^ faces (fun _ -> "f -1//-1 -2//-2 -3//-3\n"));
            ("apart", vertices ^ faces (fun k -> Printf.sprintf "f %d//%d %d//%d %d//%d\n" (k + 1) (k + 2) (k + 2) (k + 3) (k + 3) (k + 1)));
            ("apart before the cut", vertices ^ "f 1//2 2//3 3//1\n" ^ faces alike) ]
        in
        List.iter
          (fun (what, text) ->
            let n = String.length text in
            let expected = one ~max_vertices:100_000 ~max_triangles:100_000 text in
            List.iter
              (fun at ->
                let split = if at = 0 then 0 else String.index_from text at '\n' + 1 in
                match two ~max_vertices:100_000 ~max_triangles:100_000 text split with
                | r, true -> same (Printf.sprintf "%s cut at byte %d" what split) expected r
                | _, false -> Alcotest.failf "%s: not joined at byte %d" what split)
              [ 0; String.length vertices / 2; String.length vertices; n / 2; n - 100 ])
          texts);
    Alcotest.test_case "a join whose bytes are cut short or not a part's raises, and leaves the reader as it was" `Quick (fun () ->
        let text = knot in
        let split = String.index_from text (String.length text / 2) '\n' + 1 in
        let sent = Buffer.create 4096 in
        let q = Obj_parts.create_part ~output:(Buffer.add_subbytes sent) ~name ~max_vertices:1000 ~max_triangles:1000 in
        let part =
          match Result.bind (Mesh.Obj.feed q text split (String.length text - split)) (fun () -> Obj_parts.finish_part q) with
          | Ok part -> part
          | Error (`Msg e) -> Alcotest.fail e
        in
        let bytes = Buffer.to_bytes sent in
        let input bytes =
          let at = ref 0 in
          fun b off len ->
            if !at + len > Bytes.length bytes then raise End_of_file;
            Bytes.blit bytes !at b off len;
            at := !at + len
        in
        let corrupt = Bytes.copy bytes in
        Bytes.set corrupt 0 '\009';
        List.iter
          (fun (what, bytes, raised) ->
            let p = Mesh.Obj.create ~name ~max_vertices:1000 ~max_triangles:1000 in
            ignore (Mesh.Obj.feed p text 0 split);
            (match Obj_parts.join p part ~input:(input bytes) with
            | _ -> Alcotest.failf "%s: joined" what
            | exception e -> if not (raised e) then Alcotest.failf "%s: raised %s" what (Printexc.to_string e));
            (* The reader reads the rest itself, as it would have. *)
            same what (one text) (Result.bind (Mesh.Obj.feed p text split (String.length text - split)) (fun () -> Mesh.Obj.finish p)))
          [ ("cut short", Bytes.sub bytes 0 (Bytes.length bytes - 8), ( = ) End_of_file);
            ("not a part's", corrupt, function Failure _ -> true | _ -> false) ]);
    Alcotest.test_case "an error after the cut is one reader's, at its line and column" `Quick (fun () ->
        List.iter
          (fun (what, text) ->
            (match one text with Ok _ -> Alcotest.failf "%s: read" what | Error _ -> ());
            ignore (every_split what text);
            ignore (every_split (what ^ ", CRLF") (crlf text));
            ignore (every_split (what ^ ", noisy") (noisy text)))
          errors);
    Alcotest.test_case "the bounds on vertices, normals and triangles crossed after the cut are one reader's errors" `Quick
      (fun () ->
        let text = String.concat "" (List.init 12 (fun k -> Printf.sprintf "v %d 0 0\nvn 0 0 %d\n" k k))
                   ^ String.concat "" (List.init 10 (fun k -> Printf.sprintf "f %d//1 %d//2 %d//3 %d//4\n" (k + 1) (k + 2) (k + 3) (k + 1))) in
        (* 12 vertices and normals, 20 triangles. *)
        List.iter
          (fun (max_vertices, max_triangles) ->
            let what = Printf.sprintf "at most %d vertices and %d triangles" max_vertices max_triangles in
            let joined = every_split ~max_vertices ~max_triangles what text in
            let fits = max_vertices >= 12 && max_triangles >= 20 in
            if fits && joined <> List.length (line_starts text) then Alcotest.failf "%s: joined at %d cuts" what joined;
            if (not fits) && joined > 0 then Alcotest.failf "%s: joined at %d cuts, over the bounds" what joined)
          [ (12, 20); (11, 20); (12, 19); (6, 20); (12, 10); (1, 1) ]);
    Alcotest.test_case "join refuses a reader that is finished, failed or not at a line start" `Quick (fun () ->
        let reader text =
          let p = Mesh.Obj.create ~name ~max_vertices:10 ~max_triangles:10 in
          ignore (Mesh.Obj.feed p text 0 (String.length text));
          p
        in
        let join p = Helpers.obj_part_joined p ~name ~max_vertices:10 ~max_triangles:10 "f 1 2 3\n" 0 8 in
        Alcotest.(check bool) __LOC__ true (Option.is_some (join (reader v3)));
        Alcotest.(check bool) "mid-line" true (Option.is_none (join (reader (v3 ^ "v 1"))));
        Alcotest.(check bool) "failed" true (Option.is_none (join (reader (v3 ^ "v 1 2 x\n"))));
        let p = reader v3 in
        ignore (Mesh.Obj.finish p);
        Alcotest.(check bool) "finished" true (Option.is_none (join p));
        Alcotest.(check bool) "out of range" true (Option.is_none (join (reader "v 1 1 1\n")));
        match Obj_parts.finish_part (Mesh.Obj.create ~name ~max_vertices:1 ~max_triangles:1) with
        | _ -> Alcotest.fail "finish_part of a whole text's reader"
        | exception Invalid_argument _ -> ());
    Alcotest.test_case "a mesh file read on two cores is the one read on one, from a child process" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let path = Filename.concat dir "t.obj" in
        let write text =
          let oc = open_out_bin path in
          output_string oc text;
          close_out oc
        in
        let read ?jobs ?on_part () = Raytrace_unix.Files.read_mesh ?jobs ~split_bytes:1 ?on_part path in
        Fun.protect ~finally:(fun () -> (try Sys.remove path with Sys_error _ -> ()); Unix.rmdir dir) @@ fun () ->
        let big = Mesh.Obj.to_string (Mesh.Gen.torus_knot ~p:2 ~q:3 ~radius:1. ~tube:0.2 ~segments:60 ~sides:8) in
        write big;
        let parts = ref [] in
        same "a knot of 960 triangles" (read ~jobs:1 ()) (read ~jobs:2 ~on_part:(fun ~pid k -> parts := (pid, k) :: !parts) ());
        (match !parts with
        | [ (pid, k) ] ->
            (* The part is a child's: a fork that fails reads it in this process. *)
            if pid = Unix.getpid () then Alcotest.fail "the part was read by this process, not a child";
            (* The faces follow the positions and normals, in the second half. *)
            if k <> 960 then Alcotest.failf "the child's part has %d triangles of 960" k
        | l -> Alcotest.failf "%d parts joined" (List.length l));
        let none = ref 0 in
        ignore (read ~jobs:1 ~on_part:(fun ~pid:_ _ -> incr none) ());
        ignore (Raytrace_unix.Files.read_mesh ~jobs:2 ~on_part:(fun ~pid:_ _ -> incr none) path);
        Alcotest.(check int) "one job, or a file under 4 MiB: no child" 0 !none;
        List.iter
          (fun (what, text) ->
            write text;
            same what (read ~jobs:1 ()) (read ~jobs:2 ()))
          (valid @ [ ("CRLF", crlf big); ("no last line end", unended big); ("noisy", noisy big) ]);
        (* Errors in the second half, whose line only the first tells. *)
        let lines = List.length (String.split_on_char '\n' big) in
        List.iter
          (fun bad ->
            write (big ^ bad ^ "f 1 2 3\n");
            match read ~jobs:2 () with
            | Ok _ -> Alcotest.failf "%S read" bad
            | Error (`Msg m) as e ->
                same bad (read ~jobs:1 ()) e;
                let at = Printf.sprintf "%s:%d:" path lines in
                if not (String.length m > String.length at && String.sub m 0 (String.length at) = at) then
                  Alcotest.failf "the error %S is not at %s" m at)
          [ "v 1 2 x\n"; "f 1 2 999\n"; "f -999 1 2\n"; "f 1 0 2\n"; "f 1//1 2//2 3//9999\n"; "f 1/1 2 3\n" ];
        (* An error in the first half: the child's part is waited for, then dropped. *)
        write ("v 1 2\n" ^ big);
        match read ~jobs:2 () with
        | Ok _ -> Alcotest.fail "v 1 2 read"
        | Error (`Msg m) as e ->
            same "an error on the first line" (read ~jobs:1 ()) e;
            Alcotest.(check string) __LOC__ (path ^ ":1:6: expected 3 numbers (v x y z), found 2") m);
    Alcotest.test_case "render --jobs 2 of a big mesh: the image of one job, or its one-line error and no image" `Quick
      (fun () ->
        let dir = Helpers.temp_dir () in
        let file name = Filename.concat dir name in
        let write name text =
          let oc = open_out_bin (file name) in
          output_string oc text;
          close_out oc
        in
        let big = Mesh.Obj.to_string (Mesh.Gen.torus_knot ~p:2 ~q:3 ~radius:1. ~tube:0.2 ~segments:400 ~sides:64) in
        (* Big enough for render to read it on two cores. *)
        if String.length big < Raytrace_unix.Files.split_bytes then Alcotest.failf "the mesh has only %d bytes" (String.length big);
        write "t.scene"
          "(canvas (width 24) (height 18)) (camera (position 0 0 -4))\n\
           (mesh (file \"t.obj\") (color 230 150 40) (smooth true))\n(light ambient (intensity 1))\n";
        let render jobs out = Helpers.run (Helpers.raytrace ()) [ "render"; file "t.scene"; "--jobs"; jobs; "-o"; file out ] in
        let read name = In_channel_free.read (file name) in
        Fun.protect ~finally:(fun () ->
            Array.iter (fun f -> Sys.remove (file f)) (Sys.readdir dir);
            Unix.rmdir dir) @@ fun () ->
        write "t.obj" big;
        let code1, _, err1 = render "1" "one.ppm" and code2, _, err2 = render "2" "two.ppm" in
        Alcotest.(check (pair int int)) (err1 ^ err2) (0, 0) (code1, code2);
        Alcotest.(check bool) "the same image" true (read "one.ppm" = read "two.ppm");
        let line = List.length (String.split_on_char '\n' big) in
        List.iter
          (fun bad ->
            write "t.obj" (big ^ bad);
            let code1, _, err1 = render "1" "bad1.ppm" and code2, _, err2 = render "2" "bad2.ppm" in
            Alcotest.(check string) bad err1 err2;
            Alcotest.(check int) bad code1 code2;
            if code2 = 0 then Alcotest.failf "%S rendered" bad;
            let at = Printf.sprintf "t.obj:%d:" line in
            if not (Astring_free.contains err2 at) then Alcotest.failf "the error %S is not at %s" err2 at;
            if List.length (String.split_on_char '\n' (String.trim err2)) <> 1 then Alcotest.failf "not one line: %S" err2;
            Alcotest.(check bool) "no image" false (Sys.file_exists (file "bad2.ppm")))
          [ "f 1 2 0\n"; "f 1 2 99999\n"; "v 1 2 x\n" ]);
  ]
