type key = { frame : int; position : Vec3.t; look_at : Vec3.t; up : Vec3.t } [@@deriving eq]
(* An array, so that the key of a frame is found by binary search. *)
type t = key array [@@deriving eq]

let error fmt = Printf.ksprintf (fun m -> Error (`Msg m)) fmt
let max_frame = 1_000_000
let key ?(up = Vec3.oy) ~frame ~position look_at = { frame; position; look_at; up }
let ( let* ) = Result.bind
let keys p = Array.to_list p
let first_frame p = p.(0).frame
let last_frame p = p.(Array.length p - 1).frame
let look k = Camera.look_at ~up:k.up ~position:k.position k.look_at

let check_key k =
  if k.frame < 0 || k.frame > max_frame then
    (error "camera-path key frame must lie in [0, %d], got %d" max_frame k.frame)
  else
    let* _ = Limits.check_point "camera-path key position" k.position in
    let* _ = Limits.check_point "camera-path key look-at" k.look_at in
    let* _ = Limits.check_point "camera-path key up" k.up in
    match look k with Ok _ -> Ok k | Error e -> Error e

(* [(1 - t) a + t b]: exact at both ends (t = 1 gives [0 a + b = b]). *)
let lerp t (a : Vec3.t) (b : Vec3.t) =
  let s = 1. -. t in
  Vec3.v ((s *. a.x) +. (t *. b.x)) ((s *. a.y) +. (t *. b.y)) ((s *. a.z) +. (t *. b.z))

let between k0 k1 f =
  let t = Float.of_int (f - k0.frame) /. Float.of_int (k1.frame - k0.frame) in
  {
    frame = f;
    position = lerp t k0.position k1.position;
    look_at = lerp t k0.look_at k1.look_at;
    up = lerp t k0.up k1.up;
  }

let check_segment k0 k1 =
  if k1.frame <= k0.frame then
    (error
      "camera-path keys must come in increasing frame order, but frame %d follows frame %d"
         k1.frame k0.frame)
  else
    let rec frames f =
      if f >= k1.frame then Ok ()
      else
        match look (between k0 k1 f) with
        | Ok _ -> frames (f + 1)
        | Error (`Msg e) -> error "at frame %d, between the keys of frames %d and %d, %s" f k0.frame k1.frame e
    in
    frames (k0.frame + 1)

let v keys =
  let rec segments = function
    | k0 :: (k1 :: _ as rest) ->
        let* () = check_segment k0 k1 in
        segments rest
    | [ _ ] | [] -> Ok ()
  in
  match keys with
  | [] -> Error (`Msg "a camera path needs at least one key")
  | _ ->
      let* () = List.fold_left (fun acc k -> let* () = acc in Result.map ignore (check_key k)) (Ok ()) keys in
      let* () = segments keys in
      Ok (Array.of_list keys)

let camera p f =
  let outside () =
    Error
      (`Msg
        (Printf.sprintf "frame %d is outside the camera path, which runs from frame %d to %d" f
           (first_frame p) (last_frame p)))
  in
  (* The last key at or before [f]: [lo] is at or before it, [hi] after. *)
  let rec last_key lo hi = if hi - lo <= 1 then lo else
      let mid = lo + ((hi - lo) / 2) in
      if p.(mid).frame <= f then last_key mid hi else last_key lo mid
  in
  let find () =
    let n = Array.length p in
    if f < first_frame p || f > last_frame p then outside ()
    else
      let i = last_key 0 n in
      if p.(i).frame = f then Ok p.(i) else Ok (between p.(i) p.(i + 1) f)
  in
  let* k = find () in
  (* Checked when the path was built: every frame in range has a camera. *)
  match look k with Ok c -> Ok c | Error (`Msg e) -> error "frame %d: %s" f e

let pp_key ppf k =
  Format.fprintf ppf "(key (frame %d) (position %a) (look-at %a)" k.frame Vec3.pp_components k.position
    Vec3.pp_components k.look_at;
  (* +y is the default up: a scene file leaves it out. *)
  if not (Vec3.equal k.up Vec3.oy) then Format.fprintf ppf " (up %a)" Vec3.pp_components k.up;
  Format.pp_print_string ppf ")"

let show_key k = Format.asprintf "%a" pp_key k

let pp ppf p =
  Format.pp_print_string ppf "(camera-path";
  Array.iter (fun k -> Format.fprintf ppf "\n %a" pp_key k) p;
  Format.pp_print_string ppf ")"

let show p = Format.asprintf "%a" pp p
