type op =
  | Scale of Vec3.t
  | Rotate_x of float
  | Rotate_y of float
  | Rotate_z of float
  | Rotate of Vec3.t * float
  | Translate of Vec3.t

type t = { ops : op list; world : float array; obj : float array }

let ops t = t.ops
let to_world t = Array.copy t.world
let to_object t = Array.copy t.obj

(* The cosine and sine of [x] in [0, pi/4] by their Taylor series to
   x^18 and x^17 (the next terms are below 1e-19), in Horner's form: plain
   IEEE arithmetic, so that the native program and the web page (whose
   [Math.sin] is not the C library's) turn objects by the same bits. *)
let taylor_cos_sin x =
  let x2 = x *. x in
  let f n = 1. /. n in
  (* 1/n! by products of exact small integers: the same rounding everywhere. *)
  let c2 = f 2. and c4 = f 24. and c6 = f 720. and c8 = f 40320. and c10 = f 3628800. in
  let c12 = f 479001600. and c14 = f 87178291200. and c16 = f 20922789888000. and c18 = f 6402373705728000. in
  let s3 = f 6. and s5 = f 120. and s7 = f 5040. and s9 = f 362880. and s11 = f 39916800. in
  let s13 = f 6227020800. and s15 = f 1307674368000. and s17 = f 355687428096000. in
  let c =
    1. -. (x2 *. (c2 -. (x2 *. (c4 -. (x2 *. (c6 -. (x2 *. (c8 -. (x2 *. (c10 -. (x2 *. (c12 -. (x2 *. (c14 -. (x2 *. (c16 -. (x2 *. c18)))))))))))))))))
  in
  let s =
    x *. (1. -. (x2 *. (s3 -. (x2 *. (s5 -. (x2 *. (s7 -. (x2 *. (s9 -. (x2 *. (s11 -. (x2 *. (s13 -. (x2 *. (s15 -. (x2 *. s17))))))))))))))))
  in
  (c, s)

(* Reduced exactly to [0, 45] degrees by the quadrant and the complement
   (each subtraction is exact: its operands are within a factor 2), so
   that multiples of 90 give 0, 1 and -1 exactly ([cos (pi / 2)] in
   floats is 6e-17: a quarter-turned box would have faces off the axes'
   planes). *)
let cos_sin deg =
  let r = Float.rem deg 360. in
  let r = if r < 0. then r +. 360. else r in
  let r = if r >= 360. then 0. else r in
  let q = Float.to_int (r /. 90.) in
  let q = if q > 3 then 3 else q in
  let a = r -. (90. *. Float.of_int q) in
  let c, s =
    if a <= 45. then taylor_cos_sin (a *. (Float.pi /. 180.))
    else
      let c', s' = taylor_cos_sin ((90. -. a) *. (Float.pi /. 180.)) in
      (s', c')
  in
  match q with 0 -> (c, s) | 1 -> (-.s, c) | 2 -> (-.c, -.s) | _ -> (s, -.c)

let identity_matrix () = [| 1.; 0.; 0.; 0.; 0.; 1.; 0.; 0.; 0.; 0.; 1.; 0. |]

(* The 3x3 linear part [l] (row-major) and translation [b] as a matrix. *)
let affine (l : float array) (b : Vec3.t) = [| l.(0); l.(1); l.(2); b.x; l.(3); l.(4); l.(5); b.y; l.(6); l.(7); l.(8); b.z |]

(* [mul m n] is the matrix of [m] after [n]: [p -> m (n p)]. *)
let mul m n =
  let r = Array.make 12 0. in
  for i = 0 to 2 do
    for j = 0 to 3 do
      let s = ref (if j = 3 then m.((4 * i) + 3) else 0.) in
      for k = 0 to 2 do
        s := !s +. (m.((4 * i) + k) *. n.((4 * k) + j))
      done;
      r.((4 * i) + j) <- !s
    done
  done;
  r

let rotation_about (axis : Vec3.t) deg =
  let c, s = cos_sin deg in
  let a = Vec3.unit axis in
  let x = a.x and y = a.y and z = a.z and k = 1. -. c in
  (* Rodrigues's formula. *)
  [|
    c +. (x *. x *. k); (x *. y *. k) -. (z *. s); (x *. z *. k) +. (y *. s);
    (y *. x *. k) +. (z *. s); c +. (y *. y *. k); (y *. z *. k) -. (x *. s);
    (z *. x *. k) -. (y *. s); (z *. y *. k) +. (x *. s); c +. (z *. z *. k);
  |]

let rotation_x deg =
  let c, s = cos_sin deg in
  [| 1.; 0.; 0.; 0.; c; -.s; 0.; s; c |]

let rotation_y deg =
  let c, s = cos_sin deg in
  [| c; 0.; s; 0.; 1.; 0.; -.s; 0.; c |]

let rotation_z deg =
  let c, s = cos_sin deg in
  [| c; -.s; 0.; s; c; 0.; 0.; 0.; 1. |]

(* Each operation's matrix and its exact inverse's. *)
let matrices = function
  | Scale v -> (affine [| v.x; 0.; 0.; 0.; v.y; 0.; 0.; 0.; v.z |] Vec3.zero,
                affine [| 1. /. v.x; 0.; 0.; 0.; 1. /. v.y; 0.; 0.; 0.; 1. /. v.z |] Vec3.zero)
  | Rotate_x a -> (affine (rotation_x a) Vec3.zero, affine (rotation_x (-.a)) Vec3.zero)
  | Rotate_y a -> (affine (rotation_y a) Vec3.zero, affine (rotation_y (-.a)) Vec3.zero)
  | Rotate_z a -> (affine (rotation_z a) Vec3.zero, affine (rotation_z (-.a)) Vec3.zero)
  | Rotate (axis, a) -> (affine (rotation_about axis a) Vec3.zero, affine (rotation_about axis (-.a)) Vec3.zero)
  | Translate v -> (affine [| 1.; 0.; 0.; 0.; 1.; 0.; 0.; 0.; 1. |] v, affine [| 1.; 0.; 0.; 0.; 1.; 0.; 0.; 0.; 1. |] (Vec3.neg v))

let build ops =
  List.fold_left
    (fun (w, o) op ->
      let m, inv = matrices op in
      (mul m w, mul o inv))
    (identity_matrix (), identity_matrix ())
    ops

let name = function
  | Scale _ -> "scale"
  | Rotate_x _ -> "rotate-x"
  | Rotate_y _ -> "rotate-y"
  | Rotate_z _ -> "rotate-z"
  | Rotate _ -> "rotate"
  | Translate _ -> "translate"

let check_op op =
  let bad fmt = Printf.ksprintf (fun m -> Error (`Msg m)) fmt in
  let finite x = Float.is_finite x in
  match op with
  | Scale v ->
      if not (Vec3.is_finite v) then bad "transform scale must be finite"
      else if v.x = 0. || v.y = 0. || v.z = 0. then bad "transform scale must not be 0 on any axis, got %s %s %s" (Float_text.to_string v.x) (Float_text.to_string v.y) (Float_text.to_string v.z)
      else Result.map ignore (Limits.check_point "transform scale" v)
  | Rotate_x a | Rotate_y a | Rotate_z a -> if finite a then Ok () else bad "transform %s angle must be finite" (name op)
  | Rotate (axis, a) ->
      if not (finite a) then bad "transform rotate angle must be finite"
      else if not (Vec3.is_finite axis) || Vec3.norm2 axis = 0. || not (Float.is_finite (Vec3.norm2 axis)) then
        bad "transform rotate axis must be a finite nonzero vector"
      else Ok ()
  | Translate v -> Result.map ignore (Limits.check_point "transform translate" v)

let v ops =
  let rec check = function [] -> Ok () | op :: rest -> Result.bind (check_op op) (fun () -> check rest) in
  Result.bind (check ops) (fun () ->
      let world, obj = build ops in
      if Array.for_all Float.is_finite world && Array.for_all Float.is_finite obj then Ok { ops; world; obj }
      else Error (`Msg "transform: the composed matrix is not finite (scales too large or too small)"))

let identity = { ops = []; world = identity_matrix (); obj = identity_matrix () }

let compose a b =
  match v (a.ops @ b.ops) with Ok t -> t | Error (`Msg m) -> invalid_arg ("Transform.compose: " ^ m)

let point t (p : Vec3.t) =
  let m = t.world in
  Vec3.v
    ((m.(0) *. p.x) +. (m.(1) *. p.y) +. (m.(2) *. p.z) +. m.(3))
    ((m.(4) *. p.x) +. (m.(5) *. p.y) +. (m.(6) *. p.z) +. m.(7))
    ((m.(8) *. p.x) +. (m.(9) *. p.y) +. (m.(10) *. p.z) +. m.(11))

let direction t (d : Vec3.t) =
  let m = t.world in
  Vec3.v
    ((m.(0) *. d.x) +. (m.(1) *. d.y) +. (m.(2) *. d.z))
    ((m.(4) *. d.x) +. (m.(5) *. d.y) +. (m.(6) *. d.z))
    ((m.(8) *. d.x) +. (m.(9) *. d.y) +. (m.(10) *. d.z))

let normal_to_world t (n : Vec3.t) =
  let a = t.obj in
  Vec3.unit
    (Vec3.v
       ((a.(0) *. n.x) +. (a.(4) *. n.y) +. (a.(8) *. n.z))
       ((a.(1) *. n.x) +. (a.(5) *. n.y) +. (a.(9) *. n.z))
       ((a.(2) *. n.x) +. (a.(6) *. n.y) +. (a.(10) *. n.z)))

let frobenius m = sqrt (Array.fold_left ( +. ) 0. (Array.init 9 (fun k -> let x = m.((4 * (k / 3)) + (k mod 3)) in x *. x)))
let stretch t = Float.max 1. (frobenius t.world *. frobenius t.obj)

let bounds t ((lo : Vec3.t), (hi : Vec3.t)) =
  let corner k = point t (Vec3.v (if k land 1 = 0 then lo.x else hi.x) (if k land 2 = 0 then lo.y else hi.y) (if k land 4 = 0 then lo.z else hi.z)) in
  let cs = List.init 8 corner in
  let fold f get = List.fold_left (fun a c -> f a (get c)) (get (List.hd cs)) cs in
  let x (v : Vec3.t) = v.x and y (v : Vec3.t) = v.y and z (v : Vec3.t) = v.z in
  let lo' = Vec3.v (fold Float.min x) (fold Float.min y) (fold Float.min z) in
  let hi' = Vec3.v (fold Float.max x) (fold Float.max y) (fold Float.max z) in
  let big (v : Vec3.t) = Float.max (Float.abs v.x) (Float.max (Float.abs v.y) (Float.abs v.z)) in
  let room = 32. *. epsilon_float *. (Float.max (big lo') (big hi') +. big (Vec3.sub hi lo) +. big (Vec3.sub hi' lo')) *. stretch t in
  (Vec3.v (lo'.x -. room) (lo'.y -. room) (lo'.z -. room), Vec3.v (hi'.x +. room) (hi'.y +. room) (hi'.z +. room))

let equal_op a b =
  match (a, b) with
  | Scale u, Scale v | Translate u, Translate v -> Vec3.equal u v
  | Rotate_x a, Rotate_x b | Rotate_y a, Rotate_y b | Rotate_z a, Rotate_z b -> Float.equal a b
  | Rotate (u, a), Rotate (v, b) -> Vec3.equal u v && Float.equal a b
  | _ -> false

let equal a b = List.equal equal_op a.ops b.ops

let pp_op ppf op =
  let f = Float_text.to_string in
  let vec (v : Vec3.t) = Printf.sprintf "%s %s %s" (f v.x) (f v.y) (f v.z) in
  match op with
  | Scale v | Translate v -> Format.fprintf ppf "(%s %s)" (name op) (vec v)
  | Rotate_x a | Rotate_y a | Rotate_z a -> Format.fprintf ppf "(%s %s)" (name op) (f a)
  | Rotate (axis, a) -> Format.fprintf ppf "(rotate (axis %s) (angle %s))" (vec axis) (f a)

let pp ppf t =
  Format.fprintf ppf "(%a)" (Format.pp_print_list ~pp_sep:(fun ppf () -> Format.pp_print_string ppf " ") pp_op) t.ops
