module Sexp = Sexplib0.Sexp
module Positions = Parsexp.Positions

(* Conversion errors name the offending node; its position is found only if
   there is an error (see [of_string]). *)
exception Located of Sexp.t * string

let fail node fmt = Printf.ksprintf (fun m -> raise (Located (node, m))) fmt
let position (p : Positions.pos) = Printf.sprintf "%d:%d" p.line (p.col + 1)

(* Atoms echoed in messages are kept on one line and short. *)
let show_atom a =
  let plain =
    a <> "" && String.length a <= 40
    && String.for_all (fun c -> c > ' ' && c < '\127' && c <> '"' && c <> '\\') a
  in
  if plain then a
  else
    let a = if String.length a > 40 then String.sub a 0 40 ^ "..." else a in
    Printf.sprintf "%S" a

(* Edit distance, to suggest the name a user probably meant. *)
let distance a b =
  let la = String.length a and lb = String.length b in
  let d = Array.make_matrix (la + 1) (lb + 1) 0 in
  for i = 0 to la do d.(i).(0) <- i done;
  for j = 0 to lb do d.(0).(j) <- j done;
  for i = 1 to la do
    for j = 1 to lb do
      let cost = if a.[i - 1] = b.[j - 1] then 0 else 1 in
      d.(i).(j) <- min (min (d.(i - 1).(j) + 1) (d.(i).(j - 1) + 1)) (d.(i - 1).(j - 1) + cost)
    done
  done;
  d.(la).(lb)

let suggestion name candidates =
  let near c =
    let bound = max 1 (String.length c / 3) in
    (* The distance is at least the difference of the lengths: checking that
       first keeps a hostile name of megabytes from costing a table of its
       length times the candidate's (docs/performance.md, "Numbers moved
       out of the library's comments"). *)
    abs (String.length name - String.length c) <= bound && distance name c <= bound
  in
  let close = List.filter near candidates in
  match close with c :: _ -> Printf.sprintf " (did you mean %s?)" c | [] -> ""

let one_of names =
  match List.rev names with
  | [] -> ""
  | [ n ] -> n
  | last :: rest -> String.concat ", " (List.rev rest) ^ " or " ^ last

(* Values *)

(* [what] names the value in error messages. It is a function so that the
   name is built only for an error: concatenating it for every value was a
   large part of the loading time of big scenes (docs/performance.md). *)
let number (what : unit -> string) node =
  match node with
  | Sexp.Atom atom -> (
      match Float_text.of_string atom with
      | Some x -> x
      | None -> (
          match float_of_string_opt atom with
          | Some _ -> fail node "%s must be a finite number, got %s" (what ()) (show_atom atom)
          | None -> fail node "%s: expected a number, got %s" (what ()) (show_atom atom)))
  | Sexp.List _ -> fail node "%s: expected a number, got a list" (what ())

let integer (what : unit -> string) node =
  match node with
  | Sexp.Atom atom -> (
      match int_of_string_opt atom with
      | Some n -> n
      | None -> fail node "%s: expected an integer, got %s" (what ()) (show_atom atom))
  | Sexp.List _ -> fail node "%s: expected an integer, got a list" (what ())

let check node = function Ok x -> x | Error (`Msg m) -> fail node "%s" m

(* Fields: a form's [(name args...)] children. [where] gives a node's
   position when it is known (the second, located pass). *)

type field = { name_node : Sexp.t; node : Sexp.t; args : Sexp.t list }

let fields ~where ~form ~allowed nodes =
  List.fold_left
    (fun acc node ->
      match node with
      | Sexp.List ((Sexp.Atom name as name_node) :: args) ->
          if not (List.exists (String.equal name) allowed) then
            fail name_node "unknown %s field %s; expected %s%s" form (show_atom name) (one_of allowed)
              (suggestion name allowed);
          (match List.find_opt (fun (n, _) -> String.equal n name) acc with
          | Some (_, first) ->
              fail name_node "duplicate %s field %s (first given at %s)" form name
                (Option.fold ~none:"?" ~some:position (where first.name_node))
          | None -> ());
          (name, { name_node; node; args }) :: acc
      | Sexp.List _ -> fail node "%s: expected a field (name value...), e.g. (%s ...)" form (List.hd allowed)
      | Sexp.Atom atom ->
          fail node "%s: expected a field in parentheses, e.g. (%s ...), got %s" form (List.hd allowed)
            (show_atom atom))
    [] nodes

let field_what form name () = form ^ " " ^ name

let find fs name = List.find_map (fun (n, f) -> if String.equal n name then Some f else None) fs
let get ~form fs name parse = Option.map (fun f -> parse (field_what form name) f) (find fs name)

let require ~form ~form_node name = function
  | Some v -> v
  | None -> fail form_node "%s is missing its (%s ...) field" form name

let required ~form ~form_node fs name parse = require ~form ~form_node name (get ~form fs name parse)

let single form name f =
  match f.args with
  | [ x ] -> x
  | args -> fail f.node "%s takes 1 value, got %d" (field_what form name ()) (List.length args)

let float_field form name f = number (field_what form name) (single form name f)
let int_field form name f = integer (field_what form name) (single form name f)

let triple ~names what node = function
  | [ x; y; z ] -> (number what x, number what y, number what z)
  | nodes -> fail node "%s takes 3 numbers (%s), got %d values" (what ()) names (List.length nodes)

let vec3_of_nodes what node nodes =
  let x, y, z = triple ~names:"x y z" what node nodes in
  Vec3.v x y z

let color_of_nodes what node nodes =
  let r, g, b = triple ~names:"r g b" what node nodes in
  Color.v r g b

let vec3_field form name f = vec3_of_nodes (field_what form name) f.node f.args
let color_field form name f = color_of_nodes (field_what form name) f.node f.args

(* A checked number: the error points at the value. *)
let checked_float form fs name check_value =
  Option.map
    (fun f ->
      let x = float_field form name f in
      check (single form name f) (check_value x))
    (find fs name)

(* Forms *)

let canvas ~limits ~where form_node nodes =
  let form = "canvas" in
  let fs = fields ~where ~form ~allowed:[ "width"; "height" ] nodes in
  let dim name =
    Option.value ~default:600
      (get ~form fs name (fun _ f ->
           check (single form name f) (Limits.check_dimension name (int_field form name f))))
  in
  let width = dim "width" in
  let height = dim "height" in
  ignore (check form_node (Limits.check_canvas limits width height));
  (width, height)

let viewport ~where nodes =
  let form = "viewport" in
  let fs = fields ~where ~form ~allowed:[ "width"; "height"; "distance" ] nodes in
  let dim name =
    Option.value ~default:1. (checked_float form fs name (Viewport.check_dimension name))
  in
  let width = dim "width" in
  let height = dim "height" in
  let distance = dim "distance" in
  Viewport.v ~width ~height ~distance

let rotation form name f =
  let what = field_what form name in
  match f.args with
  | [ r0; r1; r2 ] ->
      let row node =
        match node with
        | Sexp.List elements -> vec3_of_nodes (fun () -> what () ^ " row") node elements
        | Sexp.Atom atom ->
            fail node "%s: expected a row of 3 numbers in parentheses, got %s" (what ()) (show_atom atom)
      in
      Camera.{ row0 = row r0; row1 = row r1; row2 = row r2 }
  | args ->
      fail f.node "%s takes 3 rows, e.g. (1 0 0) (0 1 0) (0 0 1), got %d values" (what ()) (List.length args)

(* A camera's [(lens-sampling stratified)] or [(lens-sampling uniform)]. *)
let lens_sampling form f =
  let kinds = [ "stratified"; "uniform" ] and name = "lens-sampling" in
  match single form name f with
  | Sexp.Atom "stratified" -> Camera.Stratified
  | Sexp.Atom "uniform" -> Camera.Uniform
  | Sexp.Atom a as node ->
      fail node "%s: expected %s, got %s%s" (field_what form name ()) (one_of kinds) (show_atom a) (suggestion a kinds)
  | node -> fail node "%s: expected %s" (field_what form name ()) (one_of kinds)

let camera ~where nodes =
  let form = "camera" in
  let fs =
    fields ~where ~form
      ~allowed:[ "position"; "rotation"; "look-at"; "up"; "aperture"; "focal-distance"; "lens-sampling" ]
      nodes
  in
  let with_node name parse = get ~form fs name (fun _ f -> (f.node, parse f)) in
  let position =
    match with_node "position" (vec3_field form "position") with
    | Some (node, p) -> check node (Camera.check_position p)
    | None -> Vec3.zero
  in
  let rot = with_node "rotation" (rotation form "rotation") in
  let look = with_node "look-at" (vec3_field form "look-at") in
  let up = with_node "up" (vec3_field form "up") in
  let aperture = checked_float form fs "aperture" Camera.check_aperture in
  let focal_distance = checked_float form fs "focal-distance" Camera.check_focal_distance in
  (* Without a target, a lens has nothing to focus on by default. *)
  (match (find fs "aperture", aperture, focal_distance, look) with
  | Some f, Some a, None, None when a > 0. ->
      fail f.node "camera (aperture ...) needs a (focal-distance ...), or a (look-at ...) target to focus on"
  | _ -> ());
  let lens_sampling = Option.map (lens_sampling form) (find fs "lens-sampling") in
  (* A pinhole has no lens to sample: say so rather than drop the field. *)
  (match (find fs "lens-sampling", aperture) with
  | Some f, (None | Some 0.) -> fail f.node "camera (lens-sampling ...) needs an (aperture ...) above 0"
  | _ -> ());
  match (rot, look, up) with
  | Some _, Some (node, _), _ -> fail node "camera takes either (rotation ...) or (look-at ...), not both"
  | _, None, Some (node, _) -> fail node "camera (up ...) needs a (look-at ...) target"
  | Some (node, rotation), None, None ->
      Camera.v ~rotation:(check node (Camera.check_rotation rotation)) ?aperture ?focal_distance ?lens_sampling position
  | None, Some (node, target), up -> (
      ignore (check node (Limits.check_point "camera look-at" target));
      match Camera.look_at ?up:(Option.map snd up) ?aperture ?focal_distance ?lens_sampling ~position target with
      (* The default focal distance, the target's, may be out of range. *)
      | Ok cam -> check node (Camera.validate cam)
      | Error (`Msg m) -> fail node "%s" m)
  | None, None, _ -> Camera.v ?aperture ?focal_distance ?lens_sampling position

