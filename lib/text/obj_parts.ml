(* The two-part reading of [Obj_text], shown apart from [Obj_file]. *)
type part = Obj_text.part

let create_part = Obj_text.create_part
let finish_part = Obj_text.finish_part
let part_triangle_count = Obj_text.part_triangle_count
let part_bytes = Obj_text.part_bytes
let join = Obj_text.join
