(* The public face of Scene_text: the machinery of parts stays there. *)
type error = { file : string; line : int; column : int; message : string }

let error_message e =
  Scene_text.error_message { Scene_text.file = e.file; line = e.line; column = e.column; message = e.message }

let pp_error ppf e = Format.pp_print_string ppf (error_message e)

let located ?limits ?load_mesh ?load_texture ?file ?reader text =
  Result.map_error
    (fun (e : Scene_text.error) -> { file = e.file; line = e.line; column = e.column; message = e.message })
    (Scene_text.located ?limits ?load_mesh ?load_texture ?file ?reader text)

let of_string = Scene_text.of_string
let to_string = Scene_text.to_string
