open Raytrace

let scene_file = "fuzz.scene"
let ( let* ) = Result.bind

(* Every exception, Stack_overflow and Out_of_memory included, is a
   finding: the user would see a backtrace instead of a message. *)
let guard what f =
  match f () with
  | r -> r
  | exception e -> Error (Printf.sprintf "%s raised %s" what (Printexc.to_string e))

let one_line what m =
  if m = "" then Error (what ^ ": empty error message")
  else if String.contains m '\n' || String.contains m '\r' then
    Error (Printf.sprintf "%s: error message spans several lines: %S" what m)
  else Ok ()

let lines_of text =
  let n = ref 1 in
  String.iter (fun c -> if c = '\n' then incr n) text;
  !n

(* "fuzz.scene:L:C: message" with L a line of [text] and C >= 1, or
   "fuzz.scene: message" for the size bound. *)
let located text m =
  let prefix = scene_file ^ ":" in
  let lp = String.length prefix in
  if String.length m < lp || String.sub m 0 lp <> prefix then
    Error (Printf.sprintf "error does not start with %s: %S" prefix m)
  else
    let rest = String.sub m lp (String.length m - lp) in
    if String.length rest > 0 && rest.[0] = ' ' then Ok ()
    else
      match String.split_on_char ':' rest with
      | l :: c :: msg :: _ -> (
          match (int_of_string_opt l, int_of_string_opt c) with
          | Some l, Some c when l >= 1 && l <= lines_of text && c >= 1 && String.length msg > 1 ->
              Ok ()
          | _ -> Error (Printf.sprintf "bad location in %S (the text has %d lines)" m (lines_of text)))
      | _ -> Error (Printf.sprintf "no line:column in %S" m)

let work_budget = 1_000_000
let limits_of budget = Limits.with_bound Limits.default `Work (Float.of_int budget)

(* Mesh files by name, read from memory as the command line reads them
   from disk: the same parser and the same bounds. *)
let loader meshes name =
  match List.assoc_opt name meshes with
  | None -> Error (`Msg (Printf.sprintf "cannot read mesh file %s: no such file" name))
  | Some text -> Mesh.Obj.of_string ~name ~max_vertices:Limits.max_triangles ~max_triangles:Limits.max_triangles text

(* Texture files by name, read from memory as the command line reads them
   from disk: the same PPM reader and pixel bound, the same prefix. *)
let texture_loader files name =
  let cannot m = Error (`Msg ("cannot read texture file: " ^ m)) in
  match List.assoc_opt name files with
  | None -> cannot (name ^ ": No such file or directory")
  | Some bytes -> (
      match Image.Ppm.of_string ~limits:Limits.default bytes with
      | Error (`Msg m) -> cannot (name ^ ": " ^ m)
      | Ok img -> Ok (Image.Texture.of_image img))

let starts_with prefix m = String.length m >= String.length prefix && String.sub m 0 (String.length prefix) = prefix

(* A render at 3 x 2 pixels under a budget of [budget] tests ends with an
   image, or with one line: the estimate's refusal, or a render stopped
   past its budget by at most [slack] tests. *)
let rendered ~budget ~slack valid =
  match Result.bind (Scene.override ~width:3 ~height:2 valid) (Render.image ~limits:(limits_of budget)) with
  | Ok _ -> Ok ()
  | Error (`Msg m) ->
      let* () = one_line "render" m in
      let stopped = "the render was stopped after " in
      if starts_with stopped m then
        let rest = String.sub m (String.length stopped) (String.length m - String.length stopped) in
        match int_of_string_opt (List.hd (String.split_on_char ' ' rest)) with
        | Some n when n <= budget + slack -> Ok ()
        | _ -> Error (Printf.sprintf "the render ran far past its work budget of %d tests: %s" budget m)
      else if starts_with "the render needs about" m then Ok ()
      else Error ("rendering the scene at 3x2 failed: " ^ m)

let scene ?(files = []) text =
  let load_mesh = loader files and load_texture = texture_loader files in
  guard "Scene_file.of_string" (fun () ->
      match Scene_file.of_string ~load_mesh ~load_texture ~file:scene_file text with
      | Error (`Msg m) ->
          let* () = one_line "scene" m in
          located text m
      | Ok valid ->
          let s = Scene.of_valid valid in
          let* _ =
            Result.map_error (fun (`Msg m) -> "accepted a scene that fails validation: " ^ m) (Scene.validate s)
          in
          let printed = Scene_file.to_string s in
          let* () =
            match Scene_file.of_string ~load_mesh ~load_texture printed with
            | Ok s' when Scene.equal s (Scene.of_valid s') -> Ok ()
            | Ok _ -> Error ("the printed scene reads back different:\n" ^ printed)
            | Error (`Msg m) -> Error (Printf.sprintf "the printed scene does not parse (%s):\n%s" m printed)
          in
          (* Within the budget, and past a tiny one by no more than a
             pixel's (a hit's, in a ray tree) work: for these small
             scenes, far less than the budget. *)
          let* () = rendered ~budget:work_budget ~slack:work_budget valid in
          rendered ~budget:100 ~slack:20_000 valid)

