(* A witness of a type, as OCaml 5.1's [Type.Id]: two descriptions' values
   compare only when their witnesses are one. *)
type (_, _) eq = Equal : ('a, 'a) eq
type _ id = ..

module type ID = sig
  type t
  type _ id += Id : t id
end

type 'a witness = (module ID with type t = 'a)

let witness (type a) () : a witness =
  (module struct
    type t = a
    type _ id += Id : t id
  end)

let same (type a b) ((module A) : a witness) ((module B) : b witness) : (a, b) eq option =
  match A.Id with B.Id -> Some Equal | _ -> None

type field = Point | Number | Flag of bool

type reader = { point : string -> Vec3.t; number : string -> float; flag : string -> bool }

type 'a t = {
  name : string;
  kind : Kind.t;
  witness : 'a witness;
  fields : (string * field) list;
  read : reader -> Material.t -> 'a;
  validate : 'a -> ('a, [ `Msg of string ]) result;
  material : 'a -> Material.t;
  closed : 'a -> bool;
  bounds : 'a -> Vec3.t * Vec3.t;
  store : 'a -> float array -> int -> unit;
  pp : Format.formatter -> 'a -> unit;
  equal : 'a -> 'a -> bool;
  literal : 'a -> origin:Vec3.t -> direction:Vec3.t -> (float * Vec3.t) list;
}

type primitive = Primitive : 'a t * 'a -> primitive
type any = Any : 'a t -> any

let equal_primitive (Primitive (d, x)) (Primitive (e, y)) =
  match same d.witness e.witness with Some Equal -> d.equal x y | None -> false

let pp_primitive ppf (Primitive (d, x)) = d.pp ppf x
let name (Primitive (d, _)) = d.name
let kind (Primitive (d, _)) = d.kind
let material (Primitive (d, x)) = d.material x
let closed (Primitive (d, x)) = Kind.closed d.kind && d.closed x
let bounds (Primitive (d, x)) = d.bounds x
let store (Primitive (d, x)) g o = d.store x g o
let literal (Primitive (d, x)) ~origin ~direction = d.literal x ~origin ~direction

let validate (Primitive (d, x)) =
  match d.validate x with
  | Ok x -> Ok (Primitive (d, x))
  | Error (`Msg m) -> Error (`Msg m)
