(* The library as a user installs it: the core package alone builds the
   README's example (examples/hello_scene.ml) in a dune project of its own,
   and requires no system library. *)

(* The libraries installed by `dune build @install`, as `dune install`
   would lay them out. *)
let installed = Filename.concat (Sys.getcwd ()) "../../install/default/lib"

let read path = match File_io.read path with Ok s -> s | Error (`Msg m) -> Alcotest.fail m

let write path text =
  let oc = open_out_bin path in
  output_string oc text;
  close_out oc

(* The packages that the top-level [requires] of a META file names (those
   of its sub-packages, which come after their [package] line, are not the
   core's). *)
let top_level_requires meta =
  let lines = String.split_on_char '\n' meta in
  let rec go acc = function
    | [] -> acc
    | l :: _ when String.length (String.trim l) >= 7 && String.sub (String.trim l) 0 7 = "package" -> acc
    | l :: rest -> (
        let l = String.trim l in
        match String.index_opt l '"' with
        | Some i when String.length l > 8 && String.sub l 0 8 = "requires" ->
            let j = String.rindex l '"' in
            let names = String.split_on_char ' ' (String.sub l (i + 1) (j - i - 1)) in
            go (acc @ List.filter (( <> ) "") names) rest
        | _ -> go acc rest)
  in
  go [] lines


(* The public surface, read from the installed interfaces: raytrace.mli is
   the compiled interface of [Raytrace] (the compiler checks raytrace.ml
   against it), and each module's .mli is installed under its own name. *)
let installed_mli name = read (Filename.concat installed ("raytrace/" ^ String.uncapitalize_ascii name ^ ".mli"))

let is_ident_char c = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c = '_' || c = '\''

(* The identifiers of [text], in order. *)
let identifiers text =
  let words = ref [] and start = ref (-1) in
  String.iteri
    (fun i c ->
      if is_ident_char c then (if !start < 0 then start := i)
      else if !start >= 0 then begin
        words := String.sub text !start (i - !start) :: !words;
        start := -1
      end)
    text;
  if !start >= 0 then words := String.sub text !start (String.length text - !start) :: !words;
  List.rev !words

let starts_with ~prefix s = String.length s >= String.length prefix && String.sub s 0 (String.length prefix) = prefix

(* The names of the modules that [Raytrace] declares at its top level. *)
let top_modules mli =
  List.filter_map
    (fun line -> if starts_with ~prefix:"module " line then Some (List.nth (identifiers line) 1) else None)
    (String.split_on_char '\n' mli)

(* The text before [module Private], and the modules it exposes: [B] of
   every [module A = B] and of every [include B], nested ones included. *)
let public_part mli =
  let rec before acc = function
    | [] -> List.rev acc
    | l :: _ when starts_with ~prefix:"module Private" l -> List.rev acc
    | l :: rest -> before (l :: acc) rest
  in
  before [] (String.split_on_char '\n' mli)

let public_modules mli =
  List.concat_map
    (fun line ->
      match identifiers line with
      | "module" :: _ :: _ when String.contains line '=' ->
          let rhs = String.sub line (String.index line '=' + 1) (String.length line - String.index line '=' - 1) in
          (match identifiers rhs with m :: _ -> [ m ] | [] -> [])
      | ws ->
          let rec includes = function
            | "include" :: m :: rest when m <> "module" -> m :: includes rest
            | _ :: rest -> includes rest
            | [] -> []
          in
          includes ws)
    (public_part mli)
  |> List.sort_uniq compare

(* The documented interface: the text outside the (**/**) pairs, which
   odoc leaves out (a marker hides what follows it, the next shows again). *)
let documented mli =
  let marker = "(**/**)" in
  let n = String.length marker in
  let b = Buffer.create (String.length mli) in
  let rec go i shown =
    if i >= String.length mli then ()
    else if i + n <= String.length mli && String.sub mli i n = marker then go (i + n) (not shown)
    else begin
      if shown then Buffer.add_char b mli.[i];
      go (i + 1) shown
    end
  in
  go 0 true;
  Buffer.contents b

(* The kernel's names, which no public module's documentation may show:
   as a path or a reference ([Trace.t], [{!Raytrace.Private.Trace}],
   [= Trace]), not as a word of prose (the book is "Computer Graphics
   from Scratch"). *)
let kernel_names = [ "Scratch"; "Trace"; "Tracer"; "Prepared"; "Kind" ]

let kernel_mentions ~name text =
  let text = documented text in
  let len = String.length text in
  let rec prev_visible i = if i >= 0 && text.[i] = ' ' then prev_visible (i - 1) else i in
  let found = ref [] in
  let i = ref 0 in
  while !i < len do
    if is_ident_char text.[!i] && (!i = 0 || not (is_ident_char text.[!i - 1])) then begin
      let j = ref !i in
      while !j < len && is_ident_char text.[!j] do incr j done;
      let w = String.sub text !i (!j - !i) in
      let before = prev_visible (!i - 1) in
      let as_path =
        (!i > 0 && (text.[!i - 1] = '.' || text.[!i - 1] = '!'))
        || (!j < len && text.[!j] = '.')
        || (before >= 0 && (text.[before] = '=' || text.[before] = ':'))
      in
      if List.mem w kernel_names && as_path then found := (name ^ ": " ^ w) :: !found;
      i := !j
    end
    else incr i
  done;
  List.rev !found

let tests =
  [
    Alcotest.test_case "Raytrace lists at most 20 modules, Private among them" `Quick (fun () ->
        let modules = top_modules (installed_mli "Raytrace") in
        if not (List.mem "Private" modules) then Alcotest.failf "no Private among %s" (String.concat " " modules);
        if List.length modules > 20 then
          Alcotest.failf "Raytrace lists %d modules: %s" (List.length modules) (String.concat " " modules));
    Alcotest.test_case "no public module's documented interface names the kernel" `Quick (fun () ->
        let raytrace = installed_mli "Raytrace" in
        let modules = public_modules raytrace in
        (* The nested ones are found too: a user meets Camera.Path. *)
        List.iter
          (fun m -> if not (List.mem m modules) then Alcotest.failf "%s is not among the public modules %s" m (String.concat " " modules))
          [ "Camera_path"; "Obj_file"; "Sampling"; "Image_diff"; "Scene"; "Shape" ];
        let mentions =
          kernel_mentions ~name:"Raytrace" (String.concat "\n" (public_part raytrace))
          @ List.concat_map (fun m -> kernel_mentions ~name:m (installed_mli m)) modules
        in
        if mentions <> [] then Alcotest.failf "kernel names in the documented interface: %s" (String.concat ", " mentions));
    Alcotest.test_case "the installed core library requires no system library" `Quick (fun () ->
        let requires = top_level_requires (read (Filename.concat installed "raytrace/META")) in
        Alcotest.(check bool) __LOC__ true (List.mem "parsexp" requires);
        List.iter
          (fun banned ->
            if List.exists (fun r -> r = banned || String.length r > String.length banned && String.sub r 0 (String.length banned + 1) = banned ^ ".") requires
            then Alcotest.failf "the core's META requires %s: %s" banned (String.concat " " requires))
          [ "unix"; "threads"; "graphics"; "camlimages"; "cmdliner"; "raytrace-png" ]);
    Alcotest.test_case "the README example builds against the installed core library alone, and renders" `Slow
      (fun () ->
        let dir = Helpers.temp_dir () in
        write (Filename.concat dir "dune-project") "(lang dune 2.9)\n";
        write (Filename.concat dir "dune") "(executable\n (name hello_scene)\n (libraries raytrace))\n";
        write (Filename.concat dir "hello_scene.ml") (read "../examples/hello_scene.ml");
        (* OCAMLPATH: the installed libraries first, then the system's;
           INSIDE_DUNE would make the inner dune share this build's
           settings. *)
        let env =
          Array.of_list
            (("OCAMLPATH=" ^ installed)
            :: List.filter
                 (fun v -> not (List.exists (fun p -> String.length v >= String.length p && String.sub v 0 (String.length p) = p) [ "OCAMLPATH="; "INSIDE_DUNE="; "DUNE_" ]))
                 (Array.to_list (Unix.environment ())))
        in
        let code, _, err =
          Helpers.run ~env "/bin/sh" [ "-c"; "cd " ^ Filename.quote dir ^ " && dune build --root . --display quiet ./hello_scene.exe" ]
        in
        if code <> 0 then Alcotest.failf "dune build failed (%d): %s" code err;
        let out = Filename.concat dir "hello.ppm" in
        let code, stdout, err = Helpers.run (Filename.concat dir "_build/default/hello_scene.exe") [ out ] in
        Alcotest.(check int) err 0 code;
        Alcotest.(check string) __LOC__ ("wrote " ^ out ^ "\n") stdout;
        match (Files.read_ppm out, Files.read_ppm "golden/hello_scene.ppm") with
        | Ok img, Ok expected -> Helpers.check_images ~max_abs:1 "hello_scene" ~expected img
        | Error (`Msg m), _ | _, Error (`Msg m) -> Alcotest.fail m);
  ]
