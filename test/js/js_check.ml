(* The core library compiled to JavaScript: a scene parsed from a string,
   rendered, encoded as PPM and decoded back, and one pixel traced alone;
   and the window model (raytrace.view): a view turned by a key, rendered
   coarse-first.
   Built twice, native and JavaScript (run by node); the dune rule checks
   that both print the same lines, so the core builds for JavaScript and
   computes the same bytes there. *)

let scene_text =
  {|(canvas (width 48) (height 32))
(recursion-depth 3)
(epsilon 0.001)
(sphere (center 0 -1 3) (radius 1) (color 255 0 0) (specular 500) (reflective 0.2))
(sphere (center 2 0 4) (radius 1) (color 0 0 255) (specular 500) (reflective 0.3))
(sphere (center -2 0 4) (radius 1) (color 0 255 0) (specular 10) (reflective 0.4))
(sphere (center 0 -5001 0) (radius 5000) (color 255 255 0) (specular 1000) (reflective 0.5))
(light ambient (intensity 0.2))
(light point (intensity 0.6) (position 2 1 0))
(light directional (intensity 0.2) (direction 1 4 4))
|}

let () =
  match Raytrace.Scene_file.of_string ~file:"js.scene" scene_text with
  | Error (`Msg m) -> failwith m
  | Ok scene -> (
      match Raytrace.Render.image scene with
      | Error (`Msg m) -> failwith m
      | Ok (img, stats) -> (
          let ppm = Raytrace.Image.Ppm.to_string img in
          Printf.printf "ppm %d bytes, md5 %s\n" (String.length ppm) (Digest.to_hex (Digest.string ppm));
          Printf.printf "primary rays %d\n" stats.primary;
          (match Raytrace.Image.Ppm.of_string ppm with
          | Ok back -> Printf.printf "decoded back equal: %b\n" (Raytrace.Image.equal img back)
          | Error (`Msg m) -> failwith m);
          let view, _ = Raytrace_view.View.handle (Raytrace_view.View.v scene) (Raytrace_view.View.Key 'E') in
          let r = Raytrace_view.Progressive.create view.valid in
          let rec go bands = match Raytrace_view.Progressive.step ~rows:4 r with Some _ -> go (bands + 1) | None -> bands in
          let bands = go 0 in
          Printf.printf "progressive: %d bands, md5 %s\n" bands
            (Digest.to_hex (Digest.string (Raytrace.Image.Ppm.to_string (Raytrace_view.Progressive.image r))));
          let c = Raytrace.Render.Pixel.color (Raytrace.Render.Pixel.v scene) 24 20 in
          Printf.printf "pixel (24, 20): %d %d %d\n" (Raytrace.Color.to_byte c.r) (Raytrace.Color.to_byte c.g)
            (Raytrace.Color.to_byte c.b);
          match Raytrace.render_string "(canvas (width 2) (height 2)) (sphere (radius 1))" with
          | Ok _ -> failwith "a sphere without a center was accepted"
          | Error (`Msg m) -> print_endline m))

(* Numbers read by the scene and mesh readers, whose integers have 32 bits
   in JavaScript: decimals of 9 digits and more, 17-digit doubles, eight
   fraction digits at a time, and indices of 10 digits; printed as their
   bits, which both builds must agree on. *)
