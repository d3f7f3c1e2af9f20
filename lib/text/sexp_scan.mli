(** Plain S-expressions read straight from text.

    The scene reader's fast path: most scene files are parentheses, plain
    atoms ([A-Z a-z 0-9 . + - _]), blanks and [;] line comments, and this
    reads those several times faster than parsexp's general automaton.
    Anything else (strings, [#|] block and [#;] sexp comments, other
    characters in atoms, a lone carriage return, very long or deep forms,
    syntax errors) raises {!Unusual}: the caller then reads that text with
    parsexp, which decides what it means and reports the errors. Whatever
    this reads, parsexp reads alike.

    @canonical Raytrace.Private.Sexp_scan *)

exception Unusual
(** The text holds something this module leaves to parsexp. *)

val is_atom_char : char -> bool
(** [is_atom_char c] is [true] iff [c] may appear in a plain atom here:
    an ASCII letter or digit, or one of [. + - _]. *)

val skip_blank : string -> int -> int
(** [skip_blank s i] is the index of the first character at or after [i]
    that is neither blank (space, tab, newline, form feed, or a carriage
    return followed by a newline) nor in a [;] line comment, or
    [String.length s] if there is none.
    @raise Unusual on a carriage return not followed by a newline (parsexp
    refuses it). *)

val atom_end : string -> int -> int
(** [atom_end s i] is the index just past the plain atom that starts at
    [i]: the first index at or after [i] whose character is not
    {!is_atom_char}, or [String.length s]. *)

val form : string -> int -> max_bytes:int -> Sexplib0.Sexp.t * int
(** [form s i ~max_bytes] is the list that opens at [s.[i] = '('] and the
    index just past its closing parenthesis.
    @raise Unusual if the list holds anything but plain atoms, lists,
    blanks and line comments, is nested more than 64 deep, is not closed
    within [max_bytes] bytes of [i], or [s.[i]] is not ['(']. *)
