let to_string x =
  if Float.is_integer x && Float.abs x < 1e15 then Printf.sprintf "%.0f" x
  else
    let rec shortest precision =
      let s = Printf.sprintf "%.*g" precision x in
      if precision >= 17 || float_of_string s = x then s else shortest (precision + 1)
    in
    if Float.is_nan x then "nan"
    else if x = Float.infinity then "inf"
    else if x = Float.neg_infinity then "-inf"
    else shortest 1

let of_string s =
  (* OCaml accepts "1_000" and "0x1p3" (fine) but also "nan" and "inf",
     which mean nothing in a scene. *)
  match float_of_string_opt s with
  | Some x when Float.is_finite x -> Some x
  | _ -> None
