(* An exact value is a list of floats whose exact sum it is. After each
   operation the list is a nonoverlapping expansion in increasing
   magnitude without zeros (Shewchuk's Grow-Expansion with zero
   elimination), so that it stays short and its last component has the
   value's sign. *)
type t = float list

(* Knuth's two-sum: [s + e = a + b] exactly, [s] the rounded sum. *)
let two_sum a b =
  let s = a +. b in
  let bv = s -. a in
  let av = s -. bv in
  (s, (a -. av) +. (b -. bv))

(* [p + e = a * b] exactly, [p] the rounded product (fma rounds once). *)
let two_product a b =
  let p = a *. b in
  (p, Float.fma a b (-.p))

(* Adds [b] to the expansion [e] (increasing magnitude, nonoverlapping). *)
let grow e b =
  let rec go q acc = function
    | [] -> List.rev (if q = 0. then acc else q :: acc)
    | x :: rest ->
        let q, h = two_sum q x in
        go q (if h = 0. then acc else h :: acc) rest
  in
  go b [] e

let compress xs = List.fold_left grow [] xs
let of_float x = if x = 0. then [] else [ x ]

let diff a b =
  let s, e = two_sum a (-.b) in
  compress [ e; s ]

let add a b = compress (a @ b)
let neg a = List.map Float.neg a
let sub a b = add a (neg b)

let mul a b =
  compress
    (List.concat_map
       (fun x ->
         List.concat_map
           (fun y ->
             let p, e = two_product x y in
             [ e; p ])
           b)
       a)

let rec last = function [] -> 0. | [ x ] -> x | _ :: rest -> last rest

let approx = last

let sign a =
  let x = last a in
  if x > 0. then 1 else if x < 0. then -1 else 0

let compare_fractions n1 d1 n2 d2 = sign (sub (mul n1 d2) (mul n2 d1)) * sign d1 * sign d2
