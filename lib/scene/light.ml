type t =
  | Ambient of { intensity : float }
  | Point of { intensity : float; position : Vec3.t }
  | Directional of { intensity : float; direction : Vec3.t }
[@@deriving eq]

let error fmt = Printf.ksprintf (fun m -> Error (`Msg m)) fmt
let ambient intensity = Ambient { intensity }
let point intensity position = Point { intensity; position }
let directional intensity direction = Directional { intensity; direction }

let intensity = function
  | Ambient { intensity } | Point { intensity; _ } | Directional { intensity; _ } -> intensity

let check_intensity i =
  if i >= 0. && i <= Limits.max_intensity then Ok i
  else
    (error
      "light intensity must lie in [0, 1e6], got %s" (Float_text.to_string i))

let check_position q = Limits.check_point "point light position" q

let check_direction l =
  match Limits.check_point "directional light direction" l with
  | Ok l when Vec3.norm l < Limits.min_size ->
      Error (`Msg "directional light direction must not be the zero vector (its length must be at least 1e-30)")
  | r -> r

let validate l =
  let ( let* ) = Result.bind in
  let* _ = check_intensity (intensity l) in
  let* _ =
    match l with
    | Ambient _ -> Ok Vec3.zero
    | Point { position; _ } -> check_position position
    | Directional { direction; _ } -> check_direction direction
  in
  Ok l

let vector l p =
  match l with
  | Ambient _ -> None
  | Point { position; _ } -> Some (Vec3.sub position p)
  | Directional { direction; _ } -> Some direction

let shadow_t_max = function Point _ -> 1. | Ambient _ | Directional _ -> infinity

type point = float * float * float
type document = { k : char; i : float; v : point option }

let of_document d =
  let light =
    match (d.k, d.v) with
    | 'a', None -> Ok (ambient d.i)
    | 'p', Some p -> Ok (point d.i (Vec3.of_tuple p))
    | 'd', Some p -> Ok (directional d.i (Vec3.of_tuple p))
    | 'a', Some _ -> Error (`Msg "an ambient light ('a') has no vector: v must be None")
    | ('p' | 'd'), None ->
        (error "a light of kind '%c' needs a vector: v must be Some _" d.k)
    | k, _ -> (error "unknown light kind %C: expected 'a', 'p' or 'd'" k)
  in
  Result.bind light validate

let of_document_exn d =
  match of_document d with Ok l -> l | Error (`Msg e) -> invalid_arg ("Light.of_document: " ^ e)

let to_document = function
  | Ambient { intensity } -> { k = 'a'; i = intensity; v = None }
  | Point { intensity; position } -> { k = 'p'; i = intensity; v = Some (Vec3.to_tuple position) }
  | Directional { intensity; direction } ->
      { k = 'd'; i = intensity; v = Some (Vec3.to_tuple direction) }

let pp ppf = function
  | Ambient { intensity } -> Format.fprintf ppf "(light ambient (intensity %s))" (Float_text.to_string intensity)
  | Point { intensity; position } ->
      Format.fprintf ppf "(light point (intensity %s) (position %a))" (Float_text.to_string intensity)
        Vec3.pp_components position
  | Directional { intensity; direction } ->
      Format.fprintf ppf "(light directional (intensity %s) (direction %a))" (Float_text.to_string intensity)
        Vec3.pp_components direction

let show l = Format.asprintf "%a" pp l
