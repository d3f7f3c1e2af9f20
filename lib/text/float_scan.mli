(** Decimal floats read from bytes without allocating.

    The numbers of large text files (Wavefront OBJ meshes) are read here
    rather than by [float_of_string], which needs a fresh string per
    number. The result is always [float_of_string]'s, correctly rounded:
    simple decimals take Clinger's exact fast path (an integer mantissa of
    at most 2{^53} and a power of ten of at most 10{^22}, both exact
    floats, so one correctly rounded multiplication or division gives the
    correctly rounded result); decimals of 17 digits (doubles printed
    exactly) with such a power of ten are the integer split in two exact
    floats, multiplied or divided with the exact error terms of fused
    multiply-adds, and the sum rounded once when the bound on its error
    proves the rounding (else they fall back); any other decimal falls
    back to [float_of_string] on a copy of its bytes. *)

val to_float : Bytes.t -> int -> int -> float
(** [to_float b i j] is the value of the decimal [b.[i] .. b.[j-1]], equal
    to [float_of_string] of those bytes, or [nan] if they are not of the
    form [[+-]?digits[.digits]([eE][+-]?digits)?] with at least one digit
    in the mantissa (so ["nan"], ["inf"], hexadecimal floats and [_]
    separators are refused). Overflow gives an infinity, underflow zero,
    as [float_of_string].
    @raise Invalid_argument if [0 <= i <= j <= Bytes.length b] is false. *)

val into : Bytes.t -> int -> int -> float array -> int -> unit
(** [into b i j dst d] stores {!to_float}[ b i j] in [dst.(d)]. Unlike
    {!to_float}, whose result a caller receives boxed unless it is
    inlined, it allocates only on the fallback path: big scene files read
    their numbers with it.
    @raise Invalid_argument if [0 <= i <= j <= Bytes.length b] or
    [0 <= d < Array.length dst] is false. *)

val scan : Bytes.t -> int -> int -> float array -> int -> int
(** [scan b i j dst d] is the index just past the longest decimal of the
    form of {!to_float} that starts at [b.[i]] and ends at or before
    [b.[j-1]], its value {!to_float}[ b i e] stored in [dst.(d)]; it is
    [i], and [dst.(d)] is [nan], if no such decimal starts at [i]. An
    exponent marker that no digit follows is not part of the decimal:
    ["1e+x"] gives [1.] and the index of ['e']. A caller that checks the
    byte at the result (a delimiter) reads a number in one pass, where
    {!into} needs its end first; [into b i j dst d] is [scan b i j dst d]
    with [nan] stored unless the result is [j]. It allocates only where
    {!into} does.
    @raise Invalid_argument if [0 <= i <= j <= Bytes.length b] or
    [0 <= d < Array.length dst] is false. *)

val unsafe_scan : Bytes.t -> int -> int -> float array -> int -> int
(** [unsafe_scan b i j dst d] is {!scan}[ b i j dst d] without its checks:
    the caller knows [0 <= i <= j <= Bytes.length b] and
    [0 <= d < Array.length dst] (else memory is read or written out of
    bounds). A mesh's [v] lines read their numbers with it. *)

val of_string : string -> float
(** [of_string s] is {!to_float} on all of [s]. *)
