open Raytrace

let parse ?(max_vertices = 1000) ?(max_triangles = 1000) s =
  Mesh.Obj.of_string ~name:"t.obj" ~max_vertices ~max_triangles s

let mesh s = match parse s with Ok m -> m | Error (`Msg e) -> Alcotest.failf "refused %S: %s" s e
let error ?max_vertices ?max_triangles s =
  match parse ?max_vertices ?max_triangles s with
  | Ok _ -> Alcotest.failf "accepted %S" s
  | Error (`Msg e) -> e

let floats = Alcotest.(array (float 0.))
let ints = Alcotest.(array int)

(* [s] fed in chunks that end at the offsets [cuts] (sorted, in range). *)
let chunked ?(max_vertices = 1000) ?(max_triangles = 1000) s cuts =
  let p = Mesh.Obj.create ~name:"t.obj" ~max_vertices ~max_triangles in
  let rec go start = function
    | [] -> (match Mesh.Obj.feed p s start (String.length s - start) with Error _ as e -> e | Ok () -> Mesh.Obj.finish p)
    | c :: rest -> (match Mesh.Obj.feed p s start (c - start) with Error _ as e -> e | Ok () -> go c rest)
  in
  go 0 cuts

let same_result a b =
  match (a, b) with
  | Ok a, Ok b -> Mesh.Obj.equal a b
  | Error (`Msg a), Error (`Msg b) -> String.equal a b
  | _ -> false

let square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"

(* A text with every construct: CRLF and LF, comments, skipped kinds,
   all vertex forms, negative indices, a pentagon, a last line without a
   line end. *)
let rich =
  "# a comment\r\nmtllib x.mtl\no thing\ng group\r\n"
  ^ "v 0 0 0\nv 1.5 0 0 1\nv 1 1 0 0.5 0.25 1\nv -1e1 2.5e-1 .5\r\nv 3. -0 +7\n"
  ^ "vt 0 0\nvt 1 0\nvn 0 0 1\nvn 0 1 0\ns off\nusemtl red\n"
  ^ "f 1 2 3\nf 1/1 2/2 3/1\nf 1//1 2//2 3//1\r\nf 1/1/1 2/2/2 3/1/1 4/2/2 5/1/1\n"
  ^ "f -1 -2 -3\nl 1 2\np 1\n  \t \nfoo bar\nf 1/-1/-1 2//-2 3"

(* Do the lines [fast] and [slow] (the same lines written so that the
   general reader reads them) give the same mesh or error, read whole and
   read in two parts cut at line [cut] (the second as a part, then joined,
   as two cores read a big file; [None] where the join declines)? *)
let same_whole_and_joined ~max_vertices fast slow ~cut =
  let text ls = String.concat "\n" ls ^ "\n" in
  let whole = same_result (parse ~max_vertices (text fast)) (parse ~max_vertices (text slow)) in
  let joined ls =
    let cut = min cut (List.length ls) in
    let a = text (List.filteri (fun k _ -> k < cut) ls) and b = text (List.filteri (fun k _ -> k >= cut) ls) in
    let p = Mesh.Obj.create ~name:"t.obj" ~max_vertices ~max_triangles:1000 in
    match Mesh.Obj.feed p a 0 (String.length a) with
    | Ok () ->
        Option.map (fun m -> Ok m)
          (Helpers.obj_part_joined p ~name:"t.obj" ~max_vertices ~max_triangles:1000 b 0 (String.length b))
    | Error _ -> None
  in
  let parts =
    match (joined fast, joined slow) with Some a, Some b -> same_result a b | None, None -> true | _ -> false
  in
  whole && parts

