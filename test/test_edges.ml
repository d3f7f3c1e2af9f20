(* Edges, rims and tangencies of the kinds of issue 26, and those kinds
   transformed. A capped cone whose base cap lies in a plane of camera
   rays: each such ray crosses the side at the rim (it never crosses the
   cap, whose plane it runs in), so the side's normal shades it, in the
   kernel as in the oracle; rays in the tangent plane of a cone's side
   touch it, in both. The same cases for the cylinder, the disk and the
   torus. Then cylinders (capped and open), disks, cones (pointed, open)
   and tori scaled unevenly, rotated, moved and placed by [use]: the fast
   tracer against the literal oracle in both modes, nothing allocated per
   pixel; a cylinder scaled by 2 is the cylinder of twice the radius and
   length, hit masks exact. *)
open Raytrace
module Cone = Private.Cone
module Transform = Shape.Transform

let parse = Helpers.parse_ok

let stats (s : Scene.t) = match Helpers.render s with Ok (_, st) -> st | Error (`Msg m) -> Alcotest.fail m
let modes = [ None; Some 0.001 ]
let mode = function None -> "robust mode" | Some _ -> "epsilon 0.001"

(* A 96x96 canvas: the camera rays of its middle column lie in the plane
   x = 0, and those through (2k, k) on the canvas in the plane x = 2y. *)
let head =
  "(canvas (width 96) (height 96)) (light ambient (intensity 0.2)) (light point (intensity 0.6) (position 2 3 0))\n\
   (plane (point 0 -1 0) (normal 0 1 0) (color 200 200 200))\n"

(* The fast image is the oracle's, to the byte, in both modes. *)
let same_as_oracle what text =
  let s = parse text in
  List.iter
    (fun epsilon ->
      let s = Scene.with_overrides ~epsilon s in
      Helpers.check_images ~max_abs:0 (what ^ ", " ^ mode epsilon) ~expected:(Private.Literal.render (Helpers.valid s))
        (Helpers.image_exn s))
    modes

(* The base cap of this cone is in the plane x = 0, and the plane x = 2y
   through the camera is tangent to its side along its top line. *)
let cone_on_edge = "(cone (base 0 -0.5 7) (top -1 -0.5 7) (radius 0.5) (top-radius 0) (color 50 50 200))"

let edge_scenes =
  [
    ("a capped cone whose base cap's plane holds camera rays, its side tangent to others", cone_on_edge);
    ("the same cone open", "(cone (base 0 -0.5 7) (top -1 -0.5 7) (radius 0.5) (top-radius 0) (capped false) (color 50 50 200))");
    ("a cone cut at the top, its base cap in the plane x = 0", "(cone (base 0 -0.5 7) (top 1 -0.5 7) (radius 0.5) (top-radius 0.25) (color 50 50 200))");
    ("a cone whose point is on the middle column", "(cone (base 0 0 7) (top 0 -1 7) (radius 0.5) (top-radius 0) (color 50 50 200))");
    ("a capped cylinder whose base cap's plane holds camera rays", "(cylinder (base 0 -0.5 7) (top -1 -0.5 7) (radius 0.5) (color 50 50 200))");
    ("the same cylinder open", "(cylinder (base 0 -0.5 7) (top -1 -0.5 7) (radius 0.5) (capped false) (color 50 50 200))");
    ("a cylinder whose side holds the middle column's rays", "(cylinder (base 0 -0.5 7) (top 0 0.5 7) (radius 0.5) (color 50 50 200))");
    ("a disk in the plane of the middle column's rays", "(disk (center 0 -0.5 7) (normal 1 0 0) (radius 0.5) (color 50 50 200))");
    ("a torus whose middle plane holds camera rays", "(torus (center 0 -0.5 7) (axis 1 0 0) (major 0.5) (minor 0.25) (color 50 50 200))");
    ("a torus about the vertical axis", "(torus (center 0 0 7) (axis 0 1 0) (major 1) (minor 0.25) (color 50 50 200))");
  ]

let edges_match_oracle () = List.iter (fun (what, form) -> same_as_oracle what (head ^ form)) edge_scenes

(* The ray in the plane of the base cap: the root kept is the side's, at
   the rim, and so is the normal, which leans off the cap's plane toward
   the narrowing (the cap's would be the axis, (1, 0, 0)). *)
let normal_at_rim () =
  let c = Cone.v ~base:(Vec3.v 0. (-0.5) 7.) ~top:(Vec3.v (-1.) (-0.5) 7.) ~radius:0.5 ~top_radius:0. (Material.v Color.white) in
  let g = Array.make 9 0. in
  Cone.store c g 0;
  let s = Private.Scratch.create () in
  Private.Scratch.set_ray s Vec3.zero (Vec3.v 0. (-1. /. 12.) 1.);
  Alcotest.(check bool) "hit" true (Cone.roots s g 0);
  let t = s.near in
  s.px <- s.ox +. (t *. s.dx);
  s.py <- s.oy +. (t *. s.dy);
  s.pz <- s.oz +. (t *. s.dz);
  Cone.normal s g 0;
  (* The side's normal at the rim: the unit radial (0, y, z) less the
     slope (-0.5) along the unit axis (-1, 0, 0), normalised. *)
  let r = Vec3.unit (Vec3.v 0. (s.py +. 0.5) (s.pz -. 7.)) in
  let n = Vec3.unit (Vec3.v (-0.5) r.y r.z) in
  Alcotest.(check (float 1e-12)) "n.x" n.x s.nx;
  Alcotest.(check (float 1e-12)) "n.y" n.y s.ny;
  Alcotest.(check (float 1e-12)) "n.z" n.z s.nz;
  Alcotest.(check (float 0.)) "the root is kept" t s.near

(* A camera ray exactly through the front rim of a cylinder seen along
   its axis touches it there alone: it enters by the cap (against whose
   normal it goes) and leaves by the side; the oracle lists both at the
   same [t], and takes for the entry the one the ray goes in by, as the
   kernel does. The same through a cone's rim, and for the exit through
   a back rim. *)
let touching_a_rim () =
  let m = Material.v Color.white in
  let check what literal kernel_normal direction =
    match literal ~origin:Vec3.zero ~direction with
    | [ (t0, (n0 : Vec3.t)); (t1, n1) ] ->
        let (kn : Vec3.t), entry = kernel_normal direction in
        Alcotest.(check (float 0.)) (what ^ ": the entry's root") entry t0;
        if t1 < t0 then Alcotest.failf "%s: the exit before the entry" what;
        Alcotest.(check bool) (what ^ ": the oracle's entry goes in") true (Vec3.dot n0 direction < 0.);
        Alcotest.(check bool) (what ^ ": the oracle's exit goes out") true (Vec3.dot n1 direction > 0.);
        Alcotest.(check (list (float 1e-12))) (what ^ ": the kernel's entry normal is the oracle's") [ n0.x; n0.y; n0.z ] [ kn.x; kn.y; kn.z ]
    | l -> Alcotest.failf "%s: %d crossings" what (List.length l)
  in
  let kernel roots normal store n direction =
    let g = Array.make n 0. and s = Private.Scratch.create () in
    store g;
    Private.Scratch.set_ray s Vec3.zero direction;
    if not (roots s g 0) then Alcotest.fail "missed";
    let t = s.near in
    s.px <- t *. s.dx;
    s.py <- t *. s.dy;
    s.pz <- t *. s.dz;
    normal s g 0;
    (Vec3.v s.nx s.ny s.nz, t)
  in
  let cyl = Private.Cylinder.v ~base:(Vec3.v 0. 0. 6.) ~top:(Vec3.v 0. 0. 8.) ~radius:0.5 m in
  let cone = Cone.v ~base:(Vec3.v 0. 0. 6.) ~top:(Vec3.v 0. 0. 8.) ~radius:0.5 ~top_radius:0.25 m in
  List.iter
    (fun (x, y) ->
      let d = Vec3.v x y 1. in
      check "cylinder, front rim" (Private.Cylinder.desc.literal cyl)
        (kernel Private.Cylinder.roots Private.Cylinder.normal (fun g -> Private.Cylinder.store cyl g 0) 7)
        d;
      check "cone, front rim" (Cone.desc.literal cone) (kernel Cone.roots Cone.normal (fun g -> Cone.store cone g 0) 9) d)
    [ (1. /. 12., 0.); (0., -1. /. 12.); (-0.0625, 0.) ]

(* {1 Transformed shapes} *)

(* Each kind four times: scaled unevenly, turned and moved by [transform],
   and placed twice by [use] of a definition with its own transform and
   material (one of them reflective). *)
let placed form =
  head
  ^ "(light directional (intensity 0.2) (direction 1 4 -2))\n(define it " ^ form ^ ")\n\
     (transform ((scale 1.6 0.6 1.2) (rotate-x 35) (rotate-y -20) (translate -1.4 0.4 7)) " ^ form ^ ")\n\
     (transform ((rotate (axis 1 2 3) (angle 50)) (translate 1.4 0.5 6.5)) " ^ form ^ ")\n\
     (use it (transform ((scale 0.7 1.3 0.9) (rotate-z 60) (translate -0.6 -0.4 5))) (color 30 200 60) (specular 20))\n\
     (use it (transform ((rotate-y 90) (rotate-x -30) (scale 1.1) (translate 1.1 -0.5 5.5))) (color 200 200 40) (reflective 0.3))\n"

let kinds =
  [
    ("capped cylinders", "(cylinder (base 0 -0.5 0) (top 0 0.5 0) (radius 0.4) (color 200 60 60) (specular 50))");
    ("open cylinders", "(cylinder (base 0 -0.5 0) (top 0 0.5 0) (radius 0.4) (capped false) (color 200 60 60))");
    ("disks", "(disk (center 0 0 0) (normal 0 0 -1) (radius 0.5) (color 60 60 200))");
    ("pointed cones", "(cone (base 0 -0.5 0) (top 0 0.5 0) (radius 0.45) (top-radius 0) (color 60 200 200) (specular 30))");
    ("open cones", "(cone (base 0 -0.5 0) (top 0 0.5 0) (radius 0.45) (top-radius 0.15) (capped false) (color 60 200 200))");
    ("tori", "(torus (center 0 0 0) (axis 0 1 0) (major 0.45) (minor 0.15) (color 200 120 40) (specular 40))");
  ]

(* Within 1 per channel: the two tracers carry a ray into an object's
   frame by the same matrix, but the oracle's roots and shading round
   otherwise than the kernel's. The oracle traces a scene without an
   epsilon with the document's ([Scene.document_epsilon]): there the
   kernel at that epsilon is compared to the byte's neighbour, and the
   robust mode, which also sees a secondary ray's hits nearer than it
   (an open cone's inside, from a point by its rim, shows one), on all
   but 1 in 1,000 pixels. *)
let transformed_match_oracle () =
  List.iter
    (fun (what, form) ->
      let s = Scene.with_overrides ~width:64 ~height:48 (parse (placed form)) in
      List.iter
        (fun epsilon ->
          let s = Scene.with_overrides ~epsilon s in
          let oracle = Private.Literal.render (Helpers.valid s) in
          let what = "transformed " ^ what ^ ", " ^ mode epsilon in
          match epsilon with
          | Some _ -> Helpers.check_images ~max_abs:1 what ~expected:oracle (Helpers.image_exn s)
          | None ->
              let at_document = Scene.with_overrides ~epsilon:(Some Scene.document_epsilon) s in
              Helpers.check_images ~max_abs:1 (what ^ " (the kernel at the document's epsilon)") ~expected:oracle
                (Helpers.image_exn at_document);
              Helpers.check_images ~min_share:0.999 what ~expected:oracle (Helpers.image_exn s))
        modes)
    kinds

let transformed_allocate_nothing () =
  List.iter
    (fun (what, form) ->
      let s = parse (placed form) in
      List.iter
        (fun epsilon ->
          let s = Scene.with_overrides ~width:48 ~height:36 (Scene.with_overrides ~epsilon s) in
          Alcotest.(check (float 0.)) ("transformed " ^ what ^ ", " ^ mode epsilon ^ ": minor words") 0. (stats s).minor_words)
        modes)
    kinds

(* The camera rays' hit mask: whether each pixel's ray hits object 1 (the
   one after the floor). *)
let mask s =
  let tr = Private.Trace.create (Helpers.prepare s) in
  let w = Scene.width s and h = Scene.height s in
  Array.init h (fun row ->
      Array.init w (fun col ->
          Private.Trace.pixel tr (Canvas.min_x w + col) (Canvas.max_y h - row);
          Private.Trace.hit_object tr = 1))

(* Scaling by 2 and moving by floats that need no rounding: the ray in
   the object's frame is the world's halved, exactly. *)
let scaled_cylinder () =
  List.iter
    (fun capped ->
      let cyl ~base ~top ~radius =
        Printf.sprintf "(cylinder (base %s) (top %s) (radius %s) (capped %b) (color 200 60 60))" base top radius capped
      in
      let placed =
        parse
          (head ^ "(transform ((scale 2) (translate 0.5 -0.25 8)) "
          ^ cyl ~base:"0 -0.5 0" ~top:"0.25 0.5 0.125" ~radius:"0.375" ^ ")")
      and plain = parse (head ^ cyl ~base:"0.5 -1.25 8" ~top:"1 0.75 8.25" ~radius:"0.75") in
      List.iter
        (fun epsilon ->
          let a = Scene.with_overrides ~epsilon placed and b = Scene.with_overrides ~epsilon plain in
          let ma = mask a and mb = mask b in
          let hits = Array.fold_left (fun n row -> Array.fold_left (fun n x -> if x then n + 1 else n) n row) 0 ma in
          if hits < 200 then Alcotest.failf "only %d pixels hit the cylinder" hits;
          Alcotest.(check bool) (Printf.sprintf "capped %b, %s: the hit masks are equal" capped (mode epsilon)) true (ma = mb);
          Helpers.check_images ~max_abs:1
            (Printf.sprintf "capped %b, %s: the images" capped (mode epsilon))
            ~expected:(Helpers.image_exn b) (Helpers.image_exn a))
        modes)
    [ true; false ]

let tests =
  [
    Alcotest.test_case
      "rims, caps' planes and tangent planes holding camera rays: cones, cylinders, disks and tori render as the oracle, to the byte, in both modes"
      `Quick edges_match_oracle;
    Alcotest.test_case "a ray in a cone's cap's plane enters through the side at the rim, and takes the side's normal" `Quick
      normal_at_rim;
    Alcotest.test_case "a ray touching a cylinder's or a cone's rim enters by the cap and leaves by the side, in the oracle as in the kernel"
      `Quick touching_a_rim;
    Alcotest.test_case
      "cylinders, disks, cones and tori scaled unevenly, turned, moved and used: the fast tracer is the oracle within 1, in both modes"
      `Quick transformed_match_oracle;
    Alcotest.test_case "transformed cylinders, disks, cones and tori allocate nothing per pixel, in both modes" `Quick
      transformed_allocate_nothing;
    Alcotest.test_case "a cylinder scaled by 2 is the cylinder of twice the radius and length: hit masks exact" `Quick
      scaled_cylinder;
  ]