(* [(pattern checker (color r g b) (size s))], the optional field of
   every object's material. *)
let pattern ~where ~form fs =
  Option.map
    (fun f ->
      let kinds = [ "checker" ] in
      match f.args with
      | Sexp.Atom "checker" :: rest ->
          let pform = form ^ " pattern checker" in
          let pfs = fields ~where ~form:pform ~allowed:[ "color"; "size" ] rest in
          let color =
            let node, c = required ~form:pform ~form_node:f.node pfs "color" (fun _ f -> (f.node, color_field pform "color" f)) in
            check node (Material.check_color ~form:(form ^ " pattern") c)
          in
          let size =
            let node, x = required ~form:pform ~form_node:f.node pfs "size" (fun _ f -> (single pform "size" f, float_field pform "size" f)) in
            check node (Pattern.check_size ~form x)
          in
          Pattern.checker ~size color
      | (Sexp.Atom kind as node) :: _ ->
          fail node "unknown %s pattern %s; expected %s%s" form (show_atom kind) (one_of kinds) (suggestion kind kinds)
      | _ -> fail f.node "%s pattern: expected a kind, e.g. (pattern checker (color 20 20 20) (size 1))" form)
    (find fs "pattern")

(* A field [(name true)] or [(name false)]. *)
let bool_field form name f =
  match single form name f with
  | Sexp.Atom "true" -> true
  | Sexp.Atom "false" -> false
  | node -> fail node "%s: expected true or false" (field_what form name ())

(* An area light's [(sampling stratified)] or [(sampling uniform)]. *)
let area_sampling form f =
  let kinds = [ "stratified"; "uniform" ] in
  match single form "sampling" f with
  | Sexp.Atom "stratified" -> Light.Stratified
  | Sexp.Atom "uniform" -> Light.Uniform
  | Sexp.Atom a as node ->
      fail node "%s: expected %s, got %s%s" (field_what form "sampling" ()) (one_of kinds) (show_atom a)
        (suggestion a kinds)
  | node -> fail node "%s: expected %s" (field_what form "sampling" ()) (one_of kinds)

(* The optical fields of every object: transparency, refractive index,
   Fresnel; the split [reflective + transparency <= 1] is reported at the
   transparency. *)
let optics_fields = [ "transparency"; "refractive-index"; "fresnel" ]

(* [base]: the fields of the named material that inline fields override. *)
let optics ~form ?base fs ~reflective =
  let checked name check_value =
    Option.map (fun f -> check (single form name f) (check_value (float_field form name f))) (find fs name)
  in
  let default field value = match base with Some m -> field m | None -> value in
  let transparency =
    Option.value ~default:(default Material.transparency 0.) (checked "transparency" (Material.check_transparency ~form))
  in
  let refractive_index =
    Option.value ~default:(default Material.refractive_index 1.)
      (checked "refractive-index" (Material.check_refractive_index ~form))
  in
  let fresnel =
    Option.fold ~none:(default Material.fresnel false) ~some:(bool_field form "fresnel") (find fs "fresnel")
  in
  (* A named material passed the check: only an inline field can break it. *)
  (match (find fs "transparency", find fs "reflective") with
  | Some f, _ -> ignore (check (single form "transparency" f) (Material.check_split ~form ~reflective ~transparency))
  | None, Some f -> ignore (check (single form "reflective" f) (Material.check_split ~form ~reflective ~transparency))
  | None, None -> ());
  (transparency, refractive_index, fresnel)

(* The material fields that every object takes: a named material
   [(material glass)], and fields that override it or stand alone. *)
let material_fields = [ "material"; "color"; "specular"; "reflective" ] @ optics_fields @ [ "pattern"; "texture" ]

(* How texture fields are read: [load] reads an image file (the path as
   the scene gives it). *)
type textures = { load : string -> (Texture.t, [ `Msg of string ]) result }

(* Named materials, as [(material name ...)] defined them, and how the
   textures of materials are read. *)
type named = { materials : (string, Material.t * Positions.pos option) Hashtbl.t; textures : textures }

let named_material ~(named : named) ~form f =
  match f.args with
  | [ (Sexp.Atom name as node) ] -> (
      match Hashtbl.find_opt named.materials name with
      | Some (m, _) -> m
      | None ->
          let known = Hashtbl.fold (fun n _ acc -> n :: acc) named.materials [] |> List.sort String.compare in
          if known = [] then fail node "unknown material %s: no (material %s ...) form comes before it" (show_atom name) name
          else fail node "unknown material %s; defined before it: %s%s" (show_atom name) (one_of known) (suggestion name known))
  | _ -> fail f.node "%s material: expected the name of a material, e.g. (material glass)" form

(* [(texture (file "earth.png") (mapping spherical) (size s))], the
   optional field of every object's material, with its node; [size] only
   for a planar mapping. The file is read, its errors told at the file's
   name. *)
let texture ~where ~(named : named) ~form fs =
  Option.map
    (fun f ->
      let tform = form ^ " texture" in
      let tfs = fields ~where ~form:tform ~allowed:[ "file"; "mapping"; "size" ] f.args in
      let file_node, file =
        required ~form:tform ~form_node:f.node tfs "file" (fun what f ->
            match f.args with
            | [ Sexp.Atom a ] when a <> "" -> (f.node, a)
            | _ -> fail f.node "%s: expected a file name, e.g. (file \"earth.png\")" (what ()))
      in
      let mapping =
        required ~form:tform ~form_node:f.node tfs "mapping" (fun what f ->
            let names = Texture_map.mapping_names in
            match f.args with
            | [ (Sexp.Atom a as node) ] -> (
                match Texture_map.mapping_of_string a with
                | Some m -> m
                | None -> fail node "unknown %s %s; expected %s%s" (what ()) (show_atom a) (one_of names) (suggestion a names))
            | _ -> fail f.node "%s: expected one of %s" (what ()) (one_of names))
      in
      let size =
        match find tfs "size" with
        | None -> 1.
        | Some sf when mapping <> Texture_map.Planar ->
            fail sf.name_node "%s size: only a planar mapping takes a size (one copy of the image per size x size square)" tform
        | Some sf ->
            let x = float_field tform "size" sf in
            check (single tform "size" sf) (Limits.check_size (tform ^ " size") x)
      in
      let image = check file_node (named.textures.load file) in
      (f.node, Texture_map.v ~size ~file mapping image))
    (find fs "texture")

(* Whether [form] names a [(material name ...)] definition rather than an
   object. *)
let is_definition form = String.length form > 9 && String.sub form 0 9 = "material "

(* An object of kind [form] takes the one mapping that fits its surface;
   a named material's texture is checked where an object uses it, a
   transform's or use's where Shape.validate checks its object's
   surfaces. *)
let check_mapping ~form ~node (t : Texture_map.t) =
  let names = "spheres (spherical), planes (planar), boxes (box) and meshes (uv)" in
  if form = "transform" || String.starts_with ~prefix:"use " form then ()
  else
    match Texture_map.mapping_for form with
    | None -> fail node "a %s takes no texture; textures map onto %s" form names
    | Some m when m <> t.mapping ->
        fail node "%s texture mapping must be %s, got %s" form (Texture_map.mapping_name m) (Texture_map.mapping_name t.mapping)
    | Some _ -> ()

let material ~where ~named ~form ~form_node fs =
  let base = Option.map (named_material ~named ~form) (find fs "material") in
  let color =
    match (base, find fs "color") with
    | Some m, None -> Material.color m
    | _ ->
        let node, c = required ~form ~form_node fs "color" (fun _ f -> (f.node, color_field form "color" f)) in
        check node (Material.check_color ~form c)
  in
  let checked name check_value =
    Option.map
      (fun f -> check (single form name f) (check_value (float_field form name f)))
      (find fs name)
  in
  let default field value = match base with Some m -> field m | None -> value in
  let specular =
    Option.value ~default:(default Material.specular Material.matte) (checked "specular" (Material.check_specular ~form))
  in
  let reflective =
    Option.value ~default:(default Material.reflective 0.) (checked "reflective" (Material.check_reflective ~form))
  in
  let transparency, refractive_index, fresnel = optics ~form ?base fs ~reflective in
  let pattern = match pattern ~where ~form fs with Some _ as p -> p | None -> default Material.pattern None in
  let texture =
    match texture ~where ~named ~form fs with
    | Some (node, t) ->
        if not (is_definition form) then check_mapping ~form ~node t;
        if Option.is_some pattern then fail node "%s has a pattern and a texture; a material's colour comes from one of them" form;
        Some t
    | None ->
        let t = default Material.texture None in
        Option.iter (check_mapping ~form ~node:(Option.fold ~none:form_node ~some:(fun f -> f.node) (find fs "material"))) t;
        t
  in
  Material.v ~specular ~reflective ~transparency ~refractive_index ~fresnel ?pattern ?texture color

let sphere ~where ~named form_node nodes =
  let form = "sphere" in
  let fs =
    fields ~where ~form
      ~allowed:([ "center"; "radius" ] @ material_fields)
      nodes
  in
  let node_and parse name = required ~form ~form_node fs name (fun _ f -> (f.node, parse f)) in
  let center =
    let node, c = node_and (vec3_field form "center") "center" in
    check node (Sphere.check_center c)
  in
  let radius = require ~form ~form_node "radius" (checked_float form fs "radius" Sphere.check_radius) in
  Sphere.v ~center ~radius (material ~where ~named ~form ~form_node fs)

let point_field ~form ~form_node fs name =
  let node, p = required ~form ~form_node fs name (fun _ f -> (f.node, vec3_field form name f)) in
  (node, check node (Limits.check_point (field_what form name ()) p))

let plane ~where ~named form_node nodes =
  let form = "plane" in
  let fs = fields ~where ~form ~allowed:([ "point"; "normal" ] @ material_fields) nodes in
  let _, point = point_field ~form ~form_node fs "point" in
  let normal_node, normal = point_field ~form ~form_node fs "normal" in
  let m = material ~where ~named ~form ~form_node fs in
  Shape.Plane (check normal_node (Plane.validate (Plane.v ~point ~normal m)))

let triangle ~where ~named form_node nodes =
  let form = "triangle" in
  let fs = fields ~where ~form ~allowed:("vertices" :: material_fields) nodes in
  let node, (v0, v1, v2) =
    required ~form ~form_node fs "vertices" (fun what f ->
        let vertex node =
          match node with
          | Sexp.List elements ->
              let p = vec3_of_nodes (fun () -> what () ^ " vertex") node elements in
              check node (Limits.check_point (what () ^ " vertex") p)
          | Sexp.Atom atom ->
              fail node "%s: expected a vertex of 3 numbers in parentheses, got %s" (what ()) (show_atom atom)
        in
        match f.args with
        | [ a; b; c ] -> (f.node, (vertex a, vertex b, vertex c))
        | args ->
            fail f.node "%s takes 3 vertices, e.g. (-1 0 4) (1 0 4) (0 1.5 4), got %d values" (what ())
              (List.length args))
  in
  let m = material ~where ~named ~form ~form_node fs in
  Shape.Triangle (check node (Triangle.validate (Triangle.v v0 v1 v2 m)))

let box_solid ~where ~named form_node nodes =
  let form = "box" in
  let fs = fields ~where ~form ~allowed:([ "min"; "max" ] @ material_fields) nodes in
  let _, min = point_field ~form ~form_node fs "min" in
  let max_node, max = point_field ~form ~form_node fs "max" in
  let m = material ~where ~named ~form ~form_node fs in
  check max_node (Box.validate (Box.v ~min ~max m))

let box ~where ~named form_node nodes = Shape.Box (box_solid ~where ~named form_node nodes)

(* A form of a kind its module describes ({!Primitives}): the fields the
   description lists, read on its demand, and the material's. *)
let primitive_solid (Shape_desc.Any d) ~where ~named form_node nodes =
  let form = d.name in
  let fs = fields ~where ~form ~allowed:(List.map fst d.fields @ material_fields) nodes in
  let flag name =
    match List.assoc_opt name d.fields with
    | Some (Shape_desc.Flag default) -> Option.fold ~none:default ~some:(bool_field form name) (find fs name)
    | _ -> invalid_arg (Printf.sprintf "Scene_text: %s's field %s is not a flag" form name)
  in
  let reader =
    {
      Shape_desc.point = (fun name -> snd (point_field ~form ~form_node fs name));
      number = (fun name -> require ~form ~form_node name (checked_float form fs name Result.ok));
      flag;
    }
  in
  let m = material ~where ~named ~form ~form_node fs in
  check form_node (Shape_desc.validate (Shape_desc.Primitive (d, d.read reader m)))

(* The described kind a CSG operand [kw] names, if it is closed. *)
let closed_primitive kw =
  match Primitives.find kw with Some (Shape_desc.Any d as a) when Kind.closed d.kind -> Some a | _ -> None

(* The operands a CSG form takes, for its messages. *)
let operands =
  let described = List.filter_map (fun (Shape_desc.Any d) -> if Kind.closed d.kind then Some (d.name ^ ", ") else None) Primitives.all in
  "a sphere, box, " ^ String.concat "" described ^ "closed mesh, csg, or a transform or use of one"

(* A mesh: its file is read by [load] (the path as the scene gives it). *)
let mesh_solid ~where ~named ~load ~add_triangles form_node nodes =
  let form = "mesh" in
  let fs = fields ~where ~form ~allowed:([ "file"; "scale"; "translate"; "smooth" ] @ material_fields) nodes in
  let file_node, file =
    required ~form ~form_node fs "file" (fun what f ->
        match f.args with
        | [ Sexp.Atom a ] when a <> "" -> (f.node, a)
        | _ -> fail f.node "%s: expected a file name, e.g. (file \"models/knot.obj\")" (what ()))
  in
  let scale =
    Option.value ~default:1.
      (Option.map
         (fun f ->
           let x = float_field form "scale" f in
           if x > 0. then x else fail (single form "scale" f) "mesh scale must be > 0, got %s" (Float_text.to_string x))
         (find fs "scale"))
  in
  let translate =
    match find fs "translate" with
    | Some f -> check f.node (Limits.check_point "mesh translate" (vec3_field form "translate" f))
    | None -> Vec3.zero
  in
  let smooth = Option.fold ~none:false ~some:(bool_field form "smooth") (find fs "smooth") in
  let m = material ~where ~named ~form ~form_node fs in
  let obj = check file_node (load file) in
  (match Material.texture m with
  | Some t when Obj_file.texcoord_count obj = 0 || obj.triangle_texcoords = [||] ->
      let node = match (find fs "texture", find fs "material") with Some f, _ | None, Some f -> f.node | None, None -> form_node in
      fail node "mesh texture mapping %s needs the file's texture coordinates (vt and f v/vt), which %s does not give"
        (Texture_map.mapping_name t.mapping) file
  | _ -> ());
  (* Each form places its own copy of the file's triangles: counted over
     the whole scene before this one is made. *)
  check form_node (add_triangles (Array.length obj.Obj_file.triangles / 3));
  check form_node
(Mesh.of_obj ~smooth ~scale ~translate ~source:file obj m)

let mesh ~where ~named ~load ~add_triangles form_node nodes = Shape.Mesh (mesh_solid ~where ~named ~load ~add_triangles form_node nodes)

let csg_ops = [ "union"; "intersection"; "difference" ]

(* The CSG operand that a [transform] or [use] form at [node] made: its
   object must be a closed solid, at any depth of placement. *)
let rec operand_of_shape node = function
  | Shape.Sphere s -> Csg.Sphere s
  | Shape.Box b -> Csg.Box b
  | Shape.Mesh m ->
      check node (Csg.check_closed m);
      Csg.Mesh m
  | Shape.Csg c -> Csg.Csg c
  | Shape.Primitive p ->
      if not (Shape_desc.closed p) then
        fail node "csg: the object placed here, %s, is not a closed solid; an operand is %s" (Shape_desc.not_closed p) operands;
      Csg.Primitive p
  | Shape.Instance i -> Csg.placed ?material:i.own_material ?name:i.name i.transform (operand_of_shape node i.shape)
  | (Shape.Plane _ | Shape.Triangle _) as sh ->
      fail node "csg: the object placed here, a %s, is not a closed solid; an operand is %s" (Shape.name sh) operands

(* A CSG form [(csg op A B)], nested [depth] deep: each operand is a
   closed solid's form, or a [transform] or [use] of one, which [placed]
   reads as any object's. *)
let rec csg ~where ~named ~load ~add_triangles ~placed ~depth form_node nodes =
  if depth > Csg.max_depth then fail form_node "csg nested deeper than %d levels" Csg.max_depth;
  match nodes with
  | Sexp.Atom name :: rest as all -> (
      let op =
        match Csg.op_of_string name with
        | Some op -> op
        | None ->
            fail (List.hd all) "unknown csg operation %s; expected %s%s" (show_atom name) (one_of csg_ops)
              (suggestion name csg_ops)
      in
      match rest with
      | [ a; b ] ->
          Csg.v op (csg_operand ~where ~named ~load ~add_triangles ~placed ~depth a) (csg_operand ~where ~named ~load ~add_triangles ~placed ~depth b)
      | _ -> fail form_node "csg %s takes 2 solids, got %d" name (List.length rest))
  | _ ->
      fail form_node "csg: expected an operation first, e.g. (csg difference (sphere ...) (box ...)); operations are %s"
        (one_of csg_ops)

and csg_operand ~where ~named ~load ~add_triangles ~placed ~depth node =
  match node with
  | Sexp.List (Sexp.Atom "sphere" :: rest) -> Csg.Sphere (sphere ~where ~named node rest)
  | Sexp.List (Sexp.Atom "box" :: rest) -> Csg.Box (box_solid ~where ~named node rest)
  | Sexp.List (Sexp.Atom "mesh" :: rest) ->
      let m = mesh_solid ~where ~named ~load ~add_triangles node rest in
      check node (Csg.check_closed m);
      Csg.Mesh m
  | Sexp.List (Sexp.Atom "csg" :: rest) -> Csg.Csg (csg ~where ~named ~load ~add_triangles ~placed ~depth:(depth + 1) node rest)
  | Sexp.List (Sexp.Atom ("transform" | "use") :: _) ->
      let o = operand_of_shape node (placed node) in
      (* As [Csg.validate] refuses it, but located at this form. *)
      if List.exists (fun (_, (m : Material.t), ts) -> ts <> [] && Option.is_some m.pattern) (Csg.leaves (Csg.v Csg.Union o o)) then
        fail node "csg: a transformed operand cannot have a pattern (patterns are not carried into an object's frame yet)";
      o
  | Sexp.List (Sexp.Atom kw :: rest) when closed_primitive kw <> None ->
      let p = primitive_solid (Option.get (closed_primitive kw)) ~where ~named node rest in
      (* Of a closed kind, but possibly left open (a cylinder without caps). *)
      if not (Shape_desc.closed p) then fail node "csg: %s is not a closed solid; an operand is %s" (Shape_desc.not_closed p) operands;
      Csg.Primitive p
  | Sexp.List (Sexp.Atom kw :: _) when kw = "plane" || kw = "triangle" || Primitives.find kw <> None ->
      fail node "csg: a %s is not a closed solid; an operand is %s" kw operands
  | Sexp.List (Sexp.Atom kw :: _) -> fail node "csg: unknown solid %s; an operand is %s" (show_atom kw) operands
  | _ -> fail node "csg: expected a solid in parentheses, e.g. (sphere ...), (box ...), (mesh ...), (csg ...) or (transform ...)"

let light ~where form_node nodes =
  let kinds = [ "ambient"; "point"; "directional"; "area"; "sphere"; "spot" ] in
  match nodes with
  | (Sexp.Atom kind as kind_node) :: rest ->
      let form = "light " ^ kind in
      let others =
        match kind with
        | "point" -> [ "position" ]
        | "directional" -> [ "direction" ]
        | "area" -> [ "corner"; "edge1"; "edge2"; "samples"; "adaptive"; "sampling" ]
        | "sphere" -> [ "position"; "radius"; "samples" ]
        | "spot" -> [ "position"; "direction"; "angle"; "falloff" ]
        | _ -> []
      in
      if not (List.exists (String.equal kind) kinds) then
        fail kind_node "unknown light kind %s; expected %s%s" (show_atom kind) (one_of kinds)
          (suggestion kind kinds);
      let fs = fields ~where ~form ~allowed:("intensity" :: others) rest in
      let intensity =
        require ~form ~form_node "intensity" (checked_float form fs "intensity" Light.check_intensity)
      in
      let vec name check_v =
        let node, p = required ~form ~form_node fs name (fun _ f -> (f.node, vec3_field form name f)) in
        check node (check_v p)
      in
      let point name = vec name (Limits.check_point (field_what form name ())) in
      let num name = require ~form ~form_node name (checked_float form fs name Result.ok) in
      (* The samples' counts, each checked where it is written. *)
      let samples n =
        let f = require ~form ~form_node "samples" (find fs "samples") in
        if List.length f.args <> n then
          fail f.node "%s takes %d integer%s, got %d values" (field_what form "samples" ()) n
            (if n = 1 then "" else "s") (List.length f.args);
        List.map
          (fun a ->
            let k = integer (field_what form "samples") a in
            if k < 1 || k > Light.max_samples then
              fail a "%s must lie in [1, %d], got %d" (field_what form "samples" ()) Light.max_samples k;
            k)
          f.args
      in
      (* The checks of the whole light (edges not parallel, the ranges of
         radius, angle, falloff), located at the form. *)
      let whole l = check form_node (Light.validate l) in
      (match kind with
      | "point" -> Light.point intensity (vec "position" Light.check_position)
      | "directional" -> Light.directional intensity (vec "direction" Light.check_direction)
      | "area" ->
          let corner = point "corner" and edge1 = point "edge1" and edge2 = point "edge2" in
          let u, v = match samples 2 with [ u; v ] -> (u, v) | _ -> (1, 1) in
          let adaptive = Option.fold ~none:false ~some:(bool_field form "adaptive") (find fs "adaptive") in
          let sampling = Option.fold ~none:Light.Stratified ~some:(area_sampling form) (find fs "sampling") in
          whole (Light.area ~adaptive ~sampling intensity ~corner ~edge1 ~edge2 ~samples:(u, v))
      | "sphere" ->
          let position = point "position" and radius = num "radius" in
          let n = match samples 1 with [ n ] -> n | _ -> 1 in
          whole (Light.sphere intensity ~position ~radius ~samples:n)
      | "spot" ->
          let position = point "position" and direction = point "direction" in
          let angle = num "angle" and falloff = num "falloff" in
          whole (Light.spot intensity ~position ~direction ~angle ~falloff)
      | _ -> Light.ambient intensity)
  | _ ->
      fail form_node
        "light: expected its kind first, e.g. (light point (intensity 0.6) (position 2 1 0)); kinds are %s"
        (one_of kinds)

let path_key ~where key_node nodes =
  let form = "camera-path key" in
  let fs = fields ~where ~form ~allowed:[ "frame"; "position"; "look-at"; "up" ] nodes in
  let frame =
    required ~form ~form_node:key_node fs "frame" (fun _ f ->
        let n = int_field form "frame" f in
        if n < 0 || n > Camera_path.max_frame then
          fail (single form "frame" f) "camera-path key frame must lie in [0, %d], got %d" Camera_path.max_frame n;
        n)
  in
  let point name =
    let node, p = required ~form ~form_node:key_node fs name (fun _ f -> (f.node, vec3_field form name f)) in
    check node (Limits.check_point (field_what form name ()) p)
  in
  let position = point "position" in
  let target = point "look-at" in
  let up =
    Option.map
      (fun (node, p) -> check node (Limits.check_point (field_what form "up" ()) p))
      (get ~form fs "up" (fun _ f -> (f.node, vec3_field form "up" f)))
  in
  check key_node (Camera_path.check_key (Camera_path.key ?up ~frame ~position target))

let camera_path ~where form_node nodes =
  (* Tail-recursive maps throughout (List.rev_map, then List.rev): a scene
     file may hold very many keys, and List.map of OCaml 4.13 recurses as
     deep as the list is long. *)
  let keys =
    List.rev @@ List.rev_map
      (fun node ->
        match node with
        | Sexp.List (Sexp.Atom "key" :: rest) -> (node, path_key ~where node rest)
        | Sexp.List _ -> fail node "camera-path: expected a keyframe (key (frame N) (position x y z) (look-at x y z))"
        | Sexp.Atom atom -> fail node "camera-path: expected a keyframe (key ...), got %s" (show_atom atom))
      nodes
  in
  let rec segments = function
    | (_, k0) :: ((node, k1) :: _ as rest) ->
        ignore (check node (Camera_path.check_segment k0 k1));
        segments rest
    | [ _ ] | [] -> ()
  in
  (match keys with
  | [] -> fail form_node "camera-path needs at least one (key (frame N) (position x y z) (look-at x y z))"
  | _ -> segments keys);
  check form_node (Camera_path.v (List.rev (List.rev_map snd keys)))

(* A top-level form that takes its values directly, e.g. (epsilon 0.001). *)
let value form form_node = function
  | [ x ] -> x
  | nodes -> fail form_node "%s takes 1 value, got %d" form (List.length nodes)

(* The scene being read, form by form. *)
type builder = {
  limits : Limits.t;
  where : Sexp.t -> Positions.pos option;
  load : string -> (Obj_file.t, [ `Msg of string ]) result;  (** Reads a mesh file. *)
  seen : (string, Positions.pos option) Hashtbl.t;
      (** Forms that may appear once, and where they first did. *)
  named : named;  (** The materials defined so far. *)
  mutable scene : Scene.t;
  spheres : Spheres.builder;
  mutable shapes : (int * Shape.t) list;
      (** In reverse order, each with the number of spheres before it. *)
  mutable lights : Light.t list;  (** In reverse order. *)
  mutable n_spheres : int;
  mutable n_lights : int;
  mutable n_triangles : int;  (** Of every mesh form so far. *)
  defined : (string, Shape.t * Positions.pos option) Hashtbl.t;  (** The objects [define]d so far. *)
}

let builder ~limits ~load ~textures where =
  {
    limits;
    where;
    load;
    seen = Hashtbl.create 8;
    named = { materials = Hashtbl.create 8; textures };
    scene = Scene.v ~objects:[] ~lights:[] ();
    spheres = Spheres.builder ();
    shapes = [];
    lights = [];
    n_spheres = 0;
    n_lights = 0;
    n_triangles = 0;
    defined = Hashtbl.create 8;
  }

let add_triangles b n =
  b.n_triangles <- b.n_triangles + n;
  Result.map ignore (Limits.check_triangles b.limits b.n_triangles)

let once b kw kw_node =
  match Hashtbl.find_opt b.seen kw with
  | Some first ->
      fail kw_node "duplicate %s form (first given at %s); it may appear only once" kw
        (Option.fold ~none:"?" ~some:position first)
  | None -> Hashtbl.add b.seen kw (b.where kw_node)

(* What the count of spheres and shapes is, for its message: "spheres"
   while the scene has no other shape. *)
let objects b = match b.shapes with [] -> `Spheres | _ :: _ -> `Objects

(* An object other than a sphere, after the spheres read so far. *)
let place b sh = b.shapes <- (Spheres.builder_length b.spheres, sh) :: b.shapes

(* [(material name field...)]: defined once, before the objects that use it. *)
let define_material b node = function
  | (Sexp.Atom name as name_node) :: nodes ->
      (match Hashtbl.find_opt b.named.materials name with
      | Some (_, first) ->
          fail name_node "material %s is defined twice (first at %s); a name may be defined only once" (show_atom name)
            (Option.fold ~none:"?" ~some:position first)
      | None -> ());
      let form = "material " ^ name in
      let allowed = List.filter (fun f -> f <> "material") material_fields in
      let fs = fields ~where:b.where ~form ~allowed nodes in
      let m = material ~where:b.where ~named:b.named ~form ~form_node:node fs in
      Hashtbl.add b.named.materials name (m, b.where name_node)
  | _ ->
      fail node "material: expected its name first, e.g. (material glass (color 230 230 255) (transparency 0.9))"

(* A setting, given at most once: [set b node rest scene] is [scene] with
   it. *)
let setting kw set b ~kw_node node rest =
  once b kw kw_node;
  b.scene <- set b node rest b.scene

(* Objects are counted as they come, so that the error points at the
   first form beyond the bound, before the rest of the file is read. *)
let count b node kind =
  b.n_spheres <- b.n_spheres + 1;
  ignore (check node (Limits.check_count b.limits kind b.n_spheres))

(* An object other than a sphere: it counts against the bound of
   spheres, both are objects. *)
let shape parse b ~kw_node:_ node rest =
  count b node `Objects;
  place b (parse b node rest)

let sphere_form b ~kw_node:_ node rest =
  count b node (objects b);
  Spheres.add b.spheres (sphere ~where:b.where ~named:b.named node rest)

let light_form b ~kw_node:_ node rest =
  b.n_lights <- b.n_lights + 1;
  ignore (check node (Limits.check_count b.limits `Lights b.n_lights));
  b.lights <- light ~where:b.where node rest :: b.lights

