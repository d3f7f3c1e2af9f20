(* The fuzz target: crowbar generators of hostile scene files and PPM
   images, checked by the properties of [Hostile]. Run by AFL++ (`make
   fuzz`), crowbar's input bytes steer the generators and coverage guides
   the search; run alone it draws random inputs (the tests do so briefly). *)

open Crowbar

(* With RAYTRACE_FUZZ_DUMP=DIR, every input is also saved in DIR, named by
   its digest: that turns the crowbar-encoded files of a campaign's queue
   into the scene and image files of test/corpus/. *)
let dump extension input =
  match Sys.getenv_opt "RAYTRACE_FUZZ_DUMP" with
  | None | Some "" -> ()
  | Some dir ->
      let oc = open_out_bin (Filename.concat dir (Digest.to_hex (Digest.string input) ^ extension)) in
      output_string oc input;
      close_out oc

let check extension property input =
  dump extension input;
  match property input with Ok () -> () | Error m -> fail m
let token tokens = map [ range (Array.length tokens) ] (fun i -> tokens.(i))

let number =
  choose
    [
      map [ int ] string_of_int;
      map [ int8 ] string_of_int;
      map [ float ] Raytrace.Private.Float_text.to_string;
      map [ float ] (Printf.sprintf "%h");
      (* Numbers of a sensible size, so that scenes are often valid. *)
      map [ int16 ] (fun n -> Raytrace.Private.Float_text.to_string (Float.of_int n /. 256.));
      map [ uint8 ] string_of_int;
      token Hostile.scene_tokens;
    ]

let atom = choose [ number; token Hostile.scene_tokens; bytes ]

let sexp =
  fix (fun sexp ->
      choose [ atom; map [ list sexp ] (fun l -> "(" ^ String.concat " " l ^ ")") ])

let names =
  [|
    "canvas"; "viewport"; "camera"; "camera-path"; "key"; "frame"; "background"; "recursion-depth"; "epsilon";
    "sphere"; "light";
    "width"; "height"; "distance"; "position"; "rotation"; "look-at"; "up"; "center"; "radius"; "color";
    "specular"; "reflective"; "intensity"; "direction"; "ambient"; "point"; "directional";
    "plane"; "triangle"; "box"; "mesh"; "csg"; "normal"; "vertices"; "min"; "max"; "file"; "scale"; "translate";
    "smooth"; "transparency"; "refractive-index"; "fresnel"; "pattern"; "checker"; "size";
    "cylinder"; "base"; "top"; "capped"; "disk"; "cone"; "top-radius"; "torus"; "axis"; "major"; "minor";
    "corner"; "edge1"; "edge2"; "samples"; "adaptive"; "angle"; "falloff"; "aperture"; "focal-distance"; "texture";
    "mapping";
  |]

let field =
  map [ token names; list (choose [ number; number; sexp ]) ] (fun n values ->
      "(" ^ n ^ " " ^ String.concat " " values ^ ")")

let form =
  map [ token names; option (token [| "ambient"; "point"; "directional"; "area"; "sphere"; "spot" |]); list (choose [ field; number ]) ]
    (fun n kind fields ->
      "(" ^ n ^ (match kind with Some k -> " " ^ k | None -> "") ^ " " ^ String.concat " " fields ^ ")")

let separator = choose [ const "\n"; const " "; token [| "; c\n"; "#| b |#"; "#;"; "\r\n"; "" |] ]

let scene_text =
  map [ list (pair separator (choose [ form; form; form; sexp ])) ] (fun forms ->
      String.concat "" (List.map (fun (sep, f) -> sep ^ f) forms))

(* Scenes that are valid most of the time, with values anywhere in their
   domains and sometimes at or beyond its edges, so that validation, the
   printer and the renderer see many real scenes. *)
let scaled lo hi = map [ uint16 ] (fun n -> Raytrace.Private.Float_text.to_string (lo +. ((hi -. lo) *. Float.of_int n /. 65535.)))
let value lo hi = choose [ scaled lo hi; scaled lo hi; scaled lo hi; number ]
let triple lo hi = map [ value lo hi; value lo hi; value lo hi ] (fun a b c -> String.concat " " [ a; b; c ])
let optional name v = map [ bool; v ] (fun present x -> if present then Printf.sprintf " (%s %s)" name x else "")

