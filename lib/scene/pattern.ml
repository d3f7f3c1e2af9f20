type t = Checker of { color : Color.t; size : float }

let checker ~size color = Checker { color; size }
let color (Checker { color; _ }) = color
let size (Checker { size; _ }) = size

let equal (Checker a) (Checker b) = Color.equal a.color b.color && a.size = b.size

let pp ppf (Checker { color; size }) =
  Format.fprintf ppf "(pattern checker (color %a) (size %s))" Color.pp_components color
    (Float_text.to_string size)

let pp_optional ppf = function None -> () | Some p -> Format.fprintf ppf " %a" pp p

let check_size ~form s = Limits.check_size (form ^ " pattern size") s

let validate ~form p =
  let (Checker { color; size }) = p in
  if not (Color.in_gamut color) then
    Error (`Msg (Format.asprintf "%s pattern color channels must lie in [0, 255], got %a" form Color.pp color))
  else Result.map (fun _ -> p) (check_size ~form size)

(* The table: size, the object's origin (3), its scale, its extent. *)
let stride = 6

let store_frame ~(origin : Vec3.t) ~scale ~extent table o =
  table.(o + 1) <- origin.x;
  table.(o + 2) <- origin.y;
  table.(o + 3) <- origin.z;
  table.(o + 4) <- scale;
  table.(o + 5) <- extent

let store (Checker { size; _ }) ~(origin : Vec3.t) ~scale ~extent table o =
  table.(o) <- size;
  store_frame ~origin ~scale ~extent table o

let frame table o = (Vec3.v table.(o + 1) table.(o + 2) table.(o + 3), table.(o + 4), table.(o + 5))

(* The same bound as the tracer's offset of secondary rays off a surface
   (64 u): twice what the rounding of [P] can account for. *)
let offset_bound = 32. *. epsilon_float

(* [floor x] modulo 2, as a float: 0. or 1. Floats, not ints: beyond
   2^62 a cell index would overflow an int (beyond 2^53 every float is
   even, and so is its cell). *)
let[@inline] parity x =
  let f = Float.floor x in
  f -. (2. *. Float.floor (f *. 0.5))

let odd (s : Scratch.t) table o =
  let px = s.px and py = s.py and pz = s.pz in
  let nx = s.nx and ny = s.ny and nz = s.nz in
  let e =
    offset_bound
    *. (Float.abs s.ox +. Float.abs s.oy +. Float.abs s.oz +. Float.abs px +. Float.abs py +. Float.abs pz
       +. Array.unsafe_get table (o + 5))
  in
  (* Toward the side the ray comes from: against [D]. *)
  let e = if (nx *. s.dx) +. (ny *. s.dy) +. (nz *. s.dz) > 0. then -.e else e in
  let size = Array.unsafe_get table o and scale = Array.unsafe_get table (o + 4) in
  let qx = (px +. (e *. nx) -. Array.unsafe_get table (o + 1)) /. scale /. size in
  let qy = (py +. (e *. ny) -. Array.unsafe_get table (o + 2)) /. scale /. size in
  let qz = (pz +. (e *. nz) -. Array.unsafe_get table (o + 3)) /. scale /. size in
  let sum = parity qx +. parity qy +. parity qz in
  sum = 1. || sum = 3.
