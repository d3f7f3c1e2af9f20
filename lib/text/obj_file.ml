(* The public part of the OBJ reader and writer, whose code is in
   [Obj_text] (it shares the parser with the two-part reading of
   [Obj_parts]). *)
include Obj_text
