module Cst = Parsexp.Cst
module Positions = Parsexp.Positions

exception Located of Positions.range * string

let fail (loc : Positions.range) fmt = Printf.ksprintf (fun m -> raise (Located (loc, m))) fmt
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

let loc_of = function Cst.Atom { loc; _ } | Cst.List { loc; _ } -> loc
let sexps elements = List.filter_map (function Cst.Sexp s -> Some s | Cst.Comment _ -> None) elements

(* Edit distance, to suggest the field a user probably meant. *)
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
       first keeps a hostile 10 MB name from costing a 10 MB x 15 table
       (it took 51 s and 2.4 GB). *)
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

let number what node =
  match node with
  | Cst.Atom { atom; loc; _ } -> (
      match Float_text.of_string atom with
      | Some x -> x
      | None -> (
          match float_of_string_opt atom with
          | Some _ -> fail loc "%s must be a finite number, got %s" what (show_atom atom)
          | None -> fail loc "%s: expected a number, got %s" what (show_atom atom)))
  | Cst.List { loc; _ } -> fail loc "%s: expected a number, got a list" what

let integer what node =
  match node with
  | Cst.Atom { atom; loc; _ } -> (
      match int_of_string_opt atom with
      | Some n -> n
      | None -> fail loc "%s: expected an integer, got %s" what (show_atom atom))
  | Cst.List { loc; _ } -> fail loc "%s: expected an integer, got a list" what

let check loc = function Ok x -> x | Error m -> fail loc "%s" m

