type rotation = { row0 : Vec3.t; row1 : Vec3.t; row2 : Vec3.t } [@@deriving eq]
type lens_sampling = Stratified | Uniform [@@deriving eq]

type t = {
  position : Vec3.t;
  rotation : rotation;
  aperture : float;
  focal_distance : float;
  lens_sampling : lens_sampling;
}
[@@deriving eq]

let identity = { row0 = Vec3.ox; row1 = Vec3.oy; row2 = Vec3.oz }

(* A pinhole focuses everywhere and has no lens to sample: its focal
   distance and lens sampling are the defaults, so that two pinholes are
   equal and [pp] reads back whatever was given. *)
let v ?(rotation = identity) ?(aperture = 0.) ?(focal_distance = 1.) ?(lens_sampling = Stratified) position =
  let pinhole = aperture = 0. in
  {
    position;
    rotation;
    aperture;
    focal_distance = (if pinhole then 1. else focal_distance);
    lens_sampling = (if pinhole then Stratified else lens_sampling);
  }

let default = v Vec3.zero
let position c = c.position
let rotation c = c.rotation
let aperture c = c.aperture
let focal_distance c = c.focal_distance
let lens_sampling c = c.lens_sampling
let has_lens c = c.aperture > 0.
let is_identity m = equal_rotation m identity
let determinant m = Vec3.dot m.row0 (Vec3.cross m.row1 m.row2)

let direction cam v =
  let m = cam.rotation in
  Vec3.v (Vec3.dot v m.row0) (Vec3.dot v m.row1) (Vec3.dot v m.row2)

let look_at ?(up = Vec3.oy) ?aperture ?focal_distance ?lens_sampling ~position target =
  let forward = Vec3.sub target position in
  if Vec3.norm2 forward = 0. then Error (`Msg "the camera looks at its own position")
  else
    let f = Vec3.unit forward in
    let right = Vec3.cross up f in
    (* Relative test: [up] parallel to [f] (or zero) leaves no horizontal. *)
    if Vec3.norm2 up = 0. || Vec3.norm right <= 1e-9 *. Vec3.norm up then
      Error (`Msg "the camera's up vector is zero or parallel to its view direction")
    else
      let r = Vec3.unit right in
      let u = Vec3.cross f r in
      (* Columns right, up, forward: D = r V_x + u V_y + f d. *)
      let rotation =
        { row0 = Vec3.v r.x u.x f.x; row1 = Vec3.v r.y u.y f.y; row2 = Vec3.v r.z u.z f.z }
      in
      (* Focused on what it looks at unless told otherwise. *)
      let focal_distance = match focal_distance with Some f -> f | None -> Vec3.norm forward in
      Ok (v ~rotation ?aperture ~focal_distance ?lens_sampling position)

let check_position p = Limits.check_point "camera position" p

let check_rotation m =
  if not (Vec3.is_finite m.row0 && Vec3.is_finite m.row1 && Vec3.is_finite m.row2) then
    Error (`Msg "camera rotation must be finite")
  else
    (* Relative to the rows' scale, so that a uniformly scaled matrix passes
       or fails alike. *)
    let scale = Vec3.norm m.row0 *. Vec3.norm m.row1 *. Vec3.norm m.row2 in
    if Float.abs (determinant m) <= 1e-12 *. scale || scale = 0. then
      Error (`Msg "camera rotation must be invertible, but its rows are (nearly) linearly dependent")
    else Ok m

let check_aperture a =
  if a = 0. || Limits.size_ok a then Ok a
  else
    (* The value as the scene text writes numbers, the bounds (Limits.min_size,
       Limits.max_coordinate) as the lights' messages write them. *)
    Error (`Msg (Printf.sprintf "camera aperture must be 0 or in [1e-30, 1e12], got %s" (Float_text.to_string a)))

let check_focal_distance f = Limits.check_size "camera focal-distance" f

let validate cam =
  match
    (check_position cam.position, check_rotation cam.rotation, check_aperture cam.aperture, check_focal_distance cam.focal_distance)
  with
  | Ok _, Ok _, Ok _, Ok _ -> Ok cam
  | (Error e, _, _, _ | _, Error e, _, _ | _, _, Error e, _ | _, _, _, Error e) -> Error e

let pp_rotation ppf m =
  Format.fprintf ppf "(rotation (%a) (%a) (%a))" Vec3.pp_components m.row0 Vec3.pp_components m.row1
    Vec3.pp_components m.row2

let show_rotation m = Format.asprintf "%a" pp_rotation m

(* The identity and the pinhole are the defaults: a scene file leaves
   them out. *)
let pp ppf c =
  Format.fprintf ppf "(camera (position %a)" Vec3.pp_components c.position;
  if not (is_identity c.rotation) then Format.fprintf ppf " %a" pp_rotation c.rotation;
  if has_lens c then
    Format.fprintf ppf " (aperture %s) (focal-distance %s)" (Float_text.to_string c.aperture)
      (Float_text.to_string c.focal_distance);
  if has_lens c && c.lens_sampling = Uniform then Format.fprintf ppf " (lens-sampling uniform)";
  Format.fprintf ppf ")"

let show c = Format.asprintf "%a" pp c
