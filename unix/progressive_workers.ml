(* Primary, shadow and reflection rays, tests, box tests, early stops. *)
let counter_fields = 6

let v ~jobs ~width ~height =
  if jobs < 2 then invalid_arg "Progressive_workers.v: jobs < 2";
  let image = Image.of_buffer width height (Parallel.shared_bytes (3 * width * height)) in
  let ints = Parallel.shared_ints (jobs * counter_fields) in
  let budget = Parallel.shared_ints (jobs * Raytrace.Private.Render_work.counter_fields) in
  let run n work =
    Bigarray.Array1.fill ints 0L;
    let child w =
      let counts = work w in
      Array.iteri (fun i c -> ints.{(w * counter_fields) + i} <- Int64.of_int c) counts
    in
    match Parallel.run n child with
    | exception Unix.Unix_error (e, f, _) -> Error (`Msg (Printf.sprintf "%s: %s" f (Unix.error_message e)))
    | Error (`Msg m) -> Error (`Msg m)
    | Ok () -> Ok (Array.init n (fun w -> Array.init counter_fields (fun i -> Int64.to_int ints.{(w * counter_fields) + i})))
  in
  { Raytrace_view.Progressive.jobs; image; run; budget }
