(* An all-float record: OCaml stores its fields unboxed, so a vector is one
   block of three doubles rather than three pointers to boxed floats. *)
type t = { x : float; y : float; z : float } [@@deriving eq]

let v x y z = { x; y; z }
let zero = v 0. 0. 0.
let ox = v 1. 0. 0.
let oy = v 0. 1. 0.
let oz = v 0. 0. 1.
let add a b = { x = a.x +. b.x; y = a.y +. b.y; z = a.z +. b.z }
let sub a b = { x = a.x -. b.x; y = a.y -. b.y; z = a.z -. b.z }
let neg a = { x = -.a.x; y = -.a.y; z = -.a.z }
let smul k a = { x = k *. a.x; y = k *. a.y; z = k *. a.z }
let dot a b = (a.x *. b.x) +. (a.y *. b.y) +. (a.z *. b.z)

let cross a b =
  {
    x = (a.y *. b.z) -. (a.z *. b.y);
    y = (a.z *. b.x) -. (a.x *. b.z);
    z = (a.x *. b.y) -. (a.y *. b.x);
  }

let norm2 a = dot a a
let norm a = sqrt (dot a a)
let unit a = smul (1. /. norm a) a
let is_finite a = Float.is_finite a.x && Float.is_finite a.y && Float.is_finite a.z
let to_tuple a = (a.x, a.y, a.z)
let of_tuple (x, y, z) = { x; y; z }
let equal_f eq a b = eq a.x b.x && eq a.y b.y && eq a.z b.z

let compare a b =
  match Float.compare a.x b.x with
  | 0 -> ( match Float.compare a.y b.y with 0 -> Float.compare a.z b.z | c -> c)
  | c -> c

let ( + ) = add
let ( - ) = sub
let ( * ) = smul

let pp_components ppf a =
  Format.fprintf ppf "%s %s %s" (Float_text.to_string a.x) (Float_text.to_string a.y)
    (Float_text.to_string a.z)

let pp ppf a = Format.fprintf ppf "(%a)" pp_components a

let show a = Format.asprintf "%a" pp a