let ppm bytes =
  let* () =
    guard "Image.Ppm.of_string" (fun () ->
        match Image.Ppm.of_string bytes with
        | Error (`Msg m) -> one_line "ppm" m
        | Ok img -> (
            match Image.Ppm.of_string (Image.Ppm.to_string img) with
            | Ok img' when Image.equal img img' -> Ok ()
            | Ok _ -> Error "the image written as P6 reads back different"
            | Error (`Msg m) -> Error ("the image written as P6 does not read back: " ^ m)))
  in
  let* () = guard "Image.Ppm.header_comments" (fun () -> ignore (Image.Ppm.header_comments bytes); Ok ()) in
  (* The parts that [raytrace merge] reads are PPM files too. *)
  guard "Part.of_string" (fun () ->
      match Part.of_string bytes with
      | Error (`Msg m) -> one_line "part" m
      | Ok part -> (
          match Part.of_string (Part.to_string part) with
          | Ok _ -> Ok ()
          | Error (`Msg m) -> Error ("the part written back does not read back: " ^ m)))

let scene_tokens =
  [|
    "("; ")"; "(("; "))"; " "; "\n"; "\t"; "\r\n"; ";"; "; comment\n"; "#|"; "|#"; "#| block |#"; "#;"; "#;)"; "(#;)"; "#; #;";
    "\""; "\"str\""; "\"\\n\""; "\\"; "canvas"; "viewport"; "camera"; "background"; "recursion-depth";
    "epsilon"; "sphere"; "light"; "camera-path"; "key"; "frame"; "width"; "height"; "distance"; "position"; "rotation"; "look-at"; "up";
    "center"; "radius"; "color"; "specular"; "reflective"; "intensity"; "direction"; "ambient"; "point";
    "directional"; "spot"; "0"; "1"; "-1"; "-0"; "0.5"; "3"; "255"; "256"; "600"; "65536"; "65537"; "1e12";
    "1.0000001e12"; "1e13"; "-1e12"; "1e308"; "1e309"; "-1e309"; "4.9e-324"; "1e-320"; "0x1p-1074";
    "0x1.fffffffffffffp1023"; "nan"; "-nan"; "inf"; "-inf"; "infinity"; "1_000"; "_"; "."; "-"; "+1"; "e5";
    "9223372036854775807"; "9223372036854775808"; "-9223372036854775809"; "99999999999999999999999";
    "0.1"; "1e-3"; "0.7071"; "(center 0 0 3)"; "(radius 1)"; "(color 255 0 0)"; "(specular 500)";
    "(reflective 0.5)"; "(intensity 0.6)"; "(position 2 1 0)"; "(direction 1 4 4)"; "(look-at 0 0 1)";
    "(up 0 1 0)"; "(rotation (1 0 0) (0 1 0) (0 0 1))"; "(canvas (width 4) (height 3))";
    "(sphere (center 0 -1 3) (radius 1) (color 255 0 0) (specular 500) (reflective 0.2))";
    "(light point (intensity 0.6) (position 2 1 0))"; "(light ambient (intensity 0.2))";
    "(light directional (intensity 0.2) (direction 1 4 4))"; "(recursion-depth 64)"; "(recursion-depth 65)";
    "(epsilon 0.001)"; "(camera (position 0 0 0) (look-at 0 0 0))";
    "(camera-path (key (frame 0) (position 0 0 -1) (look-at 0 0 3)) (key (frame 48) (position 3 1 1) (look-at 0 0 3)))";
    "(key (frame 10) (position 1 0 0) (look-at 0 0 3) (up 0 1 0))";
    (* Issue 26's kinds and their fields. *)
    "cylinder"; "disk"; "cone"; "torus"; "base"; "top"; "top-radius"; "capped"; "axis"; "major"; "minor";
    "(capped false)"; "(top-radius 0)"; "(axis 0 1 0)"; "(major 1)"; "(minor 0.25)";
    "(cylinder (base 0 0 5) (top 0 2 5) (radius 0.5) (color 200 50 50))";
    "(disk (center 0 0 5) (normal 0 1 0) (radius 1) (color 200 50 50))";
    "(cone (base 0 0 5) (top 0 2 5) (radius 0.5) (top-radius 0) (capped false) (color 200 50 50))";
    "(torus (center 0 0 5) (axis 0 1 0) (major 1) (minor 0.25) (color 200 50 50))";
    "\xff"; "\x00"; "\xc3\xa9";
  |]

let ppm_tokens =
  [|
    "# raytrace-part 1\n"; "# canvas 4 3\n"; "# region 0 0 4 3\n"; "# region 1 1 2 2\n"; "# depth 3\n";
    "# samples 1\n"; "# scene 9e107d9d372bb6826bd81d3542a419d6\n"; "# frame 0\n";
    "P6"; "P3"; "P5"; "P1"; "P"; " "; "\n"; "\t"; "#"; "# comment\n"; "0"; "1"; "2"; "3"; "-1"; "255"; "256";
    "65535"; "65536"; "16384"; "16385"; "268435456"; "99999999999"; "1e3"; "0x10"; "\x00"; "\xff"; "\x00\x00\x00";
    "\xff\xff\xff";
  |]

let mutate rand ~tokens s =
  let int n = if n <= 0 then 0 else Random.State.int rand n in
  let edit s =
    let n = String.length s in
    let a = int (n + 1) in
    let b = a + int (n - a + 1) in
    let before = String.sub s 0 a and span = String.sub s a (b - a) and after = String.sub s b (n - b) in
    match int 8 with
    | 0 -> before ^ after
    | 1 -> before ^ String.make 1 (Char.chr (int 256)) ^ after
    | 2 ->
        if n = 0 then s
        else
          let k = int n in
          String.mapi (fun i c -> if i = k then Char.chr (int 256) else c) s
    | 3 | 4 -> before ^ tokens.(int (Array.length tokens)) ^ span ^ after
    | 5 -> before ^ span ^ span ^ after
    | 6 ->
        let depth = if int 4 = 0 then int 10000 else int 5 in
        before ^ String.make depth '(' ^ span ^ String.make (int (depth + 2)) ')' ^ after
    | _ -> String.sub s 0 a
  in
  let rec go k s = if k = 0 then s else go (k - 1) (edit s) in
  go (1 + int 8) s

(* Scenes of every form, most of them valid, some not: each value comes
   from its domain, now and then from a token at or beyond an edge. *)
module Gen = struct
  let int rand n = Random.State.int rand (max 1 n)
  let pick rand a = a.(int rand (Array.length a))
  let chance rand n = int rand n = 0
  let edges = [| "0"; "-1"; "1e12"; "1e13"; "nan"; "inf"; "-0"; "4.9e-324"; "9223372036854775807" |]

  (* A third of the scenes are hostile: values at or beyond the edges of
     their domains, words out of place, missing files; the others valid
     (most of the time). *)
  let hostile = ref false
  let odd rand = !hostile && chance rand 12

  let num rand lo hi =
    if odd rand then pick rand edges
    else Raytrace.Private.Float_text.to_string (lo +. ((hi -. lo) *. Random.State.float rand 1.))

  let triple rand lo hi = String.concat " " [ num rand lo hi; num rand lo hi; num rand lo hi ]
  let opt rand field v = if chance rand 2 then Printf.sprintf " (%s %s)" field (v ()) else ""

  (* Glass and mirrors, patterns: reflective + transparency stays within
     1 but for the edges. *)
  let good_textures = [| "tex.ppm"; "tex3.ppm" |]

  (* Texture files that are not images the renderer can take (and one
     that is absent). *)
  let bad_texture_files =
    [
      ("empty.ppm", ""); ("truncated.ppm", "P6\n4 4\n255\n\001\002\003"); ("huge.ppm", "P6\n99999 99999\n255\n");
      ("huge-bound.ppm", "P6\n16384 16384\n255\n"); ("zero.ppm", "P6\n0 0\n255\n"); ("maxval.ppm", "P6\n1 1\n65536\n\000\000\000");
      ("wrong.ppm", "v 0 0 0\nf 1 1 1\n"); ("png.ppm", "\137PNG\r\n\026\n");
    ]

  let bad_textures = Array.of_list ("missing.ppm" :: "closed.obj" :: List.map fst bad_texture_files)

  (* Issue 27's image textures: the mapping that fits the object (a
     sphere's spherical, a plane's planar with a size now and then, a
     box's box, a mesh's uv), a valid P6 or P3 file of ours; hostile, a
     mapping that does not fit, a size on a non-planar one, a texture on
     a form that takes none, a file missing, empty, truncated, huge in
     declared size or of another format. *)
  let texture rand form =
    let fits = match form with "sphere" -> "spherical" | "plane" -> "planar" | "box" -> "box" | "mesh" -> "uv" | _ -> "" in
    let mapping = if fits = "" || odd rand then pick rand [| "spherical"; "planar"; "box"; "uv"; "cubic"; "" |] else fits in
    let file = if odd rand then pick rand bad_textures else pick rand good_textures in
    let size = if mapping = "planar" || odd rand then opt rand "size" (fun () -> num rand 0.1 3.) else "" in
    Printf.sprintf " (texture (file %S) (mapping %s)%s)" file mapping size

  (* Whether an object may take a texture: not as a CSG operand (refused,
     "cannot have a texture yet"), but when hostile. *)
  let textured = ref true

  let material ?(form = "") rand =
    let refl = if chance rand 2 then 0. else Random.State.float rand 0.6 in
    let transparency = if chance rand 2 then 0. else Random.State.float rand (1. -. refl) in
    Printf.sprintf "(color %s)%s%s%s%s%s%s" (triple rand 0. 255.)
      (opt rand "specular" (fun () -> if chance rand 3 then "-1" else num rand 0. 1000.))
      (if refl > 0. then Printf.sprintf " (reflective %s)" (Raytrace.Private.Float_text.to_string refl) else "")
      (if transparency > 0. then Printf.sprintf " (transparency %s)" (Raytrace.Private.Float_text.to_string transparency) else "")
      (opt rand "refractive-index" (fun () -> num rand 0.5 2.5))
      (opt rand "fresnel" (fun () -> if odd rand then "maybe" else pick rand [| "true"; "false" |]))
      (if chance rand 4 then Printf.sprintf " (pattern checker (color %s) (size %s))" (triple rand 0. 255.) (num rand 0.1 2.)
       else if (form <> "" && !textured && chance rand 3) || odd rand then texture rand form
       else "")

  let sphere rand =
    Printf.sprintf "(sphere (center %s) (radius %s) %s)" (triple rand (-3.) 3.) (num rand 0.1 2.) (material ~form:"sphere" rand)

  let box rand =
    let x = Random.State.float rand 4. -. 2. and y = Random.State.float rand 4. -. 2. and z = Random.State.float rand 4. +. 1. in
    let f = Raytrace.Private.Float_text.to_string in
    Printf.sprintf "(box (min %s %s %s) (max %s %s %s) %s)" (f x) (f y) (f z)
      (if chance rand 30 then "nan" else f (x +. Random.State.float rand 2.))
      (f (y +. Random.State.float rand 2.)) (f (z +. Random.State.float rand 2.)) (material ~form:"box" rand)

  (* Issue 26's kinds: a capped or open cylinder (an open one refused as
     a CSG operand), a disk. *)
  let cylinder rand =
    Printf.sprintf "(cylinder (base %s) (top %s) (radius %s)%s %s)" (triple rand (-2.) 2.) (triple rand (-2.) 2.)
      (num rand 0.1 1.5)
      (opt rand "capped" (fun () -> if odd rand then "maybe" else pick rand [| "true"; "false" |]))
      (material rand)

  let disk rand =
    Printf.sprintf "(disk (center %s) (normal %s) (radius %s) %s)" (triple rand (-2.) 2.) (triple rand (-1.) 1.)
      (num rand 0.1 2.) (material rand)

  (* A cone, capped or open (an open one refused as a CSG operand), its
     top radius 0 (pointed) one time in three, now and then both radii 0
     (refused); a torus, now and then with [minor >= major] (refused). *)
  let cone rand =
    let top_radius () = if chance rand 3 then "0" else num rand 0. 1.5 in
    Printf.sprintf "(cone (base %s) (top %s) (radius %s)%s%s %s)" (triple rand (-2.) 2.) (triple rand (-2.) 2.)
      (if odd rand then "0" else num rand 0.1 1.5)
      (* Its top radius is required: missing only when hostile. *)
      (if odd rand then "" else Printf.sprintf " (top-radius %s)" (top_radius ()))
      (opt rand "capped" (fun () -> if odd rand then "maybe" else pick rand [| "true"; "false" |]))
      (material rand)

  let torus rand =
    let major = 0.3 +. Random.State.float rand 1.5 in
    let minor = if odd rand then major *. (1. +. Random.State.float rand 1.) else major *. (0.05 +. Random.State.float rand 0.9) in
    let f = Raytrace.Private.Float_text.to_string in
    Printf.sprintf "(torus (center %s) (axis %s) (major %s) (minor %s) %s)" (triple rand (-2.) 2.) (triple rand (-1.) 1.)
      (if odd rand then pick rand edges else f major)
      (f minor) (material rand)

  let mesh rand names =
    Printf.sprintf "(mesh (file %S)%s%s%s %s)" (if odd rand then "missing.obj" else pick rand names)
      (opt rand "scale" (fun () -> num rand 0.1 3.))
      (opt rand "translate" (fun () -> triple rand (-2.) 2.))
      (opt rand "smooth" (fun () -> pick rand [| "true"; "false" |]))
      (material ~form:"mesh" rand)

  let ops = [| "union"; "intersection"; "difference" |]

  let rec csg rand names depth =
    let operand () =
      match int rand (if depth > 0 then 7 else 6) with
      | 0 -> sphere rand
      | 1 -> box rand
      | 2 -> mesh rand (if odd rand then names else [| "closed.obj" |])
      | 3 -> cylinder rand
      | 4 -> cone rand
      | 5 -> torus rand
      | _ -> csg rand names (depth - 1)
    in
    let outer = !textured in
    textured := false;
    let a = operand () in
    let b = operand () in
    textured := outer;
    Printf.sprintf "(csg %s %s %s)" (pick rand ops) a b

  let shape rand names =
    match int rand 11 with
    | 7 -> cylinder rand
    | 8 -> disk rand
    | 9 -> cone rand
    | 10 -> torus rand
    | 0 -> sphere rand
    | 1 ->
        Printf.sprintf "(plane (point %s) (normal %s) %s)" (triple rand (-2.) 2.) (triple rand (-1.) 1.)
          (material ~form:"plane" rand)
    | 2 ->
        Printf.sprintf "(triangle (vertices (%s) (%s) (%s)) %s)" (triple rand (-2.) 2.) (triple rand (-2.) 2.)
          (triple rand 1. 5.) (material rand)
    | 3 -> box rand
    | 4 -> mesh rand names
    | _ -> csg rand names (int rand 4)

  (* A closed tetrahedron (a CSG operand), its corners anywhere, or loose
     triangles, now and then with a broken line. *)
  let obj rand ~closed =
    let v () = Printf.sprintf "v %s\n" (triple rand (-1.) 1.) in
    let text =
      if closed then
        Printf.sprintf "v %s\nv %s\nv %s\nv %s\n%s" (triple rand (-1.) 1.) (triple rand (-1.) 1.) (triple rand (-1.) 1.)
          (triple rand (-1.) 1.)
          (* With texture coordinates half the time, for a uv texture. *)
          (if chance rand 2 then "f 1 2 3\nf 1 4 2\nf 2 4 3\nf 3 4 1\n"
           else "vt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\nf 1/1 2/2 3/3\nf 1/1 4/4 2/2\nf 2/2 4/4 3/3\nf 3/3 4/4 1/1\n")
      else
        let n = 3 + int rand 6 in
        String.concat "" (List.init n (fun _ -> v ()))
        ^ String.concat ""
            (List.init (1 + int rand 6) (fun _ ->
                 Printf.sprintf "f %d %d %d\n" (1 + int rand n) (1 + int rand n) (1 + int rand n)))
    in
    if odd rand then text ^ pick rand [| "f 1 2 99\n"; "v nan 0 0\n"; "f 1\n"; "vn 0 0 0\nf 1//1 2//1 3//1\n" |]
    else text

  (* A light's sample count: small, or (hostile) at and beyond its bounds,
     4096 x 4096 among them, which the work estimate refuses. *)
  let samples rand = if odd rand then pick rand [| "0"; "-1"; "4096"; "4097"; "64"; "1.5"; "nan"; "9223372036854775807" |]
    else string_of_int (1 + int rand 6)

  (* Issue 27's kinds: an area light (its edges now and then parallel or
     zero), a sphere light, a spot light (its angle and falloff anywhere
     in their domains, now and then beyond). *)
  let soft_light rand =
    match int rand 3 with
    | 0 ->
        let edge () = if odd rand then pick rand [| "0 0 0"; "1 0 0"; "1e-320 0 0"; "1e12 1e12 1e12" |] else triple rand (-2.) 2. in
        Printf.sprintf "(light area (intensity %s) (corner %s) (edge1 %s) (edge2 %s) (samples %s %s)%s)" (num rand 0. 1.)
          (triple rand (-5.) 5.) (edge ()) (edge ()) (samples rand) (samples rand)
          (opt rand "adaptive" (fun () -> if odd rand then "1" else pick rand [| "true"; "false" |]))
    | 1 ->
        Printf.sprintf "(light sphere (intensity %s) (position %s) (radius %s) (samples %s))" (num rand 0. 1.)
          (triple rand (-5.) 5.) (num rand 0.01 2.) (samples rand)
    | _ ->
        Printf.sprintf "(light spot (intensity %s) (position %s) (direction %s) (angle %s)%s)" (num rand 0. 1.)
          (triple rand (-5.) 5.) (triple rand (-1.) 1.)
          (if odd rand then pick rand [| "0"; "180"; "180.0001"; "-1"; "1e-30" |] else num rand 1. 180.)
          (* Its falloff is required: missing only when hostile. *)
          (if odd rand then "" else Printf.sprintf " (falloff %s)" (if odd rand then pick rand [| "1e6"; "1e7"; "-1" |] else num rand 0. 50.))

  let light rand =
    match int rand 5 with
    | 0 -> Printf.sprintf "(light ambient (intensity %s))" (num rand 0. 1.)
    | 1 -> Printf.sprintf "(light point (intensity %s) (position %s))" (num rand 0. 1.) (triple rand (-5.) 5.)
    | 2 -> Printf.sprintf "(light directional (intensity %s) (direction %s))" (num rand 0. 1.) (triple rand (-5.) 5.)
    | _ -> soft_light rand

  (* Texture files of ours: a P6 or P3 image of up to 4 x 4 pixels. *)
  let ppm rand =
    let w = 1 + int rand 4 and h = 1 + int rand 4 in
    let channels = List.init (3 * w * h) (fun _ -> int rand 256) in
    if chance rand 2 then Printf.sprintf "P6\n%d %d\n255\n%s" w h (String.concat "" (List.map (fun c -> String.make 1 (Char.chr c)) channels))
    else Printf.sprintf "P3\n%d %d\n255\n%s\n" w h (String.concat " " (List.map string_of_int channels))

  let scene rand =
    hostile := chance rand 3;
    let names = [| "closed.obj"; "loose.obj" |] in
    let meshes =
      [ ("closed.obj", obj rand ~closed:true); ("loose.obj", obj rand ~closed:false); ("tex.ppm", ppm rand); ("tex3.ppm", ppm rand) ]
      @ bad_texture_files
    in
    let settings =
      [
        Printf.sprintf "(canvas (width %d) (height %d))" (1 + int rand 8) (1 + int rand 8);
        Printf.sprintf "(recursion-depth %d)" (int rand 12);
        (if chance rand 3 then Printf.sprintf "(epsilon %s)" (num rand 0. 0.01) else "");
        (if chance rand 3 then
           Printf.sprintf "(camera (position %s)%s%s%s)" (triple rand (-3.) 3.)
             (if chance rand 4 && !hostile then "" else " (look-at 0 0 3)")
             (opt rand "aperture" (fun () -> if odd rand then pick rand [| "-1"; "1e12"; "1e13"; "1e-31" |] else num rand 0. 1.))
             (opt rand "focal-distance" (fun () -> num rand 0.5 10.))
         else "");
      ]
    in
    let forms = List.init (1 + int rand 6) (fun _ -> shape rand names) @ List.init (int rand 3) (fun _ -> light rand) in
    (String.concat "\n" (settings @ forms) ^ "\n", meshes)