(* {2 Transforms, definitions and instances} *)

let transform_ops_named = [ "scale"; "rotate-x"; "rotate-y"; "rotate-z"; "rotate"; "translate" ]

(* One operation of a transform's list, checked alone so that its error
   points at it. *)
let transform_op ~where node =
  let op =
    match node with
    | Sexp.List ((Sexp.Atom name as name_node) :: args) -> (
        let what () = "transform " ^ name in
        let angle () =
          match args with
          | [ a ] -> number what a
          | _ -> fail node "%s takes 1 angle in degrees, got %d values" name (List.length args)
        in
        match name with
        | "scale" -> (
            match args with
            | [ k ] ->
                let k = number what k in
                Transform.Scale (Vec3.v k k k)
            | _ -> Transform.Scale (vec3_of_nodes what node args))
        | "translate" -> Transform.Translate (vec3_of_nodes what node args)
        | "rotate-x" -> Transform.Rotate_x (angle ())
        | "rotate-y" -> Transform.Rotate_y (angle ())
        | "rotate-z" -> Transform.Rotate_z (angle ())
        | "rotate" ->
            let fs = fields ~where ~form:"transform rotate" ~allowed:[ "axis"; "angle" ] args in
            let form = "transform rotate" in
            let axis = required ~form ~form_node:node fs "axis" (fun _ f -> vec3_field form "axis" f) in
            let angle = required ~form ~form_node:node fs "angle" (fun _ f -> float_field form "angle" f) in
            Transform.Rotate (axis, angle)
        | _ ->
            fail name_node "unknown transform operation %s; expected %s%s" (show_atom name) (one_of transform_ops_named)
              (suggestion name transform_ops_named))
    | _ -> fail node "transform: expected an operation such as (rotate-y 30) or (translate 0 0 5)"
  in
  ignore (check node (Transform.v [ op ]));
  op

