(* The command line fuzzed: random argument vectors built from the real
   commands, options and values (and junk), random RAYTRACE_* variables
   with hostile values, TERM and DISPLAY set or not, descriptors 0, 1 and
   2 closed or full. Every run
   must end, within a time bound, with a documented status (0, 1, 3, 124),
   at most one line on stderr besides the "wrote" lines (more with
   --stats), and never a backtrace, "Fatal error" or "internal error".

   RAYTRACE_FUZZ_CLI=N runs N cases instead of the default 120 (fixed seed;
   RAYTRACE_FUZZ_CLI_SEED changes it). *)

let exe () = Helpers.raytrace ()

let write path text =
  let oc = open_out_bin path in
  output_string oc text;
  close_out oc

let pick rand a = a.(Random.State.int rand (Array.length a))

let junk rand =
  let n = Random.State.int rand 12 in
  String.init n (fun _ ->
      match Random.State.int rand 4 with
      | 0 -> Char.chr (1 + Random.State.int rand 255)
      | _ -> pick rand [| 'a'; '-'; '='; '%'; 'd'; '/'; '.'; '0'; '9'; ':'; ','; ' '; 'e'; '\n' |])

(* Issue 27's scenes (soft lights, a lens, textures: globe.scene reads
   earth.ppm and tiles.ppm) and scenes whose texture file is a directory,
   empty, truncated, huge in declared size or missing are among them. *)
let files =
  [| "s.scene"; "orbit.scene"; "bad.scene"; "i.ppm"; "p1.ppm"; "p2.ppm"; "link.scene"; "missing.scene"; "."; "sub"; "/dev/null";
     "/dev/stdin"; "-"; ""; "area-room.scene"; "focus.scene"; "globe.scene"; "tex-sub.scene"; "tex-empty.scene";
     "tex-truncated.scene"; "tex-huge.scene"; "tex-missing.scene"; "earth.ppm"; "empty.ppm" |]

let outputs =
  [| "out.ppm"; "out.png"; "-"; "/dev/null"; "/dev/full"; "/dev/stdout"; "f%d.ppm"; "f%04d.png"; "."; "missing/x.ppm";
     "s.scene"; "p1.ppm"; "i.ppm"; "link.scene"; ""; "sub/../out.ppm" |]

let ints = [| "0"; "1"; "3"; "17"; "-1"; "65537"; "abc"; ""; "1e3"; "0x10"; "99999999999999999999"; "4"; "2" |]

(* An option and its values; [None] for a flag. *)
let options =
  [|
    ("--width", Some ints); ("--height", Some ints); ("--depth", Some [| "0"; "1"; "3"; "64"; "65"; "-1"; "x" |]);
    ("-d", Some [| "2"; "-5" |]); ("--jobs", Some [| "1"; "2"; "0"; "-3"; "100000"; "x" |]); ("-j", Some [| "2" |]);
    ("--samples", Some [| "1"; "2"; "3"; "0"; "65"; "-1" |]); ("--adaptive", Some [| "0"; "2"; "255"; "-1"; "300" |]);
    ("--subsample", None); ("--stats", None); ("--literal", None);
    ("--tile", Some [| "1/2"; "2/2"; "0/2"; "3/2"; "1/0"; "a/b"; "1/100000" |]);
    ("--region", Some [| "0,0,2,2"; "0,0,0,0"; "5,5,1,1"; "0,0,99999,1"; "x" |]);
    ("--frames", Some [| "0"; "0:1"; "1:0"; "0:2"; "47"; "999999999"; "x:y"; "-1:2"; "46:48" |]);
    ("-o", Some outputs); ("--output", Some outputs); ("--max-diff", Some [| "0"; "1"; "-1"; "x" |]);
    ("--help", None); ("--help=plain", None); ("--help=groff", None); ("--version", None); ("--", None);
    ("--bogus", None);
  |]

let commands = [| "render"; "render"; "render"; "merge"; "diff"; "view"; "help"; "rendr"; "--help"; "--version"; "" |]

let variables = [| "PIXELS"; "DEPTH"; "SAMPLES"; "SPHERES"; "LIGHTS"; "SCENE_BYTES"; "WORK" |]

let hostile_values =
  [| ""; "0"; "-1"; "1"; "10"; "1e309"; "nan"; "inf"; "lots"; "99999999999999999999"; "1_000"; " 5"; "1e12"; "0x7fffffff"; "3.5" |]

type case = { args : string list; env : string list; closed : int list; full : int list }