end

let random_scene = Gen.scene

let scene_tokens =
  Array.append scene_tokens
    [|
      "plane"; "triangle"; "box"; "mesh"; "csg"; "union"; "intersection"; "difference"; "normal"; "vertices"; "min";
      "max"; "file"; "scale"; "translate"; "smooth"; "transparency"; "refractive-index"; "fresnel"; "true"; "false";
      "pattern"; "checker"; "size"; "(transparency 0.9) (refractive-index 1.5) (fresnel true)";
      "(pattern checker (color 30 30 30) (size 1))"; "(plane (point 0 -1 0) (normal 0 1 0) (color 200 200 200))";
      "(box (min -1 -1 2) (max 1 1 4) (color 240 240 230))";
      "(csg difference (box (min -1 -1 2) (max 1 1 4) (color 1 2 3)) (sphere (center 0 0 3) (radius 1.4) (color 1 2 3)))";
      "(triangle (vertices (0 0 3) (1 0 3) (0 1 3)) (color 255 0 0))"; "(mesh (file \"closed.obj\") (color 1 2 3))";
      "(recursion-depth 40)";
      (* Issue 27's lights, lens and textures, their fields and values at
         their bounds. *)
      "area"; "corner"; "edge1"; "edge2"; "samples"; "adaptive"; "angle"; "falloff"; "aperture"; "focal-distance";
      "texture"; "mapping"; "spherical"; "planar"; "uv"; "4096"; "4097"; "(samples 4096 4096)"; "(samples 4097 1)";
      "(samples 0 0)"; "(samples 64 64)"; "(samples 1)"; "(adaptive true)"; "(angle 180)"; "(angle 0)"; "(falloff 1e6)";
      "(aperture 0.3)"; "(aperture 1e12)"; "(focal-distance 1e-30)"; "(focal-distance 8)";
      "(light area (intensity 0.6) (corner -1 3 4) (edge1 2 0 0) (edge2 0 0 2) (samples 4 4))";
      "(light area (intensity 0.6) (corner -1 3 4) (edge1 2 0 0) (edge2 0 0 2) (samples 4096 4096) (adaptive true))";
      "(light sphere (intensity 0.6) (position 2 3 0) (radius 0.5) (samples 16))";
      "(light spot (intensity 0.8) (position 0 4 3) (direction 0 -1 0) (angle 25) (falloff 5))";
      "(camera (position 0 1 -2) (look-at 0 0.5 6) (aperture 0.3))";
      "(camera (position 0 1 -2) (aperture 0.3) (focal-distance 8))"; "(texture (file \"tex.ppm\") (mapping spherical))";
      "(texture (file \"tex.ppm\") (mapping planar) (size 2))"; "(texture (file \"tex3.ppm\") (mapping box))";
      "(texture (file \"closed.obj\") (mapping uv))"; "(texture (file \"missing.ppm\") (mapping spherical))";
      "(texture (file \"huge.ppm\") (mapping spherical))"; "(texture (file \"truncated.ppm\") (mapping spherical))";
      "(texture (file \"empty.ppm\") (mapping spherical))"; "(texture (file \"\") (mapping spherical))";
      "(sphere (center 0 0 3) (radius 1) (color 255 255 255) (texture (file \"tex.ppm\") (mapping spherical)))";
    |]
