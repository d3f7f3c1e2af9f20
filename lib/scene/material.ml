type t = {
  color : Color.t;
  specular : float;
  reflective : float;
  transparency : float;
  refractive_index : float;
  fresnel : bool;
  pattern : Pattern.t option;
  texture : Texture_map.t option;
}
[@@deriving eq]

let matte = -1.

let v ?(specular = matte) ?(reflective = 0.) ?(transparency = 0.) ?(refractive_index = 1.) ?(fresnel = false)
    ?pattern ?texture color =
  { color; specular; reflective; transparency; refractive_index; fresnel; pattern; texture }

let same_plain a b =
  let same x y = Int64.equal (Int64.bits_of_float x) (Int64.bits_of_float y) in
  same a.color.r b.color.r && same a.color.g b.color.g && same a.color.b b.color.b && same a.specular b.specular
  && same a.reflective b.reflective && same a.transparency b.transparency
  && same a.refractive_index b.refractive_index && a.fresnel = b.fresnel && a.pattern = None && b.pattern = None
  && Option.is_none a.texture && Option.is_none b.texture

module Plain = Hashtbl.Make (struct
  type nonrec t = t

  let equal = same_plain
  let hash = Hashtbl.hash
end)

let update ?color ?specular ?reflective ?transparency ?refractive_index ?fresnel ?pattern ?texture m =
  let pick o d = match o with Some x -> x | None -> d in
  {
    color = pick color m.color;
    specular = pick specular m.specular;
    reflective = pick reflective m.reflective;
    transparency = pick transparency m.transparency;
    refractive_index = pick refractive_index m.refractive_index;
    fresnel = pick fresnel m.fresnel;
    pattern = pick pattern m.pattern;
    texture = pick texture m.texture;
  }

let color m = m.color
let specular m = m.specular
let reflective m = m.reflective
let transparency m = m.transparency
let refractive_index m = m.refractive_index
let fresnel m = m.fresnel
let pattern m = m.pattern
let texture m = m.texture
let is_matte m = m.specular = matte
let error fmt = Printf.ksprintf (fun m -> Error (`Msg m)) fmt
let error_pp fmt = Format.kasprintf (fun m -> Error (`Msg m)) fmt
let num = Float_text.to_string

let check_color ~form c =
  if Color.in_gamut c then Ok c else error_pp "%s color channels must lie in [0, 255], got %a" form Color.pp c

let specular_ok s = Float.is_finite s && (s = matte || s >= 0.)

let check_specular ~form s =
  if specular_ok s then Ok s else error "%s specular must be -1 (matte) or >= 0, got %s" form (num s)

let reflective_ok r = r >= 0. && r <= 1.

let check_reflective ~form r =
  if reflective_ok r then Ok r else error "%s reflective must lie in [0, 1], got %s" form (num r)

let check_transparency ~form x =
  if x >= 0. && x <= 1. then Ok x else error "%s transparency must lie in [0, 1], got %s" form (num x)

let check_refractive_index ~form n =
  if n > 0. && Float.is_finite n then Ok n
  else error "%s refractive-index must be > 0 and finite, got %s" form (num n)

(* Each part of a hit's colour has its own weight (local 1 - r - t): the
   sum may not exceed 1. *)
let check_split ~form ~reflective ~transparency =
  if reflective +. transparency <= 1. then Ok ()
  else error "%s reflective + transparency must be <= 1, got %s + %s" form (num reflective) (num transparency)

let validate ~form m =
  let ( let* ) = Result.bind in
  let* _ = check_color ~form m.color in
  let* _ = check_specular ~form m.specular in
  let* _ = check_reflective ~form m.reflective in
  let* _ = match m.pattern with None -> Ok None | Some p -> Result.map Option.some (Pattern.validate ~form p) in
  let* _ = match m.texture with None -> Ok None | Some t -> Result.map Option.some (Texture_map.validate ~form t) in
  let* () =
    if Option.is_some m.pattern && Option.is_some m.texture then
      Error (`Msg (form ^ " has a pattern and a texture; a material's colour comes from one of them"))
    else Ok ()
  in
  let* _ = check_transparency ~form m.transparency in
  let* _ = check_refractive_index ~form m.refractive_index in
  let* () = check_split ~form ~reflective:m.reflective ~transparency:m.transparency in
  Ok m

(* The optional fields print only when they differ from their defaults, as
   a scene file would write them. *)
let pp_optional ?(transparency = 0.) ?(refractive_index = 1.) ?(fresnel = false) ppf ~specular ~reflective =
  if specular <> matte then Format.fprintf ppf " (specular %s)" (num specular);
  if reflective <> 0. then Format.fprintf ppf " (reflective %s)" (num reflective);
  if transparency <> 0. then Format.fprintf ppf " (transparency %s)" (num transparency);
  if refractive_index <> 1. then Format.fprintf ppf " (refractive-index %s)" (num refractive_index);
  if fresnel then Format.pp_print_string ppf " (fresnel true)"

let pp_fields ppf m =
  pp_optional ~transparency:m.transparency ~refractive_index:m.refractive_index ~fresnel:m.fresnel ppf
    ~specular:m.specular ~reflective:m.reflective;
  Pattern.pp_optional ppf m.pattern;
  Texture_map.pp_optional ppf m.texture

let pp ppf m =
  Format.fprintf ppf "(color %a)" Color.pp_components m.color;
  pp_fields ppf m

let show m = Format.asprintf "%a" pp m
