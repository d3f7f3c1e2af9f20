type t = { color : Color.t; specular : float; reflective : float; pattern : Pattern.t option } [@@deriving eq]

let v ?(specular = Sphere.matte) ?(reflective = 0.) ?pattern color = { color; specular; reflective; pattern }

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

let validate ~form m =
  let ( let* ) = Result.bind in
  let* _ = check_color ~form m.color in
  let* _ = check_specular ~form m.specular in
  let* _ = check_reflective ~form m.reflective in
  let* _ = match m.pattern with None -> Ok None | Some p -> Result.map Option.some (Pattern.validate ~form p) in
  Ok m

let pp ppf m =
  Format.fprintf ppf "(color %a)" Color.pp_components m.color;
  Sphere.pp_optional_material ppf ~specular:m.specular ~reflective:m.reflective;
  Pattern.pp_optional ppf m.pattern

let show m = Format.asprintf "%a" pp m
