open Raytrace

let image_2x1 () =
  let img = Image.create 2 1 in
  Image.set img 0 0 255 0 10;
  Image.set img 1 0 1 2 3;
  img

let decode s = match Image.Ppm.of_string s with Ok img -> img | Error (`Msg m) -> Alcotest.fail m
let error s = match Image.Ppm.of_string s with Ok _ -> Alcotest.failf "accepted %S" s | Error (`Msg m) -> m

let tests =
  [
    Alcotest.test_case "P6 is the header then the bytes, rows top-down" `Quick (fun () ->
        Alcotest.(check string) __LOC__ "P6\n2 1\n255\n\255\000\010\001\002\003" (Image.Ppm.to_string (image_2x1 ())));
    Alcotest.test_case "P6 reads back what it wrote" `Quick (fun () ->
        let img = image_2x1 () in
        Alcotest.(check bool) __LOC__ true (Image.equal img (decode (Image.Ppm.to_string img))));
    Alcotest.test_case "P6 holds every byte at any size, by string and by channel" `Quick (fun () ->
        (* Sizes around the 8-byte words of the copy and the 64 KiB chunks
           of [output]: 21845 pixels are 65535 bytes. *)
        List.iter
          (fun (w, h) ->
            let img = Image.create w h in
            let buf = Image.buffer img in
            let n = Bigarray.Array1.dim buf in
            for k = 0 to n - 1 do
              buf.{k} <- ((k * 7919) + (k / 251)) land 255
            done;
            let expected = Printf.sprintf "P6\n%d %d\n255\n" w h ^ String.init n (fun k -> Char.chr buf.{k}) in
            let what = Printf.sprintf "%dx%d" w h in
            Alcotest.(check bool) (what ^ " to_string") true (String.equal expected (Image.Ppm.to_string img));
            let path = Filename.temp_file "ppm" ".ppm" in
            let oc = open_out_bin path in
            Image.Ppm.output oc img;
            close_out oc;
            let written = match File_io.read path with Ok s -> s | Error (`Msg m) -> Alcotest.fail m in
            Sys.remove path;
            Alcotest.(check bool) (what ^ " output") true (String.equal expected written);
            (* In parts, as a render writes it while it traces: the header,
               then rows 0, 1 to h/2, the rest, and nothing. *)
            let oc = open_out_bin path in
            output_string oc (Image.Ppm.header img);
            let mid = max 1 (h / 2) in
            List.iter
              (fun (first, stop) -> Image.Ppm.output_rows oc img ~first ~stop)
              [ (0, 1); (1, mid); (mid, h); (h, h) ];
            close_out oc;
            let written = match File_io.read path with Ok s -> s | Error (`Msg m) -> Alcotest.fail m in
            Sys.remove path;
            Alcotest.(check bool) (what ^ " output_rows") true (String.equal expected written);
            match Image.Ppm.output_rows stdout img ~first:1 ~stop:0 with
            | () -> Alcotest.fail "rows 1 to 0 written"
            | exception Invalid_argument _ -> ())
          [ (1, 1); (2, 1); (3, 1); (8, 3); (21845, 1); (21846, 1); (21848, 1); (97, 61) ]);
    Alcotest.test_case "P3 with comments and odd spacing reads" `Quick (fun () ->
        let img = decode "P3 # plain\n2 1\n# max\n255\n255 0 10\t1 2\n3\n" in
        Alcotest.(check bool) __LOC__ true (Image.equal (image_2x1 ()) img));
    Alcotest.test_case "a maxval below 255 is rescaled" `Quick (fun () ->
        (* 1 of maxval 1 is 255; 2 of 4 is round (2 * 255 / 4) = 128 *)
        Alcotest.(check (triple int int int)) __LOC__ (255, 0, 255) (Image.get (decode "P3 1 1 1 1 0 1") 0 0);
        Alcotest.(check (triple int int int)) __LOC__ (128, 0, 255) (Image.get (decode "P3 1 1 4 2 0 4") 0 0));
    Alcotest.test_case "malformed files are errors, not exceptions" `Quick (fun () ->
        List.iter
          (fun (input, expected) -> Alcotest.(check string) (String.escaped input) expected (error input))
          [
            ("", "not a PPM file: it must start with P6 or P3 and a whitespace");
            ("P5\n1 1\n255\n\000", "not a PPM file: it must start with P6 or P3 and a whitespace");
            ("P6\n2 1\n255\n\000\000\000", "pixel data is truncated: 3 of 6 bytes");
            ("P6\n1 1\n255\n\000\000\000\000", "1 bytes of unexpected data after the pixels");
            ("P6\n1 1\n0\n\000\000\000", "maxval must lie in [1, 255], got 0");
            ("P6\n1 1\n65535\n\000\000\000", "maxval must lie in [1, 255], got 65535");
            ("P6\n-1 1\n255\n", "width: expected a decimal number at byte 3, got \"-1\"");
            ("P6\n0 1\n255\n", "image size 0x1 is empty");
            ("P6\n100000 100000\n255\n",
             "image 100000x100000 has 10000000000 pixels, more than the limit of 268435456 (set \
              RAYTRACE_MAX_PIXELS to raise it)");
            ("P6\n1 1", "unexpected end of file in the header");
            ("P3\n1 1\n255\n1 2", "pixel data is truncated: fewer than 3 samples");
            ("P3\n1 1\n255\n1 2 300", "sample 300 at byte 15 exceeds maxval 255");
            ("P3\n1 1\n255\n1 2 3 4", "unexpected data after the pixels at byte 17");
          ]);
    Alcotest.test_case "write_file replaces the file only when complete" `Quick (fun () ->
        let dir = Helpers.temp_dir () in
        let path = Filename.concat dir "out.ppm" in
        (match Files.write_ppm path (image_2x1 ()) with Ok () -> () | Error (`Msg m) -> Alcotest.fail m);
        (match Files.read_ppm path with
        | Ok img -> Alcotest.(check bool) __LOC__ true (Image.equal img (image_2x1 ()))
        | Error (`Msg m) -> Alcotest.fail m);
        Alcotest.(check (list string)) __LOC__ [ "out.ppm" ] (Array.to_list (Sys.readdir dir)));
    Alcotest.test_case "writing into a missing directory is an error that names it" `Quick (fun () ->
        match Files.write_ppm "/nonexistent-dir/out.ppm" (image_2x1 ()) with
        | Ok () -> Alcotest.fail "wrote into a missing directory"
        | Error (`Msg m) ->
            Alcotest.(check string) __LOC__
              "/nonexistent-dir/out.ppm: cannot create a file in its directory: No such file or directory" m);
    Alcotest.test_case "a full disk leaves no temporary file" `Quick (fun () ->
        if not (Sys.file_exists "/dev/full") then Helpers.skip "ppm: a full disk" ~why:"there is no /dev/full"
        else
          match Files.write_ppm "/dev/full" (image_2x1 ()) with
          | Ok () -> Alcotest.fail "wrote to /dev/full"
          | Error (`Msg m) -> Alcotest.(check string) __LOC__ "/dev/full: No space left on device" m);
  ]