let generate rand =
  let args = ref [] in
  let add a = args := a :: !args in
  (match pick rand commands with "" -> () | c -> add c);
  for _ = 1 to Random.State.int rand 7 do
    match Random.State.int rand 10 with
    | 0 | 1 -> add (pick rand files)
    | 2 -> add (junk rand)
    | _ -> (
        let name, values = pick rand options in
        match values with
        | None -> add name
        | Some v when Random.State.int rand 8 = 0 -> add (name ^ "=" ^ pick rand v)
        | Some v -> add name; if Random.State.int rand 12 > 0 then add (pick rand v))
  done;
  let env =
    List.init (Random.State.int rand 3) (fun _ ->
        Printf.sprintf "RAYTRACE_MAX_%s=%s" (pick rand variables) (pick rand hostile_values))
    @ (if Random.State.bool rand then [ "TERM=xterm" ] else [])
    (* No X server answers there: the window is status 3. *)
    @ (match Random.State.int rand 4 with 0 -> [ "DISPLAY=" ] | 1 -> [ "DISPLAY=:98765" ] | _ -> [])
  in
  let chosen p = List.filter (fun _ -> Random.State.int rand 100 < p) [ 0; 1; 2 ] in
  let closed = chosen 12 in
  let full = List.filter (fun fd -> fd > 0 && not (List.mem fd closed)) (chosen 8) in
  { args = List.rev !args; env; closed; full }

let show c =
  Printf.sprintf "%s %s%s%s" (String.concat " " c.env)
    (String.concat " " (List.map (fun a -> Filename.quote (String.escaped a)) ("raytrace" :: c.args)))
    (String.concat "" (List.map (fun fd -> Printf.sprintf " %d>&-" fd) c.closed))
    (String.concat "" (List.map (fun fd -> Printf.sprintf " %d>/dev/full" fd) c.full))

(* The inputs, written afresh before every case (a case may overwrite
   them, as a user may). *)
let workspace () =
  let dir = Helpers.temp_dir () in
  let render args =
    match Helpers.run (exe ()) args with
    | 0, out, _ -> out
    | _, _, err -> Alcotest.failf "setting up: %s" err
  in
  let scene = In_channel_free.read (Helpers.scene_path "cgfs.scene") in
  let part i = render [ "render"; Helpers.scene_path "cgfs.scene"; "--tile"; i ^ "/2"; "--width"; "8"; "--height"; "8"; "-o"; "-" ] in
  let contents =
    [ ("s.scene", scene); ("orbit.scene", In_channel_free.read (Helpers.scene_path "orbit.scene"));
      ("bad.scene", "(sphere (radius -1))\n"); ("i.ppm", render [ "render"; "--width"; "8"; "--height"; "8"; "-o"; "-" ]);
      ("p1.ppm", part "1"); ("p2.ppm", part "2") ]
    @ List.map
        (fun f -> (f, In_channel_free.read (Helpers.scene_path f)))
        [ "area-room.scene"; "focus.scene"; "globe.scene"; "earth.ppm"; "tiles.ppm" ]
    @ List.map
        (fun (name, file) ->
          ( name,
            Printf.sprintf
              "(canvas (width 8) (height 6))\n(sphere (center 0 0 3) (radius 1) (color 1 2 3) (texture (file %S) (mapping spherical)))\n"
              file ))
        [ ("tex-sub.scene", "sub"); ("tex-empty.scene", "empty.ppm"); ("tex-truncated.scene", "truncated.ppm");
          ("tex-huge.scene", "huge.ppm"); ("tex-missing.scene", "missing.ppm") ]
    @ [ ("empty.ppm", ""); ("truncated.ppm", "P6\n4 4\n255\n\001\002\003"); ("huge.ppm", "P6\n16384 16384\n255\n") ]
  in
  let reset () =
    Array.iter
      (fun f ->
        let p = Filename.concat dir f in
        if (Unix.lstat p).st_kind <> S_DIR then Sys.remove p)
      (Sys.readdir dir);
    List.iter (fun (f, text) -> write (Filename.concat dir f) text) contents;
    Unix.symlink "s.scene" (Filename.concat dir "link.scene");
    if not (Sys.file_exists (Filename.concat dir "sub")) then Unix.mkdir (Filename.concat dir "sub") 0o755
  in
  (dir, reset)

let time_bound = 60.

