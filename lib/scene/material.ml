type t = {
  color : Color.t;
  specular : float;
  reflective : float;
  transparency : float;
  refractive_index : float;
  fresnel : bool;
  pattern : Pattern.t option;
}
[@@deriving eq]

let v ?(specular = Sphere.matte) ?(reflective = 0.) ?(transparency = 0.) ?(refractive_index = 1.) ?(fresnel = false)
    ?pattern color =
  { color; specular; reflective; transparency; refractive_index; fresnel; pattern }

let same_plain a b =
  let same x y = Int64.equal (Int64.bits_of_float x) (Int64.bits_of_float y) in
  same a.color.r b.color.r && same a.color.g b.color.g && same a.color.b b.color.b && same a.specular b.specular
  && same a.reflective b.reflective && same a.transparency b.transparency
  && same a.refractive_index b.refractive_index && a.fresnel = b.fresnel && a.pattern = None && b.pattern = None

module Plain = Hashtbl.Make (struct
  type nonrec t = t

  let equal = same_plain
  let hash = Hashtbl.hash
end)

let of_sphere (s : Sphere.t) =
  v ~specular:s.specular ~reflective:s.reflective ~transparency:s.transparency ~refractive_index:s.refractive_index
    ~fresnel:s.fresnel ?pattern:s.pattern s.color

(* The sphere's checks hold for every material; only the form they name
   differs. *)
let rename ~form m =
  let prefix = "sphere " in
  let n = String.length prefix in
  if String.length m >= n && String.sub m 0 n = prefix then form ^ " " ^ String.sub m n (String.length m - n)
  else m

let named ~form r = Result.map_error (fun (`Msg e) -> `Msg (rename ~form e)) r
let check_color ~form c = named ~form (Sphere.check_color c)
let check_specular ~form x = named ~form (Sphere.check_specular x)
let check_reflective ~form x = named ~form (Sphere.check_reflective x)
let check_transparency ~form x = named ~form (Sphere.check_transparency x)
let check_refractive_index ~form x = named ~form (Sphere.check_refractive_index x)
let check_split ~form ~reflective ~transparency = named ~form (Sphere.check_split ~reflective ~transparency)

let validate ~form m =
  let ( let* ) = Result.bind in
  let* _ = check_color ~form m.color in
  let* _ = check_specular ~form m.specular in
  let* _ = check_reflective ~form m.reflective in
  let* _ = match m.pattern with None -> Ok None | Some p -> Result.map Option.some (Pattern.validate ~form p) in
  let* _ = check_transparency ~form m.transparency in
  let* _ = check_refractive_index ~form m.refractive_index in
  let* () = check_split ~form ~reflective:m.reflective ~transparency:m.transparency in
  Ok m

let pp ppf m =
  Format.fprintf ppf "(color %a)" Color.pp_components m.color;
  Sphere.pp_optional_material ~transparency:m.transparency ~refractive_index:m.refractive_index ~fresnel:m.fresnel ppf
    ~specular:m.specular ~reflective:m.reflective;
  Pattern.pp_optional ppf m.pattern

let show m = Format.asprintf "%a" pp m
