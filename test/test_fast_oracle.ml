(* The fast tracer, with its skips on (the default: first-blocker shadow
   rays, the last blocker first, culling, the hierarchy, the early stop)
   and off, against the literal oracle, on the scenes of Gen_placed:
   every kind of object on every side of every light, touching and
   coinciding surfaces, the camera inside solids and glass, rays exactly
   through edges and vertices. In the document's mode, which these scenes
   use, the fast tracer and the oracle do the document's arithmetic where
   it defines one (spheres, shading), and each decides the other shapes'
   hits its own way: the oracle exactly, the kernel in floats within its
   stated bounds. So the images must be equal byte for byte on every pixel
   whose rays no rounding decides; only the pixels where
   [Private.Literal.rounding_dependent] counts a search are left out: a ray
   within rounding of a triangle's edge or vertex or of another root
   without touching it, a shadow, mirror or refracted ray (from a rounded
   hit point, along a rounded direction) exactly through a triangle's
   edge (a shadow ray that slides along the wall it leaves, through the
   edge where the ceiling meets it), a checker point within rounding of a
   cell's boundary. A camera ray exactly through an edge or vertex, and
   exact ties of two roots (touching CSG operands, coinciding faces, a
   box's edge), are held to bytes: leaving out the ties hid three CSG
   mutants (docs/testing.md). In the robust mode the kernel uses other
   formulas, and there the skips alone are held to bytes, on and off. *)
open Raytrace

let show_pixel (r, g, b) = Printf.sprintf "(%d, %d, %d)" r g b

(* The oracle's image, and the pixels whose rays rounding may decide
   ([Private.Literal.rounding_dependent]), by column and row. *)
let oracle (s : Scene.t) =
  let s = Scene.of_valid (Helpers.valid s) in
  let img = Image.create (Scene.width s) (Scene.height s) and rounding = Hashtbl.create 16 in
  for gx = Canvas.min_x (Scene.width s) to Canvas.max_x (Scene.width s) do
    for gy = Canvas.min_y (Scene.height s) to Canvas.max_y (Scene.height s) do
      let before = Private.Literal.rounding_dependent () in
      let c = Private.Literal.pixel s gx gy in
      let x = Canvas.column ~width:(Scene.width s) gx and y = Canvas.row ~height:(Scene.height s) gy in
      Image.set img x y (Color.to_byte c.r) (Color.to_byte c.g) (Color.to_byte c.b);
      if Private.Literal.rounding_dependent () > before then Hashtbl.replace rounding (x, y) ()
    done
  done;
  (img, rounding)

(* [None] if [actual] is [expected] byte for byte on every pixel but
   those of [rounding]; otherwise how many pixels differ, by how much,
   and the first of them. *)
let difference what ?(rounding = Hashtbl.create 0) ~expected actual =
  let n = ref 0 and gt1 = ref 0 and most = ref 0 and first = ref None in
  for y = 0 to Image.height expected - 1 do
    for x = 0 to Image.width expected - 1 do
      let ((r, g, b) as e) = Image.get expected x y and ((r', g', b') as a) = Image.get actual x y in
      if e <> a && not (Hashtbl.mem rounding (x, y)) then begin
        let d = max (abs (r - r')) (max (abs (g - g')) (abs (b - b'))) in
        incr n;
        if d > 1 then incr gt1;
        most := max !most d;
        if !first = None then first := Some (x, y)
      end
    done
  done;
  match !first with
  | None -> None
  | Some (x, y) ->
      Some
        (Printf.sprintf
           "%s: %d of %d pixels differ (%d by more than 1), by up to %d per channel, %d pixels whose rays rounding may \
            decide left out; the first at column %d, row %d: %s where the oracle has %s"
           what !n (Image.width expected * Image.height expected) !gt1 !most (Hashtbl.length rounding) x y
           (show_pixel (Image.get actual x y))
           (show_pixel (Image.get expected x y)))

let fail_with = function
  | [] -> true
  | l -> QCheck.Test.fail_reportf "%s\n(the scene above is Gen_placed.print's: its meshes' files follow it)" (String.concat "\n" l)

(* The fast tracer with the skips on and off, each against the oracle. *)
let as_the_oracle (s : Scene.t) =
  let expected, rounding = oracle s in
  fail_with
    (List.filter_map
       (fun (what, skips) -> difference what ~rounding ~expected (Helpers.image_exn ~skips s))
       [ ("with the skips on", true); ("with the skips off", false) ])

let robust (s : Scene.t) = (Scene.with_overrides ~epsilon:None s)

let skips_exact (s : Scene.t) =
  let s = robust s in
  fail_with
    (Option.to_list
       (difference "in the robust mode (the scene above without its epsilon), skips on against skips off" ~expected:(Helpers.image_exn ~skips:false s)
          (Helpers.image_exn ~skips:true s)))

(* Two exact roots of coinciding surfaces (a triangle in the floor, a
   box's face) are equal, and their rounded ones may come in either
   order: the kernel's object may be any whose exact root is within this
   relative distance of the nearest. *)
let coinciding = Q.of_float (Float.ldexp 1. (-40))

(* The object that the kernel's camera ray of pixel [(gx, gy)] hits,
   [Trace.hit_object], against the exact roots: [None] if it is one
   whose exact root is (within [coinciding] of) the nearest, or no object
   where none has a root. *)
let wrong_hit (s : Scene.t) roots tr gx gy =
  Trace.pixel tr gx gy;
  let origin = (Scene.camera s).position in
  let direction =
    Vec3.v
      (Float.of_int gx *. (Scene.viewport s).width /. Float.of_int (Scene.width s))
      (Float.of_int gy *. (Scene.viewport s).height /. Float.of_int (Scene.height s))
      (Scene.viewport s).distance
  in
  let exact = Array.map (fun root -> root ~origin ~direction ~t_min:Q.one) roots in
  let nearest = Array.fold_left (fun m r -> match (m, r) with Some a, Some b -> Some (Q.min a b) | None, r -> r | m, None -> m) None exact in
  let k = Trace.hit_object tr in
  let seen = if k < 0 then None else exact.(k) in
  let show = function Some t -> Printf.sprintf "t = %s" (Q.to_string t) | None -> "no hit" in
  let near_enough t m = Q.leq (Q.sub t m) (Q.mul m coinciding) in
  match (nearest, seen) with
  | None, _ when k < 0 -> None
  | Some m, Some t when near_enough t m -> None
  | _ ->
      let first = ref (-1) in
      Array.iteri (fun i r -> if !first < 0 && r <> None && r = nearest then first := i) exact;
      Some
        (Printf.sprintf "pixel (%d, %d): the kernel sees object %d (exactly: %s), the nearest is object %d at %s" gx gy k
           (show seen) !first (show nearest))

(* Every camera ray's first object, with the skips on and off, against
   exact arithmetic: how many pixels are wrong, and the first. *)
let exact_first_hits (s : Scene.t) =
  let roots = Exact_hits.roots s in
  fail_with
    (List.filter_map
       (fun (what, skips) ->
         let tr = Trace.create (Helpers.prepare ~skips s) and wrong = ref [] in
         for gy = Canvas.max_y (Scene.height s) downto Canvas.min_y (Scene.height s) do
           for gx = Canvas.min_x (Scene.width s) to Canvas.max_x (Scene.width s) do
             Option.iter (fun w -> wrong := w :: !wrong) (wrong_hit s roots tr gx gy)
           done
         done;
         match List.rev !wrong with
         | [] -> None
         | first :: _ as l ->
             Some (Printf.sprintf "%s: %d of %d pixels see another object than the exact one; %s" what (List.length l) ((Scene.width s) * (Scene.height s)) first))
       [ ("with the skips on", true); ("with the skips off", false) ])

let tests =
  [
    Helpers.qcheck ~count:500 "every kind of object, placed around the lights, touching and grazed, renders as the oracle does with the skips on and off"
      Gen_placed.arbitrary as_the_oracle;
    Helpers.qcheck ~count:300 "spheres alone, placed around the lights, touching and around the camera, render as the oracle does with the skips on and off"
      Gen_placed.arbitrary_spheres as_the_oracle;
    Helpers.qcheck ~count:400 "planes, triangles, boxes and meshes placed and grazed: every camera ray sees the object exact arithmetic says, with the skips on and off"
      Gen_placed.arbitrary_flat exact_first_hits;
    Alcotest.test_case "a ray parallel to a plane misses it, though the plane's unit normal is rounded" `Quick (fun () ->
        (* <D, N> = 0.125 - 0.375 + 0.25 = 0 exactly, but N / |N| is
           rounded, and <D, N / |N|> is not 0: the exact property above
           found the plane seen at a huge t. *)
        let p = Plane.v ~point:(Vec3.v 1. 2. 4.) ~normal:(Vec3.v (-0.5) (-1.) 0.25) (Material.v Color.white) in
        List.iter
          (fun direction -> Alcotest.(check (float 0.)) __LOC__ infinity (Plane.intersect p ~origin:Vec3.zero ~direction))
          [ Vec3.v (-0.25) 0.375 1.; Vec3.v 0.5 (-0.25) 0.; Vec3.v 2. 0. 4. ]);
    Helpers.qcheck ~count:300 "in the robust mode the skips change no byte of such scenes" Gen_placed.arbitrary skips_exact;
  ]
