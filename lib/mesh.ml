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
}

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
      Ok { positions = placed; triangles; normals; triangle_normals; smooth; material; source; scale; translate; skipped }

let triangle_count m = Array.length m.triangles / 3

let vertex m k c =
  let i = 3 * m.triangles.((3 * k) + c) in
  Vec3.v m.positions.(i) m.positions.(i + 1) m.positions.(i + 2)

let triangle m k = Triangle.v (vertex m k 0) (vertex m k 1) (vertex m k 2) m.material

let degenerate m k =
  let v0 = vertex m k 0 in
  let n = Vec3.norm (Vec3.cross (Vec3.sub (vertex m k 1) v0) (Vec3.sub (vertex m k 2) v0)) in
  not (n > 0. && Float.is_finite n && Float.is_finite (1. /. n))

let corner_normals m k g o =
  m.smooth
  &&
  let unit c =
    let j = m.triangle_normals.((3 * k) + c) in
    if j < 0 then None
    else
      let n = Vec3.v m.normals.(3 * j) m.normals.((3 * j) + 1) m.normals.((3 * j) + 2) in
      let l = Vec3.norm n in
      if l > 0. && Float.is_finite l && Float.is_finite (1. /. l) then Some (Vec3.smul (1. /. l) n) else None
  in
  match (unit 0, unit 1, unit 2) with
  | Some a, Some b, Some c ->
      List.iteri
        (fun i (n : Vec3.t) ->
          g.(o + (3 * i)) <- n.x;
          g.(o + (3 * i) + 1) <- n.y;
          g.(o + (3 * i) + 2) <- n.z)
        [ a; b; c ];
      true
  | _ -> false

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
