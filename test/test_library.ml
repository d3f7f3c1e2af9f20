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

let tests =
  [
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