let valid_sphere =
  map
    [ triple (-10.) 10.; value 0. 5.; triple 0. 255.; optional "specular" (choose [ const "-1"; value 0. 1000. ]);
      optional "reflective" (value 0. 1.) ]
    (fun c r col spec refl -> Printf.sprintf "(sphere (center %s) (radius %s) (color %s)%s%s)" c r col spec refl)

let samples = choose [ map [ range ~min:1 8 ] string_of_int; map [ range ~min:1 8 ] string_of_int; number ]

let valid_light =
  choose
    [
      map [ value 0. 1. ] (Printf.sprintf "(light ambient (intensity %s))");
      map [ value 0. 1.; triple (-10.) 10. ] (Printf.sprintf "(light point (intensity %s) (position %s))");
      map [ value 0. 1.; triple (-10.) 10. ] (Printf.sprintf "(light directional (intensity %s) (direction %s))");
      (* Issue 27's lights; their sample counts small, or anything now
         and then (4096 x 4096 is refused by the work estimate). *)
      map
        [ value 0. 1.; triple (-5.) 5.; triple (-2.) 2.; triple (-2.) 2.; samples; samples;
          optional "adaptive" (choose [ const "true"; const "false"; token Hostile.scene_tokens ]) ]
        (Printf.sprintf "(light area (intensity %s) (corner %s) (edge1 %s) (edge2 %s) (samples %s %s)%s)");
      map [ value 0. 1.; triple (-5.) 5.; value 0. 2.; samples ]
        (Printf.sprintf "(light sphere (intensity %s) (position %s) (radius %s) (samples %s))");
      map [ value 0. 1.; triple (-5.) 5.; triple (-1.) 1.; value 0. 180.; map [ value 0. 100. ] (Printf.sprintf " (falloff %s)") ]
        (Printf.sprintf "(light spot (intensity %s) (position %s) (direction %s) (angle %s)%s)");
    ]

let valid_setting =
  choose
    [
      map [ range ~min:1 40; range ~min:1 40 ] (Printf.sprintf "(canvas (width %d) (height %d))");
      map [ value 0.1 3.; value 0.1 3.; value 0.1 3. ] (Printf.sprintf "(viewport (width %s) (height %s) (distance %s))");
      map [ triple (-5.) 5.; optional "look-at" (triple (-5.) 5.) ] (Printf.sprintf "(camera (position %s)%s)");
      (* A thin lens: aperture and focal distance, each optional. *)
      map [ triple (-5.) 5.; optional "look-at" (triple (-5.) 5.); optional "aperture" (value 0. 1.); optional "focal-distance" (value 0. 10.) ]
        (Printf.sprintf "(camera (position %s)%s%s%s)");
      map [ triple 0. 255. ] (Printf.sprintf "(background %s)");
      map [ range 10 ] (Printf.sprintf "(recursion-depth %d)");
      map
        [ list1 (map [ range 100; triple (-5.) 5.; triple (-5.) 5.; optional "up" (triple (-1.) 1.) ] (fun f p l u ->
              Printf.sprintf "(key (frame %d) (position %s) (look-at %s)%s)" f p l u)) ]
        (fun keys -> "(camera-path " ^ String.concat " " keys ^ ")");
      map [ value 0. 0.1 ] (Printf.sprintf "(epsilon %s)");
    ]

let valid_scene =
  map [ list valid_setting; list valid_sphere; list valid_light ] (fun settings spheres lights ->
      String.concat "\n" (settings @ spheres @ lights))

(* The forms of round 2 and 3 and issue 27's textures: glass (transparency, refractive index,
   Fresnel), mirrors and patterns on every shape; planes, triangles,
   boxes, meshes of files the test makes, issue 26's cylinders, disks,
   cones and tori, CSG solids nested with every operation. *)
(* Issue 27's image textures: every mapping (each fits one kind of
   object, the others are refused), a size, the files of [files] below. *)
let texture =
  map
    [ token [| "tex.ppm"; "tex.ppm"; "tex3.ppm"; "missing.ppm"; "empty.ppm"; "truncated.ppm"; "huge.ppm"; "wrong.ppm"; "closed.obj" |];
      token [| "spherical"; "planar"; "box"; "uv" |]; optional "size" (value 0. 4.) ]
    (Printf.sprintf "(file %S) (mapping %s)%s")

