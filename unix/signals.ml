let handled =
  Sys.
    [
      sigint; sigterm; sighup; sigquit; sigusr1; sigusr2; sigalrm; sigpipe; sigxcpu; sigxfsz; sigvtalrm; sigprof;
    ]

(* Signals that C code of another library handles itself, which
   [Sys.signal] reports as [Signal_default] and would then reset. *)
let left_alone = ref []

let leave_alone signal = if not (List.mem signal !left_alone) then left_alone := signal :: !left_alone
let active () = List.filter (fun s -> not (List.mem s !left_alone)) handled

let redeliver signal previous =
  match previous with
  | Sys.Signal_handle f -> f signal
  | Sys.Signal_ignore -> ()
  | Sys.Signal_default ->
      (* The signal is blocked while its OCaml handler runs: delivered
         again with its default action when this handler returns. *)
      Sys.set_signal signal Sys.Signal_default;
      Unix.kill (Unix.getpid ()) signal

let protect ~cleanup f =
  let owner = Unix.getpid () in
  let cleaned = ref false in
  let install signal =
    let saved = ref Sys.Signal_default in
    let handler s =
      (* A child forked inside the section inherits this handler until it
         calls [reset_in_child]: it must not clean up after its parent,
         and ends by the signal as it would have by default. *)
      if Unix.getpid () <> owner then redeliver s Sys.Signal_default
      else begin
        if not !cleaned then begin
          cleaned := true;
          cleanup ()
        end;
        redeliver s !saved
      end
    in
    match Sys.signal signal (Sys.Signal_handle handler) with
    | Sys.Signal_ignore ->
        Sys.set_signal signal Sys.Signal_ignore;
        (signal, Sys.Signal_ignore)
    | before ->
        saved := before;
        (signal, before)
  in
  let previous = List.map install (active ()) in
  Fun.protect ~finally:(fun () -> List.iter (fun (s, b) -> Sys.set_signal s b) previous) f

let reset_in_child () =
  List.iter
    (fun s ->
      match Sys.signal s Sys.Signal_default with
      | Sys.Signal_ignore -> Sys.set_signal s Sys.Signal_ignore
      | _ -> ())
    (active ())

let without_sigxfsz f =
  match Sys.signal Sys.sigxfsz Sys.Signal_ignore with
  | previous -> Fun.protect ~finally:(fun () -> Sys.set_signal Sys.sigxfsz previous) f
  | exception (Invalid_argument _ | Sys_error _) -> f ()