(* Fields: a form's [(name args...)] children. *)

type field = { name_loc : Positions.range; loc : Positions.range; args : Cst.t list }

let fields ~form ~allowed nodes =
  List.fold_left
    (fun acc node ->
      match node with
      | Cst.List { loc; elements } -> (
          match sexps elements with
          | Cst.Atom { atom = name; loc = name_loc; _ } :: args ->
              if not (List.mem name allowed) then
                fail name_loc "unknown %s field %s; expected %s%s" form (show_atom name)
                  (one_of allowed) (suggestion name allowed);
              (match List.assoc_opt name acc with
              | Some first ->
                  fail name_loc "duplicate %s field %s (first given at %s)" form name
                    (position first.name_loc.start_pos)
              | None -> ());
              (name, { name_loc; loc; args }) :: acc
          | _ -> fail loc "%s: expected a field (name value...), e.g. (%s ...)" form (List.hd allowed))
      | Cst.Atom { loc; atom; _ } ->
          fail loc "%s: expected a field in parentheses, e.g. (%s ...), got %s" form
            (List.hd allowed) (show_atom atom))
    [] nodes

let field_what form name = form ^ " " ^ name

let arity form name f n =
  if List.length f.args <> n then
    fail f.loc "%s takes %d value%s, got %d" (field_what form name) n
      (if n = 1 then "" else "s")
      (List.length f.args)

let get ~form fs name parse = Option.map (fun f -> parse (field_what form name) f) (List.assoc_opt name fs)

let require ~form ~form_loc name = function
  | Some v -> v
  | None -> fail form_loc "%s is missing its (%s ...) field" form name

let required ~form ~form_loc fs name parse = require ~form ~form_loc name (get ~form fs name parse)

let single form name f =
  arity form name f 1;
  List.hd f.args

let float_field form name f = number (field_what form name) (single form name f)
let int_field form name f = integer (field_what form name) (single form name f)

let triple ~names what loc = function
  | [ x; y; z ] -> (number what x, number what y, number what z)
  | nodes -> fail loc "%s takes 3 numbers (%s), got %d values" what names (List.length nodes)

let vec3_of_nodes what loc nodes =
  let x, y, z = triple ~names:"x y z" what loc nodes in
  Vec3.v x y z

let color_of_nodes what loc nodes =
  let r, g, b = triple ~names:"r g b" what loc nodes in
  Color.v r g b

let vec3_field form name f = vec3_of_nodes (field_what form name) f.loc f.args
let color_field form name f = color_of_nodes (field_what form name) f.loc f.args

(* Located value checks: the error points at the value, or at the field for
   vectors. *)
let checked_float form fs name check =
  Option.map
    (fun f ->
      let x = float_field form name f in
      check (loc_of (List.hd f.args)) x)
    (List.assoc_opt name fs)

let with_loc fs name = Option.map (fun f -> f.loc) (List.assoc_opt name fs)

(* Forms *)

let canvas form_loc nodes =
  let form = "canvas" in
  let fs = fields ~form ~allowed:[ "width"; "height" ] nodes in
  let dim name =
    Option.value ~default:600
      (get ~form fs name (fun _ f ->
           check (loc_of (single form name f)) (Limits.check_dimension name (int_field form name f))))
  in
  let width = dim "width" in
  let height = dim "height" in
  ignore (check form_loc (Limits.check_canvas width height));
  (width, height)

let viewport nodes =
  let form = "viewport" in
  let fs = fields ~form ~allowed:[ "width"; "height"; "distance" ] nodes in
  let dim name =
    Option.value ~default:1.
      (checked_float form fs name (fun loc x -> check loc (Viewport.check_dimension name x)))
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
        | Cst.List { loc; elements } -> vec3_of_nodes (what ^ " row") loc (sexps elements)
        | Cst.Atom { loc; atom; _ } ->
            fail loc "%s: expected a row of 3 numbers in parentheses, got %s" what (show_atom atom)
      in
      Camera.{ row0 = row r0; row1 = row r1; row2 = row r2 }
  | args -> fail f.loc "%s takes 3 rows, e.g. (1 0 0) (0 1 0) (0 0 1), got %d values" what (List.length args)

let camera nodes =
  let form = "camera" in
  let fs = fields ~form ~allowed:[ "position"; "rotation"; "look-at"; "up" ] nodes in
  let position =
    Option.value ~default:Vec3.zero (get ~form fs "position" (fun _ f -> vec3_field form "position" f))
  in
  ignore (Option.map (fun loc -> check loc (Camera.check_position position)) (with_loc fs "position"));
  let rot = get ~form fs "rotation" (fun _ f -> (f.loc, rotation form "rotation" f)) in
  let look = get ~form fs "look-at" (fun _ f -> (f.loc, vec3_field form "look-at" f)) in
  let up = get ~form fs "up" (fun _ f -> (f.loc, vec3_field form "up" f)) in
  match (rot, look, up) with
  | Some _, Some (loc, _), _ -> fail loc "camera takes either (rotation ...) or (look-at ...), not both"
  | _, None, Some (loc, _) -> fail loc "camera (up ...) needs a (look-at ...) target"
  | Some (loc, rotation), None, None -> Camera.v ~rotation:(check loc (Camera.check_rotation rotation)) position
  | None, Some (loc, target), up -> (
      ignore (check loc (Limits.check_point "camera look-at" target));
      let up = Option.map snd up in
      match Camera.look_at ?up ~position target with
      | Ok cam -> cam
      | Error m -> fail loc "%s" m)
  | None, None, _ -> Camera.v position

let sphere form_loc nodes =
  let form = "sphere" in
  let fs =
    fields ~form ~allowed:[ "center"; "radius"; "color"; "specular"; "reflective" ] nodes
  in
  let center = required ~form ~form_loc fs "center" (fun _ f -> (f.loc, vec3_field form "center" f)) in
  let center = check (fst center) (Sphere.check_center (snd center)) in
  let radius =
    require ~form ~form_loc "radius"
      (checked_float form fs "radius" (fun loc r -> check loc (Sphere.check_radius r)))
  in
  let color = required ~form ~form_loc fs "color" (fun _ f -> (f.loc, color_field form "color" f)) in
  let color = check (fst color) (Sphere.check_color (snd color)) in
  let specular =
    Option.value ~default:Sphere.matte
      (checked_float form fs "specular" (fun loc s -> check loc (Sphere.check_specular s)))
  in
  let reflective =
    Option.value ~default:0.
      (checked_float form fs "reflective" (fun loc r -> check loc (Sphere.check_reflective r)))
  in
  Sphere.v ~specular ~reflective ~center ~radius color

let light form_loc nodes =
  let kinds = [ "ambient"; "point"; "directional" ] in
  match nodes with
  | Cst.Atom { atom = kind; loc = kind_loc; _ } :: rest ->
      let form = "light " ^ kind in
      let vector = match kind with "point" -> [ "position" ] | "directional" -> [ "direction" ] | _ -> [] in
      if not (List.mem kind kinds) then
        fail kind_loc "unknown light kind %s; expected %s%s" (show_atom kind) (one_of kinds)
          (suggestion kind kinds);
      let fs = fields ~form ~allowed:("intensity" :: vector) rest in
      let intensity =
        require ~form ~form_loc "intensity"
          (checked_float form fs "intensity" (fun loc i -> check loc (Light.check_intensity i)))
      in
      let vec name check_v =
        let loc, p = required ~form ~form_loc fs name (fun _ f -> (f.loc, vec3_field form name f)) in
        check loc (check_v p)
      in
      (match kind with
      | "point" -> Light.point intensity (vec "position" Light.check_position)
      | "directional" -> Light.directional intensity (vec "direction" Light.check_direction)
      | _ -> Light.ambient intensity)
  | _ ->
      fail form_loc "light: expected its kind first, e.g. (light point (intensity 0.6) (position 2 1 0)); kinds are %s"
        (one_of kinds)

(* A top-level form that takes its values directly, e.g. (epsilon 0.001). *)
let values form form_loc nodes n =
  if List.length nodes <> n then
    fail form_loc "%s takes %d value%s, got %d" form n (if n = 1 then "" else "s") (List.length nodes);
  nodes

let top_level = [ "canvas"; "viewport"; "camera"; "background"; "recursion-depth"; "epsilon"; "sphere"; "light" ]

let scene_of_forms forms =
  let seen = Hashtbl.create 8 in
  let once kw kw_loc =
    match Hashtbl.find_opt seen kw with
    | Some (first : Positions.range) ->
        fail kw_loc "duplicate %s form (first given at %s); it may appear only once" kw
          (position first.start_pos)
    | None -> Hashtbl.add seen kw kw_loc
  in
  let s = ref (Scene.v ~spheres:[] ~lights:[] ()) in
  let spheres = ref [] and lights = ref [] in
  (* Counted as they come, so that the error points at the first form
     beyond the bound. *)
  let n_spheres = ref 0 and n_lights = ref 0 in
  let count kind n loc =
    incr n;
    ignore (check loc (Limits.check_count kind !n))
  in
  List.iter
    (fun node ->
      match node with
      | Cst.Atom { loc; atom; _ } ->
          fail loc "expected a form in parentheses such as (sphere ...), got %s" (show_atom atom)
      | Cst.List { loc; elements } -> (
          match sexps elements with
          | [] -> fail loc "empty form (); expected one of %s" (one_of top_level)
          | Cst.List { loc; _ } :: _ -> fail loc "expected a form name such as sphere or light, got a list"
          | Cst.Atom { atom = kw; loc = kw_loc; _ } :: rest -> (
              if not (List.mem kw [ "sphere"; "light" ]) && List.mem kw top_level then once kw kw_loc;
              match kw with
              | "canvas" ->
                  let width, height = canvas loc rest in
                  s := { !s with width; height }
              | "viewport" -> s := { !s with viewport = viewport rest }
              | "camera" -> s := { !s with camera = camera rest }
              | "background" ->
                  let c = color_of_nodes kw loc rest in
                  s := { !s with background = check loc (Scene.check_background c) }
              | "recursion-depth" ->
                  let node = List.hd (values kw loc rest 1) in
                  let d = integer kw node in
                  s := { !s with depth = check (loc_of node) (Limits.check_depth d) }
              | "epsilon" ->
                  let node = List.hd (values kw loc rest 1) in
                  let e = number kw node in
                  s := { !s with epsilon = Some (check (loc_of node) (Scene.check_epsilon e)) }
              | "sphere" ->
                  count `Spheres n_spheres loc;
                  spheres := sphere loc rest :: !spheres
              | "light" ->
                  count `Lights n_lights loc;
                  lights := light loc rest :: !lights
              | _ ->
                  fail kw_loc "unknown form %s; expected %s%s" (show_atom kw) (one_of top_level)
                    (suggestion kw top_level))))
    forms;
  { !s with spheres = List.rev !spheres; lights = List.rev !lights }

let of_string ?(file = "<string>") text =
  let error (p : Positions.pos) m = Error (`Msg (Printf.sprintf "%s:%s: %s" file (position p) m)) in
  match Limits.check_scene_bytes (String.length text) with
  | Error m -> Error (`Msg (Printf.sprintf "%s: %s" file m))
  | Ok _ ->
  let syntax_error e = error (Parsexp.Parse_error.position e) ("syntax error: " ^ Parsexp.Parse_error.message e) in
  match Parsexp.Many_cst.parse_string text with
  | exception e -> (
      (* parsexp v0.15's CST parser fails an assertion where a sexp comment
         [#;] has nothing to comment before a closing parenthesis, as in
         "(#;)" (found by fuzzing); its plain parser reports the error. *)
      match Parsexp.Many.parse_string text with
      | Error e -> syntax_error e
      | Ok _ | (exception _) ->
          error { line = 1; col = 0; offset = 0 } ("syntax error: the S-expression parser failed: " ^ Printexc.to_string e))
  | Error e -> syntax_error e
  | Ok forms -> (
      match scene_of_forms (sexps forms) with
      | exception Located (loc, m) -> error loc.start_pos m
      | scene -> (
          (* Every field was checked where it was read; this is a net. *)
          match Scene.validate scene with
          | Ok s -> Ok s
          | Error (`Msg m) -> error { line = 1; col = 0; offset = 0 } m))

let read path =
  match File_io.read ~check_size:Limits.check_scene_bytes path with
  | Error e -> Error e
  | Ok text -> of_string ~file:path text

let to_string (s : Scene.t) =
  let b = Buffer.create 1024 in
  let num = Float_text.to_string in
  let vec (p : Vec3.t) = Printf.sprintf "%s %s %s" (num p.x) (num p.y) (num p.z) in
  let line fmt = Printf.kbprintf (fun b -> Buffer.add_char b '\n') b fmt in
  line "(canvas (width %d) (height %d))" s.width s.height;
  line "(viewport (width %s) (height %s) (distance %s))" (num s.viewport.width)
    (num s.viewport.height) (num s.viewport.distance);
  let m = s.camera.rotation in
  if Camera.is_identity m then line "(camera (position %s))" (vec s.camera.position)
  else
    line "(camera (position %s) (rotation (%s) (%s) (%s)))" (vec s.camera.position) (vec m.row0)
      (vec m.row1) (vec m.row2);
  line "(background %s %s %s)" (num s.background.r) (num s.background.g) (num s.background.b);
  line "(recursion-depth %d)" s.depth;
  Option.iter (fun e -> line "(epsilon %s)" (num e)) s.epsilon;
  List.iter
    (fun (sp : Sphere.t) ->
      Buffer.add_string b
        (Printf.sprintf "(sphere (center %s) (radius %s) (color %s %s %s)" (vec sp.center)
           (num sp.radius) (num sp.color.r) (num sp.color.g) (num sp.color.b));
      if not (Sphere.is_matte sp) then Buffer.add_string b (Printf.sprintf " (specular %s)" (num sp.specular));
      if sp.reflective <> 0. then Buffer.add_string b (Printf.sprintf " (reflective %s)" (num sp.reflective));
      line ")")
    s.spheres;
  List.iter
    (function
      | Light.Ambient { intensity } -> line "(light ambient (intensity %s))" (num intensity)
      | Light.Point { intensity; position } ->
          line "(light point (intensity %s) (position %s))" (num intensity) (vec position)
      | Light.Directional { intensity; direction } ->
          line "(light directional (intensity %s) (direction %s))" (num intensity) (vec direction))
    s.lights;
  Buffer.contents b
