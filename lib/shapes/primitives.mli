(** The registry of described primitive kinds: one line per kind. The
    scene text makes a form of each ({!Shape_desc.t.fields}), and a CSG
    operand of each closed one.

    The sphere, plane, triangle and box predate the descriptions: they are
    {!Shape.t}'s own constructors and not listed here. *)

val all : Shape_desc.any list
(** [all] is every described kind, in the order scene text lists their forms. *)

val find : string -> Shape_desc.any option
(** [find name] is the described kind whose form is [name], if any. *)
