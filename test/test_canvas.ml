let int = Alcotest.(check int)

let tests =
  [
    Alcotest.test_case "a 600 x 600 canvas spans [-300, 300) both ways" `Quick (fun () ->
        int __LOC__ (-300) (Canvas.min_x 600);
        int __LOC__ 299 (Canvas.max_x 600);
        int __LOC__ (-300) (Canvas.min_y 600);
        int __LOC__ 299 (Canvas.max_y 600));
    Alcotest.test_case "an odd canvas still has exactly w columns" `Quick (fun () ->
        (* 5 columns: -2 .. 2 *)
        int __LOC__ (-2) (Canvas.min_x 5);
        int __LOC__ 2 (Canvas.max_x 5);
        int __LOC__ 5 (Canvas.max_x 5 - Canvas.min_x 5 + 1));
    Alcotest.test_case "plotc puts the origin in the middle (section 1)" `Quick (fun () ->
        (* x + 600/2, y + 600/2 *)
        Alcotest.(check (pair int int)) __LOC__ (300, 300) (Canvas.screen ~width:600 ~height:600 0 0);
        Alcotest.(check (pair int int)) __LOC__ (0, 0) (Canvas.screen ~width:600 ~height:600 (-300) (-300)));
    Alcotest.test_case "image rows run top-down, canvas y up" `Quick (fun () ->
        (* the top canvas row y = 299 is image row 0; y = -300 is row 599 *)
        int __LOC__ 0 (Canvas.row ~height:600 299);
        int __LOC__ 599 (Canvas.row ~height:600 (-300));
        int __LOC__ 0 (Canvas.column ~width:600 (-300));
        int __LOC__ 599 (Canvas.column ~width:600 299));
    Helpers.qcheck "column/row and x_of_column/y_of_row are inverse"
      QCheck.(pair (int_range 1 999) (int_range 0 998))
      (fun (size, k) ->
        let k = k mod size in
        Canvas.column ~width:size (Canvas.x_of_column ~width:size k) = k
        && Canvas.row ~height:size (Canvas.y_of_row ~height:size k) = k
        && (* plotc's window y is the image row flipped *)
        snd (Canvas.screen ~width:size ~height:size 0 (Canvas.y_of_row ~height:size k)) = size - 1 - k);
  ]