let () =
  let decimals =
    [ "2.608632225956649"; "-0.0598994318"; "2.32335784"; "123456789.5"; "1234567890123"; "0.30000000000000004";
      "9007199254740993"; "1e22"; "1.5e-7"; "-499.5"; "2000" ]
  in
  List.iter
    (fun s -> Printf.printf "scan %s %Lx\n" s (Int64.bits_of_float (Raytrace.Private.Float_scan.of_string s)))
    decimals;
  let line = "(sphere (center 0.2398439109344519 2.608632225956649 6.308065847849772) (radius 1) (color 0 0 255))" in
  let f = Raytrace.Private.Sphere_scan.create () in
  let e = Raytrace.Private.Sphere_scan.read f (line ^ String.make 16 ' ') 0 in
  Printf.printf "sphere %d %s\n" e
    (String.concat " " (List.map (fun x -> Printf.sprintf "%Lx" (Int64.bits_of_float x)) (Array.to_list f.values)));
  let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4294967299\n" in
  match Raytrace.Mesh.Obj.of_string ~name:"js.obj" ~max_vertices:10 ~max_triangles:10 obj with
  | Ok m -> Printf.printf "obj %d triangles\n" (Raytrace.Mesh.Obj.triangle_count m)
  | Error (`Msg m) -> Printf.printf "obj %s\n" m

(* The text of [header], then a balanced union of the [n] spheres that
   [sphere b i] writes, rendered: its image's digest and its tests, or the
   message, after [what]. *)
let balanced_union ~what ~file header n sphere =
  let b = Buffer.create (n * 64) in
  let rec tree lo hi =
    if hi - lo = 1 then sphere b lo
    else begin
      Buffer.add_string b "(csg union ";
      tree lo ((lo + hi) / 2);
      Buffer.add_char b ' ';
      tree ((lo + hi) / 2) hi;
      Buffer.add_char b ')'
    end
  in
  Buffer.add_string b header;
  tree 0 n;
  match Raytrace.Scene_file.of_string ~file (Buffer.contents b) with
  | Error (`Msg m) -> Printf.printf "%s: %s\n" what m
  | Ok scene -> (
      match Raytrace.Render.image scene with
      | Error (`Msg m) -> Printf.printf "%s: %s\n" what m
      | Ok (img, stats) ->
          Printf.printf "%s: md5 %s, %d tests\n" what (Digest.to_hex (Digest.string (Raytrace.Image.Ppm.to_string img))) stats.tests)

(* A union of 4096 spheres in a spiral, on 16 x 16 pixels: the surfaces'
   numbers in the kernel's intervals once wrapped JavaScript's 32-bit
   integers past 256 leaves, and the page lost spheres. *)
let () =
  balanced_union ~what:"csg spiral of 4096 spheres" ~file:"spiral.scene"
    "(canvas (width 16) (height 16)) (camera (position 0 0 -3)) (light ambient (intensity 0.3))\n\
     (light point (intensity 0.7) (position 2 3 -4))\n"
    4096 (fun b i ->
      let a = Float.of_int i *. 0.01 and r = 0.2 +. (Float.of_int i *. 1e-4) in
      Printf.bprintf b "(sphere (center %.4f %.4f 4) (radius 0.05) (color 255 0 0))" (r *. cos a) (r *. sin a))

(* CSG trees as big as the limits let a scene file make, parsed and
   rendered: a balanced union of 16384 spheres (the web page threw
   "Maximum call stack size exceeded" on it, a List.map over its leaves),
   and 100000 unions nested in one another, refused for its depth at the
   33rd with its line and column (the search for that position recursed
   as deep as the nesting). JavaScript's stack is far smaller than the
   native one: both builds must print the same lines. *)
let () =
  balanced_union ~what:"csg of 16384 spheres" ~file:"csg.scene"
    "(canvas (width 2) (height 2)) (viewport (width 4) (height 4) (distance 1)) (light ambient (intensity 1))\n"
    16384 (fun b i ->
      Printf.bprintf b "(sphere (center %d %d 40) (radius 0.4) (color 255 0 0))" ((i mod 128) - 64) ((i / 128) - 64));
  let n = 100_000 in
  let b = Buffer.create (64 * n) in
  Buffer.add_string b "(light ambient (intensity 1))\n";
  for _ = 1 to n do
    Buffer.add_string b "(csg union "
  done;
  Buffer.add_string b "(sphere (center 0 0 9) (radius 1) (color 1 0 0))";
  for _ = 1 to n do
    Buffer.add_string b " (sphere (center 0 0 9) (radius 1) (color 1 0 0)))"
  done;
  match Raytrace.Scene_file.of_string ~file:"deep.scene" (Buffer.contents b) with
  | Ok _ -> print_endline "csg nested 100000 deep: accepted"
  | Error (`Msg m) -> Printf.printf "csg nested 100000 deep: %s\n" m

(* Sample keys (area lights, lenses) on both builds: the same numbers, or
   the web page's soft shadows would differ from the command line's. *)
let () =
  let open Raytrace.Private.Sample_key in
  List.iter
    (fun (col, row, sample) ->
      let h = pixel ~col ~row ~sample in
      Printf.printf "sample key %d %d %d: %d %h %h\n" col row sample h (unit h) (stratum h ~n:7 3))
    [ (0, 0, 0); (1, 0, 0); (0, 1, 0); (-300, 299, 15); (1_000_000, -7, 4095); (0x3FFF_FFFF, -0x4000_0000, -1) ]

(* A stratified lens (the default) and the independent draw, on both
   builds: the cell permutations, and the images of a small lens scene at
   3 x 3 samples and adaptively (its lens-aware refinement and probes), whose points
   come from the concentric map's polynomials: the web page must render
   the command line's bytes. *)
let () =
  let open Raytrace.Private.Sample_key in
  List.iter
    (fun (h, n) ->
      Printf.printf "permute %d n=%d: %s\n" h n (String.concat " " (List.init (min n 12) (fun k -> string_of_int (permute h ~n k)))))
    [ (0, 1); (17, 8); (0x7FFF_FFFF, 9); (-5, 24); (123456, 48); (99, 4096) ];
  let lens sampling =
    Printf.sprintf
      "(canvas (width 40) (height 24)) (camera (position 0 1.4 -3.5) (look-at 0 0.6 6) (aperture 0.3) (lens-sampling %s))\n\
       (plane (point 0 0 0) (normal 0 1 0) (color 225 225 215) (pattern checker (color 60 70 100) (size 1)))\n\
       (sphere (center -1.2 0.6 3.8) (radius 0.6) (color 240 180 30) (specular 300))\n\
       (sphere (center 0 0.6 6) (radius 0.6) (color 40 190 80) (reflective 0.2))\n\
       (light ambient (intensity 0.2)) (light point (intensity 0.8) (position -4 6 -1))"
      sampling
  in
  (* Pinned: a change of the lens points shows here, on both builds. *)
  List.iter
    (fun (sampling, samples, adaptive, pinned) ->
      match Raytrace.Scene_file.of_string ~file:"lens.scene" (lens sampling) with
      | Error (`Msg m) -> failwith m
      | Ok scene -> (
          match Raytrace.Render.image ~samples ?adaptive scene with
          | Error (`Msg m) -> failwith m
          | Ok (img, stats) ->
              let md5 = Digest.to_hex (Digest.string (Raytrace.Image.Ppm.to_string img)) in
              Printf.printf "lens %s samples %d%s: md5 %s, %d primary rays\n" sampling samples
                (match adaptive with Some t -> Printf.sprintf " adaptive %d" t | None -> "")
                md5 stats.primary;
              if md5 <> pinned then failwith (Printf.sprintf "lens %s samples %d: md5 %s, not the pinned %s" sampling samples md5 pinned)))
    [
      ("stratified", 1, None, "1580078cf4e32f864953ddeae535001d");
      ("stratified", 3, None, "d91f4ded174ce3b38cceffd19adfdf57");
      ("stratified", 4, None, "848ada814c2cd6b033a00fd7bb1560f5");
      ("stratified", 5, Some 8, "e808a22af74450967914dc9d1fbae3fc");
      ("uniform", 3, None, "3eea459a01a1f19980d27ac9bfe70414");
    ]

(* Enough spheres for a hierarchy ([Prepared.bvh_threshold]): its build's
   node arrays are bigarrays, which JavaScript must make and read alike. *)
let () =
  let spheres =
    String.concat "\n"
      (List.init 20 (fun i ->
           Printf.sprintf "(sphere (center %d 0 %d) (radius 0.4) (color 200 100 50))" ((i mod 5) - 2) ((i / 5) + 3)))
  in
  let text = "(canvas (width 24) (height 16))\n(light ambient (intensity 1))\n" ^ spheres in
  match Raytrace.Scene_file.of_string ~file:"grid.scene" text with
  | Error (`Msg m) -> failwith m
  | Ok scene -> (
      match Raytrace.Render.image scene with
      | Error (`Msg m) -> failwith m
      | Ok (img, _) ->
          Printf.printf "20 spheres: md5 %s\n" (Digest.to_hex (Digest.string (Raytrace.Image.Ppm.to_string img))))

