(* Cylinders and disks (issue 26): their scene text, their kernel routines
   against exact rational arithmetic (Zarith) and against the oracle's
   crossings, the silhouettes of tiny far ones, and no self-shadowing at
   any scale. The routines measured are the renderer's: [Trace.roots] on a
   prepared scene of the one shape. *)
open Raytrace
module Cylinder = Private.Cylinder
module Disk = Private.Disk

let u = epsilon_float /. 2.

(* The bounds the interfaces state (cylinder.mli, disk.mli), in units of
   [u S]. *)
let cylinder_bound = 16.
let disk_bound = 16.

let white = Material.v Color.white
let cylinder ?capped ~base ~top ~radius m = Shape.Primitive (Private.Shape_desc.Primitive (Cylinder.desc, Cylinder.v ?capped ~base ~top ~radius m))
let disk ~center ~normal ~radius m = Shape.Primitive (Private.Shape_desc.Primitive (Disk.desc, Disk.v ~center ~normal ~radius m))

(* {1 Exact arithmetic} *)

(* Exact arithmetic on the float inputs, as test_shapes.ml does it. *)
let q, qv, dot, sub, add, scale, cross = Test_shapes.(q, qv, dot, sub, add, scale, cross)
let fsqrt x = sqrt (Q.to_float x)

let exact_point = Test_shapes.exact_point

