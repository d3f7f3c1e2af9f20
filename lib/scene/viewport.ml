type t = { width : float; height : float; distance : float } [@@deriving eq]

let v ~width ~height ~distance = { width; height; distance }
let width vp = vp.width
let height vp = vp.height
let distance vp = vp.distance
let default = v ~width:1. ~height:1. ~distance:1.

let check_dimension what x = Limits.check_size ("viewport " ^ what) x

let validate vp =
  let ( let* ) = Result.bind in
  let* _ = check_dimension "width" vp.width in
  let* _ = check_dimension "height" vp.height in
  let* _ = check_dimension "distance" vp.distance in
  Ok vp

let of_canvas_f vp ~canvas_width ~canvas_height gx gy =
  Vec3.v
    (gx *. vp.width /. Float.of_int canvas_width)
    (gy *. vp.height /. Float.of_int canvas_height)
    vp.distance

let of_canvas vp ~canvas_width ~canvas_height gx gy =
  of_canvas_f vp ~canvas_width ~canvas_height (Float.of_int gx) (Float.of_int gy)

let pp ppf vp =
  Format.fprintf ppf "(viewport (width %s) (height %s) (distance %s))" (Float_text.to_string vp.width)
    (Float_text.to_string vp.height) (Float_text.to_string vp.distance)

let show vp = Format.asprintf "%a" pp vp