(* A transform's list of operations, [((scale 2) (rotate-y 30))]. *)
let transform_of ~where node =
  match node with
  | Sexp.List ops -> check node (Transform.v (List.map (transform_op ~where) ops))
  | Sexp.Atom a ->
      fail node "transform: expected a list of operations in parentheses, e.g. ((rotate-y 30) (translate 0 0 5)), got %s"
        (show_atom a)

(* Material fields written on a [transform] or [use]: they make the
   instance's material, for every surface of its object. *)
let instance_material b ~form ~form_node fs =
  if List.exists (fun name -> Option.is_some (find fs name)) material_fields then
    Some (material ~where:b.where ~named:b.named ~form ~form_node fs)
  else None

let object_forms = [ "sphere"; "plane"; "triangle"; "box"; "mesh"; "csg" ] @ List.map (fun (Shape_desc.Any d) -> d.name) Primitives.all @ [ "transform"; "use" ]

(* Any object's form, as a value: what [transform] and [define] take. *)
let rec object_of b node =
  match node with
  | Sexp.List ((Sexp.Atom kw as kw_node) :: rest) -> (
      let where = b.where and named = b.named in
      match kw with
      | "sphere" -> Shape.Sphere (sphere ~where ~named node rest)
      | "plane" -> plane ~where ~named node rest
      | "triangle" -> triangle ~where ~named node rest
      | "box" -> box ~where ~named node rest
      | "mesh" -> mesh ~where ~named ~load:b.load ~add_triangles:(add_triangles b) node rest
      | "csg" -> Shape.Csg (csg ~where ~named ~load:b.load ~add_triangles:(add_triangles b) ~placed:(object_of b) ~depth:1 node rest)
      | "transform" -> transform_form b node rest
      | "use" -> use_form b node rest
      | _ -> (
          match Primitives.find kw with
          | Some d -> Shape.Primitive (primitive_solid d ~where ~named node rest)
          | None ->
              fail kw_node "unknown object %s; expected %s%s" (show_atom kw) (one_of object_forms) (suggestion kw object_forms)))
  | _ -> fail node "expected an object in parentheses, e.g. (sphere ...), (box ...) or (use NAME)"

(* [(transform (OPS...) OBJECT material-fields...)]. *)
and transform_form b node rest =
  match rest with
  | ops :: obj :: fields_nodes ->
      let t = transform_of ~where:b.where ops in
      let shape = object_of b obj in
      let fs = fields ~where:b.where ~form:"transform" ~allowed:material_fields fields_nodes in
      let material = instance_material b ~form:"transform" ~form_node:node fs in
      check node (Shape.validate (Shape.instance ?material t shape))
  | _ ->
      fail node "transform takes a list of operations and an object, e.g. (transform ((rotate-y 30)) (box (min -1 -1 -1) (max 1 1 1) (color 0 0 255)))"

(* [(use NAME (transform (OPS...)) material-fields...)]. *)
and use_form b node rest =
  match rest with
  | (Sexp.Atom name as name_node) :: fields_nodes ->
      let shape =
        match Hashtbl.find_opt b.defined name with
        | Some (sh, _) -> sh
        | None ->
            let known = Hashtbl.fold (fun n _ acc -> n :: acc) b.defined [] |> List.sort String.compare in
            if known = [] then fail name_node "unknown object %s: no (define %s ...) form comes before it" (show_atom name) name
            else fail name_node "unknown object %s; defined before it: %s%s" (show_atom name) (one_of known) (suggestion name known)
      in
      let form = "use " ^ name in
      let fs = fields ~where:b.where ~form ~allowed:("transform" :: material_fields) fields_nodes in
      let t =
        match find fs "transform" with
        | Some f -> (
            match f.args with
            | [ ops ] -> transform_of ~where:b.where ops
            | _ -> fail f.node "%s transform takes one list of operations, e.g. (transform ((rotate-y 30) (translate 0 0 5)))" form)
        | None -> Transform.identity
      in
      let material = instance_material b ~form ~form_node:node fs in
      check node (Shape.validate (Shape.instance ?material ~name t shape))
  | _ -> fail node "use: expected the name of a defined object first, e.g. (use knot (transform ((rotate-x 90))))"

(* [(define NAME OBJECT)]: named, not placed. *)
let define_object b node = function
  | [ (Sexp.Atom name as name_node); obj ] ->
      (match Hashtbl.find_opt b.defined name with
      | Some (_, first) ->
          fail name_node "object %s is defined twice (first at %s); a name may be defined only once" (show_atom name)
            (Option.fold ~none:"?" ~some:position first)
      | None -> ());
      let shape = check obj (Shape.validate (object_of b obj)) in
      Hashtbl.add b.defined name (shape, b.where name_node)
  | _ -> fail node "define: expected a name and one object, e.g. (define knot (mesh (file \"knot.obj\") (color 200 200 200)))"

(* The forms of the top level, in the order their names are listed. *)
let forms =
  [
    ("material", fun b ~kw_node:_ node rest -> define_material b node rest);
    ( "canvas",
      setting "canvas" (fun b node rest s ->
          let width, height = canvas ~limits:b.limits ~where:b.where node rest in
          Scene.with_overrides ~width ~height s) );
    ("viewport", setting "viewport" (fun b _ rest s -> Scene.with_overrides ~viewport:(viewport ~where:b.where rest) s));
    ("camera", setting "camera" (fun b _ rest s -> Scene.with_overrides ~camera:(camera ~where:b.where rest) s));
    ( "camera-path",
      setting "camera-path" (fun b node rest s ->
          Scene.with_overrides ~camera_path:(Some (camera_path ~where:b.where node rest)) s) );
    ( "background",
      setting "background" (fun _ node rest s ->
          let c = color_of_nodes (fun () -> "background") node rest in
          Scene.with_overrides ~background:(check node (Scene.check_background c)) s) );
    ( "recursion-depth",
      setting "recursion-depth" (fun b node rest s ->
          let v = value "recursion-depth" node rest in
          Scene.with_overrides ~depth:(check v (Limits.check_depth b.limits (integer (fun () -> "recursion-depth") v))) s) );
    ( "epsilon",
      setting "epsilon" (fun _ node rest s ->
          let v = value "epsilon" node rest in
          Scene.with_overrides ~epsilon:(Some (check v (Scene.check_epsilon (number (fun () -> "epsilon") v)))) s) );
    ("sphere", sphere_form);
    ("plane", shape (fun b -> plane ~where:b.where ~named:b.named));
    ("triangle", shape (fun b -> triangle ~where:b.where ~named:b.named));
    ("box", shape (fun b -> box ~where:b.where ~named:b.named));
    ("mesh", shape (fun b -> mesh ~where:b.where ~named:b.named ~load:b.load ~add_triangles:(add_triangles b)));
    ( "csg",
      shape (fun b node rest ->
          Shape.Csg
            (csg ~where:b.where ~named:b.named ~load:b.load ~add_triangles:(add_triangles b) ~placed:(object_of b) ~depth:1 node rest))
    );
  ]
  @ List.map
      (fun (Shape_desc.Any d as a) -> (d.name, shape (fun b node rest -> Shape.Primitive (primitive_solid a ~where:b.where ~named:b.named node rest))))
      Primitives.all
  @ [
      ("transform", shape transform_form);
      ("define", fun b ~kw_node:_ node rest -> define_object b node rest);
      ("use", shape use_form);
      ("light", light_form);
    ]

let top_level = List.map fst forms

let add_form b node =
  match node with
  | Sexp.Atom atom -> fail node "expected a form in parentheses such as (sphere ...), got %s" (show_atom atom)
  | Sexp.List [] -> fail node "empty form (); expected one of %s" (one_of top_level)
  | Sexp.List (Sexp.List _ :: _) -> fail node "expected a form name such as sphere or light, got a list"
  | Sexp.List ((Sexp.Atom kw as kw_node) :: rest) -> (
      match List.assoc_opt kw forms with
      | Some form -> form b ~kw_node node rest
      | None -> fail kw_node "unknown form %s; expected %s%s" (show_atom kw) (one_of top_level) (suggestion kw top_level))

let finish b =
  (* Without a camera form, a still picture is the path's first frame. *)
  let camera =
    match Scene.camera_path b.scene with
    | Some path when not (Hashtbl.mem b.seen "camera") -> (
        match Camera_path.camera path (Camera_path.first_frame path) with Ok c -> c | Error _ -> Scene.camera b.scene)
    | _ -> Scene.camera b.scene
  in
  Scene.with_objects
    (Scene.with_overrides ~camera ~lights:(List.rev b.lights) b.scene)
    ~spheres:(Spheres.build b.spheres) ~placed:(List.rev b.shapes)

(* Where the text comes from: [open_text ()] reads it from its start, a
   few bytes at a time ([read buf pos len] is how many it put in [buf] at
   [pos], [0] at the end), as often as an error needs another pass. *)
type source = unit -> reader

and reader = { read : Bytes.t -> int -> int -> int; close : unit -> unit }

let string_source text () =
  let at = ref 0 in
  let read buf pos len =
    let k = min len (String.length text - !at) in
    Bytes.blit_string text !at buf pos k;
    at := !at + k;
    k
  in
  { read; close = ignore }

(* [src] with a UTF-8 byte order mark at its start (some editors write
   one) read as three spaces: both readers then skip it, and every offset
   and column is the file's. Where the text starts otherwise, its bytes
   as they are. *)
let without_byte_order_mark (src : source) () =
  let r = src () in
  (* The text's first 3 bytes (fewer if it is shorter), read before
     anything is given, then given first. *)
  let head = Bytes.create 3 and head_len = ref (-1) and given = ref 0 in
  let rec fill n = if n < 3 then match r.read head n (3 - n) with 0 -> n | k -> fill (n + k) else n in
  let read buf pos len =
    if !head_len < 0 then begin
      head_len := fill 0;
      if !head_len = 3 && Bytes.to_string head = "\xef\xbb\xbf" then Bytes.fill head 0 3 ' '
    end;
    if !given < !head_len && len > 0 then begin
      let k = min len (!head_len - !given) in
      Bytes.blit head !given buf pos k;
      given := !given + k;
      k
    end
    else r.read buf pos len
  in
  { read; close = r.close }

(* [each_chunk src f] calls [f bytes len] on the text of [src], 64 KiB at a
   time, in order. *)
let each_chunk (src : source) f =
  let r = src () in
  let buf = Bytes.create 65536 in
  Fun.protect ~finally:r.close (fun () ->
      let rec go () =
        match r.read buf 0 (Bytes.length buf) with
        | 0 -> ()
        | k ->
            f buf k;
            go ()
      in
      go ())

(* The located pass: the same conversion over a parse that kept positions. *)
(* The located pass streams too: it keeps the positions of the form being
   converted only, so locating an error costs no more memory than loading. *)
(* The number, in [form]'s positions, of the first position of [sub]:
   an atom has two positions, a list one before its elements and one after.
   parsexp's own search ([Positions.find_sub_sexp_phys]) recurses as deep as
   the nesting, and a form nested a million deep (a CSG refused for its
   depth, found by the hostile tests) overflowed the stack; this loop
   keeps the lists still to finish in a list of its own. *)
let position_index form ~sub =
  let rec go i todo stack =
    match todo with
    | x :: _ when x == sub -> Some i
    | Sexp.Atom _ :: rest -> go (i + 2) rest stack
    | Sexp.List l :: rest -> go (i + 1) l (rest :: stack)
    | [] -> ( match stack with [] -> None | rest :: stack -> go (i + 1) rest stack)
  in
  go 0 [ form ] []

let locate_error ~limits ~load ~textures (src : source) =
  let module P = Parsexp.Eager_and_positions in
  let current = ref None in
  let where node =
    match !current with
    | None -> None
    | Some (form, positions) ->
        Option.map
          (fun i -> Positions.Iterator.advance_exn (Positions.Iterator.create positions) ~skip:i)
          (position_index form ~sub:node)
  in
  let b = builder ~limits ~load ~textures where in
  let state =
    P.State.create (fun _ (form, positions) ->
        current := Some (form, positions);
        add_form b form)
  in
  let stack = ref P.Stack.empty in
  match
    each_chunk src (fun buf k -> stack := P.feed_subbytes state buf ~pos:0 ~len:k !stack);
    P.feed_eoi state !stack
  with
  | () -> `Not_found
  | exception Parsexp.Parse_error.Parse_error e -> `Syntax e
  | exception Located (node, m) -> `Located (where node, m)

(* The position of the first character at or after [offset] of the text
   that is neither blank nor in a line comment: where the next form
   starts. *)
let form_start (src : source) offset =
  let line = ref 1 and bol = ref 0 and at = ref 0 and comment = ref false in
  let found = ref None in
  (try
     each_chunk src (fun buf k ->
         for j = 0 to k - 1 do
           let i = !at + j in
           let c = Bytes.unsafe_get buf j in
           if i >= offset && !found = None then begin
             if !comment then (if c = '\n' then comment := false)
             else
               match c with
               | ' ' | '\t' | '\n' | '\r' | '\012' -> ()
               | ';' -> comment := true
               | _ -> found := Some i
           end;
           if !found = None && c = '\n' then begin
             incr line;
             bol := i + 1
           end
         done;
         at := !at + k;
         if !found <> None then raise Exit)
   with Exit -> ());
  let i = Option.value !found ~default:!at in
  Positions.{ line = !line; col = i - !bol; offset = i }

(* Fast reading. Most forms are plain text (parentheses, plain atoms,
   blanks, line comments): [Sexp_scan] reads those, and spheres straight
   into their values, with no tree; anything else goes to parsexp. Both
   accept and refuse the same texts, and every error is reported by the
   located pass, so the messages are parsexp's and the converters'. *)

(* parsexp holds a form whole, in 30 to 50 times its text: the text is fed
   to it in chunks, and a form that grows past the form bound is refused
   before it can take more. *)
let chunk = 65536

(* Longer plain forms go to parsexp, which bounds their memory. *)
let simple_form_bytes = 16384

exception Form_too_long of string
exception Too_big of string

(* The number of bytes ['\n'] in [x]: those of [x lxor 0x0a0a...] that
   are zero, whose high bit stays clear when [0x7f] is added to their low
   bits (no carry crosses a byte), then counted by a multiplication. *)
let newlines x =
  let x = Int64.logxor x 0x0a0a0a0a0a0a0a0aL in
  let low = 0x7f7f7f7f7f7f7f7fL in
  let t = Int64.logor (Int64.add (Int64.logand x low) low) x in
  let zero = Int64.logand (Int64.lognot t) 0x8080808080808080L in
  Int64.to_int (Int64.shift_right_logical (Int64.mul (Int64.shift_right_logical zero 7) 0x0101010101010101L) 56)

(* The text is read a window at a time: [text] holds the bytes from
   offset [base] of the whole text; [eof] says whether they run to its
   end. Offsets within a window are relative to it, those kept across
   windows ([form_end], the form bound's points, positions) absolute. *)
type window = { mutable text : string; mutable base : int; mutable eof : bool }

(* A text being read: its window, the line count up to absolute offset
   [at] ([line], and [bol] the start of that line), and the size of the
   next window, which grows from 4 KiB to [window_bytes] by doubling: a
   small scene costs no big buffer, whose allocation the garbage
   collector would pay on every small render (docs/performance.md). *)
type stream = {
  r : reader;
  w : window;
  mutable at : int;
  mutable line : int;
  mutable bol : int;
  mutable reading : int;
  window_bytes : int;
  scene_limits : Limits.t;
}

let stream ~limits ~window_bytes r ~from =
  let window_bytes = max 1 window_bytes in
  {
    r;
    w = { text = ""; base = from; eof = false };
    at = from;
    line = 1;
    bol = from;
    reading = min 4096 window_bytes;
    window_bytes;
    scene_limits = limits;
  }

(* A word of a window where 8 bytes are known to be there. *)
external get64 : string -> int -> int64 = "%caml_string_get64u"

(* [line_at st p] is the position of absolute offset [p], which must be in
   the window or at its end (an offset before [st.at] is not counted
   again: it is placed on [st.at]'s line); offsets only grow from call to
   call, so counting lines costs one pass over the text in all. *)
let line_at st p =
  let w = st.w in
  if p > st.at then begin
    let text = w.text and from = st.at - w.base and upto = p - w.base in
    (* Eight bytes at a time: every window passes here once. *)
    let k = ref from and line = ref st.line in
    while !k + 8 <= upto do
      line := !line + newlines (get64 text !k);
      k := !k + 8
    done;
    for j = !k to upto - 1 do
      if String.unsafe_get text j = '\n' then incr line
    done;
    st.line <- !line;
    match String.rindex_from_opt text (upto - 1) '\n' with
    | Some j when j >= from -> st.bol <- w.base + j + 1
    | _ -> ()
  end;
  st.at <- max st.at p;
  Positions.{ line = st.line; col = p - st.bol; offset = p }

(* The next window: the text from [keep] (relative) on, then at least
   [want] bytes more if there are, and [st.reading] at least. *)
let refill st ~keep ~want =
  let w = st.w in
  let kept = String.length w.text - keep in
  ignore (line_at st (w.base + keep));
  let size = kept + max want st.reading in
  st.reading <- min st.window_bytes (2 * st.reading);
  let next = Bytes.create size in
  Bytes.blit_string w.text keep next 0 kept;
  let rec fill k =
    if k >= size then k
    else match st.r.read next k (size - k) with 0 -> w.eof <- true; k | n -> fill (k + n)
  in
  let k = fill kept in
  w.text <- (if k = size then Bytes.unsafe_to_string next else Bytes.sub_string next 0 k);
  w.base <- w.base + keep;
  match Limits.check_scene_bytes st.scene_limits (w.base + k) with Ok _ -> () | Error (`Msg m) -> raise (Too_big m)

(* Where to go on reading after blanks that run to the end of the window,
   maybe in a comment: the last line's start, outside any. *)
let blank_keep w p =
  let n = String.length w.text in
  match String.rindex_from_opt w.text (n - 1) '\n' with Some j when j >= p -> j + 1 | _ -> p

(* Fast reads look this far past a form's start (twice [simple_form_bytes])
   before they trust a failure: what they refuse within it, they refuse
   whatever follows. *)
let lookahead = 2 * simple_form_bytes

(* A sphere's fields as numbers, and the materials of recent spheres: the
   grid layout repeats a dozen materials, and a sphere whose material is
   one of those is added without making a [Material.t] to find it. *)
type fast = {
  form : Sphere_scan.t;  (** The sphere's fields. *)
  recent : float array;  (** Per slot [k] of a hash, at [4 k]: color r g b, specular. *)
  recent_reflective : float array;  (** Per slot, the reflective of its material. *)
  recent_index : int array;  (** Per slot, its material's index in the spheres' table, or [-1]. *)
}

let n_recent = 64

let fast_state () =
  {
    form = Sphere_scan.create ();
    recent = Array.make (4 * n_recent) 0.;
    recent_reflective = Array.make n_recent 0.;
    recent_index = Array.make n_recent (-1);
  }

(* Reads the plain sphere form at [s.[i] = '('] into [f] and is the index
   past it: each field once, numbers that [Float_scan] reads as finite
   floats (the same as [Float_text.of_string]), [center], [radius] and
   [color] given. @raise Sexp_scan.Unusual otherwise. *)
let sphere_fields f s i =
  let e = Sphere_scan.read f.form s i in
  if f.form.seen land 7 <> 7 then raise Sexp_scan.Unusual;
  e

let[@inline] same_float x y = Int64.equal (Int64.bits_of_float x) (Int64.bits_of_float y)

(* Does recent slot [k] hold this material? *)
let[@inline] holds f k r g bl specular reflective =
  let c = f.recent in
  f.recent_index.(k) >= 0
  && same_float c.(4 * k) r && same_float c.((4 * k) + 1) g && same_float c.((4 * k) + 2) bl
  && same_float c.((4 * k) + 3) specular && same_float f.recent_reflective.(k) reflective

(* Adds the sphere read by [sphere_fields], checked as [sphere] checks it.
   @raise Sexp_scan.Unusual if a check fails: [sphere] then reports it. *)
let add_sphere b f =
  let ok = function Ok x -> x | Error _ -> raise Sexp_scan.Unusual in
  let v = f.form.values and seen = f.form.seen in
  (* [Limits.check_count]'s test, without building its messages. *)
  if not (Float.of_int (b.n_spheres + 1) <= Limits.bound b.limits `Spheres) then raise Sexp_scan.Unusual;
  let x = v.(0) and y = v.(1) and z = v.(2) in
  (* The checks' predicates: the checks' results would be boxed. *)
  if not (Limits.coordinate_ok x && Limits.coordinate_ok y && Limits.coordinate_ok z) then raise Sexp_scan.Unusual;
  let radius = v.(3) in
  if not (Limits.size_ok radius) then raise Sexp_scan.Unusual;
  let specular = if seen land 8 = 0 then Material.matte else v.(7) in
  if not (Material.specular_ok specular) then raise Sexp_scan.Unusual;
  let reflective = if seen land 16 = 0 then 0. else v.(8) in
  if not (Material.reflective_ok reflective) then raise Sexp_scan.Unusual;
  let r = v.(4) and g = v.(5) and bl = v.(6) in
  (* Any hash will do; [truncate] is defined for every finite float here
     (checked above, or garbage but harmless for a colour out of range). *)
  let k =
    ((truncate r * 7) + (truncate g * 5) + (truncate bl * 3) + (truncate specular * 11)
    + truncate (reflective *. 64.))
    land (n_recent - 1)
  in
  let k' = k lxor 1 in
  let m =
    if holds f k r g bl specular reflective then f.recent_index.(k)
    else if holds f k' r g bl specular reflective then f.recent_index.(k')
    else begin
      let color = ok (Sphere.check_color (Color.v r g bl)) in
      let i = Spheres.material b.spheres (Material.v ~specular ~reflective color) in
      (* Two ways: the slot's last material moves to its pair, so that
         two materials of one hash both stay (the grid's 12 have a pair). *)
      if f.recent_index.(k) >= 0 then begin
        Array.blit f.recent (4 * k) f.recent (4 * k') 4;
        f.recent_reflective.(k') <- f.recent_reflective.(k);
        f.recent_index.(k') <- f.recent_index.(k)
      end;
      let c = f.recent in
      c.(4 * k) <- r;
      c.((4 * k) + 1) <- g;
      c.((4 * k) + 2) <- bl;
      c.((4 * k) + 3) <- specular;
      f.recent_reflective.(k) <- reflective;
      f.recent_index.(k) <- i;
      i
    end
  in
  b.n_spheres <- b.n_spheres + 1;
  Spheres.add_fields b.spheres ~x ~y ~z ~radius m

(* Without a loader, a scene names no mesh or image file it can read. *)
let no_file what path =
  Error
    (`Msg
      (Printf.sprintf "cannot read %s file %s: this scene was given as text, with no way to read files" what path))

let no_loader path = no_file "mesh" path
let no_texture_loader path = no_file "texture" path

(* The smallest multiple of [chunk] at or after [e]: the next point where
   the form bound is checked once a form has ended at [e]. *)
let next_boundary e = (e + chunk - 1) / chunk * chunk

type part = {
  from : int;
  first : int;
  first_end : int;
  stop : int;
  lines : int;
  stop_bol : int;
  count : int;
  materials : Material.t array;
  spheres : Spheres.t;
}

let part_length p = p.count
let part_materials p = Array.copy p.materials
let part_spheres p = p.spheres
let part_header p = { p with spheres = Spheres.empty }
let append_part b p = Spheres.append b p.spheres

(* What the sequential read does from the first sphere at or after [from]
   on, for as long as it reads plain spheres on the fast path: the same
   windows, the same [sphere_fields] and [add_sphere], and the form
   bound's checks between spheres (those before the first sphere depend
   on what precedes [from], and are left to the reader that knows it).
   It stops at anything else, before the form that is not such a sphere:
   the sequential read takes over there and meets what it would have
   met, errors included. *)
let read_part ?(limits = Limits.default) ?(window_bytes = 1 lsl 20) (r : reader) ~from =
  let st = stream ~limits ~window_bytes r ~from in
  let w = st.w in
  let b = builder ~limits ~load:no_loader ~textures:{ load = no_texture_loader } (fun _ -> None) in
  let fast = fast_state () in
  let first = ref (-1) and first_end = ref (-1) and first_line = ref 1 in
  let stop = ref from and stop_pos = ref (line_at st from) in
  let boundary = ref max_int in
  (* The position of [!stop], taken before a refill moves past it. *)
  let mark () = if !stop >= st.at then stop_pos := line_at st !stop in
  (* The form bound's checks that the sequential read makes before adding
     a sphere that ends at [e]. *)
  let fits e =
    let ok = ref true in
    while !ok && !boundary < e do
      match Limits.check_form_bytes limits (!boundary - !stop) with
      | Ok _ -> boundary := !boundary + chunk
      | Error _ -> ok := false
    done;
    !ok
  in
  let rec go p =
    let n = String.length w.text in
    match Sexp_scan.skip_blank w.text p with
    | i when i >= n && w.eof -> ()
    | i when i >= n ->
        mark ();
        refill st ~keep:(blank_keep w p) ~want:lookahead;
        go 0
    | i when n - i < lookahead && not w.eof ->
        mark ();
        refill st ~keep:i ~want:lookahead;
        go 0
    | i -> (
        match sphere_fields fast w.text i with
        | exception Sexp_scan.Unusual -> ()
        | e ->
            let e_abs = w.base + e in
            if !first >= 0 && not (fits e_abs) then ()
            else
              match add_sphere b fast with
              | exception Sexp_scan.Unusual -> ()
              | () ->
                  if !first < 0 then begin
                    first := w.base + i;
                    first_end := e_abs;
                    first_line := (line_at st !first).line;
                    boundary := next_boundary e_abs
                  end;
                  stop := e_abs;
                  go e)
    | exception Sexp_scan.Unusual -> ()
  in
  (* A failed read (the file cut short under it) ends the part where it
     got to, as anything unusual does. *)
  (try
     refill st ~keep:0 ~want:0;
     go 0
   with Too_big _ | Sys_error _ | End_of_file -> ());
  mark ();
  let s = !stop_pos in
  let spheres = Spheres.build b.spheres in
  {
    from;
    first = !first;
    first_end = !first_end;
    stop = !stop;
    lines = (if !first < 0 then 0 else s.line - !first_line);
    stop_bol = s.offset - s.col;
    count = b.n_spheres;
    materials = Spheres.materials spheres;
    spheres;
  }

type beside = {
  split : int;
  wait : unit -> part option;
  append : Spheres.builder -> part -> unit;
  seek : int -> unit;
}

(* Mesh and image files are named relative to the scene file; each is
   read once, even when an error makes a second, located pass over the
   text. *)
(* A loader's message, given a file name that may hold any byte, as one
   line: control characters escaped as the command line escapes them. *)
let one_line m =
  if not (String.exists (fun c -> c < ' ' || c = '\127') m) then m
  else
    String.concat ""
      (List.map
         (function
           | '\n' -> "\\n" | '\r' -> "\\r" | '\t' -> "\\t"
           | c when c < ' ' || c = '\127' -> Printf.sprintf "\\x%02x" (Char.code c)
           | c -> String.make 1 c)
         (List.init (String.length m) (String.get m)))

let file_loader ~file load_mesh =
  let loaded = Hashtbl.create 4 in
  fun path ->
    let dir = Filename.dirname file in
    let path = if Filename.is_relative path && dir <> Filename.current_dir_name then Filename.concat dir path else path in
    match Hashtbl.find_opt loaded path with
    | Some r -> r
    | None ->
        let r = match load_mesh path with Ok m -> Ok m | Error (`Msg m) -> Error (`Msg (one_line m)) in
        Hashtbl.add loaded path r;
        r

(* Texture files read as [file_loader] reads them, their pixels counted
   together against the pixel bound: each file alone is within it (its
   reader's check), but the scene keeps every texture it reads, so many
   big files would hold memory without bound. A file read twice (one
   path) counts once. *)
let texture_loader ~limits ~file load_texture =
  let pixels = ref 0 in
  file_loader ~file (fun path ->
      match load_texture path with
      | Error _ as e -> e
      | Ok t ->
          pixels := !pixels + (Texture.width t * Texture.height t);
          if Float.of_int !pixels <= Limits.bound limits `Pixels then Ok t
          else
            Error
              (`Msg
                (Limits.exceeded limits `Pixels
                   (Printf.sprintf "texture %s brings the scene's textures to %d pixels in all" path !pixels))))

(* The sequential read of [of_source]: each form is converted as soon as
   it is read, and positions are not recorded, so that big scenes load in
   little time and memory. *)
type read = {
  limits : Limits.t;
  reader : [ `Fast | `Parsexp ];
  beside : beside option;
  b : builder;
  fast : fast;
  st : stream;
  mutable form_end : int;  (** Where the last form read ended. *)
  mutable boundary : int;  (** The next multiple of [chunk] where the form bound is checked. *)
  mutable split : int;  (** The offset of the part read beside until it is taken, [max_int] after. *)
  mutable pending : bool;  (** A part is being read beside and was not taken. *)
}

(* The form bound is checked as it was when parsexp read the whole text
   64 KiB at a time: at each multiple of 64 KiB (and at the end), the
   bytes since the last form's end, counted before the form that
   straddles that point is converted. The end of the text is checked once
   it is known. *)
let check_below r e =
  let w = r.st.w in
  let rec go () =
    let total = if w.eof then w.base + String.length w.text else max_int in
    let at = min r.boundary total in
    if r.boundary < max_int && at < e then begin
      (match Limits.check_form_bytes r.limits (at - r.form_end) with
      | Ok _ -> ()
      | Error (`Msg m) -> raise (Form_too_long m));
      r.boundary <- (if at >= total then max_int else r.boundary + chunk);
      go ()
    end
  in
  go ()

(* A plain form, read by [Sexp_scan] and converted; spheres are read
   straight into their values. *)
let simple r i =
  let form, e = Sexp_scan.form r.st.w.text i ~max_bytes:simple_form_bytes in
  check_below r (r.st.w.base + e);
  add_form r.b form;
  e

let fast_form r i =
  match sphere_fields r.fast r.st.w.text i with
  | e -> (
      check_below r (r.st.w.base + e);
      match add_sphere r.b r.fast with () -> e | exception Sexp_scan.Unusual -> simple r i)
  | exception Sexp_scan.Unusual -> simple r i

(* The part read beside, waited for when the read gets to its split. *)
let take_part r =
  r.split <- max_int;
  match r.beside with
  | Some bs when r.pending ->
      r.pending <- false;
      bs.wait ()
  | _ -> None

(* The part is what this read would read from [i] (relative) on if its
   first sphere starts there, where this read's next form starts: from
   there on, both read the same text the same way (whatever the part's
   reader made of the text before, where the split may be in a form, a
   string or a comment), and the part stops where this read would leave
   its fast path for spheres. Its spheres must also keep within the
   bound, which this read checks one by one. *)
let use_part r i (p : part) =
  p.first >= 0 && p.first = r.st.w.base + i
  && Float.of_int (r.b.n_spheres + part_length p) <= Limits.bound r.limits `Spheres

(* Goes on after the part's last sphere as the sequential read would:
   the form bound checked before its first sphere, its spheres and
   materials appended in order, the lines counted past them. *)
let skip_part r i (p : part) =
  let st = r.st and w = r.st.w in
  check_below r p.first_end;
  ignore (line_at st (w.base + i));
  (match r.beside with Some bs -> bs.append r.b.spheres p | None -> ());
  r.b.n_spheres <- r.b.n_spheres + part_length p;
  r.form_end <- p.stop;
  r.boundary <- max r.boundary (next_boundary p.stop);
  st.at <- p.stop;
  st.line <- st.line + p.lines;
  if p.lines > 0 then st.bol <- p.stop_bol;
  (match r.beside with Some bs -> bs.seek p.stop | None -> ());
  w.text <- "";
  w.base <- p.stop;
  w.eof <- false;
  refill st ~keep:0 ~want:0

(* Anything but a plain form, from [p] (the end of the last form) to the
   end of the next form, goes to parsexp, fed up to the next closing
   parenthesis at a time so that it stops where that form does. *)
let rec slow_from r p =
  let st = r.st and w = r.st.w in
  let completed = ref false in
  let state =
    Parsexp.Eager.State.create ~pos:(line_at st (w.base + p)) (fun _ form ->
        completed := true;
        add_form r.b form)
  in
  let rec go p stack =
    let n = String.length w.text in
    if p >= n && w.eof then Parsexp.Eager.feed_eoi state stack
    else if p >= n then begin
      (* parsexp holds what it was fed: nothing of this window is needed. *)
      refill st ~keep:n ~want:0;
      go 0 stack
    end
    else begin
      let stop = min (r.boundary - w.base) n in
      let q = ref p in
      while !q < stop && String.unsafe_get w.text !q <> ')' do
        incr q
      done;
      let q = if !q < stop then !q + 1 else stop in
      let stack = Parsexp.Eager.feed_substring state w.text ~pos:p ~len:(q - p) stack in
      if !completed then r.form_end <- w.base + q;
      check_below r (w.base + q + 1);
      if !completed then fast_from r q else go q stack
    end
  in
  go p Parsexp.Eager.Stack.empty

(* Plain forms on the fast path, until something else. *)
and fast_from r p =
  let st = r.st and w = r.st.w in
  let n = String.length w.text in
  if r.reader = `Parsexp then
    if p >= n && w.eof then check_below r (w.base + n + 1)
    else if p >= n then begin
      refill st ~keep:n ~want:0;
      fast_from r 0
    end
    else slow_from r p
  else
    match Sexp_scan.skip_blank w.text p with
    | i when i >= n && w.eof -> check_below r (w.base + n + 1)
    | i when i >= n ->
        refill st ~keep:(blank_keep w p) ~want:lookahead;
        fast_from r 0
    | i when n - i < lookahead && not w.eof ->
        refill st ~keep:i ~want:lookahead;
        fast_from r 0
    | i when w.base + i >= r.split -> (
        match take_part r with
        | Some part when use_part r i part ->
            skip_part r i part;
            fast_from r 0
        | _ -> fast_from r p)
    | i -> (
        match fast_form r i with
        | e ->
            r.form_end <- w.base + e;
            fast_from r e
        | exception Sexp_scan.Unusual -> slow_from r p)
    | exception Sexp_scan.Unusual -> slow_from r p

(* An error with its location, beside its message. *)
type error = { file : string; line : int; column : int; message : string }

let error_message e =
  if e.line = 0 then Printf.sprintf "%s: %s" e.file e.message
  else Printf.sprintf "%s:%d:%d: %s" e.file e.line e.column e.message


let msg r = Result.map_error (fun e -> `Msg (error_message e)) r

(* The whole text in one pass: [`Done] with the scene or an error that
   needs no position, or what the error passes must locate. *)
let read_all r ~file ~origin ~error ~syntax =
  Fun.protect
    ~finally:(fun () ->
      (* A part still being read is waited for, so that no process is
         left behind: the read ended before its split. *)
      if r.pending then ignore (take_part r);
      r.st.r.close ())
    (fun () ->
      match
        refill r.st ~keep:0 ~want:0;
        fast_from r 0
      with
      | () -> (
          (* Every field was checked where it was read; this is a net. *)
          match Scene.validate ~limits:r.limits (finish r.b) with
          | Ok s -> `Done (Ok s)
          | Error (`Msg m) -> `Done (error origin m))
      | exception Too_big message -> `Done (Error { file; line = 0; column = 0; message })
      | exception Form_too_long m -> `Form_too_long m
      | exception Parsexp.Parse_error.Parse_error e -> `Done (syntax e)
      | exception Located _ -> `Locate)

let of_source_located ?(limits = Limits.default) ?(load_mesh = no_loader) ?(load_texture = no_texture_loader)
    ?(file = "<string>") ?(reader = `Fast) ?(window_bytes = 1 lsl 20) ?beside (src : source) =
  let src = without_byte_order_mark src in
  let load = file_loader ~file load_mesh in
  let textures = { load = texture_loader ~limits ~file load_texture } in
  let origin = Positions.{ line = 1; col = 0; offset = 0 } in
  let error (p : Positions.pos) message = Error { file; line = p.line; column = p.col + 1; message } in
  let syntax e = error (Parsexp.Parse_error.position e) ("syntax error: " ^ Parsexp.Parse_error.message e) in
  let r =
    {
      limits;
      reader;
      beside;
      b = builder ~limits ~load ~textures (fun _ -> None);
      fast = fast_state ();
      st = stream ~limits ~window_bytes (src ()) ~from:0;
      form_end = 0;
      boundary = chunk;
      split = (match beside with Some bs when reader = `Fast -> bs.split | _ -> max_int);
      pending = Option.is_some beside;
    }
  in
  (* Only an error triggers a second pass that records positions, and
     fails on the same node: it reads the text again from its start. *)
  match read_all r ~file ~origin ~error ~syntax with
  | `Done result -> result
  | `Form_too_long m -> error (form_start src r.form_end) m
  | `Locate -> (
      match locate_error ~limits ~load ~textures src with
      | `Syntax e -> syntax e
      | `Located (pos, m) -> error (Option.value pos ~default:origin) m
      | `Not_found -> error origin "internal error: the located pass found no error")

let of_source ?limits ?load_mesh ?load_texture ?file ?reader ?window_bytes ?beside src =
  msg (of_source_located ?limits ?load_mesh ?load_texture ?file ?reader ?window_bytes ?beside src)

let located ?(limits = Limits.default) ?load_mesh ?load_texture ?(file = "<string>") ?reader text =
  match Limits.check_scene_bytes limits (String.length text) with
  | Error (`Msg message) -> Error { file; line = 0; column = 0; message }
  | Ok _ -> of_source_located ~limits ?load_mesh ?load_texture ~file ?reader (string_source text)

let of_string ?limits ?load_mesh ?load_texture ?file ?reader text =
  msg (located ?limits ?load_mesh ?load_texture ?file ?reader text)

let to_string = Scene.show
