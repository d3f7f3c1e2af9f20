(* One line per described kind, in the order scene text lists them. *)
let all : Shape_desc.any list = [ Any Cylinder.desc; Any Disk.desc; Any Cone.desc; Any Torus.desc ]

let find name = List.find_opt (fun (Shape_desc.Any d) -> d.name = name) all
