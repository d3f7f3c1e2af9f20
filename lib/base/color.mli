(** Colours (document section 2).

    A colour is an RGB triple of floats in the additive model, on the 0-255
    scale of 8-bit channels. Lighting and the reflection blend may push a
    channel outside [\[0, 255\]]: colours stay unclamped floats through the
    whole computation, and each channel is clamped and rounded once, by
    {!to_byte}, when a pixel is stored. *)

(** {1:colors Colours} *)

type t = { r : float; g : float; b : float }
(** The type for colours: red, green and blue on the 0-255 scale,
    unclamped. *)

val v : float -> float -> float -> t
(** [v r g b] is the colour [(r, g, b)]. *)

val black : t
(** [black] is [(0, 0, 0)]. *)

val white : t
(** [white] is [(255, 255, 255)]. *)

(** {1:functions Functions} *)

val add : t -> t -> t
(** [add c c'] is [c + c'], channel-wise: adding two lights' colours. *)

val smul : float -> t -> t
(** [smul k c] is [k (r, g, b) = (k r, k g, k b)] (section 2): [k > 1]
    brightens, [k < 1] darkens. *)

val blend : reflective:float -> local:t -> reflected:t -> t
(** [blend ~reflective:r ~local ~reflected] is
    [local * (1 - r) + reflected * r] (section 7.8), the colour of a point
    of a mirror of reflectivity [r], channel by channel in that order. *)

val clamp : float -> float
(** [clamp x] is [x] clamped to [\[0, 255\]] (section 2): [255] if
    [x > 255], [0] if [x < 0] or [x] is NaN, [x] otherwise. *)

val to_byte : float -> int
(** [to_byte x] is [clamp x] rounded to the nearest integer, ties to even
    (as the CGFS demos' canvas stores it): an integer in [\[0, 255\]], [0]
    for NaN. This is the one place where a channel is clamped. *)

val to_rgb8 : t -> int
(** [to_rgb8 c] is the pixel the renderer stores for [c], packed in one
    integer (no allocation): [(to_byte c.r lsl 16) lor (to_byte c.g lsl 8)
    lor to_byte c.b], so [0xRRGGBB] in [\[0, 0xFFFFFF\]]; red is
    [p lsr 16], green [(p lsr 8) land 0xFF], blue [p land 0xFF]. A NaN
    channel gives [0], as {!to_byte}. *)

val is_finite : t -> bool
(** [is_finite c] is [true] iff no channel is NaN or infinite. *)

val in_gamut : t -> bool
(** [in_gamut c] is [true] iff every channel lies in [\[0, 255\]] (so is
    not NaN): the colours a scene may give to objects and background. *)

(** {1:predicates Predicates and comparisons} *)

val equal : t -> t -> bool
(** [equal c c'] is [true] iff the channels are equal as floats. *)

val equal_f : (float -> float -> bool) -> t -> t -> bool
(** [equal_f eq c c'] is [true] iff [eq] holds on each pair of channels. *)

val compare : t -> t -> int
(** [compare c c'] orders colours lexicographically with [Float.compare]. *)

(** {1:fmt Formatters} *)

val pp : Format.formatter -> t -> unit
(** [pp ppf c] prints [c] as [(r g b)], the syntax of scene files. *)

val show : t -> string
(** [show c] is [c] formatted by {!pp}. *)

val pp_components : Format.formatter -> t -> unit
(** [pp_components ppf c] prints [c] as {!pp} does, without the
    parentheses: [r g b], as the [color] fields of scene forms write it. *)
