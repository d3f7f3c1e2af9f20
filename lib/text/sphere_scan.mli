(** Plain sphere forms read straight into numbers.

    The scene reader's fastest path: a big scene is mostly lines such as
    [(sphere (center -499.5 -0.6 2000) (radius 0.4) (color 255 0 0))], and
    this reads their fields into a float array with no tree and no string.
    Two readers, which agree wherever the first reads: {!layout} knows
    only the one-space layout that generators write, reads a literal such
    as [") (radius "] with a comparison or two and each number in one
    pass ({!Float_scan.scan}), and gives up on anything else; {!general}
    reads any plain form of a sphere (blanks and line comments anywhere,
    {!Sexp_scan}'s atoms). {!read} tries the first, then the second.

    @canonical Raytrace.Private.Sphere_scan *)

type t = private {
  values : float array;
      (** center x y z, radius, color r g b, specular, reflective: 9 floats,
          those of the fields read. *)
  mutable seen : int;
      (** The fields read, one bit each: center 1, radius 2, color 4,
          specular 8, reflective 16. *)
}
(** The type for a sphere's fields being read. *)

val create : unit -> t
(** [create ()] is a reader's fields, none read. *)

val general : t -> string -> int -> int
(** [general f s i] reads the plain sphere form that opens at [s.[i]] into
    [f] and is the index just past its closing parenthesis: the atom
    [sphere], then fields [(center x y z)], [(radius r)], [(color r g b)],
    [(specular s)], [(reflective k)] in any order, each at most once,
    whose values are atoms that {!Float_scan.into} reads as finite floats
    ([Float_text]'s numbers), separated by blanks and line comments
    ({!Sexp_scan.skip_blank}). [f.seen] tells which fields it read;
    required fields are the caller's to check.
    @raise Sexp_scan.Unusual on anything else (the form is then not
    plain, or not a sphere this reads: parsexp and the scene's checks
    decide). *)

val layout : t -> string -> int -> int
(** [layout f s i] is {!general}[ f s i] where the form at [s.[i]] is in
    the layout [(sphere (FIELD N ...) ... (FIELD N))]: no blank but one
    space between a field's name and each of its numbers and between two
    fields, nothing else between parentheses, each number a decimal that
    a space or a closing parenthesis ends, and the form ends 16 bytes or
    more before the end of [s]. Elsewhere it is [-1], and [f] holds
    garbage: the caller reads the form with {!general}. It never
    raises. *)

val read : t -> string -> int -> int
(** [read f s i] is {!layout}[ f s i] where that is not [-1], else
    {!general}[ f s i].
    @raise Sexp_scan.Unusual as {!general} does. *)
