(* The skip mechanism itself (Helpers.skip), as a run of the test program
   shows it: this suite runs the program again on itself, with a check
   forced to skip, once as a developer runs it and once under CI=true. *)

let force = "RAYTRACE_TEST_FORCE_SKIP"

(* The test program, run on this suite alone, with [vars] added to the
   environment less CI, and Alcotest's output files in a fresh directory. *)
let run_self vars =
  let env =
    Unix.environment () |> Array.to_list
    |> List.filter (fun v -> not (String.starts_with ~prefix:"CI=" v || String.starts_with ~prefix:(force ^ "=") v))
  in
  Helpers.run ~env:(Array.of_list (vars @ env)) Sys.executable_name
    [ "test"; "skips"; "--color=never"; "-o"; Helpers.temp_dir () ]

let contains what text expected =
  if not (Astring_free.contains text expected) then Alcotest.failf "%s: expected %S in:\n%s" what expected text

let tests =
  [
    Alcotest.test_case "a skipped check is on the console, and fails the run under CI=true" `Quick (fun () ->
        match Sys.getenv_opt force with
        | Some "" -> () (* a child run that has nothing to skip *)
        | Some why -> Helpers.skip "skips: the forced check" ~why
        | None ->
            let line = "SKIPPED skips: the forced check: forced by the test of skips" in
            let code, out, err = run_self [ force ^ "=forced by the test of skips" ] in
            Alcotest.(check int) ("without CI, a skip passes:\n" ^ out ^ err) 0 code;
            contains "the skip, as it happens" err (line ^ "\n");
            contains "the summary" err ("1 check SKIPPED, so not everything was tested:\n  " ^ line ^ "\n");
            let code, out, err = run_self [ force ^ "=forced by the test of skips"; "CI=true" ] in
            Alcotest.(check int) ("under CI=true, a skip fails the run:\n" ^ out ^ err) 1 code;
            contains "the failed test" out "[FAIL]";
            contains "the summary under CI" err ("1 check SKIPPED, so not everything was tested:\n  " ^ line ^ "\n");
            (* And a run without skips has no summary. *)
            let code, _, err = run_self [ force ^ "="; "CI=true" ] in
            Alcotest.(check int) "no skip, CI=true" 0 code;
            if Astring_free.contains err "SKIPPED" then Alcotest.failf "a run without skips mentions one:\n%s" err);
  ]
