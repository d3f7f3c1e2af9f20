(* What the mesh found of its triangles when it was made, for the
   kernel: kept out of the fields users read. *)
type found = { flat : Bytes.t; objects : int }

type t = {
  positions : float array;
  triangles : int array;
  normals : float array;
  triangle_normals : int array;
  texcoords : float array;
  triangle_texcoords : int array;
  smooth : bool;
  material : Material.t;
  source : string;
  scale : float;
  translate : Vec3.t;
  skipped : int;
  found : found;
}

(* Whether the triangle of corners [a], [b], [c] (offsets in [p]) has no
   normal, in floats, not vectors: asked once for each of millions of
   triangles, when the mesh is made. *)
let[@inline] flat_triangle (p : float array) a b c =
  let e1x = p.(b) -. p.(a) and e1y = p.(b + 1) -. p.(a + 1) and e1z = p.(b + 2) -. p.(a + 2) in
  let e2x = p.(c) -. p.(a) and e2y = p.(c + 1) -. p.(a + 1) and e2z = p.(c + 2) -. p.(a + 2) in
  let nx = (e1y *. e2z) -. (e1z *. e2y) and ny = (e1z *. e2x) -. (e1x *. e2z) and nz = (e1x *. e2y) -. (e1y *. e2x) in
  let n = sqrt ((nx *. nx) +. (ny *. ny) +. (nz *. nz)) in
  (* [x -. x = 0.] is [Float.is_finite x], without a call. *)
  let inv = 1. /. n in
  not (n > 0. && n -. n = 0. && inv -. inv = 0.)

