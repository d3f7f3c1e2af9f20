type sampling = Stratified | Uniform [@@deriving eq]

type t =
  | Ambient of { intensity : float }
  | Point of { intensity : float; position : Vec3.t }
  | Directional of { intensity : float; direction : Vec3.t }
  | Area of {
      intensity : float;
      corner : Vec3.t;
      edge1 : Vec3.t;
      edge2 : Vec3.t;
      samples_u : int;
      samples_v : int;
      adaptive : bool;
      sampling : sampling;
    }
  | Sphere of { intensity : float; position : Vec3.t; radius : float; samples : int }
  | Spot of { intensity : float; position : Vec3.t; direction : Vec3.t; angle : float; falloff : float }
[@@deriving eq]

let max_samples = 4096

let error fmt = Printf.ksprintf (fun m -> Error (`Msg m)) fmt
let ambient intensity = Ambient { intensity }
let point intensity position = Point { intensity; position }
let directional intensity direction = Directional { intensity; direction }

let area ?(adaptive = false) ?(sampling = Stratified) intensity ~corner ~edge1 ~edge2 ~samples:(samples_u, samples_v) =
  Area { intensity; corner; edge1; edge2; samples_u; samples_v; adaptive; sampling }

let sphere intensity ~position ~radius ~samples = Sphere { intensity; position; radius; samples }
let spot intensity ~position ~direction ~angle ~falloff = Spot { intensity; position; direction; angle; falloff }

let intensity = function
  | Ambient { intensity }
  | Point { intensity; _ }
  | Directional { intensity; _ }
  | Area { intensity; _ }
  | Sphere { intensity; _ }
  | Spot { intensity; _ } ->
      intensity

(* Four corner rays cost more than they save on fewer than four samples
   (docs/run-time-against-error.md). *)
let corners_first = function
  | Area { samples_u; samples_v; adaptive; _ } -> adaptive && samples_u * samples_v >= 4
  | Ambient _ | Point _ | Directional _ | Spot _ | Sphere _ -> false

let samples = function
  | Ambient _ | Point _ | Directional _ | Spot _ -> 1
  (* An adaptive light's four corner rays come first, then its samples'
     where the corners disagree. *)
  | Area { samples_u; samples_v; _ } as l -> (samples_u * samples_v) + if corners_first l then 4 else 0
  | Sphere { samples; _ } -> samples

let sampled = function Area _ | Sphere _ -> true | Ambient _ | Point _ | Directional _ | Spot _ -> false

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

let check_vector what l =
  match Limits.check_point what l with
  | Ok l when Vec3.norm l < Limits.min_size ->
      error "%s must not be the zero vector (its length must be at least 1e-30)" what
  | r -> r

let check_samples what n =
  if n >= 1 && n <= max_samples then Ok n else error "%s must lie in [1, %d], got %d" what max_samples n

(* The rectangle's edges must span a plane: parallel edges make a segment,
   whose samples would all lie on one line. *)
let check_edges e1 e2 =
  let ( let* ) = Result.bind in
  let* e1 = check_vector "area light edge1" e1 in
  let* e2 = check_vector "area light edge2" e2 in
  if Vec3.norm (Vec3.cross e1 e2) = 0. then
    Error (`Msg "area light edge1 and edge2 must not be parallel (they span the rectangle)")
  else Ok (e1, e2)

let check_radius r =
  if r >= Limits.min_size && r <= Limits.max_coordinate then Ok r
  else error "sphere light radius must lie in [1e-30, 1e12], got %s" (Float_text.to_string r)

let check_angle a =
  if a > 0. && a <= 180. then Ok a
  else error "spot light angle must lie in (0, 180] degrees, got %s" (Float_text.to_string a)

let check_falloff k =
  if k >= 0. && k <= Limits.max_intensity then Ok k
  else error "spot light falloff must lie in [0, 1e6], got %s" (Float_text.to_string k)

let validate l =
  let ( let* ) = Result.bind in
  let* _ = check_intensity (intensity l) in
  let* () =
    match l with
    | Ambient _ -> Ok ()
    | Point { position; _ } -> Result.map ignore (check_position position)
    | Directional { direction; _ } -> Result.map ignore (check_direction direction)
    | Area { corner; edge1; edge2; samples_u; samples_v; _ } ->
        let* _ = Limits.check_point "area light corner" corner in
        let* _ = check_edges edge1 edge2 in
        let* _ = check_samples "area light samples (along edge1)" samples_u in
        Result.map ignore (check_samples "area light samples (along edge2)" samples_v)
    | Sphere { position; radius; samples; _ } ->
        let* _ = Limits.check_point "sphere light position" position in
        let* _ = check_radius radius in
        Result.map ignore (check_samples "sphere light samples" samples)
    | Spot { position; direction; angle; falloff; _ } ->
        let* _ = Limits.check_point "spot light position" position in
        let* _ = check_vector "spot light direction" direction in
        let* _ = check_angle angle in
        Result.map ignore (check_falloff falloff)
  in
  Ok l

let centre = function
  | Area { corner; edge1; edge2; _ } -> Some (Vec3.add corner (Vec3.smul 0.5 (Vec3.add edge1 edge2)))
  | Sphere { position; _ } | Spot { position; _ } | Point { position; _ } -> Some position
  | Ambient _ | Directional _ -> None

let vector l p =
  match l with
  | Ambient _ -> None
  | Point { position; _ } -> Some (Vec3.sub position p)
  | Directional { direction; _ } -> Some direction
  | (Area _ | Sphere _ | Spot _) as l -> Option.map (fun c -> Vec3.sub c p) (centre l)

let shadow_t_max = function Point _ | Area _ | Sphere _ | Spot _ -> 1. | Ambient _ | Directional _ -> infinity

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
  | Area _ | Sphere _ | Spot _ ->
      invalid_arg "Light.to_document: the document has no area, sphere or spot light"
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
  | Area { intensity; corner; edge1; edge2; samples_u; samples_v; adaptive; sampling } ->
      Format.fprintf ppf "(light area (intensity %s) (corner %a) (edge1 %a) (edge2 %a) (samples %d %d)%s%s)"
        (Float_text.to_string intensity) Vec3.pp_components corner Vec3.pp_components edge1 Vec3.pp_components edge2
        samples_u samples_v
        (match sampling with Stratified -> "" | Uniform -> " (sampling uniform)")
        (if adaptive then " (adaptive true)" else "")
  | Sphere { intensity; position; radius; samples } ->
      Format.fprintf ppf "(light sphere (intensity %s) (position %a) (radius %s) (samples %d))"
        (Float_text.to_string intensity) Vec3.pp_components position (Float_text.to_string radius) samples
  | Spot { intensity; position; direction; angle; falloff } ->
      Format.fprintf ppf "(light spot (intensity %s) (position %a) (direction %a) (angle %s) (falloff %s))"
        (Float_text.to_string intensity) Vec3.pp_components position Vec3.pp_components direction
        (Float_text.to_string angle) (Float_text.to_string falloff)

let show l = Format.asprintf "%a" pp l

(* The largest [m] with [m * m <= n]: exact, no float square root. *)
let sectors n =
  let m = ref 1 in
  while (!m + 1) * (!m + 1) <= n do
    incr m
  done;
  !m
