(** Floats as the text of scene files.

    Scene files and printed scenes write each number as the shortest decimal
    that reads back as the same float, so a printed scene parses back to an
    equal one.

    @canonical Raytrace.Private.Float_text *)

val to_string : float -> string
(** [to_string x] is the shortest decimal of [x] that [float_of_string]
    reads back as [x]; integral values print without a decimal point ([3],
    [-1]); [nan] and infinities print as [nan], [inf] and [-inf]. *)

val of_string : string -> float option
(** [of_string s] is the finite float written [s] in OCaml's float syntax
    (decimal or hexadecimal, with or without exponent), or [None] if [s] is
    not a number or denotes NaN or an infinity. *)
