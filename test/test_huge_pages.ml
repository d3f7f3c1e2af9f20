(* Huge pages: the kernel's setting read right, the blocks of 4 MiB or
   more marked in a program linked as the command line is (this test
   program is), huge pages held where the kernel gives them, and the same
   image with them on and off. *)

let mode = Alcotest.testable (fun ppf m ->
  Format.pp_print_string ppf
    (match m with
     | Huge_pages.Always -> "always" | Madvise -> "madvise" | Never -> "never" | Unknown -> "unknown"))
  ( = )

let setting () =
  List.iter
    (fun (text, expected) -> Alcotest.check mode text expected (Huge_pages.mode_of_setting text))
    [
      ("always [madvise] never", Huge_pages.Madvise);
      ("[always] madvise never", Always);
      ("always madvise [never]", Never);
      ("always madvise [never]\n", Never);
      ("", Unknown);
      ("always madvise never", Unknown);
      ("[sometimes] never", Unknown);
      ("] [", Unknown);
    ]

let starts_with ~prefix s = String.length s >= String.length prefix && String.sub s 0 (String.length prefix) = prefix

(* A 64 MiB array, written: marked, and held in huge pages where the
   kernel's mode lets a program ask for them. *)
let in_process () =
  if Huge_pages.mode () = Unknown then
    (* Not Linux, or no huge pages in its kernel: nothing is asked. *)
    Alcotest.(check bool) "status off" true (starts_with ~prefix:"off (" (Huge_pages.status ()))
  else if not (Huge_pages.wrapped ()) then Alcotest.fail "the test program is not linked with -Wl,--wrap=malloc"
  else if not (Huge_pages.enabled ()) then Helpers.skip "huge pages in this process" ~why:(Huge_pages.variable ^ "=0 here")
  else begin
    let before = Huge_pages.asked () and held_before = Huge_pages.resident_mb () in
    let a = Array.make (8 * 1024 * 1024) 1. in
    Alcotest.(check bool) "a 64 MiB array is marked" true (Huge_pages.asked () > before);
    let status = Huge_pages.status () in
    (match (Huge_pages.mode (), Huge_pages.resident_mb (), held_before) with
    | (Madvise | Always), Some after, Some before ->
        (* The kernel may fall short of free huge pages: most of the
           array, not all of it. *)
        Alcotest.(check bool)
          (Printf.sprintf "huge pages held: %.1f MB before, %.1f MB after (at least 16 more)" before after)
          true (after -. before >= 16.);
        Alcotest.(check bool) ("status on: " ^ status) true (starts_with ~prefix:"on" status)
    | (Madvise | Always), None, _ | (Madvise | Always), _, None ->
        Helpers.skip "huge pages held" ~why:"no /proc/self/smaps_rollup"
    | (Never | Unknown), _, _ -> Alcotest.(check bool) ("status off: " ^ status) true (starts_with ~prefix:"off (" status));
    Alcotest.(check (float 0.)) "the array is intact" 1. a.(Array.length a - 1)
  end

(* The command line's --stats line, on and off, and the same bytes. *)
let command_line () =
  let dir = Helpers.temp_dir () in
  let render env name =
    let out = Filename.concat dir name in
    let c, _, err =
      Helpers.run ~env:(Array.append env (Unix.environment ())) (Helpers.raytrace ())
        [ "render"; Helpers.scene_path "cgfs.scene"; "--width"; "1200"; "--height"; "1200"; "--jobs"; "1"; "--stats"; "-o"; out ]
    in
    Alcotest.(check int) ("exit status: " ^ err) 0 c;
    let line =
      List.find_opt (starts_with ~prefix:"huge pages") (String.split_on_char '\n' err)
      |> Option.map (fun l -> String.trim (String.sub l 10 (String.length l - 10)))
    in
    match line with None -> Alcotest.fail ("no huge pages line in --stats: " ^ err) | Some l -> (out, l)
  in
  let off, off_line = render [| Huge_pages.variable ^ "=0" |] "off.ppm" in
  let on, on_line = render [| Huge_pages.variable ^ "=1" |] "on.ppm" in
  (match Huge_pages.mode () with
  | Madvise ->
      Alcotest.(check string) "off" ("off (" ^ Huge_pages.variable ^ "=0)") off_line;
      Alcotest.(check bool) ("on: " ^ on_line) true (starts_with ~prefix:"on, " on_line)
  | Always -> Alcotest.(check bool) ("on: " ^ on_line) true (starts_with ~prefix:"on (" on_line)
  | Never | Unknown -> Alcotest.(check bool) ("off: " ^ on_line) true (starts_with ~prefix:"off (" on_line));
  let read p = In_channel_free.read p in
  Alcotest.(check bool) "the same image on and off" true (read on = read off)

let tests =
  [
    Alcotest.test_case "the kernel's setting" `Quick setting;
    Alcotest.test_case "a large block in huge pages" `Quick in_process;
    Alcotest.test_case "--stats, on and off, same image" `Quick command_line;
  ]