let error fmt = Printf.ksprintf (fun m -> Error (`Msg m)) fmt

(* Whether every element of [a] is in [[lo, hi)]: a loop, not
   [Array.for_all]'s call of a closure per element of millions. *)
let within lo hi (a : int array) =
  let ok = ref true in
  for i = 0 to Array.length a - 1 do
    let x = Array.unsafe_get a i in
    if x < lo || x >= hi then ok := false
  done;
  !ok

let v ?(smooth = false) ?(scale = 1.) ?(translate = Vec3.zero) ?(source = "") ?(skipped = 0) ?(texcoords = [||])
    ?(triangle_texcoords = [||]) ~positions ~triangles ~normals ~triangle_normals material =
  let np = Array.length positions and nt = Array.length triangles and nn = Array.length normals in
  if np mod 3 <> 0 || nt mod 3 <> 0 || nn mod 3 <> 0 || Array.length triangle_normals <> nt
     || Array.length texcoords mod 2 <> 0
     || (triangle_texcoords <> [||] && Array.length triangle_texcoords <> nt)
  then error "mesh arrays have inconsistent lengths"
  else if nt = 0 then error "mesh %s has no triangle" (if source = "" then "" else source)
  else if not (within 0 (np / 3) triangles) then error "mesh triangle refers to a vertex that does not exist"
  else if not (within (-1) (nn / 3) triangle_normals) then
    error "mesh triangle refers to a normal that does not exist"
  else if not (within (-1) (Array.length texcoords / 2) triangle_texcoords) then
    error "mesh triangle refers to a texture coordinate that does not exist"
  else if not (Float.is_finite scale && scale > 0.) then
    error "mesh scale must be finite and > 0, got %s" (Float_text.to_string scale)
  else
    (* Every element is written below. *)
    let placed = Array.create_float np in
    let tx = translate.x and ty = translate.y and tz = translate.z in
    let ok = ref true in
    (* A vertex at a time: no [i mod 3] (a division) per coordinate. *)
    for j = 0 to (np / 3) - 1 do
      let i = 3 * j in
      let x = (scale *. positions.(i)) +. tx in
      let y = (scale *. positions.(i + 1)) +. ty in
      let z = (scale *. positions.(i + 2)) +. tz in
      if not (Float.abs x <= Limits.max_coordinate && Float.abs y <= Limits.max_coordinate && Float.abs z <= Limits.max_coordinate)
      then ok := false;
      placed.(i) <- x;
      placed.(i + 1) <- y;
      placed.(i + 2) <- z
    done;
    if not !ok then
      error "mesh coordinates, scaled and translated, must lie within +-%s" (Float_text.to_string Limits.max_coordinate)
    else
      let flat = Bytes.create (nt / 3) and objects = ref 0 in
      for k = 0 to (nt / 3) - 1 do
        let a = 3 * triangles.(3 * k) and b = 3 * triangles.((3 * k) + 1) and c = 3 * triangles.((3 * k) + 2) in
        if flat_triangle placed a b c then Bytes.unsafe_set flat k '\001'
        else begin
          Bytes.unsafe_set flat k '\000';
          incr objects
        end
      done;
      Ok
        {
          positions = placed;
          triangles;
          normals;
          triangle_normals;
          texcoords;
          triangle_texcoords;
          smooth;
          material;
          source;
          scale;
          translate;
          skipped;
          found = { flat; objects = !objects };
        }

let of_obj ?smooth ?scale ?translate ?source (obj : Obj_file.t) material =
  v ?smooth ?scale ?translate ?source ~skipped:(Obj_file.skipped_total obj) ~positions:obj.positions
    ~triangles:obj.triangles ~normals:obj.normals ~triangle_normals:obj.triangle_normals ~texcoords:obj.texcoords
    ~triangle_texcoords:obj.triangle_texcoords material

let triangle_count m = Array.length m.triangles / 3

let vertex m k c =
  let i = 3 * m.triangles.((3 * k) + c) in
  Vec3.v m.positions.(i) m.positions.(i + 1) m.positions.(i + 2)

let triangle m k = Triangle.v (vertex m k 0) (vertex m k 1) (vertex m k 2) m.material

let has_texcoords m = m.triangle_texcoords <> [||]

let store_texcoords m t uv j =
  for c = 0 to 2 do
    let k = m.triangle_texcoords.((3 * t) + c) in
    if k >= 0 then begin
      uv.(j + (2 * c)) <- m.texcoords.(2 * k);
      uv.(j + (2 * c) + 1) <- m.texcoords.((2 * k) + 1)
    end
  done

let texcoord m k ~b1 ~b2 =
  if k < 0 || k >= triangle_count m then invalid_arg "Mesh.texcoord: no such triangle";
  if m.triangle_texcoords = [||] then None
  else
    let t c = m.triangle_texcoords.((3 * k) + c) in
    let t0 = t 0 and t1 = t 1 and t2 = t 2 in
    if t0 < 0 || t1 < 0 || t2 < 0 then None
    else
      let uv j = (m.texcoords.(2 * j), m.texcoords.((2 * j) + 1)) in
      Some (Texture_map.interpolate ~b1 ~b2 (uv t0) (uv t1) (uv t2))

let degenerate m k = Bytes.unsafe_get m.found.flat k <> '\000'
let objects m = m.found.objects


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

let flat_view m = if m.smooth || m.normals = [||] then m else { m with normals = [||] }

let equal a b =
  let fa x y = Array.length x = Array.length y && Array.for_all2 Float.equal x y in
  let ia x y = Array.length x = Array.length y && Array.for_all2 Int.equal x y in
  fa a.positions b.positions && ia a.triangles b.triangles && fa a.normals b.normals
  && ia a.triangle_normals b.triangle_normals && fa a.texcoords b.texcoords
  && ia a.triangle_texcoords b.triangle_texcoords && a.smooth = b.smooth && Material.equal a.material b.material
  && String.equal a.source b.source && Float.equal a.scale b.scale && Vec3.equal a.translate b.translate
  && a.skipped = b.skipped

let pp ppf m =
  let source = if m.source = "" then "built in code" else Printf.sprintf "%S" m.source in
  Format.fprintf ppf "<mesh %s: %d triangles, scale %s, translate %a%s>" source (triangle_count m)
    (Float_text.to_string m.scale) Vec3.pp m.translate (if m.smooth then ", smooth" else "")

(* The file's text is not kept: a mesh prints as the form that reads it
   again. *)
let pp_form ppf m =
  if m.source = "" then
    Format.fprintf ppf "; a mesh built in code (%d triangle%s): no file to read it from@\n" (triangle_count m)
      (if triangle_count m = 1 then "" else "s");
  Format.fprintf ppf "(mesh (file %S) (scale %s) (translate %a)%s %a)" m.source (Float_text.to_string m.scale)
    Vec3.pp_components m.translate
    (if m.smooth then " (smooth true)" else "")
    Material.pp m.material
