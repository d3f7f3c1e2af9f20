type t = { r : float; g : float; b : float } [@@deriving eq]

let v r g b = { r; g; b }
let black = v 0. 0. 0.
let white = v 255. 255. 255.
let add c c' = { r = c.r +. c'.r; g = c.g +. c'.g; b = c.b +. c'.b }
let smul k c = { r = k *. c.r; g = k *. c.g; b = k *. c.b }

let blend ~reflective ~local ~reflected =
  let keep = 1. -. reflective in
  {
    r = (local.r *. keep) +. (reflected.r *. reflective);
    g = (local.g *. keep) +. (reflected.g *. reflective);
    b = (local.b *. keep) +. (reflected.b *. reflective);
  }

(* Written as comparisons that fail on NaN, so NaN falls through to 0. *)
let clamp x = if x > 255. then 255. else if x > 0. then x else 0.

let to_byte x =
  if not (x > 0.) then 0
  else if x >= 255. then 255
  else
    let f = Float.of_int (truncate x) in
    let frac = x -. f in
    let n = truncate f in
    if frac > 0.5 then n + 1 else if frac < 0.5 then n else n + (n land 1)
[@@inline]

let to_rgb8 c = (to_byte c.r lsl 16) lor (to_byte c.g lsl 8) lor to_byte c.b

let in_gamut c =
  let ok x = x >= 0. && x <= 255. in
  ok c.r && ok c.g && ok c.b

let is_finite c = Float.is_finite c.r && Float.is_finite c.g && Float.is_finite c.b
let equal_f eq c c' = eq c.r c'.r && eq c.g c'.g && eq c.b c'.b

let compare c c' =
  match Float.compare c.r c'.r with
  | 0 -> ( match Float.compare c.g c'.g with 0 -> Float.compare c.b c'.b | n -> n)
  | n -> n

let pp_components ppf c =
  Format.fprintf ppf "%s %s %s" (Float_text.to_string c.r) (Float_text.to_string c.g)
    (Float_text.to_string c.b)

let pp ppf c = Format.fprintf ppf "(%a)" pp_components c

let show c = Format.asprintf "%a" pp c