(* Runs a case; its exit status, stderr, and seconds. *)
let run_case dir c =
  let err = Filename.temp_file "rtfuzz" ".err" and out = Filename.temp_file "rtfuzz" ".out" in
  let env = Array.of_list (("PATH=" ^ Option.value (Sys.getenv_opt "PATH") ~default:"/usr/bin:/bin") :: c.env) in
  let argv = Array.of_list (exe () :: c.args) in
  let exe = exe () in
  flush stdout;
  flush stderr;
  let t0 = Unix.gettimeofday () in
  let pid =
    match Unix.fork () with
    | 0 -> (
        try
          Unix.chdir dir;
          let target fd = if List.mem fd c.full then "/dev/full" else if fd = 1 then out else err in
          Unix.dup2 (Unix.openfile "/dev/null" [ O_RDONLY ] 0) Unix.stdin;
          List.iter
            (fun (fd, d) -> Unix.dup2 (Unix.openfile (target fd) [ O_WRONLY; O_TRUNC ] 0) d)
            [ (1, Unix.stdout); (2, Unix.stderr) ];
          List.iter (fun fd -> Unix.close (List.nth [ Unix.stdin; Unix.stdout; Unix.stderr ] fd)) c.closed;
          List.iter (fun s -> Sys.set_signal s Sys.Signal_default) [ Sys.sigint; Sys.sigpipe ];
          Unix.execve exe argv env
        with _ -> Unix._exit 97)
    | pid -> pid
  in
  let rec wait () =
    match Unix.waitpid [ WNOHANG ] pid with
    | 0, _ when Unix.gettimeofday () -. t0 > time_bound ->
        Unix.kill pid Sys.sigkill;
        ignore (Unix.waitpid [] pid);
        None
    | 0, _ ->
        Unix.sleepf 0.01;
        wait ()
    | _, status -> Some status
  in
  let status = wait () in
  let seconds = Unix.gettimeofday () -. t0 in
  let text = In_channel_free.read err in
  Sys.remove err;
  Sys.remove out;
  (status, text, seconds)

let forbidden = [ "internal error"; "Fatal error"; "exception"; "Raised at"; "Called from"; "uncaught" ]

(* How many runs ended with each status, to show what was reached. *)
let statuses = Hashtbl.create 8

let check c (status, err, seconds) =
  let fail fmt = Printf.ksprintf (fun m -> Alcotest.failf "%s\n  case: %s\n  stderr: %S" m (show c) err) fmt in
  let code =
    match status with
    | None -> fail "still running after %.0f s" seconds
    | Some (Unix.WEXITED c) -> c
    | Some (WSIGNALED s) -> fail "killed by signal %d" s
    | Some (WSTOPPED s) -> fail "stopped by signal %d" s
  in
  Hashtbl.replace statuses code (1 + Option.value (Hashtbl.find_opt statuses code) ~default:0);
  if code = 97 then fail "the test could not start raytrace (status 97 of its own child)";
  if not (List.mem code [ 0; 1; 3; 124 ]) then fail "exit status %d" code;
  List.iter (fun w -> if Astring_free.contains err w then fail "%S on stderr" w) forbidden;
  let lines =
    String.split_on_char '\n' err
    |> List.filter (fun l -> l <> "" && not (String.length l > 16 && String.sub l 0 16 = "raytrace: wrote "))
  in
  let stats = code = 0 && List.exists (fun a -> a = "--stats") c.args in
  if List.length lines > 1 && not stats then fail "%d lines on stderr" (List.length lines);
  if code <> 0 && lines = [] && not (List.mem 2 c.closed || List.mem 2 c.full) then fail "status %d without a message" code

let cases () =
  match Sys.getenv_opt "RAYTRACE_FUZZ_CLI" with
  | Some n -> ( match int_of_string_opt n with Some n when n >= 0 -> n | _ -> Alcotest.failf "RAYTRACE_FUZZ_CLI=%S" n)
  | None -> 120

let seed () = match Option.bind (Sys.getenv_opt "RAYTRACE_FUZZ_CLI_SEED") int_of_string_opt with Some s -> s | None -> 11

let fuzz () =
  let dir, reset = workspace () in
  let rand = Random.State.make [| seed () |] in
  let slowest = ref 0. in
  for _ = 1 to cases () do
    let c = generate rand in
    reset ();
    let (_, _, seconds) as result = run_case dir c in
    slowest := Float.max !slowest seconds;
    check c result
  done;
  Printf.printf "%d command lines (seed %d), the slowest %.2f s; statuses %s\n" (cases ()) (seed ()) !slowest
    (Hashtbl.fold (fun code n acc -> Printf.sprintf "%d: %d" code n :: acc) statuses []
    |> List.sort compare |> String.concat ", ")

let tests =
  [
    Alcotest.test_case "random command lines, environments and closed descriptors end in a documented status and one line"
      `Quick fuzz;
  ]