let material =
  map
    [ triple 0. 255.; optional "specular" (choose [ const "-1"; value 0. 1000. ]); optional "reflective" (value 0. 0.5);
      optional "transparency" (value 0. 0.5); optional "refractive-index" (value 0.5 2.5);
      optional "fresnel" (choose [ const "true"; const "false"; token Hostile.scene_tokens ]);
      optional "pattern" (map [ triple 0. 255.; value 0.1 2. ] (Printf.sprintf "checker (color %s) (size %s)"));
      (* Rarer than the rest: a texture fits one kind of object only. *)
      choose [ const ""; const ""; optional "texture" texture ] ]
    (fun col spec refl tr idx fres pat tex -> Printf.sprintf "(color %s)%s%s%s%s%s%s%s" col spec refl tr idx fres pat tex)

let sphere_form = map [ triple (-3.) 3.; value 0.1 2.; material ] (Printf.sprintf "(sphere (center %s) (radius %s) %s)")

let box_form =
  map [ triple (-2.) 2.; triple 0. 2.; material ] (fun lo size m ->
      (* [max] = [min] + [size], written as the parser reads it. *)
      let parse t = List.map (fun x -> Option.value ~default:0. (float_of_string_opt x)) (String.split_on_char ' ' t) in
      let hi = List.map2 ( +. ) (parse lo) (parse size) in
      Printf.sprintf "(box (min %s) (max %s) %s)" lo
        (String.concat " " (List.map Raytrace.Private.Float_text.to_string hi)) m)

let mesh_form =
  map
    [ choose [ const "closed.obj"; const "loose.obj"; const "missing.obj" ]; optional "scale" (value 0.1 3.);
      optional "translate" (triple (-2.) 2.); optional "smooth" (choose [ const "true"; const "false" ]); material ]
    (Printf.sprintf "(mesh (file %S)%s%s%s %s)")

(* Issue 26's kinds: a cylinder, capped or open (an open one refused as
   an operand), and a disk. *)
let cylinder_form =
  map [ triple (-2.) 2.; triple (-2.) 2.; value 0.1 1.5; optional "capped" (choose [ const "true"; const "false" ]); material ]
    (Printf.sprintf "(cylinder (base %s) (top %s) (radius %s)%s %s)")

let disk_form =
  map [ triple (-2.) 2.; triple (-1.) 1.; value 0.1 2.; material ] (Printf.sprintf "(disk (center %s) (normal %s) (radius %s) %s)")

(* A cone, capped or open, pointed (top radius 0) one time in three; a
   torus whose minor radius is a fraction of its major one (a ring torus),
   or any value now and then (refused when not below the major). *)
let cone_form =
  map
    [ triple (-2.) 2.; triple (-2.) 2.; value 0.1 1.5; map [ choose [ const "0"; value 0. 1.5; value 0. 1.5 ] ] (Printf.sprintf " (top-radius %s)");
      optional "capped" (choose [ const "true"; const "false" ]); material ]
    (Printf.sprintf "(cone (base %s) (top %s) (radius %s)%s%s %s)")

let torus_form =
  map [ triple (-2.) 2.; triple (-1.) 1.; range ~min:1 65535; range ~min:1 65535; choose [ const None; map [ number ] Option.some ]; material ]
    (fun c axis major fraction odd_minor m ->
      let major = 0.2 +. (2. *. Float.of_int major /. 65535.) in
      let minor =
        match odd_minor with Some x -> x | None -> Raytrace.Private.Float_text.to_string (major *. Float.of_int fraction /. 65536.)
      in
      Printf.sprintf "(torus (center %s) (axis %s) (major %s) (minor %s) %s)" c axis
        (Raytrace.Private.Float_text.to_string major) minor m)

let csg_form =
  fix (fun csg ->
      map
        [ choose [ const "union"; const "intersection"; const "difference"; token Hostile.scene_tokens ];
          choose [ sphere_form; box_form; mesh_form; cylinder_form; cone_form; torus_form; csg ];
          choose [ sphere_form; box_form; mesh_form; cylinder_form; cone_form; torus_form; csg ] ]
        (Printf.sprintf "(csg %s %s %s)"))

let shape_form =
  choose
    [
      sphere_form; box_form; mesh_form; csg_form; cylinder_form; disk_form; cone_form; torus_form;
      map [ triple (-2.) 2.; triple (-1.) 1.; material ] (Printf.sprintf "(plane (point %s) (normal %s) %s)");
      map [ triple (-2.) 2.; triple (-2.) 2.; triple 1. 5.; material ]
        (Printf.sprintf "(triangle (vertices (%s) (%s) (%s)) %s)");
    ]

