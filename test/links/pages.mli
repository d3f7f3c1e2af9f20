(** The documentation's pages, for the checks of test/links. *)

val read : string -> string
(** [read path] is the contents of the file [path]. *)

val lines : string -> string list
(** [lines path] is the lines of the file [path]. *)

val is_fence : string -> bool
(** [is_fence l] is [true] iff [l] opens or closes a fenced code block. *)

val prose : string -> (int * string) list
(** [prose path] is the lines of [path] outside fenced code blocks, each
    with its 1-based number. *)

val all : string -> string list
(** [all root] is README.md and docs/*.md, relative to [root], sorted. *)
