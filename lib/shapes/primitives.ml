(* One line per described kind, in the order scene text lists them. *)
let all : Shape_desc.any list = [ Any Torus.desc ]

let find name = List.find_opt (fun (Shape_desc.Any d) -> d.name = name) all