(* A closed tetrahedron, and loose triangles (with whatever lines). *)
let obj_files =
  map
    [ list1 (triple (-1.) 1.); list (map [ range ~min:1 8; range ~min:1 8; range ~min:1 8 ] (Printf.sprintf "f %d %d %d"));
      list (token [| "v nan 0 0"; "f 1 2 99"; "vn 0 0 1"; "f 1//1 2//1 3//1"; "# c"; "o x"; "f 1" |]) ]
    (fun vertices faces junk ->
      let v = List.map (fun p -> "v " ^ p) vertices in
      [
        ("closed.obj", "v 0 0 2\nv 1 0 3\nv -1 0 3\nv 0 1 2.5\nf 1 2 3\nf 1 4 2\nf 2 4 3\nf 3 4 1\n");
        ("loose.obj", String.concat "\n" (v @ faces @ junk) ^ "\n");
      ])

(* Texture files: a P6 image of ours (its size and bytes drawn, the
   bytes now and then too few) and files the reader refuses. *)
let texture_files =
  map [ range ~min:1 5; range ~min:1 5; bytes ] (fun w h data ->
      let n = 3 * w * h in
      let pixels = if String.length data >= n then String.sub data 0 n else data ^ String.make (n - String.length data) '\128' in
      [
        ("tex.ppm", Printf.sprintf "P6\n%d %d\n255\n%s" w h pixels);
        ("tex3.ppm", Printf.sprintf "P6\n%d %d\n255\n%s" w h data);
        ("empty.ppm", ""); ("truncated.ppm", "P6\n4 4\n255\n\001\002\003"); ("huge.ppm", "P6\n99999 99999\n255\n");
        ("wrong.ppm", "P5\n1 1\n255\n\000");
      ])

let scene_with_meshes =
  map [ list valid_setting; list1 shape_form; list valid_light; obj_files; texture_files ] (fun settings shapes lights meshes textures ->
      (String.concat "\n" (settings @ shapes @ lights), meshes @ textures))

(* Deep nesting, balanced or not, around a generated form. *)
let nested =
  map [ range 100_000; range 3; scene_text ] (fun depth shape inner ->
      let opening = String.make depth '(' and closing = String.make depth ')' in
      match shape with
      | 0 -> opening ^ inner ^ closing
      | 1 -> opening ^ inner
      | _ -> "(sphere " ^ opening ^ inner ^ closing ^ ")")

let ppm_text =
  map
    [
      token Hostile.ppm_tokens; list (pair (token [| " "; "\n"; "#c\n"; "\t" |]) (choose [ number; token Hostile.ppm_tokens ]));
      bool; bytes;
    ]
    (fun magic header one_space data ->
      magic
      ^ String.concat "" (List.map (fun (sep, f) -> sep ^ f) header)
      ^ (if one_space then "\n" else "")
      ^ data)

(* Images whose header is right and whose pixel data has the right length
   (most of the time), so that the pixel checks and rescaling are reached;
   at most 9 x 9 pixels, as crowbar draws at most 256 bytes at once. *)
let ppm_image =
  dynamic_bind (pair (range ~min:1 9) (range ~min:1 9)) (fun (w, h) ->
      map [ range ~min:1 255; bool; bytes_fixed (3 * w * h); range 3 ] (fun maxval plain data slack ->
          if plain then
            Printf.sprintf "P3\n%d %d\n%d\n" w h maxval
            ^ String.concat " " (List.init (String.length data - slack) (fun i -> string_of_int (Char.code data.[i])))
          else Printf.sprintf "P6\n%d %d\n%d\n" w h maxval ^ String.sub data 0 (String.length data - slack)))

let () =
  add_test ~name:"scene: any bytes" [ bytes ] (check ".scene" Hostile.scene);
  add_test ~name:"scene: forms and fields" [ scene_text ] (check ".scene" Hostile.scene);
  add_test ~name:"scene: mostly valid" [ valid_scene ] (check ".scene" Hostile.scene);
  add_test ~name:"scene: deep nesting" [ nested ] (check ".scene" Hostile.scene);
  add_test ~name:"scene: meshes, CSG, glass, patterns, textures" [ scene_with_meshes ] (fun (text, meshes) ->
      dump ".scene" text;
      match Hostile.scene ~files:meshes text with Ok () -> () | Error m -> fail m);
  add_test ~name:"ppm: any bytes" [ bytes ] (check ".ppm" Hostile.ppm);
  add_test ~name:"ppm: headers" [ ppm_text ] (check ".ppm" Hostile.ppm);
  add_test ~name:"ppm: pixels" [ ppm_image ] (check ".ppm" Hostile.ppm)