let tests =
  [
    Alcotest.test_case "a triangle keeps its positions and 0-based indices" `Quick (fun () ->
        let m = mesh "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n" in
        Alcotest.check floats __LOC__ [| 0.; 0.; 0.; 1.; 0.; 0.; 0.; 1.; 0. |] m.positions;
        Alcotest.check ints __LOC__ [| 0; 1; 2 |] m.triangles;
        Alcotest.check ints __LOC__ [| -1; -1; -1 |] m.triangle_normals;
        Alcotest.check floats __LOC__ [||] m.normals;
        Alcotest.(check int) __LOC__ 0 (Mesh.Obj.skipped_total m));
    Alcotest.test_case "a quad is two triangles and a pentagon three, fanned from the first vertex" `Quick
      (fun () ->
        let m = mesh (square ^ "v 0.5 2 0\nf 1 2 3 4\nf 5 4 3 2 1\n") in
        (* 1 2 3 4 -> (1 2 3) (1 3 4); 5 4 3 2 1 -> (5 4 3) (5 3 2) (5 2 1); minus 1 each. *)
        Alcotest.check ints __LOC__ [| 0; 1; 2; 0; 2; 3; 4; 3; 2; 4; 2; 1; 4; 1; 0 |] m.triangles;
        Alcotest.(check int) __LOC__ 5 (Mesh.Obj.triangle_count m));
    Alcotest.test_case "negative indices count back from the last one defined so far" `Quick (fun () ->
        (* After 4 vertices -1 is vertex 4 (0-based 3); after the 5th, -1 is the 5th. *)
        let m = mesh (square ^ "f -4 -3 -1\nvn 0 0 1\nv 9 9 9\nf -1//-1 -2//1 -5//-1\n") in
        Alcotest.check ints __LOC__ [| 0; 1; 3; 4; 3; 0 |] m.triangles;
        Alcotest.check ints __LOC__ [| -1; -1; -1; 0; 0; 0 |] m.triangle_normals);
    Alcotest.test_case "every vertex form, mixed in one face, gives the same triangles" `Quick (fun () ->
        let m = mesh (square ^ "vt 0 0\nvn 0 0 1\nvn 0 0 -1\nf 1 2/1 3//2\nf 1/1/1 2/1/2 3/-1/-1\n") in
        Alcotest.check ints __LOC__ [| 0; 1; 2; 0; 1; 2 |] m.triangles;
        Alcotest.check ints __LOC__ [| -1; -1; 1; 0; 1; 1 |] m.triangle_normals;
        Alcotest.check floats __LOC__ [| 0.; 0.; 1.; 0.; 0.; -1. |] m.normals;
        (* vt is kept, not skipped; 3/-1/-1 is texture 1 (the last). *)
        Alcotest.check ints __LOC__ [| -1; 0; -1; 0; 0; 0 |] m.triangle_texcoords;
        Alcotest.(check (list (pair string int))) __LOC__ [] m.skipped);
    Alcotest.test_case "normals numbered as the vertices share the vertices' array, and only then" `Quick (fun () ->
        let normals = "vn 0 0 1\nvn 0 1 0\nvn 1 0 0\nvn 0 0 -1\n" in
        (* Over more than one of the reader's blocks of numbers. *)
        let faces n f = String.concat "" (List.init n (fun k -> f (k mod 2))) in
        let mesh s = match parse ~max_triangles:100_000 s with Ok m -> m | Error (`Msg e) -> Alcotest.fail e in
        let same = mesh (square ^ normals ^ faces 40_000 (fun k -> if k = 0 then "f 1//1 2//2 3//3\n" else "f 1//1 3//3 4//4\n")) in
        if not (same.triangle_normals == same.triangles) then Alcotest.fail "two arrays for one numbering";
        Alcotest.(check int) __LOC__ 120_000 (Array.length same.triangles);
        (* One corner differs, in the last block, or in the first. *)
        List.iter
          (fun last ->
            let text = square ^ normals ^ faces 40_000 (fun _ -> "f 1//1 2//2 3//3\n") in
            let text = if last then text ^ "f 1//1 2//2 3//4\n" else square ^ normals ^ "f 1//1 2//2 3//4\n" ^ faces 40_000 (fun _ -> "f 1//1 2//2 3//3\n") in
            let m = mesh text in
            if m.triangle_normals == m.triangles then Alcotest.fail "one array for two numberings";
            Alcotest.(check int) __LOC__ 3 (if last then m.triangle_normals.(Array.length m.triangles - 1) else m.triangle_normals.(2)))
          [ true; false ];
        (* No normals: [-1] each, never the vertices. *)
        let m = mesh (square ^ "f 1 2 3\n") in
        Alcotest.check ints __LOC__ [| -1; -1; -1 |] m.triangle_normals);
    Alcotest.test_case "normal numbers not stored while they follow the vertices (or are none) are all found after" `Quick
      (fun () ->
        (* The reader keeps no normal numbers while each triangle's are its
           vertices' or none; the first that is neither writes out those
           before it, over several of its blocks (65536 numbers). *)
        let normals = "vn 0 0 1\nvn 0 1 0\nvn 1 0 0\nvn 0 0 -1\n" in
        let mesh s = match parse ~max_triangles:100_000 s with Ok m -> m | Error (`Msg e) -> Alcotest.fail e in
        let repeat n line = String.concat "" (List.init n (fun _ -> line)) in
        let m = mesh (square ^ normals ^ repeat 30_000 "f 1//1 2//2 3//3\n" ^ "f 1//4 2//2 4//3\nf 2 3 4\n") in
        let expected = Array.concat [ Array.init 90_000 (fun k -> k mod 3); [| 3; 1; 2; -1; -1; -1 |] ] in
        Alcotest.check ints __LOC__ expected m.triangle_normals;
        let m = mesh (square ^ normals ^ repeat 30_000 "f 1 2 3 4\n" ^ "f 1//1 2//2 3//3\n") in
        let expected = Array.concat [ Array.make 180_000 (-1); [| 0; 1; 2 |] ] in
        Alcotest.check ints __LOC__ expected m.triangle_normals);
    Alcotest.test_case "a # word starts a comment in v, vn and f lines" `Quick (fun () ->
        let m = mesh "v 0 0 0 # origin\nv 1 0 0 #x\nv 0 1 0\t#\nvn 0 0 1 #up\nf 1//1 2//1 3//1 # a face\n" in
        Alcotest.check floats __LOC__ [| 0.; 0.; 0.; 1.; 0.; 0.; 0.; 1.; 0. |] m.positions;
        Alcotest.check ints __LOC__ [| 0; 1; 2 |] m.triangles;
        Alcotest.(check string) __LOC__ "t.obj:1:7: expected a number, found \"3#x\"" (error "v 1 2 3#x"));
    Alcotest.test_case "v keeps x y z of v x y z w and of v x y z r g b" `Quick (fun () ->
        let m = mesh "v 1 2 3 0.5\nv 4 5 6 1 0 0\n" in
        Alcotest.check floats __LOC__ [| 1.; 2.; 3.; 4.; 5.; 6. |] m.positions);
    Alcotest.test_case "every other statement is skipped and counted by kind" `Quick (fun () ->
        let m = mesh rich in
        (* vt is kept ({!Test_texture}), not skipped. *)
        Alcotest.(check (list (pair string int)))
          __LOC__
          [ ("#", 1); ("o", 1); ("g", 1); ("s", 1); ("usemtl", 1); ("mtllib", 1); ("l", 1); ("p", 1); ("other", 1) ]
          m.skipped;
        Alcotest.(check int) __LOC__ 9 (Mesh.Obj.skipped_total m));
    Alcotest.test_case "CRLF line ends, blank lines and a last line without line end are read" `Quick (fun () ->
        let m = mesh rich in
        Alcotest.check floats __LOC__ [| 0.; 0.; 0.; 1.5; 0.; 0.; 1.; 1.; 0.; -10.; 0.25; 0.5; 3.; -0.; 7. |] m.positions;
        (* 1 2 3 three times, the pentagon 1 2 3 4 5 as (1 2 3) (1 3 4) (1 4 5), then
           -1 -2 -3 = 5 4 3 and the last face 1 2 3 with normals -1 = 2, -2 = 1. *)
        Alcotest.check ints __LOC__
          [| 0; 1; 2; 0; 1; 2; 0; 1; 2; 0; 1; 2; 0; 2; 3; 0; 3; 4; 4; 3; 2; 0; 1; 2 |]
          m.triangles;
        Alcotest.check ints __LOC__
          [| -1; -1; -1; -1; -1; -1; 0; 1; 0; 0; 1; 0; 0; 0; 1; 0; 1; 0; -1; -1; -1; 1; 0; -1 |]
          m.triangle_normals;
        Alcotest.(check bool) __LOC__ true (Float.sign_bit m.positions.(13)));
    Alcotest.test_case "every error names file:line:column and what was expected" `Quick (fun () ->
        let v3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\n" in
        List.iter
          (fun (text, expected) -> Alcotest.(check string) (String.escaped text) expected (error text))
          [
            ("v 1 2 x", "t.obj:1:7: expected a number, found \"x\"");
            ("v 1 2 1.5.5", "t.obj:1:7: expected a number, found \"1.5.5\"");
            ("v 1 2 3e", "t.obj:1:7: expected a number, found \"3e\"");
            ("\n\nv 1 nan 3", "t.obj:3:5: expected a finite number, found nan");
            ("v 1 -inf 3", "t.obj:1:5: expected a finite number, found -inf");
            ("v 1 2 1e400", "t.obj:1:7: number 1e400 is too large (infinite as a float)");
            ("v 1 2", "t.obj:1:6: expected 3 numbers (v x y z), found 2");
            ("vn 1 2\r\n", "t.obj:1:7: expected 3 numbers (vn x y z), found 2");
            ("vn 1 2 3 4", "t.obj:1:10: expected at most 3 numbers (vn x y z), found \"4\"");
            ("v 1 2 3 4 5", "t.obj:1:12: expected x y z [w] or x y z r g b, found 5 numbers");
            ("v 1 2 3 4 5 6 7 8", "t.obj:1:17: expected at most 7 numbers (v x y z [w]), found \"8\"");
            (v3 ^ "f 1 2 0", "t.obj:4:7: vertex index 0 (indices start at 1, or -1 for the last)");
            (v3 ^ "f 1 2 4", "t.obj:4:7: vertex index 4 is out of range: 3 vertices defined so far");
            (v3 ^ "f 1 -4 2", "t.obj:4:5: vertex index -4 is out of range: 3 vertices defined so far");
            (v3 ^ "f 1 2 99999999999999999999999", "t.obj:4:7: vertex index 99999999999999999999999 is out of range: 3 vertices defined so far");
            (v3 ^ "f 1 2 3/1", "t.obj:4:9: texture index 1 is out of range: 0 textures defined so far");
            (v3 ^ "vn 0 0 1\nf 1//1 2//2 3", "t.obj:5:11: normal index 2 is out of range: 1 normal defined so far");
            (v3 ^ "f 1 2 3x", "t.obj:4:8: expected a space or the end of the line after a face vertex, found \"x\"");
            (v3 ^ "f a 2 3", "t.obj:4:3: expected a vertex index, found \"a\"");
            (v3 ^ "f 1 - 3", "t.obj:4:5: expected a vertex index, found \"-\"");
            (v3 ^ "f 1/0 2 3", "t.obj:4:5: texture index 0 (indices start at 1, or -1 for the last)");
            (v3 ^ "  f 1 2", "t.obj:4:3: a face needs at least 3 vertices, found 2");
            (v3 ^ "f", "t.obj:4:1: a face needs at least 3 vertices, found 0");
          ]);
    Alcotest.test_case "the caller's bounds on vertices, normals and triangles are errors" `Quick (fun () ->
        Alcotest.(check string) __LOC__ "t.obj:3:1: more than 2 vertices (the limit of vertices)"
          (error ~max_vertices:2 "v 0 0 0\nv 1 1 1\nv 2 2 2\n");
        Alcotest.(check string) __LOC__ "t.obj:3:2: more than 2 normals (the limit of vertices)"
          (error ~max_vertices:2 "vn 0 0 1\nvn 1 1 1\n vn 2 2 2\n");
        Alcotest.(check string) __LOC__ "t.obj:6:1: more than 2 triangles (the limit of triangles)"
          (error ~max_triangles:2 (square ^ "f 1 2 3\nf 1 2 3 4\n"));
        Alcotest.(check int) __LOC__ 2 (Mesh.Obj.triangle_count (mesh (square ^ "f 1 2 3 4\n"))));
    Alcotest.test_case "a line longer than max_line_bytes is refused, whole or in chunks" `Quick (fun () ->
        let long = "v 0 0 0\n#" ^ String.make Mesh.Obj.max_line_bytes ' ' ^ "\nv 1 1 1\n" in
        let e = error long in
        Alcotest.(check bool) e true (String.length e > 12 && String.sub e 0 12 = "t.obj:2:1048");
        let cuts = List.init 16 (fun k -> (k * 65536) + 3) in
        match chunked long cuts with
        | Ok _ -> Alcotest.fail "chunked: accepted"
        | Error (`Msg e) -> Alcotest.(check bool) e true (String.sub e 0 8 = "t.obj:2:"));
    Alcotest.test_case "after an error every feed and finish return it" `Quick (fun () ->
        let p = Mesh.Obj.create ~name:"t.obj" ~max_vertices:10 ~max_triangles:10 in
        let first = Mesh.Obj.feed p "v 1 2 x\n" 0 8 in
        let later = Mesh.Obj.feed p "v 1 2 3\n" 0 8 in
        let last = Mesh.Obj.finish p in
        let msg = function Ok _ -> "ok" | Error (`Msg m) -> m in
        Alcotest.(check string) __LOC__ "t.obj:1:7: expected a number, found \"x\"" (msg first);
        Alcotest.(check string) __LOC__ (msg first) (msg later);
        Alcotest.(check string) __LOC__ (msg first) (match last with Ok _ -> "ok" | Error (`Msg m) -> m));
    Alcotest.test_case "an empty text is an empty mesh" `Quick (fun () ->
        let m = mesh "" in
        Alcotest.(check int) __LOC__ 0 (Mesh.Obj.vertex_count m + Mesh.Obj.triangle_count m));
    Alcotest.test_case "Mesh.Obj.v refuses arrays that do not make a mesh" `Quick (fun () ->
        let bad f = match f () with _ -> Alcotest.fail "accepted" | exception Invalid_argument _ -> () in
        let p = [| 0.; 0.; 0.; 1.; 0.; 0.; 0.; 1.; 0. |] in
        bad (fun () -> Mesh.Obj.v ~positions:p ~normals:[||] ~triangles:[| 0; 1; 3 |] ~triangle_normals:[| -1; -1; -1 |]);
        bad (fun () -> Mesh.Obj.v ~positions:p ~normals:[||] ~triangles:[| 0; 1; 2 |] ~triangle_normals:[| -1; -1; 0 |]);
        bad (fun () -> Mesh.Obj.v ~positions:p ~normals:[||] ~triangles:[| 0; 1 |] ~triangle_normals:[| -1; -1 |]);
        bad (fun () -> Mesh.Obj.v ~positions:p ~normals:[||] ~triangles:[| 0; 1; 2 |] ~triangle_normals:[||]));
    Alcotest.test_case "the OBJ text of a mesh reads back equal, floats bit for bit" `Quick (fun () ->
        let m = mesh rich in
        let back = mesh (Mesh.Obj.to_string m) in
        Alcotest.(check bool) __LOC__ true (Mesh.Obj.equal (Mesh.Obj.with_texcoords ~texcoords:m.texcoords
          ~triangle_texcoords:m.triangle_texcoords (Mesh.Obj.v ~positions:m.positions ~normals:m.normals
          ~triangles:m.triangles ~triangle_normals:m.triangle_normals)) back);
        let m = Mesh.Obj.v ~positions:[| 0.1; 1. /. 3.; -1e-300; 4.9e-324; 1.7976931348623157e308; -0.; 1.; 2.; 3. |]
            ~normals:[||] ~triangles:[| 0; 1; 2 |] ~triangle_normals:[| -1; -1; -1 |] in
        Alcotest.(check bool) __LOC__ true (Mesh.Obj.equal m (mesh (Mesh.Obj.to_string m))));
    Helpers.qcheck ~count:300 "chunks cut anywhere read as the whole text, errors included"
      QCheck.(pair (int_range 0 3) (small_list (int_bound 10_000)))
      (fun (variant, cuts) ->
        let text =
          match variant with
          | 0 -> rich
          | 1 -> rich ^ "\r\n"
          | 2 -> rich ^ "\nv 1 2 3\nf 1 2 9\n"  (* an error on the last line *)
          | _ -> String.concat "\r\n" (List.init 20 (fun k -> Printf.sprintf "v %d.25 -%de-3 %d" k k (k * 7))) ^ "\nf 1 2 3 4 5 6\r\n"
        in
        let n = String.length text in
        let cuts = List.sort_uniq compare (List.map (fun c -> c mod (n + 1)) cuts) in
        same_result (parse text) (chunked text cuts));
    Helpers.qcheck ~count:3000 "a triangle read on the fast path is the triangle the general face reader reads"
      (* The fast path reads [f] lines of 3 corners [v] or [v//n] one
         space apart and nothing after; a space at the end of each [f]
         line sends them all to the general reader, which ignores it:
         the meshes and errors must be the same, whatever the corners
         (indices in range or not, 0, negative, too long, texture
         indices, other blanks, 2 to 4 corners), in a whole text or in a
         part joined to the text before it. *)
      QCheck.(
        make
          ~print:(fun (lines, cut) -> Printf.sprintf "cut %d: %S" cut (String.concat "\n" lines))
          Gen.(
            (* Mostly indices in range (8 vertices, 4 normals and 2
               texture coordinates come first), now and then not. *)
            let index =
              frequency
                [ (40, map string_of_int (int_range 1 4)); (4, oneofl [ "5"; "6"; "7"; "8"; "-1"; "-3" ]);
                  (1, oneofl [ "0"; "01"; "9"; "12"; "1234567890123456789"; "" ]) ]
            in
            let corner =
              frequency
                [ (20, index); (20, map2 (fun v n -> v ^ "//" ^ n) index index); (1, map2 (fun v t -> v ^ "/" ^ t) index index);
                  (1, map3 (fun v t n -> v ^ "/" ^ t ^ "/" ^ n) index index index); (1, map (fun v -> v ^ "/") index) ]
            in
            let blank = frequency [ (40, return " "); (1, oneofl [ "  "; "\t"; " # c " ]) ] in
            let face =
              frequency [ (10, return 3); (1, int_range 2 4) ] >>= fun n ->
              list_repeat n (pair blank corner) >|= fun cs -> "f" ^ String.concat "" (List.map (fun (b, c) -> b ^ c) cs)
            in
            let line = frequency [ (1, oneofl [ "v 1 2 3"; "vn 0 0 1"; "vt 0 0"; "# x" ]); (8, face) ] in
            let head =
              [ "v 1 2 3"; "v -1 0.5 2"; "v 0 0 0"; "v 1 1 1"; "v 2 0 1"; "v 0 3 1"; "v 1 0 4"; "v 5 5 5";
                "vn 0 0 1"; "vn 1 0 0"; "vn 0 1 0"; "vn 1 1 1"; "vt 0 0"; "vt 1 1" ]
            in
            pair (map (fun ls -> head @ ls) (list_size (int_range 1 12) line)) (int_bound 30)))
      (fun (lines, cut) ->
        let spaced = List.map (fun l -> if l <> "" && l.[0] = 'f' then l ^ " " else l) lines in
        same_whole_and_joined ~max_vertices:1000 lines spaced ~cut);
    Helpers.qcheck ~count:3000 "a vertex read on the fast path is the vertex the general vertex reader reads"
      (* The fast path reads [v] and [vn] lines of 3 numbers one space
         apart and nothing after, under the bound; a tab after the
         keyword (a byte too: the columns stay) sends every one to the
         general reader: the meshes and errors must be the same, whatever
         the numbers (exponents, signs, 17 digits, malformed, NaN,
         infinite, too large), blanks and counts, and with 5 vertices at
         most (the bound crossed), in a whole text or in a part joined to
         the text before it. *)
      QCheck.(
        make
          ~print:(fun (lines, cut) -> Printf.sprintf "cut %d: %S" cut (String.concat "\n" lines))
          Gen.(
            let number =
              frequency
                [ (30, map (fun x -> Printf.sprintf "%.9g" x) (float_range (-100.) 100.));
                  (5, map (fun x -> Printf.sprintf "%.17g" x) (float_range (-1.) 1.));
                  (3, oneofl [ "1"; "-0"; "+2"; ".5"; "5."; "1e3"; "-2.5E-3"; "1e+22"; "123456789012345678901" ]);
                  (1, oneofl [ "1e"; "1e+"; "-"; "."; "nan"; "inf"; "-infinity"; "1e400"; "1.5x"; "0x10"; "" ]) ]
            in
            let blank = frequency [ (40, return " "); (1, oneofl [ "  "; "\t"; " # c " ]) ] in
            let vertex =
              frequency [ (10, return 3); (1, int_range 1 5) ] >>= fun n ->
              pair (oneofl [ "v"; "v"; "vn" ]) (list_repeat n (pair blank number)) >>= fun (kw, ns) ->
              map (fun tail -> kw ^ String.concat "" (List.map (fun (b, x) -> b ^ x) ns) ^ tail) (frequency [ (20, return ""); (1, oneofl [ " "; " # c"; "\t" ]) ])
            in
            let line = frequency [ (8, vertex); (1, oneofl [ "f 1 2 3"; "vt 0 0"; "# x" ]) ] in
            let head = [ "v 1 2 3"; "v -1 0.5 2"; "v 0 0 0"; "vn 0 0 1" ] in
            pair (map (fun ls -> head @ ls) (list_size (int_range 1 8) line)) (int_bound 12)))
      (fun (lines, cut) ->
        let general l =
          if String.length l > 2 && String.sub l 0 2 = "v " then "v\t" ^ String.sub l 2 (String.length l - 2)
          else if String.length l > 3 && String.sub l 0 3 = "vn " then "vn\t" ^ String.sub l 3 (String.length l - 3)
          else l
        in
        same_whole_and_joined ~max_vertices:6 lines (List.map general lines) ~cut);
    Helpers.qcheck ~count:3000 "any text, of OBJ words or of any bytes, is a mesh or a one-line error"
      QCheck.(
        make ~print:String.escaped
          Gen.(
            oneof
              [
                map (String.concat "")
                  (list_size (int_bound 60)
                     (oneofl
                        [ "v"; "vn"; "vt"; "f"; " "; "\t"; "\n"; "\r\n"; "\r"; "/"; "//"; "-"; "1"; "2"; "-1"; "0";
                          "3"; "1.5"; "e"; "."; "#"; "nan"; "9999999999999999999999"; "\000"; "o x"; "\255" ]));
                string_size ~gen:char (int_bound 200);
              ]))
      (fun text ->
        match parse ~max_vertices:5 ~max_triangles:5 text with
        | Ok m -> Mesh.Obj.vertex_count m <= 5 && Mesh.Obj.triangle_count m <= 5
        | Error (`Msg e) ->
            String.length e > 6 && String.sub e 0 6 = "t.obj:" && not (String.contains e '\n' || String.contains e '\r'));
    Alcotest.test_case "one byte at a time reads as the whole text" `Quick (fun () ->
        List.iter
          (fun text ->
            let cuts = List.init (String.length text) Fun.id in
            Alcotest.(check bool) __LOC__ true (same_result (parse text) (chunked text cuts)))
          [ rich; rich ^ "\n"; "v 1 2 3\r"; "v 1 2 3\r\n"; square ^ "f 1 2 3 4 5" ]);
    Alcotest.test_case "a UTF-8 byte order mark at the start is skipped: no vertex lost, no index shifted" `Quick
      (fun () ->
        let bom = "\xef\xbb\xbf" in
        (* First lines for the fast path (v, f of plain numbers), the general
           one (a vertex with a colour, an exponent) and a comment. *)
        List.iter
          (fun text ->
            let with_bom = bom ^ text in
            let cuts = List.init (String.length with_bom) Fun.id in
            Alcotest.(check bool) (String.escaped text ^ ": whole") true (same_result (parse text) (parse with_bom));
            Alcotest.(check bool) (String.escaped text ^ ": a byte at a time") true
              (same_result (parse text) (chunked with_bom cuts)))
          [ square ^ "f 1 2 3\n"; "v 0 0 0 1 0.5 0.25\nv 1e0 0 0\nv 0 1 0\nf 1 2 3\n"; "# made by an editor\n" ^ square ^ "f -4 -3 -2\n"; rich ];
        let m = mesh (bom ^ square ^ "f 1 2 3\n") in
        (* The first vertex (0 0 0) is there and index 1 names it. *)
        Alcotest.check floats __LOC__ [| 0.; 0.; 0.; 1.; 0.; 0.; 1.; 1.; 0.; 0.; 1.; 0. |] m.positions;
        Alcotest.check ints __LOC__ [| 0; 1; 2 |] m.triangles;
        (* Only at the start of the text: elsewhere it is an unknown statement. *)
        Alcotest.(check int) __LOC__ 1 (Mesh.Obj.skipped_total (mesh (square ^ bom ^ "v 1 1 1\n")));
        (* Columns count bytes, the mark's included: 3 + "v 0 0 " (6), then x at 10. *)
        Alcotest.(check string) __LOC__ "t.obj:1:10: expected a number, found \"x\"" (error (bom ^ "v 0 0 x\n")));
    Alcotest.test_case "a mesh file with a byte order mark reads the same on one core and on two" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let path = Filename.concat dir "bom.obj" in
        let text = Mesh.Obj.to_string (Mesh.Gen.torus_knot ~p:2 ~q:3 ~radius:1. ~tube:0.3 ~segments:40 ~sides:8) in
        let oc = open_out_bin path in
        output_string oc ("\xef\xbb\xbf" ^ text);
        close_out oc;
        let expected = mesh text in
        List.iter
          (fun jobs ->
            match Raytrace_unix.Files.read_mesh ~jobs ~split_bytes:1 path with
            | Ok m -> Alcotest.(check bool) (Printf.sprintf "%d jobs: the mesh without the mark" jobs) true (Mesh.Obj.equal m expected)
            | Error (`Msg e) -> Alcotest.fail e)
          [ 1; 2 ]);
    Alcotest.test_case "feed_bytes reads from a buffer the caller then reuses" `Quick (fun () ->
        let p = Mesh.Obj.create ~name:"t.obj" ~max_vertices:10 ~max_triangles:10 in
        let buf = Bytes.create 7 in
        let text = square ^ "f 1 2 3 4\n" in
        let k = ref 0 in
        while !k < String.length text do
          let n = min 7 (String.length text - !k) in
          Bytes.blit_string text !k buf 0 n;
          (match Mesh.Obj.feed_bytes p buf 0 n with Ok () -> () | Error (`Msg e) -> Alcotest.fail e);
          Bytes.fill buf 0 7 'X';
          k := !k + n
        done;
        match Mesh.Obj.finish p with
        | Error (`Msg e) -> Alcotest.fail e
        | Ok m -> Alcotest.(check bool) __LOC__ true (Mesh.Obj.equal m (mesh text)));
    Alcotest.test_case "reading a large mesh allocates no string per number" `Quick (fun () ->
        let lines = 20_000 in
        let b = Buffer.create (lines * 40) in
        for k = 1 to lines do
          Printf.bprintf b "v %d.5 -0.%d 1e-%d\n" k k (k mod 20)
        done;
        Buffer.add_string b "vt 0 0\nvn 0 0 1\n";
        for k = 3 to lines do
          Printf.bprintf b "f %d/1 %d//1 -%d\n" k (k - 1) (k - 2)
        done;
        let text = Buffer.contents b in
        let before = Gc.minor_words () in
        let m = parse ~max_vertices:lines ~max_triangles:lines text in
        let words = Gc.minor_words () -. before in
        (match m with Ok m -> Alcotest.(check int) __LOC__ (lines - 2) (Mesh.Obj.triangle_count m) | Error (`Msg e) -> Alcotest.fail e);
        (* A string per token would be 3 words for each of the 3 numbers and
           3 indices of a line; floats boxed between functions take 2. *)
        let per_line = words /. Float.of_int (2 * lines) in
        Alcotest.(check bool) (Printf.sprintf "%.2f minor words per line" per_line) true (per_line < 6.));
    Alcotest.test_case "Mesh.of_obj makes the mesh the scene form (mesh (file ...) ...) makes" `Quick (fun () ->
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n# note\n" in
        let obj = mesh text in
        let load _ = Mesh.Obj.of_string ~name:"m.obj" ~max_vertices:1000 ~max_triangles:1000 text in
        let scene =
          "(light ambient (intensity 1))\n\
           (mesh (file \"m.obj\") (scale 2) (translate 1 2 3) (smooth true) (color 10 20 30) (specular 5))"
        in
        let from_file =
          match Scene_file.of_string ~load_mesh:load scene with
          | Error (`Msg e) -> Alcotest.failf "scene refused: %s" e
          | Ok s -> (
              match (Scene.shapes (Scene.of_valid s)) with
              | [ Shape.Mesh m ] -> m
              | _ -> Alcotest.fail "expected one mesh")
        in
        let m = Material.v ~specular:5. (Color.v 10. 20. 30.) in
        match Mesh.of_obj ~smooth:true ~scale:2. ~translate:(Vec3.v 1. 2. 3.) ~source:"m.obj" obj m with
        | Error (`Msg e) -> Alcotest.failf "of_obj refused: %s" e
        | Ok code ->
            Alcotest.(check bool) (Format.asprintf "%a = %a" Mesh.pp code Mesh.pp from_file) true (Mesh.equal code from_file);
            (* Corner 1 of triangle 0 is vertex (1, 0, 0): 2 * 1 + 1 = 3, 2 * 0 + 2 = 2, 2 * 0 + 3 = 3. *)
            Alcotest.(check bool) __LOC__ true (Vec3.equal (Mesh.vertex code 0 1) (Vec3.v 3. 2. 3.));
            Alcotest.(check int) "the comment is counted as skipped" 1 code.skipped);
    Alcotest.test_case "Mesh.of_obj refuses a scale of 0 with a message" `Quick (fun () ->
        let obj = mesh "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n" in
        match Mesh.of_obj ~scale:0. obj (Material.v Color.white) with
        | Ok _ -> Alcotest.fail "accepted a scale of 0"
        | Error (`Msg e) -> Alcotest.(check string) __LOC__ "mesh scale must be finite and > 0, got 0" e);
    Alcotest.test_case "a mesh built in code prints as a form a scene file refuses, after a comment that says why" `Quick
      (fun () ->
        let obj = mesh "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n" in
        let m = match Mesh.of_obj obj (Material.v Color.white) with Ok m -> m | Error (`Msg e) -> Alcotest.fail e in
        let printed = Format.asprintf "%a" Mesh.pp_form m in
        let first = List.hd (String.split_on_char '\n' printed) in
        Alcotest.(check string) __LOC__ "; a mesh built in code (1 triangle): no file to read it from" first;
        Alcotest.(check string) __LOC__ "<mesh built in code: 1 triangles, scale 1, translate (0 0 0)>"
          (Format.asprintf "%a" Mesh.pp m);
        match Scene_file.of_string ("(light ambient (intensity 1))\n" ^ printed) with
        | Ok _ -> Alcotest.fail "a scene file read a mesh with no file"
        | Error (`Msg e) ->
            let has = Astring_free.contains in
            Alcotest.(check bool) e true (has e "expected a file name"));
  ]
