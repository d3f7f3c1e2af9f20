(* Regions of the canvas and the tiles that split it. *)
open Raytrace

let region = Alcotest.testable Render.Region.pp Render.Region.equal
let ok = function Ok x -> x | Error (`Msg m) -> Alcotest.fail m
let error = function Ok _ -> Alcotest.fail "expected an error" | Error (`Msg m) -> m

let tiles ~width ~height count =
  List.init count (fun i -> ok (Render.Region.tile ~width ~height ~index:(i + 1) ~count))

let tests =
  [
    Alcotest.test_case "tile 2 of 7 of 600 rows is rows 85 to 170" `Quick (fun () ->
        (* (2 - 1) * 600 / 7 = 85 and 2 * 600 / 7 = 171 (1200 / 7 = 171.4) *)
        Alcotest.check region __LOC__ (Render.Region.v ~x:0 ~y:85 ~w:600 ~h:86)
          (ok (Render.Region.tile ~width:600 ~height:600 ~index:2 ~count:7));
        Alcotest.check region __LOC__ (Render.Region.v ~x:0 ~y:514 ~w:600 ~h:86)
          (ok (Render.Region.tile ~width:600 ~height:600 ~index:7 ~count:7)));
    Helpers.qcheck "the tiles cover the canvas top to bottom, within one row of each other"
      QCheck.(pair (int_range 1 300) (int_range 1 300))
      (fun (height, count) ->
        let count = 1 + (count mod height) in
        let ts = tiles ~width:3 ~height count in
        let heights = List.map (fun (r : Render.Region.t) -> r.h) ts in
        let rec contiguous y = function
          | [] -> y = height
          | (r : Render.Region.t) :: rest -> r.y = y && r.x = 0 && r.w = 3 && contiguous (r.y + r.h) rest
        in
        contiguous 0 ts
        && List.fold_left max 0 heights - List.fold_left min height heights <= 1);
    Alcotest.test_case "impossible tiles are errors" `Quick (fun () ->
        let tile index count = error (Render.Region.tile ~width:10 ~height:5 ~index ~count) in
        Alcotest.(check string) __LOC__ "tile 0/3: the tile number must lie in [1, 3]" (tile 0 3);
        Alcotest.(check string) __LOC__ "tile 4/3: the tile number must lie in [1, 3]" (tile 4 3);
        Alcotest.(check string) __LOC__ "tile 1/6: the canvas has only 5 rows, fewer than 6 tiles" (tile 1 6);
        Alcotest.(check string) __LOC__ "tile 1/0: the number of tiles must be at least 1" (tile 1 0));
    Alcotest.test_case "corners are half-open and must lie in the canvas" `Quick (fun () ->
        Alcotest.check region __LOC__ (Render.Region.v ~x:10 ~y:20 ~w:20 ~h:5)
          (ok (Render.Region.of_corners ~width:40 ~height:30 10 20 30 25));
        Alcotest.check region __LOC__ (Render.Region.full ~width:40 ~height:30)
          (ok (Render.Region.of_corners ~width:40 ~height:30 0 0 40 30));
        Alcotest.(check string) __LOC__ "region columns 0 to 41: need 0 <= x0 < x1 <= 40 (the canvas width)"
          (error (Render.Region.of_corners ~width:40 ~height:30 0 0 41 30));
        Alcotest.(check string) __LOC__ "region rows 5 to 5: need 0 <= y0 < y1 <= 30 (the canvas height)"
          (error (Render.Region.of_corners ~width:40 ~height:30 0 5 40 5)));
    Alcotest.test_case "the command line's I/N and X0,Y0,X1,Y1 parse" `Quick (fun () ->
        Alcotest.(check (pair int int)) __LOC__ (3, 16) (ok (Render.Region.parse_tile "3/16"));
        Alcotest.(check string) __LOC__ "tile \"3\": expected I/N, tile I of N, e.g. 3/16" (error (Render.Region.parse_tile "3"));
        Alcotest.(check string) __LOC__ "tile \"-1/4\": expected I/N, tile I of N, e.g. 3/16" (error (Render.Region.parse_tile "-1/4"));
        let corners = Alcotest.(pair (pair int int) (pair int int)) in
        let pairs (a, b, c, d) = ((a, b), (c, d)) in
        Alcotest.check corners __LOC__ ((0, 10), (300, 200)) (pairs (ok (Render.Region.parse_corners "0,10,300,200")));
        Alcotest.check corners __LOC__ ((0, 10), (300, 200)) (pairs (ok (Render.Region.parse_corners "0 10 300 200")));
        Alcotest.(check string) __LOC__ "region \"0,1,2\": expected four integers X0,Y0,X1,Y1, e.g. 0,0,300,200"
          (error (Render.Region.parse_corners "0,1,2")));
  ]
