type t = {
  positions : float array;
  triangles : int array;
  normals : float array;
  triangle_normals : int array;
  smooth : bool;
  material : Material.t;
  source : string;
  scale : float;
  translate : Vec3.t;
  skipped : int;
  flat : Bytes.t;
  objects : int;
}

(* Whether triangle [k] of these arrays has no normal, in floats, not
   vectors: asked once for each of millions of triangles, when the mesh is
   made. *)
let flat_triangle (positions : float array) (triangles : int array) k =
  let coord c a = positions.((3 * triangles.((3 * k) + c)) + a) in
  let e1x = coord 1 0 -. coord 0 0 and e1y = coord 1 1 -. coord 0 1 and e1z = coord 1 2 -. coord 0 2 in
  let e2x = coord 2 0 -. coord 0 0 and e2y = coord 2 1 -. coord 0 1 and e2z = coord 2 2 -. coord 0 2 in
  let nx = (e1y *. e2z) -. (e1z *. e2y) and ny = (e1z *. e2x) -. (e1x *. e2z) and nz = (e1x *. e2y) -. (e1y *. e2x) in
  let n = sqrt ((nx *. nx) +. (ny *. ny) +. (nz *. nz)) in
  not (n > 0. && Float.is_finite n && Float.is_finite (1. /. n))

let error fmt = Printf.ksprintf (fun m -> Error (`Msg m)) fmt

let v ?(smooth = false) ?(scale = 1.) ?(translate = Vec3.zero) ?(source = "") ?(skipped = 0) ~positions ~triangles
    ~normals ~triangle_normals material =
  let np = Array.length positions and nt = Array.length triangles and nn = Array.length normals in
  let in_range n a = Array.for_all (fun i -> i >= 0 && i < n) a in
  if np mod 3 <> 0 || nt mod 3 <> 0 || nn mod 3 <> 0 || Array.length triangle_normals <> nt then
    error "mesh arrays have inconsistent lengths"
  else if nt = 0 then error "mesh %s has no triangle" (if source = "" then "" else source)
  else if not (in_range (np / 3) triangles) then error "mesh triangle refers to a vertex that does not exist"
  else if not (Array.for_all (fun i -> i >= -1 && i < nn / 3) triangle_normals) then
    error "mesh triangle refers to a normal that does not exist"
  else if not (Float.is_finite scale && scale > 0.) then
    error "mesh scale must be finite and > 0, got %s" (Float_text.to_string scale)
  else
    let placed = Array.make np 0. in
    let t = [| translate.x; translate.y; translate.z |] in
    let ok = ref true in
    for i = 0 to np - 1 do
      let x = (scale *. positions.(i)) +. t.(i mod 3) in
      if not (Float.abs x <= Limits.max_coordinate) then ok := false;
      placed.(i) <- x
    done;
    if not !ok then
      error "mesh coordinates, scaled and translated, must lie within +-%s" (Float_text.to_string Limits.max_coordinate)
    else
      let flat = Bytes.init (nt / 3) (fun k -> if flat_triangle placed triangles k then '\001' else '\000') in
      let objects = ref 0 in
      Bytes.iter (fun c -> if c = '\000' then incr objects) flat;
      Ok
        {
          positions = placed;
          triangles;
          normals;
          triangle_normals;
          smooth;
          material;
          source;
          scale;
          translate;
          skipped;
          flat;
          objects = !objects;
        }

let triangle_count m = Array.length m.triangles / 3

let vertex m k c =
  let i = 3 * m.triangles.((3 * k) + c) in
  Vec3.v m.positions.(i) m.positions.(i + 1) m.positions.(i + 2)

let triangle m k = Triangle.v (vertex m k 0) (vertex m k 1) (vertex m k 2) m.material

let degenerate m k = Bytes.unsafe_get m.flat k <> '\000'
let objects m = m.objects


let unit_normal m j g o =
  let x = m.normals.(3 * j) and y = m.normals.((3 * j) + 1) and z = m.normals.((3 * j) + 2) in
  let l = sqrt ((x *. x) +. (y *. y) +. (z *. z)) in
  l > 0. && Float.is_finite l && Float.is_finite (1. /. l)
  &&
  let inv = 1. /. l in
  g.(o) <- x *. inv;
  g.(o + 1) <- y *. inv;
  g.(o + 2) <- z *. inv;
  true

(* The unit normal of corner [c] of triangle [k] written to [g] at [o],
   if it has one of a length that can be normalised. *)
let corner_normal m k c g o =
  let j = m.triangle_normals.((3 * k) + c) in
  j >= 0 && unit_normal m j g o

let corner_normals m k g o =
  m.smooth && corner_normal m k 0 g o && corner_normal m k 1 g (o + 3) && corner_normal m k 2 g (o + 6)

let[@inline] fmin (a : float) b = if a < b then a else b
let[@inline] fmax (a : float) b = if a > b then a else b

(* Floats written, not vectors returned: the kernel asks this of each of
   millions of triangles. *)
let box m k b =
  let i0 = 3 * m.triangles.(3 * k) and i1 = 3 * m.triangles.((3 * k) + 1) and i2 = 3 * m.triangles.((3 * k) + 2) in
  let p = m.positions in
  for a = 0 to 2 do
    let u = p.(i0 + a) and v = p.(i1 + a) and w = p.(i2 + a) in
    b.(a) <- fmin u (fmin v w);
    b.(a + 3) <- fmax u (fmax v w)
  done

let equal a b =
  let fa x y = Array.length x = Array.length y && Array.for_all2 Float.equal x y in
  let ia x y = Array.length x = Array.length y && Array.for_all2 Int.equal x y in
  fa a.positions b.positions && ia a.triangles b.triangles && fa a.normals b.normals
  && ia a.triangle_normals b.triangle_normals && a.smooth = b.smooth && Material.equal a.material b.material
  && String.equal a.source b.source && Float.equal a.scale b.scale && Vec3.equal a.translate b.translate
  && a.skipped = b.skipped

let pp ppf m =
  Format.fprintf ppf "<mesh %S: %d triangles, scale %s, translate %a%s>" m.source (triangle_count m)
    (Float_text.to_string m.scale) Vec3.pp m.translate (if m.smooth then ", smooth" else "")

(* The file's text is not kept: a mesh prints as the form that reads it
   again. *)
let pp_form ppf m =
  Format.fprintf ppf "(mesh (file %S) (scale %s) (translate %a)%s %a)" m.source (Float_text.to_string m.scale)
    Vec3.pp_components m.translate
    (if m.smooth then " (smooth true)" else "")
    Material.pp m.material