(* How far the exact point [P] lies from the capped (or open) cylinder's
   surface: from the side patch (the side's distance, plus how far beyond
   a cap's plane it is), or from a cap's disk (the plane's distance, plus
   how far beyond the rim). Each term is exact up to the final square
   roots' few ulps. *)
let cylinder_distance (c : Cylinder.t) p =
  let a = sub (qv c.top) (qv c.base) in
  let w = sub p (qv c.base) in
  let h2 = dot a a in
  let y = dot w a in
  let radial2 = Q.(sub (dot w w) (div (mul y y) h2)) in
  let r = c.radius in
  let side = Float.abs (Q.to_float Q.(sub radial2 (mul (q r) (q r)))) /. (fsqrt radial2 +. r) in
  let len = fsqrt h2 in
  let along = Q.to_float y /. len in
  let beyond_caps = Float.max 0. (-.along) +. Float.max 0. (along -. len) in
  let beyond_rim = Float.max 0. (fsqrt radial2 -. r) in
  let side = side +. beyond_caps in
  if c.capped then Float.min side (Float.min (Float.abs along +. beyond_rim) (Float.abs (along -. len) +. beyond_rim))
  else side

(* The exact squared distance from the cylinder's axis line to the ray's
   line: [(<O - B, A x D>)^2 / |A x D|^2]. *)
let axis_line_distance2 (c : Cylinder.t) ~origin ~direction =
  let a = sub (qv c.top) (qv c.base) in
  let n = cross a (qv direction) in
  let k = dot (sub (qv origin) (qv c.base)) n in
  Q.(div (mul k k) (dot n n))

(* The exact crossing of the ray's line with the disk's plane, and its
   squared distance from the centre ([None] when parallel). *)
let disk_crossing (d : Disk.t) ~origin ~direction =
  let n = qv d.normal in
  let dn = dot (qv direction) n in
  if Q.equal dn Q.zero then None
  else
    let t = Q.div (dot (sub (qv d.center) (qv origin)) n) dn in
    let off = sub (add (qv origin) (scale t (qv direction))) (qv d.center) in
    Some (t, dot off off)

let disk_plane_distance (d : Disk.t) p =
  let n = qv d.normal in
  Float.abs (Q.to_float (dot (sub p (qv d.center)) n)) /. fsqrt (dot n n)

(* {1 Random cases} *)

let random_unit = Test_shapes.random_unit

(* An axis along x, y or z a third of the time (the common case, where the
   projection across the axis is exact), otherwise any. *)
let random_axis rand =
  match Random.State.int rand 6 with
  | 0 -> Vec3.ox
  | 1 -> Vec3.neg Vec3.oy
  | 2 -> Vec3.oz
  | _ -> random_unit rand

type case = { shape : Shape.t; origin : Vec3.t; direction : Vec3.t }

(* A cylinder at scale [10^e], e in [-6, 6], translated by up to 1e6, and
   a ray aimed at a point near it: [far] puts the origin [1e7] radii away,
   [graze] aims within [1e-12] of the side, [middle] aims at the side away
   from the caps. *)
let cylinder_case ?(far = false) ?(graze = false) ?(middle = false) rand =
  let sc = 10. ** (Random.State.float rand 12. -. 6.) in
  let off = if Random.State.bool rand then Vec3.smul (Random.State.float rand 1e6) (random_unit rand) else Vec3.zero in
  let base = Vec3.add off (Vec3.smul (sc *. Random.State.float rand 2.) (random_unit rand)) in
  let axis = Vec3.smul (sc *. (0.3 +. Random.State.float rand 3.)) (random_axis rand) in
  let radius = sc *. (0.05 +. Random.State.float rand 1.) in
  let capped = Random.State.int rand 3 > 0 in
  let c = Cylinder.v ~capped ~base ~top:(Vec3.add base axis) ~radius white in
  let along = if middle then 0.3 +. Random.State.float rand 0.4 else Random.State.float rand 1.4 -. 0.2 in
  let u_axis = Vec3.unit axis in
  let side_dir =
    let v = random_unit rand in
    Vec3.unit (Vec3.sub v (Vec3.smul (Vec3.dot v u_axis) u_axis))
  in
  let reach = if graze then 1. +. (Random.State.float rand 2e-12 -. 1e-12) else Random.State.float rand 1.5 in
  let target = Vec3.add base (Vec3.add (Vec3.smul along axis) (Vec3.smul (reach *. radius) side_dir)) in
  let dist = if far then radius *. 1e7 else sc *. (2. +. Random.State.float rand 50.) in
  let from =
    if graze then
      (* Across the axis, so that the ray is tangent to the side. *)
      let across = Vec3.unit (Vec3.cross u_axis side_dir) in
      let tilt = Vec3.smul (Random.State.float rand 0.5 -. 0.25) u_axis in
      Vec3.unit (Vec3.add across tilt)
    else if middle then
      let v = random_unit rand in
      Vec3.unit (Vec3.sub v (Vec3.smul (0.8 *. Vec3.dot v u_axis) u_axis))
    else random_unit rand
  in
  let origin = Vec3.add target (Vec3.smul dist from) in
  let direction = Vec3.smul (10. ** (Random.State.float rand 4. -. 2.)) (Vec3.sub target origin) in
  (c, { shape = Shape.Primitive (Private.Shape_desc.Primitive (Cylinder.desc, c)); origin; direction })

let disk_case ?(far = false) ?(graze = false) rand =
  let sc = 10. ** (Random.State.float rand 12. -. 6.) in
  let off = if Random.State.bool rand then Vec3.smul (Random.State.float rand 1e6) (random_unit rand) else Vec3.zero in
  let center = Vec3.add off (Vec3.smul (sc *. Random.State.float rand 2.) (random_unit rand)) in
  let normal = Vec3.smul (10. ** (Random.State.float rand 6. -. 3.)) (random_axis rand) in
  let radius = sc *. (0.05 +. Random.State.float rand 1.) in
  let d = Disk.v ~center ~normal ~radius white in
  let n = Vec3.unit normal in
  let in_plane =
    let v = random_unit rand in
    Vec3.unit (Vec3.sub v (Vec3.smul (Vec3.dot v n) n))
  in
  let reach = Random.State.float rand 1.5 in
  let target = Vec3.add center (Vec3.smul (reach *. radius) in_plane) in
  let dist = if far then radius *. 1e7 else sc *. (2. +. Random.State.float rand 50.) in
  let from =
    if graze then Vec3.unit (Vec3.add (random_unit rand |> fun v -> Vec3.sub v (Vec3.smul (Vec3.dot v n) n)) (Vec3.smul 1e-9 n))
    else random_unit rand
  in
  let origin = Vec3.add target (Vec3.smul dist from) in
  let direction = Vec3.smul (10. ** (Random.State.float rand 4. -. 2.)) (Vec3.sub target origin) in
  (d, { shape = Shape.Primitive (Private.Shape_desc.Primitive (Disk.desc, d)); origin; direction })

(* The renderer's roots: [Trace.roots] on a prepared scene of the one
   shape, in the robust mode. *)
let trace_roots c =
  let scene = Helpers.scene ~spheres:[] ~shapes:[ c.shape ] ~lights:[] () in
  Trace.roots (Trace.create (Helpers.prepare scene)) 0 c.origin c.direction

let cases ~seed n f =
  let rand = Random.State.make [| 2026; seed |] in
  List.init n (fun _ -> f rand)

(* {1 The tests} *)

(* Does the exact line meet the cylinder? The side's quadratic across the
   axis has exact rational coefficients ([p], [q] the projections of
   [O - B] and [D]): the sign of its discriminant says whether the line
   meets the infinite cylinder; its roots, to a few ulps, and their points'
   places along the axis then say whether they fall on the segment (or,
   capped, whether the line's stretch inside the infinite cylinder meets
   the slab between the caps). [`Unsure] within [band] of the radius, or
   within [1e-9] of the axis's length of a cap's plane: there the kernel
   may answer either way. *)
let expected_hit (c : Cylinder.t) ~origin ~direction ~band =
  let a = sub (qv c.top) (qv c.base) in
  let h2 = dot a a in
  let w = sub (qv origin) (qv c.base) and d = qv direction in
  let across v = sub v (scale (Q.div (dot v a) h2) a) in
  let p = across w and qd = across d in
  let qa = dot qd qd and pq = dot p qd in
  let cc = Q.(sub (dot p p) (mul (q c.radius) (q c.radius))) in
  let disc = Q.(sub (mul pq pq) (mul qa cc)) in
  let line = fsqrt (axis_line_distance2 c ~origin ~direction) in
  if Float.abs (line -. c.radius) <= band || Q.equal qa Q.zero then `Unsure
  else if Q.sign disc < 0 then `Miss
  else
    let len = fsqrt h2 in
    let along t = (Q.to_float (dot w a) +. (t *. Q.to_float (dot d a))) /. len in
    let sq = fsqrt disc and qaf = Q.to_float qa and pqf = Q.to_float pq in
    let t0 = (-.pqf -. sq) /. qaf and t1 = (-.pqf +. sq) /. qaf in
    let y0 = along t0 and y1 = along t1 in
    let margin = 1e-9 *. len in
    let near_cap y = Float.abs y <= margin || Float.abs (y -. len) <= margin in
    if near_cap y0 || near_cap y1 then `Unsure
    else
      let on y = 0. <= y && y <= len in
      if c.capped then
        (* The stretch [y0, y1] (in either order) against [0, len]. *)
        if Float.max y0 y1 < 0. || Float.min y0 y1 > len then `Miss else `Hit
      else if on y0 || on y1 then `Hit
      else `Miss

type tally = { mutable worst : float; mutable wrong : int; mutable roots : int; mutable misses : int; mutable sure : int }

let cylinder_accuracy () =
  let families =
    [
      ("general position", fun r -> cylinder_case r);
      ("far, thin cylinders (r / d = 1e-7)", fun r -> cylinder_case ~far:true r);
      ("grazing the side (within 1e-12)", fun r -> cylinder_case ~graze:true ~middle:true r);
      ("far and grazing", fun r -> cylinder_case ~far:true ~graze:true ~middle:true r);
      ("aimed at the side's middle", fun r -> cylinder_case ~middle:true r);
    ]
  in
  List.iteri
    (fun seed (name, gen) ->
      let t = { worst = 0.; wrong = 0; roots = 0; misses = 0; sure = 0 } in
      List.iter
        (fun (c, case) ->
          let s = Vec3.norm (Vec3.sub case.origin c.Cylinder.base) +. Vec3.norm (Vec3.sub c.top c.base) +. c.radius in
          let unit = u *. s in
          let near, far = trace_roots case in
          if near > far then Alcotest.failf "%s: roots out of order %h %h" name near far;
          if near = infinity then t.misses <- t.misses + 1
          else
            List.iter
              (fun root ->
                t.roots <- t.roots + 1;
                let e = cylinder_distance c (exact_point ~origin:case.origin ~direction:case.direction root) /. unit in
                if e > t.worst then t.worst <- e)
              [ near; far ];
          (* Hit or miss as the exact line says, beyond the band. *)
          let expected = expected_hit c ~origin:case.origin ~direction:case.direction ~band:(cylinder_bound *. unit) in
          if expected <> `Unsure then t.sure <- t.sure + 1;
          match expected with
          | `Hit when near = infinity -> t.wrong <- t.wrong + 1
          | `Miss when near < infinity -> t.wrong <- t.wrong + 1
          | _ -> ())
        (cases ~seed 1500 gen);
      Printf.printf "%-40s %5d roots, %4d misses: worst %.3g u S; %d rays decided, %d wrong\n" name t.roots t.misses t.worst t.sure t.wrong;
      if t.sure < 100 then Alcotest.failf "%s: only %d rays decided by exact arithmetic" name t.sure;
      if t.worst > cylinder_bound then Alcotest.failf "%s: a root %.3g u S off the surface > %g" name t.worst cylinder_bound;
      Alcotest.(check int) (name ^ ": hit or miss as the exact line") 0 t.wrong;
      if t.roots < 500 then Alcotest.failf "%s: only %d roots" name t.roots)
    families

let disk_accuracy () =
  List.iteri
    (fun seed (name, gen) ->
      let t = { worst = 0.; wrong = 0; roots = 0; misses = 0; sure = 0 } in
      List.iter
        (fun (d, case) ->
          let near, far = trace_roots case in
          if near <> far then Alcotest.failf "%s: a disk has one root, got %h %h" name near far;
          let s t = Vec3.norm (Vec3.sub case.origin d.Disk.center) +. (Float.abs t *. Vec3.norm case.direction) in
          (match disk_crossing d ~origin:case.origin ~direction:case.direction with
          | None -> if near < infinity then t.wrong <- t.wrong + 1
          | Some (tq, off2) ->
              let unit = u *. s (Q.to_float tq) in
              let off = (fsqrt off2 -. d.radius) /. unit in
              if (near = infinity && off < -.disk_bound) || (near < infinity && off > disk_bound) then t.wrong <- t.wrong + 1);
          if near = infinity then t.misses <- t.misses + 1
          else begin
            t.roots <- t.roots + 1;
            let e = disk_plane_distance d (exact_point ~origin:case.origin ~direction:case.direction near) /. (u *. s near) in
            if e > t.worst then t.worst <- e
          end)
        (cases ~seed 1500 gen);
      Printf.printf "%-40s %5d roots, %4d misses: worst %.3g u S, %d wrong\n" name t.roots t.misses t.worst t.wrong;
      if t.worst > disk_bound then Alcotest.failf "%s: a root %.3g u S off the plane > %g" name t.worst disk_bound;
      Alcotest.(check int) (name ^ ": hit or miss as the exact line") 0 t.wrong)
    [
      ("general position", fun r -> disk_case r);
      ("far, small disks (r / d = 1e-7)", fun r -> disk_case ~far:true r);
      ("grazing the plane (1e-9)", fun r -> disk_case ~graze:true r);
    ]

(* {1 Silhouettes of tiny far shapes} *)

let hit_mask = Test_numerics.hit_mask

(* The exact mask: [classify ~origin ~direction] of each pixel's float
   ray, as test_csg.ml makes it. *)
let exact_mask = Test_csg.exact_mask

(* [x] against [r] with a band of [band] either side. *)
let side_of x r band = if x <= r -. band then `In else if x > r +. band then `Out else `Edge

(* A shape of radius [r = 1e-3] at distance [1e7 r], through a viewport
   that makes it about 30 pixels across, the camera at [translate]. *)
let far_scene ~translate shape_at =
  let r = 1e-3 in
  let dist = 1e7 *. r in
  let center = Vec3.add translate (Vec3.v (0.3 *. dist) (-0.2 *. dist) dist) in
  let camera = match Camera.look_at ~up:(Vec3.v 0.3 1. 0.2) ~position:translate center with Ok c -> c | Error (`Msg e) -> failwith e in
  let shape, classify = shape_at ~center ~r ~toward:(Vec3.sub translate center) in
  let scene =
    Helpers.scene ~width:90 ~height:90 ~viewport:(Viewport.v ~width:6e-7 ~height:6e-7 ~distance:1.) ~camera ~spheres:[]
      ~shapes:[ shape ] ~lights:[ Light.ambient 1. ] ()
  in
  (scene, classify)

(* Side-on: a long cylinder across the view (its caps out of the
   picture): the exact line's distance from the axis against [r]. *)
let side_on ~center ~r ~toward =
  let across = Vec3.unit (Vec3.cross toward (Vec3.v 0.2 1. 0.1)) in
  let half = Vec3.smul (1000. *. r) across in
  let c = Cylinder.v ~base:(Vec3.sub center half) ~top:(Vec3.add center half) ~radius:r white in
  let classify ~origin ~direction =
    let band = cylinder_bound *. u *. (Vec3.norm (Vec3.sub origin c.base) +. Vec3.norm (Vec3.sub c.top c.base) +. r) in
    side_of (fsqrt (axis_line_distance2 c ~origin ~direction)) r band
  in
  (cylinder ~base:c.base ~top:c.top ~radius:r white, classify)

(* End-on: the axis points at the camera, the near cap faces it; what
   shows is the near cap's disk: where the exact line crosses its plane,
   against [r]. *)
let end_on ~center ~r ~toward =
  let near = center and far = Vec3.sub center (Vec3.smul (20. *. r /. Vec3.norm toward) toward) in
  let cap = Disk.v ~center:near ~normal:(Vec3.sub far near) ~radius:r white in
  let classify ~origin ~direction =
    match disk_crossing cap ~origin ~direction with
    | None -> `Out
    | Some (t, off2) ->
        let band = cylinder_bound *. u *. (Vec3.norm (Vec3.sub origin far) +. Vec3.norm (Vec3.sub near far) +. r) in
        ignore t;
        side_of (fsqrt off2) r band
  in
  (cylinder ~base:far ~top:near ~radius:r white, classify)

(* A disk tilted to the view: where the exact line crosses its plane. *)
let tilted_disk ~center ~r ~toward =
  let normal = Vec3.add toward (Vec3.smul (0.7 *. Vec3.norm toward) (Vec3.v 0.3 (-0.5) 0.2)) in
  let d = Disk.v ~center ~normal ~radius:r white in
  let classify ~origin ~direction =
    match disk_crossing d ~origin ~direction with
    | None -> `Out
    | Some (t, off2) ->
        let band = disk_bound *. u *. (Vec3.norm (Vec3.sub origin center) +. (Float.abs (Q.to_float t) *. Vec3.norm direction)) in
        side_of (fsqrt off2) r band
  in
  (disk ~center ~normal ~radius:r white, classify)

let far_silhouettes () =
  List.iter
    (fun (what, shape_at) ->
      List.iter
        (fun translate ->
          let scene, classify = far_scene ~translate shape_at in
          let wrong, inside = Helpers.mask_errors (hit_mask scene) (exact_mask scene classify) in
          let what = Printf.sprintf "%s, camera at %s" what (Vec3.show translate) in
          if inside < 200 then Alcotest.failf "%s: the shape covers only %d pixels" what inside;
          Printf.printf "%s: %d pixels inside, %d off the exact shape\n" what inside wrong;
          Alcotest.(check int) (what ^ ": pixels off the exact shape") 0 wrong)
        [ Vec3.zero; Vec3.v 1e6 (-1e6) 1e6 ])
    [ ("a cylinder side-on", side_on); ("a cylinder end-on (its cap)", end_on); ("a tilted disk", tilted_disk) ]

(* {1 No self-shadowing} *)

(* A capped cylinder, an open tube seen into and a disk, white, lit by a
   point light at the camera alone: every point the camera sees sees the
   light, so a black pixel inside a shape's picture (its 8 neighbours
   showing the same object) is the shape shadowing itself. *)
let lit_from_the_camera ?epsilon ~scale ~translate () =
  let p v = Vec3.add (Vec3.smul scale v) translate in
  let l x = scale *. x in
  let shapes =
    [
      cylinder ~base:(p (Vec3.v (-1.6) (-0.8) 5.)) ~top:(p (Vec3.v (-1.2) 0.9 5.5)) ~radius:(l 0.5) white;
      cylinder ~capped:false ~base:(p (Vec3.v 0.1 (-0.6) 4.)) ~top:(p (Vec3.v 0.5 0.2 6.)) ~radius:(l 0.5) white;
      disk ~center:(p (Vec3.v 1.5 0.3 5.)) ~normal:(Vec3.v (-0.4) 0.3 (-1.)) ~radius:(l 0.7) white;
    ]
  in
  let camera = Camera.v (p Vec3.zero) in
  Helpers.scene ?epsilon ~width:80 ~height:80
    ~viewport:(Viewport.v ~width:(l 1.) ~height:(l 1.) ~distance:(l 1.))
    ~camera ~spheres:[] ~shapes ~lights:[ Light.point 1. (p Vec3.zero) ] ()

(* The pixels inside a shape's picture that are black. *)
let dark_inside scene =
  let tr = Trace.create (Helpers.prepare scene) in
  let w = Scene.width scene and h = Scene.height scene in
  let hit = Array.make_matrix h w (-1) and dark = Array.make_matrix h w false in
  for row = 0 to h - 1 do
    for col = 0 to w - 1 do
      Trace.pixel tr (Canvas.x_of_column ~width:w col) (Canvas.y_of_row ~height:h row);
      hit.(row).(col) <- Trace.hit_object tr;
      dark.(row).(col) <- Trace.red tr < 0.5
    done
  done;
  let count = ref 0 and seen = ref 0 in
  for row = 1 to h - 2 do
    for col = 1 to w - 2 do
      let k = hit.(row).(col) in
      let inside = ref (k >= 0) in
      for dr = -1 to 1 do
        for dc = -1 to 1 do
          if hit.(row + dr).(col + dc) <> k then inside := false
        done
      done;
      if !inside then begin
        incr seen;
        if dark.(row).(col) then incr count
      end
    done
  done;
  (!count, !seen)

let no_self_shadowing () =
  List.iter
    (fun (scale, translate) ->
      let dark, seen = dark_inside (lit_from_the_camera ~scale ~translate ()) in
      let what = Printf.sprintf "scale %g, moved by %s" scale (Vec3.show translate) in
      if seen < 1000 then Alcotest.failf "%s: only %d pixels inside the shapes" what seen;
      Alcotest.(check int) (what ^ ": self-shadowed pixels") 0 dark)
    [ (1e-6, Vec3.zero); (1., Vec3.zero); (1e6, Vec3.zero); (1., Vec3.v 1e6 (-1e6) 1e6); (1e-3, Vec3.v 0. 0. 1e6) ];
  (* A fixed epsilon (in the ray's parameter) does not scale: moved by
     1e6, the shadow rays' own roots exceed 1e-12 and the shapes shadow
     themselves. *)
  let dark, _ = dark_inside (lit_from_the_camera ~epsilon:1e-12 ~scale:1. ~translate:(Vec3.v 1e6 (-1e6) 1e6) ()) in
  Printf.printf "epsilon 1e-12, moved by 1e6: %d self-shadowed pixels\n" dark;
  if dark = 0 then Alcotest.fail "expected a fixed epsilon to show self-shadowing"

(* {1 Scene text} *)

let parse = Helpers.parse_ok

let error = Helpers.parse_error

let forms =
  "(cylinder (base 0 0 5) (top 0 2 5) (radius 0.5) (color 200 50 50))\n\
   (cylinder (base 1 0 5) (top 1 2 5.5) (radius 0.25) (capped false) (color 1 2 3) (specular 10))\n\
   (cylinder (base 2 0 5) (top 2 2 5) (radius 0.5) (capped true) (color 200 50 50))\n\
   (disk (center 0 0 5) (normal 0 1 0) (radius 1) (color 4 5 6) (pattern checker (color 1 1 1) (size 0.5)))\n\
   (csg difference (box (min -1 -1 4) (max 1 1 6) (color 9 9 9)) (cylinder (base 0 -2 5) (top 0 2 5) (radius 0.5) (color 1 1 1)))\n"

let reads_and_prints () =
  let scene = parse forms in
  let cylinders, disks =
    List.fold_left
      (fun (cs, ds) -> function
        | Shape.Primitive (Private.Shape_desc.Primitive (d, x)) -> (
            match (Private.Shape_desc.same d.witness Cylinder.desc.witness, Private.Shape_desc.same d.witness Disk.desc.witness) with
            | Some Private.Shape_desc.Equal, _ -> ((x : Cylinder.t) :: cs, ds)
            | _, Some Private.Shape_desc.Equal -> (cs, (x : Disk.t) :: ds)
            | _ -> (cs, ds))
        | _ -> (cs, ds))
      ([], []) (Scene.objects scene)
  in
  Alcotest.(check (list bool)) "capped by default, open when told, capped when told" [ true; false; true ]
    (List.rev_map (fun (c : Cylinder.t) -> c.capped) cylinders);
  Alcotest.(check int) "one disk" 1 (List.length disks);
  let text = Scene_file.to_string scene in
  Alcotest.(check bool) "the open cylinder prints (capped false)" true
    (Astring_free.contains text "(radius 0.25) (capped false)");
  let again = parse text in
  Alcotest.(check bool) ("printed and read back: " ^ text) true (Scene.equal scene again);
  Alcotest.(check string) "and printed again, the same" text (Scene_file.to_string again)

(* The described closed kinds join the list, read from the registry as
   the scene text reads it (a cylinder among them). *)
let operands =
  let described =
    List.filter_map
      (fun (Private.Shape_desc.Any d) -> if Private.Kind.closed d.kind then Some (d.name ^ ", ") else None)
      Private.Primitives.all
  in
  "an operand is a sphere, box, " ^ String.concat "" described ^ "closed mesh, csg, or a transform or use of one"

let bad_forms =
  [
    ("(cylinder (base 0 0 5) (top 0 0 5) (radius 0.5) (color 1 2 3))",
     "t.scene:1:1: cylinder base and top must be at least 1e-30 apart, got (0 0 5) and (0 0 5)");
    ("(cylinder (base 0 0 5) (top 0 1 5) (radius -1) (color 1 2 3))", "t.scene:1:1: cylinder radius must be > 0, got -1");
    ("(cylinder (base 0 0 5) (top 0 1 5) (color 1 2 3))", "t.scene:1:1: cylinder is missing its (radius ...) field");
    ("(cylinder (base 0 0 5) (top 0 1 5) (radius 1) (capped maybe) (color 1 2 3))",
     "t.scene:1:55: cylinder capped: expected true or false");
    ("(cylinder (base 0 0 5) (top 0 1 nan) (radius 1) (color 1 2 3))",
     "t.scene:1:33: cylinder top must be a finite number, got nan");
    ("(cylinder (base 0 0 5) (top 0 1 5) (radius 1) (cap true) (color 1 2 3))",
     "t.scene:1:48: unknown cylinder field cap; expected base, top, radius, capped, material, color, specular, reflective, transparency, refractive-index, fresnel, pattern or texture");
    ("(disk (center 0 0 5) (normal 0 0 0) (radius 1) (color 1 2 3))", "t.scene:1:1: disk normal must not be zero, got (0 0 0)");
    ("(disk (center 0 0 5) (normal 0 1 0) (radius 0) (color 1 2 3))", "t.scene:1:1: disk radius must be > 0, got 0");
    ("(csg union (sphere (center 0 0 5) (radius 1) (color 1 1 1))\n  (cylinder (base 0 0 5) (top 0 1 5) (radius 1) (capped false) (color 1 2 3)))",
     "t.scene:2:3: csg: a cylinder without its caps (capped false) is not a closed solid; " ^ operands);
    ("(csg union (disk (center 0 0 5) (normal 0 1 0) (radius 1) (color 1 2 3)) (sphere (center 0 0 5) (radius 1) (color 1 1 1)))",
     "t.scene:1:12: csg: a disk is not a closed solid; " ^ operands);
  ]

let bad_forms_located () =
  List.iter (fun (text, expected) -> Alcotest.(check string) text expected (error text)) bad_forms;
  (* Built in code, the same refusals. *)
  let open_tube = Cylinder.v ~capped:false ~base:Vec3.zero ~top:Vec3.oy ~radius:1. white in
  let csg = Csg.v Csg.Union (Csg.Primitive (Private.Shape_desc.Primitive (Cylinder.desc, open_tube))) (Csg.Sphere (Sphere.v ~center:Vec3.zero ~radius:1. white)) in
  match Shape.validate (Shape.Csg csg) with
  | Ok _ -> Alcotest.fail "an open cylinder validated as a CSG operand"
  | Error (`Msg m) -> Alcotest.(check string) "in code" "csg: a cylinder without its caps (capped false) is not a closed solid" m

let cli_refuses () =
  let dir = Helpers.temp_dir () in
  let scene = Filename.concat dir "bad.scene" and out = Filename.concat dir "out.ppm" in
  let oc = open_out scene in
  output_string oc "(canvas (width 8) (height 8))\n(disk (center 0 0 5) (normal 0 0 0) (radius 1) (color 1 2 3))\n";
  close_out oc;
  let code, stdout, stderr = Helpers.run (Helpers.raytrace ()) [ "render"; scene; "-o"; out ] in
  Alcotest.(check int) "exit status" 1 code;
  Alcotest.(check string) "nothing on stdout" "" stdout;
  Alcotest.(check string) "one line" (Printf.sprintf "raytrace: %s:2:1: disk normal must not be zero, got (0 0 0)\n" scene) stderr;
  Alcotest.(check bool) "no output file" false (Sys.file_exists out)

(* {1 The kernel against the oracle} *)

let small (s : Scene.t) = Scene.with_overrides ~width:100 ~height:75 s

(* Random cylinders (capped and open), disks and their CSG, of random
   materials (mirrors, glass, checkers), around a floor. *)
let random_scene ?(crowd = false) seed =
  let rand = Random.State.make [| 26; seed; Bool.to_int crowd |] in
  let f lo hi = lo +. Random.State.float rand (hi -. lo) in
  let point () = Vec3.v (f (-2.) 2.) (f (-1.) 1.) (f 3.5 7.) in
  let material () =
    let color = Color.v (f 20. 255.) (f 20. 255.) (f 20. 255.) in
    match Random.State.int rand 4 with
    | 0 -> Material.v ~specular:(f 0. 500.) ~reflective:(f 0. 0.5) color
    | 1 -> Material.v ~specular:100. ~transparency:0.8 ~refractive_index:1.5 ~fresnel:true color
    | 2 -> Material.v ~pattern:(Pattern.checker ~size:(f 0.1 0.5) (Color.v 30. 30. 30.)) color
    | _ -> Material.v color
  in
  let shape () =
    match Random.State.int rand 4 with
    | 0 | 1 ->
        let base = point () in
        cylinder ~capped:(Random.State.bool rand) ~base ~top:(Vec3.add base (Vec3.smul (f 0.3 1.5) (random_unit rand))) ~radius:(f 0.1 0.6) (material ())
    | 2 -> disk ~center:(point ()) ~normal:(random_unit rand) ~radius:(f 0.2 1.) (material ())
    | _ ->
        let c = point () in
        let tube = Cylinder.v ~base:(Vec3.sub c (Vec3.v 0. 1. 0.)) ~top:(Vec3.add c (Vec3.v 0.1 1. 0.)) ~radius:(f 0.1 0.4) (material ()) in
        let b = Box.v ~min:(Vec3.sub c (Vec3.v 0.5 0.5 0.5)) ~max:(Vec3.add c (Vec3.v 0.5 0.5 0.5)) (material ()) in
        let op = match Random.State.int rand 3 with 0 -> Csg.Union | 1 -> Csg.Intersection | _ -> Csg.Difference in
        Shape.Csg (Csg.v op (Csg.Box b) (Csg.Primitive (Private.Shape_desc.Primitive (Cylinder.desc, tube))))
  in
  let floor = Shape.Plane (Plane.v ~point:(Vec3.v 0. (-1.2) 0.) ~normal:Vec3.oy (Material.v ~specular:10. (Color.v 200. 200. 200.))) in
  Helpers.scene ~width:60 ~height:45 ~depth:3 ~spheres:[] ~shapes:(floor :: List.init (if crowd then 25 + Random.State.int rand 20 else 2 + Random.State.int rand 4) (fun _ -> shape ()))
    ~lights:[ Light.ambient 0.2; Light.point 0.6 (Vec3.v 2. 4. 0.); Light.directional 0.2 (Vec3.v (-1.) 4. (-2.)) ]
    ()

let as_the_oracle () =
  List.iter
    (fun name ->
      let s = small (Helpers.load_scene name) in
      Helpers.check_images ~min_share:0.999 name ~expected:(Private.Literal.render (Helpers.valid s)) (Helpers.image_exn s);
      Helpers.check_images (name ^ ", skips off") ~expected:(Helpers.image_exn s) (Helpers.image_exn ~skips:false s))
    [ "cylinder.scene"; "disk.scene" ];
  (* Crowds (more than [Prepared.bvh_threshold] objects) are traced
     through the hierarchy, built on the kinds' bounds; without the skips,
     every object is tested: the same bytes. *)
  for seed = 1 to 50 do
    let crowd = seed > 40 in
    let s = random_scene ~crowd seed in
    let what = Printf.sprintf "random scene %d%s" seed (if crowd then " (a crowd)" else "") in
    Helpers.check_images ~min_share:0.995 what ~expected:(Private.Literal.render (Helpers.valid s)) (Helpers.image_exn s);
    Helpers.check_images (what ^ ", skips off") ~expected:(Helpers.image_exn s) (Helpers.image_exn ~skips:false s);
    Helpers.check_images (what ^ ", 2 jobs") ~expected:(Helpers.image_exn s) (Helpers.image_exn ~jobs:2 s)
  done

(* {1 Both sides, bounds, allocation} *)

(* Seen from inside, an open tube shows its inner wall, lit from inside;
   a disk seen from behind is lit from behind. *)
let both_sides () =
  let red = Material.v (Color.v 255. 0. 0.) in
  let look shapes light =
    let s = Helpers.scene ~width:9 ~height:9 ~spheres:[] ~shapes ~lights:[ light ] () in
    let tr = Trace.create (Helpers.prepare s) in
    Trace.pixel tr 0 0;
    (Trace.hit_object tr, Trace.red tr)
  in
  (* The camera inside a tube along the view, the light on its axis: a
     ray to the side meets the inner wall, lit; along the axis, an open
     tube shows nothing, a capped one its far cap's inner side. *)
  let inside shapes light col =
    let s = Helpers.scene ~width:9 ~height:9 ~spheres:[] ~shapes ~lights:[ light ] () in
    let tr = Trace.create (Helpers.prepare s) in
    Trace.pixel tr col 0;
    (Trace.hit_object tr, Trace.red tr)
  in
  let light = Light.point 1. (Vec3.v 0. 0. 2.) in
  let tube capped = cylinder ~capped ~base:(Vec3.v 0. 0. (-1.)) ~top:(Vec3.v 0. 0. 10.) ~radius:1. red in
  let k, r = inside [ tube false ] light 4 in
  Alcotest.(check int) "the tube's inner wall is seen from inside" 0 k;
  if r < 100. then Alcotest.failf "the inner wall lit from the axis: red %g" r;
  Alcotest.(check int) "along the axis, an open tube shows nothing" (-1) (fst (inside [ tube false ] light 0));
  let k, r = inside [ tube true ] light 0 in
  Alcotest.(check int) "along the axis, a capped one its far cap" 0 k;
  if r < 1. then Alcotest.failf "the far cap lit from inside: red %g" r;
  List.iter
    (fun normal ->
      let d = disk ~center:(Vec3.v 0. 0. 3.) ~normal ~radius:1. red in
      let k, r = look [ d ] (Light.point 1. Vec3.zero) in
      Alcotest.(check int) "the disk is hit" 0 k;
      Alcotest.(check (float 1e-9)) (Printf.sprintf "lit from the camera's side, normal %s" (Vec3.show normal)) 255. r)
    [ Vec3.v 0. 0. (-1.); Vec3.v 0. 0. 1. ]

(* Along axis [i], a circle of radius [r] across [n] reaches
   [r sqrt ((|n|^2 - n_i^2) / |n|^2)] from its centre: a bound [b] on
   that side holds it iff [(b - c_i)^2 |n|^2 >= r^2 (|n|^2 - n_i^2)],
   decided exactly. *)
let holds_rim ~r ~n ~centre ~bound i =
  let pick (x, y, z) = if i = 0 then x else if i = 1 then y else z in
  let gap = Q.sub (q bound) (q centre) in
  let n2 = dot n n in
  Q.(geq (mul (mul gap gap) n2) (mul (mul (of_float r) (of_float r)) (sub n2 (mul (pick n) (pick n)))))

let bounded () =
  let rand = Random.State.make [| 7 |] in
  let check what ~r ~n ~ends (lo : Vec3.t) (hi : Vec3.t) =
    List.iteri
      (fun i (l, h) ->
        List.iter
          (fun (e : Vec3.t) ->
            let c = if i = 0 then e.x else if i = 1 then e.y else e.z in
            if not (l <= c && c <= h && holds_rim ~r ~n ~centre:c ~bound:l i && holds_rim ~r ~n ~centre:c ~bound:h i) then
              Alcotest.failf "%s: its rim about %s passes its bounds %s %s on axis %d" what (Vec3.show e) (Vec3.show lo)
                (Vec3.show hi) i)
          ends)
      [ (lo.x, hi.x); (lo.y, hi.y); (lo.z, hi.z) ]
  in
  for _ = 1 to 3000 do
    let c, _ = cylinder_case rand in
    let d, _ = disk_case rand in
    let lo, hi = Cylinder.desc.bounds c in
    check (Cylinder.show c) ~r:c.radius ~n:(sub (qv c.top) (qv c.base)) ~ends:[ c.base; c.top ] lo hi;
    let lo, hi = Disk.desc.bounds d in
    check (Disk.show d) ~r:d.radius ~n:(qv d.normal) ~ends:[ d.center ] lo hi
  done;
  (* Along an axis, a cylinder ends at its caps and a disk is flat, to an ulp. *)
  let lo, hi = Cylinder.desc.bounds (Cylinder.v ~base:(Vec3.v 0. 1. 0.) ~top:(Vec3.v 0. 3. 0.) ~radius:1. white) in
  Alcotest.(check (pair (float 0.) (float 0.))) "a cylinder along y: its caps" (Float.pred 1., Float.succ 3.) (lo.y, hi.y);
  let lo, hi = Disk.desc.bounds (Disk.v ~center:(Vec3.v 0. (-1.) 0.) ~normal:(Vec3.v 0. 2. 0.) ~radius:1. white) in
  Alcotest.(check (pair (float 0.) (float 0.))) "a disk across y: flat" (Float.pred (-1.), Float.succ (-1.)) (lo.y, hi.y)

let allocates_nothing () =
  List.iter
    (fun name ->
      match Helpers.render (Scene.with_overrides ~width:80 ~height:60 (Helpers.load_scene name)) with
      | Ok (_, stats) -> Alcotest.(check (float 0.)) (name ^ ": minor words") 0. stats.minor_words
      | Error (`Msg m) -> Alcotest.fail m)
    [ "cylinder.scene"; "disk.scene" ]

(* The cylinder scene, scaled and moved, is the same picture. *)
let invariant () =
  List.iter
    (fun name ->
      let base = Scene.with_overrides ~width:64 ~height:48 (Helpers.load_scene name) in
      let expected = Helpers.image_exn (Test_numerics.transform ~scale:1. ~translate:Vec3.zero base) in
      List.iter
        (fun (scale, translate) ->
          let what = Printf.sprintf "%s scaled by %g, moved by %s" name scale (Vec3.show translate) in
          Helpers.check_images ~min_share:0.999 what ~expected (Helpers.image_exn (Test_numerics.transform ~scale ~translate base)))
        [ (1e-6, Vec3.zero); (1e6, Vec3.zero); (1., Vec3.v 1e6 0. 0.); (1., Vec3.v (-1e6) 1e6 (-1e6)) ])
    [ "cylinder.scene"; "disk.scene" ]

(* {1 Promises at the boundaries, exact in floats} *)

let roots shape origin direction = Shape.roots shape ~origin ~direction
let pair = Alcotest.(pair (float 0.) (float 0.))

(* The kernel's normal for the root [t] of the ray, as [Surface] asks it. *)
let hit_normal shape origin direction t =
  let g = Array.make Private.Kind.stride 0. and sc = Private.Scratch.create () in
  let (Private.Shape_desc.Primitive (d, x)) = match shape with Shape.Primitive p -> p | _ -> assert false in
  d.store x g 0;
  Private.Scratch.set_ray sc origin direction;
  sc.near <- t;
  let p = Vec3.add origin (Vec3.smul t direction) in
  sc.px <- p.x;
  sc.py <- p.y;
  sc.pz <- p.z;
  Private.Kind_dispatch.normal d.kind sc g 0;
  Vec3.v sc.nx sc.ny sc.nz

let boundaries () =
  let v = Vec3.v in
  (* The cylinder of axis z from 0 to 2, radius 1, capped and open. *)
  let capped = cylinder ~base:Vec3.zero ~top:(v 0. 0. 2.) ~radius:1. white in
  let tube = cylinder ~capped:false ~base:Vec3.zero ~top:(v 0. 0. 2.) ~radius:1. white in
  Alcotest.check pair "along the axis, capped: the caps" (1., 3.) (roots capped (v 0.5 0. (-1.)) Vec3.oz);
  Alcotest.check pair "along the axis, open: nothing" (infinity, infinity) (roots tube (v 0.5 0. (-1.)) Vec3.oz);
  Alcotest.check pair "across, capped: the side twice" (4., 6.) (roots capped (v (-5.) 0. 1.) Vec3.ox);
  Alcotest.check pair "across, open: the same" (4., 6.) (roots tube (v (-5.) 0. 1.) Vec3.ox);
  Alcotest.check pair "from inside, open: behind and ahead" (-1., 1.) (roots tube (v 0. 0. 1.) Vec3.ox);
  Alcotest.check pair "tangent to the side: a double root" (5., 5.) (roots capped (v 1. (-5.) 1.) Vec3.oy);
  Alcotest.check pair "just outside the side: a miss" (infinity, infinity)
    (roots capped (v (Float.succ 1.) (-5.) 1.) Vec3.oy);
  Alcotest.check pair "in a cap's plane, within the radius: the whole chord" (4., 6.) (roots capped (v (-5.) 0. 2.) Vec3.ox);
  Alcotest.check pair "just above the top cap: a miss" (infinity, infinity)
    (roots capped (v (-5.) 0. (Float.succ 2.)) Vec3.ox);
  (* The open tube: a slanted ray in through the bottom opening, out
     through the side: one crossing, as both roots. *)
  Alcotest.check pair "open, in through an end: the side's crossing alone" (2., 2.)
    (roots tube (v 0. 0. (-1.)) (v 0.5 0. 0.5));
  (* Through the rim of the top cap, from above at 45 degrees: the root
     is the cap's and the side's at once; entering, the cap decides
     (its slab is entered last), so the normal is the cap's. *)
  let o = v 0. 0. 3. and d = v 1. 0. (-1.) in
  Alcotest.check pair "through the top rim: touching at one point" (1., 1.) (roots capped o d);
  Alcotest.check Helpers.vec3 "a root on a cap gets the cap's normal" (v 0. 0. (-1.))
    (hit_normal capped (v 0.5 0. (-1.)) Vec3.oz 1.);
  Alcotest.check Helpers.vec3 "and the far cap's on the way out" (v 0. 0. 1.) (hit_normal capped (v 0.5 0. (-1.)) Vec3.oz 3.);
  Alcotest.check Helpers.vec3 "a root on the side gets the side's" (v (-1.) 0. 0.) (hit_normal capped (v (-5.) 0. 1.9) Vec3.ox 4.);
  Alcotest.check Helpers.vec3 "a point alone: the nearest surface" (v 0. 0. 1.) (Shape.normal capped (v 0.5 0. 1.96875));
  Alcotest.check Helpers.vec3 "an open tube's point alone: the side" (v 1. 0. 0.) (Shape.normal tube (v 1. 0. 1.96875));
  (* The disk of radius 1 about (0, 0, 5), facing -z. *)
  let d = disk ~center:(v 0. 0. 5.) ~normal:(v 0. 0. (-4.)) ~radius:1. white in
  Alcotest.check pair "through the centre" (5., 5.) (roots d Vec3.zero Vec3.oz);
  Alcotest.check pair "through the rim: a hit" (5., 5.) (roots d (v 1. 0. 0.) Vec3.oz);
  Alcotest.check pair "just past the rim: a miss" (infinity, infinity) (roots d (v (Float.succ 1.) 0. 0.) Vec3.oz);
  Alcotest.check pair "in its plane: a miss" (infinity, infinity) (roots d (v (-3.) 0. 5.) Vec3.ox);
  Alcotest.check pair "from behind" (5., 5.) (roots d (v 0. 0. 10.) (Vec3.neg Vec3.oz));
  Alcotest.check Helpers.vec3 "its unit normal, as given" (v 0. 0. (-1.)) (Shape.normal d (v 0. 0. 5.))

let tests =
  [
    Alcotest.test_case "a cylinder's roots lie within 16 u S of its surface, and hit or miss as the exact line, at scales 1e-6..1e6"
      `Quick cylinder_accuracy;
    Alcotest.test_case "a disk's root lies within 16 u S of its plane, and hits or misses as the exact line, at scales 1e-6..1e6"
      `Quick disk_accuracy;
    Alcotest.test_case "a cylinder or disk 1e7 times smaller than its distance is its exact silhouette, translated by 1e6 too" `Quick far_silhouettes;
    Alcotest.test_case "cylinders, a tube's inside and disks never shadow themselves, at scales 1e-6..1e6 and moved by 1e6, with no scene-scale constant" `Quick no_self_shadowing;
    Alcotest.test_case "the cylinder and disk forms read with capped true by default, and print as they read" `Quick reads_and_prints;
    Alcotest.test_case "bad cylinder and disk forms, and open ones as CSG operands, are refused with located messages" `Quick bad_forms_located;
    Alcotest.test_case "raytrace render refuses a bad disk: one located line, status 1, no output file" `Quick cli_refuses;
    Alcotest.test_case "the example scenes and random scenes of cylinders, tubes, disks, glass, checkers and CSG render as the oracle does" `Quick as_the_oracle;
    Alcotest.test_case "an open tube shows its inner wall, a disk both its sides, each lit on the side seen" `Quick both_sides;
    Alcotest.test_case "a cylinder's and a disk's bounds hold their rims, in exact arithmetic, and are tight along an axis" `Quick bounded;
    Alcotest.test_case "rays along the axis, across it, tangent, in a cap's plane, through the rim, and a disk's rim and plane: the roots and normals promised" `Quick boundaries;
    Alcotest.test_case "tracing cylinders and disks allocates nothing per pixel" `Quick allocates_nothing;
    Alcotest.test_case "the cylinder and disk scenes are the same picture scaled by 1e-6 and 1e6 and moved by 1e6" `Quick invariant;
  ]