(* Textures on a CSG solid's operands and on a use's own material, in a
   turned die (scenes/textured-die.scene's forms, a small image built in):
   the web page must draw the command line's bytes. *)
let () =
  let image =
    Raytrace.Image.Texture.v ~width:4 ~height:2
      "\255\000\000\000\255\000\000\000\255\255\255\000\000\255\255\255\000\255\128\064\032\032\064\128"
  in
  let text =
    "(canvas (width 40) (height 30)) (camera (position 0 1.6 -2.2) (look-at 0 0.1 4))\n\
     (transform ((rotate-y 35) (rotate-x -20) (translate -0.9 0.25 4)) (csg intersection\n\
    \  (box (min -0.8 -0.8 -0.8) (max 0.8 0.8 0.8) (color 255 255 255) (texture (file \"t.ppm\") (mapping box)))\n\
    \  (sphere (center 0 0 0) (radius 1.08) (color 255 255 255) (texture (file \"t.ppm\") (mapping spherical)))))\n\
     (define ball (sphere (center 0 0 0) (radius 0.7) (color 255 255 255)))\n\
     (use ball (transform ((rotate-y 90) (translate 1.3 0 4.2))) (color 255 255 255) (texture (file \"t.ppm\") (mapping spherical)))\n\
     (light ambient (intensity 0.3)) (light point (intensity 0.6) (position 3 4 -1))"
  in
  match Raytrace.Scene_file.of_string ~load_texture:(fun _ -> Ok image) ~file:"die.scene" text with
  | Error (`Msg m) -> failwith m
  | Ok scene -> (
      match Raytrace.Render.image scene with
      | Error (`Msg m) -> failwith m
      | Ok (img, _) -> Printf.printf "textured die: md5 %s\n" (Digest.to_hex (Digest.string (Raytrace.Image.Ppm.to_string img))))

(* A sphere light of 10 samples (3 sectors, 4 blocks of rings, the last
   short): its angles' permutations ([Sample_key.walk]) and the image, on
   both builds. *)
let () =
  let text =
    "(canvas (width 32) (height 24)) (camera (position 0 2 -3) (look-at 0 0 2))\n\
     (plane (point 0 -1 0) (normal 0 1 0) (color 200 200 200))\n\
     (sphere (center 0 0 2) (radius 0.7) (color 255 80 80) (specular 300))\n\
     (light ambient (intensity 0.1)) (light sphere (intensity 0.7) (position 1 3 1) (radius 0.8) (samples 10))"
  in
  match Raytrace.Scene_file.of_string ~file:"sphere-light.scene" text with
  | Error (`Msg m) -> failwith m
  | Ok scene -> (
      match Raytrace.Render.image ~samples:2 scene with
      | Error (`Msg m) -> failwith m
      | Ok (img, _) -> Printf.printf "sphere light: md5 %s\n" (Digest.to_hex (Digest.string (Raytrace.Image.Ppm.to_string img))))
