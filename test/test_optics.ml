(* Transparency, refraction, Fresnel and the ray tree: the optics of
   Snell's law by hand-computed cases, invisible objects byte for byte,
   shadows through glass, the tree's exact early stop, the oracle, and
   the edge seen through a glass slab where Snell's law puts it. *)
open Raytrace

let ok = function Ok x -> x | Error (`Msg m) -> Alcotest.fail m

(* [Ray_tree.split] on a ray [d] and a normal [n] facing it, from index
   [n1] to [n2]: the transmitted direction and the reflectance. *)
let split ?(fresnel = false) n1 n2 (d : Vec3.t) (n : Vec3.t) =
  let io = Array.make Ray_tree.optics_size nan in
  List.iteri (fun i x -> io.(i) <- x) [ n1; n2; d.x; d.y; d.z; n.x; n.y; n.z ];
  Ray_tree.split io ~fresnel;
  (Vec3.v io.(8) io.(9) io.(10), io.(11))

let near = Helpers.float_near 1e-12
let up = Vec3.oy

(* The invisible objects added to a scene: transparency 1, index 1. *)
let invisible_ball center radius =
  Helpers.sphere ~specular:40. ~transparency:1. ~center ~radius (Color.v 10. 200. 30.)

let invisible m = Material.v ~specular:10. ~transparency:1. m

let small (s : Scene.t) = Scene.with_overrides ~width:64 ~height:48 s

(* The camera's forward direction: the third column of its rotation. *)
let forward (c : Camera.t) = Camera.direction c (Vec3.v 0. 0. 1.)

let has_glass (s : Scene.t) =
  Private.Spheres.exists (fun (sp : Sphere.t) -> sp.material.transparency > 0.) (Scene.spheres s)
  || List.exists (fun sh -> List.exists (fun (m : Material.t) -> m.transparency > 0.) (Shape.materials sh)) (Scene.shapes s)

(* [s] with [f] applied to every material. *)
let map_materials ~sphere ~material (s : Scene.t) =
  let shape = function
    | Shape.Sphere sp -> Shape.Sphere (sphere sp)
    | Shape.Plane p -> Shape.Plane (Plane.v ~point:p.point ~normal:p.normal (material p.material))
    | Shape.Triangle t -> Shape.Triangle (Triangle.v t.v0 t.v1 t.v2 (material t.material))
    | Shape.Box b -> Shape.Box (Box.v ~min:b.min ~max:b.max (material b.material))
    | Shape.Primitive p -> Shape.Primitive (Shape_kinds.map_primitive ~point:Fun.id ~length:Fun.id ~material p)
    | (Shape.Mesh _ | Shape.Csg _ | Shape.Instance _) as sh -> sh (* no mesh, CSG or instance in the scenes changed here *)
  in
  Scene.with_overrides ~objects:(List.map shape (Scene.objects s)) s

let opaque_material (m : Material.t) = Material.update ~transparency:0. m

(* [s] without its glass: every transparency 0. *)
let opaque = map_materials ~sphere:(fun sp -> Helpers.with_sphere_material sp opaque_material) ~material:opaque_material

(* Every object of [s] glass: transparency as the reflectivity allows. *)
let all_glass =
  let glass r t = if r +. t > 1. then 1. -. r else t in
  map_materials
    ~sphere:(fun sp ->
      Helpers.with_sphere_material sp (fun m ->
          Material.update ~transparency:(glass m.reflective 0.8) ~refractive_index:1.33 m))
    ~material:(fun m -> Material.update ~transparency:(glass m.reflective 0.8) ~refractive_index:1.5 m)

let glass_scenes = QCheck.map ~rev:Fun.id all_glass Gen_scene.arbitrary

(* Same bytes, or the first differing pixel. *)
let same what ~expected img = Helpers.check_images ~max_abs:0 what ~expected img

(* Column of the first pixel of row [y] brighter than 128 (red). *)
let first_bright (img : Image.t) y =
  let rec go x = if x >= Image.width img then -1 else
      let r, _, _ = Image.get img x y in
      if r > 128 then x else go (x + 1)
  in
  go 0

let tests =
  [
    Alcotest.test_case "Snell's law: straight through at normal incidence, sin t = sin i / 1.5 at 45 degrees"
      `Quick (fun () ->
        let t, r = split 1. 1.5 (Vec3.v 0. 0. 2.) (Vec3.v 0. 0. (-1.)) in
        Alcotest.check (Helpers.vec3_near 1e-12) "normal incidence" (Vec3.v 0. 0. 1.) t;
        Alcotest.check near "no reflectance without fresnel" 0. r;
        (* d = (1, 0, 1) / sqrt 2: sin i = 0.70710678; sin t = 0.70710678 / 1.5
           = 0.47140452, cos t = sqrt (1 - 0.2222222) = 0.88191710. *)
        let t, _ = split 1. 1.5 (Vec3.v 1. 0. 1.) (Vec3.v 0. 0. (-1.)) in
        Alcotest.check near "sin t" 0.47140452079103173 t.x;
        Alcotest.check near "cos t" 0.88191710368819687 t.z;
        Alcotest.check near "unit length" 1. (Vec3.norm t));
    Alcotest.test_case "total internal reflection past the critical angle, and at it" `Quick (fun () ->
        (* From 1.5 to 1 the critical angle has sin c = 1 / 1.5; at 45
           degrees sin i = 0.7071 > 0.6667: all is reflected, R = 1. *)
        let _, r = split 1.5 1. (Vec3.v 1. 0. 1.) (Vec3.v 0. 0. (-1.)) in
        Alcotest.check near "45 degrees" 1. r;
        (* Exactly at the critical angle (n1 = 2, n2 = 1, 30 degrees:
           sin i = 1/2, eta^2 sin^2 i = 4 * 1/4 = 1, exact in floats with
           d = (1, 0, sqrt 3)). *)
        let _, r = split 2. 1. (Vec3.v 0.5 0. (sqrt 3. /. 2.)) (Vec3.v 0. 0. (-1.)) in
        Alcotest.(check bool) "critical angle: finite" true (Float.is_finite r);
        (* Just below it the ray gets through, nearly grazing, finite. *)
        let t, r = split 2. 1. (Vec3.v 0.49 0. (sqrt (1. -. (0.49 *. 0.49)))) (Vec3.v 0. 0. (-1.)) in
        Alcotest.(check bool) "below the critical angle: transmitted" true (r < 1.);
        Alcotest.(check bool) "finite" true (Float.is_finite (Vec3.norm t)));
    Alcotest.test_case "grazing incidence gives finite directions, with and without Fresnel" `Quick (fun () ->
        (* d along the surface: cos i = 0 (and a hair below 0, by rounding). *)
        List.iter
          (fun (n1, n2, d) ->
            List.iter
              (fun fresnel ->
                let t, r = split ~fresnel n1 n2 d (Vec3.v 0. 0. (-1.)) in
                if not (Float.is_finite r && r >= 0. && r <= 1.) then Alcotest.failf "R = %.17g, not in [0, 1]" r;
                if r < 1. && not (Float.is_finite (Vec3.norm t)) then Alcotest.fail "direction not finite")
              [ false; true ])
          [ (1., 1.5, Vec3.v 1. 0. 0.); (1.5, 1., Vec3.v 1. 0. 0.); (1., 1.5, Vec3.v 1. 0. 1e-300);
            (1., 1.5, Vec3.v 1. 0. (-1e-17)); (1.2, 1.3, Vec3.v 1e-300 0. 1e-300);
            (* A cosine of -1e-15, as rounding leaves a direction that should
               be along the surface: clamped to 0, not 1 - c = 1 + 1e-15 in
               Schlick's (1 - c)^5, which would make R exceed 1. *)
            (1., 1.5, Vec3.v 1. 0. (-1e-15)); (1., 1.5, Vec3.v 1. 0. (-1e-12)) ]);
    Alcotest.test_case "Schlick: R0 = 0.04 from air to 1.5 at normal incidence, 1 at grazing" `Quick (fun () ->
        (* R0 = ((1 - 1.5) / (1 + 1.5))^2 = 0.2^2 = 0.04. *)
        let _, r = split ~fresnel:true 1. 1.5 (Vec3.v 0. 0. 1.) (Vec3.v 0. 0. (-1.)) in
        Alcotest.check near "R0" 0.04 r;
        let _, r = split ~fresnel:true 1. 1.5 (Vec3.v 1. 0. 0.) (Vec3.v 0. 0. (-1.)) in
        Alcotest.check near "grazing" 1. r;
        (* Equal indices: no interface, no reflection, the same ray. *)
        let t, r = split ~fresnel:true 1.3 1.3 (Vec3.v 3. 1. 0.5) (Vec3.v 0. 0. (-1.)) in
        Alcotest.check near "equal indices" 0. r;
        Alcotest.check Helpers.vec3 "unchanged" (Vec3.v 3. 1. 0.5) t);
    Alcotest.test_case
      "total internal reflection where the rounded sin^2 t is exactly 1: R = 1, though the exact ray would pass; one \
       float closer to the normal it passes, grazing"
      `Quick (fun () ->
        (* Glass (1.5) to air, the normal (0, 0, -1), d = (x, 0, 1): sin^2 t
           = 2.25 x^2 / (1 + x^2), exactly 1 at x = 2 / sqrt 5. The x below
           is the first float, walking up from below 2 / sqrt 5, at which
           [split]'s own arithmetic (replayed op for op by [rounded_sin2])
           gives exactly 1.0; the float before it gives 1 - 2^-51. The
           exact sin^2 t of this ray is below 1 (5 x^2 < 4, checked with
           Zarith): it is total internal reflection only by rounding, the
           point where ">= 1" and "> 1" part. The interface promises R = 1
           there ("the critical angle included"). *)
        let x = 0x1.c9f25c5bfedd8p-1 in
        let normal = Vec3.v 0. 0. (-1.) in
        let rounded_sin2 x =
          (* [Ray_tree.split]'s operations for d = (x, 0, 1), x < 1: the
             largest coordinate is 1, c = 1 / |d|. *)
          let len = sqrt ((x *. x) +. 0. +. 1.) in
          let c = -.((x *. 0.) +. (0. *. 0.) +. (1. *. -1.)) *. (1. /. len) in
          let eta = 1.5 /. 1. in
          eta *. eta *. ((1. -. c) *. (1. +. c))
        in
        Alcotest.(check (float 0.)) "sin^2 t rounds to exactly 1" 1. (rounded_sin2 x);
        Alcotest.(check bool) "and below 1 one float before" true (rounded_sin2 (Float.pred x) < 1.);
        Alcotest.(check bool) "the exact sin^2 t is below 1 (5 x^2 < 4)" true Q.(lt (mul (of_int 5) (mul (of_float x) (of_float x))) (of_int 4));
        List.iter
          (fun fresnel ->
            let _, r = split ~fresnel 1.5 1. (Vec3.v x 0. 1.) normal in
            Alcotest.(check (float 0.)) (Printf.sprintf "R at the rounding point, fresnel %b" fresnel) 1. r;
            (* One float toward the normal: transmitted, along the surface
               (cos t = sqrt (2^-51) = 2.1e-8), a unit direction. *)
            let t, r = split ~fresnel 1.5 1. (Vec3.v (Float.pred x) 0. 1.) normal in
            if not (r < 1.) then Alcotest.failf "one float before, fresnel %b: R = %h, not transmitted" fresnel r;
            Alcotest.check near "transmitted: unit length" 1. (Vec3.norm t);
            Alcotest.check (Helpers.float_near 1e-9) "transmitted: grazing, cos t = 2.1e-8" (sqrt (ldexp 1. (-51))) t.z;
            Alcotest.check near "transmitted: sin t = 1" 1. t.x;
            (* Schlick with the cosine on the air's side: R = 0.04 + 0.96
               (1 - cos t)^5 = 1 - 4.8 cos t to first order = 1 - 1.0115e-7,
               continuous with the 1 of total reflection; without fresnel,
               no reflection. *)
            if fresnel then
              Alcotest.check (Helpers.float_near 1e-12) "Schlick next to the critical angle" (1. -. (4.8 *. sqrt (ldexp 1. (-51)))) r
            else Alcotest.(check (float 0.)) "no Fresnel: R = 0" 0. r)
          [ false; true ]);
    Alcotest.test_case "grazing refraction into glass: cos i = 0 gives sin t = 1 / 1.5, a unit direction" `Quick
      (fun () ->
        (* d along the surface, n = (0, 0, -1): c = 0, sin^2 t = 1 / 2.25,
           cos t = sqrt (5 / 9) = 0.74535599249992990; the transmitted
           direction is eta d + (eta c - cos t) n = (2/3, 0, cos t). A
           direction a hair away from the surface (c < 0 by rounding or
           by 1e-17) is clamped to c = 0: the same direction. *)
        List.iter
          (fun d ->
            let t, r = split 1. 1.5 d (Vec3.v 0. 0. (-1.)) in
            Alcotest.(check (float 0.)) "no Fresnel: R = 0" 0. r;
            Alcotest.check (Helpers.vec3_near 1e-15) "the transmitted direction" (Vec3.v (2. /. 3.) 0. 0.74535599249992990) t)
          [ Vec3.v 1. 0. 0.; Vec3.v 3. 0. 0.; Vec3.v 1. 0. (-1e-17) ];
        (* Leaving glass at grazing incidence: far past the critical angle. *)
        let _, r = split 1.5 1. (Vec3.v 1. 0. 0.) (Vec3.v 0. 0. (-1.)) in
        Alcotest.(check (float 0.)) "from glass: totally reflected" 1. r);
    Alcotest.test_case "Schlick leaving a denser medium takes the cosine on the air's side: 0.0948 at sin i = 0.6"
      `Quick (fun () ->
        (* From 1.5 to 1, d = (0.6, 0, 0.8), n = (0, 0, -1): cos i = 0.8,
           sin t = 1.5 * 0.6 = 0.9, cos t = sqrt 0.19 = 0.43588989435406733.
           R0 = (0.5 / 2.5)^2 = 0.04, and with the transmitted cosine,
           R = 0.04 + 0.96 (1 - 0.43588989)^5 = 0.0948391396199233 (with
           cos i it would be 0.04 + 0.96 * 0.2^5 = 0.0403072). The
           transmitted direction is (sin t, 0, cos t) = (0.9, 0,
           0.43588989). Entering glass at the same cos i = 0.8, the
           cosine is the incident one: R = 0.0403072. *)
        let t, r = split ~fresnel:true 1.5 1. (Vec3.v 0.6 0. 0.8) (Vec3.v 0. 0. (-1.)) in
        Alcotest.check near "R leaving glass" 0.0948391396199233 r;
        Alcotest.check (Helpers.vec3_near 1e-15) "direction leaving glass" (Vec3.v 0.9 0. 0.43588989435406733) t;
        let _, r = split ~fresnel:true 1. 1.5 (Vec3.v 0.6 0. 0.8) (Vec3.v 0. 0. (-1.)) in
        Alcotest.check near "R entering glass" 0.0403072 r;
        (* At normal incidence both ways: R0. *)
        let _, r = split ~fresnel:true 1.5 1. (Vec3.v 0. 0. 1.) (Vec3.v 0. 0. (-1.)) in
        Alcotest.check near "R0 leaving glass" 0.04 r;
        (* "Any length > 0": d of length 1e-300 or 1e300 (whose squares
           underflow or overflow) gives the same split. *)
        List.iter
          (fun k ->
            let t, r = split ~fresnel:true 1.5 1. (Vec3.smul k (Vec3.v 0.6 0. 0.8)) (Vec3.v 0. 0. (-1.)) in
            Alcotest.check near (Printf.sprintf "R, |d| = %g" k) 0.0948391396199233 r;
            Alcotest.check (Helpers.vec3_near 1e-15) (Printf.sprintf "direction, |d| = %g" k) (Vec3.v 0.9 0. 0.43588989435406733) t)
          [ 1e-300; 1e300; 3. ]);
    Alcotest.test_case "nested media, left one by one: each surface has the indices of the media on its two sides"
      `Quick (fun () ->
        (* Media 0, 1, 2 of indices 1.2, 1.5, 2 nested as shells: the ray
           enters 0, 1, 2 and leaves 2, 1, 0; at each surface the near
           index is the innermost medium's and the far one the next. *)
        let index = [| 1.2; 1.5; 2. |] and media = Array.make Ray_tree.media_cap (-1) in
        let io = Array.make Ray_tree.optics_size 0. in
        let n =
          List.fold_left
            (fun n (id, expected) ->
              Ray_tree.indices index media 0 n id io;
              Alcotest.(check (pair (float 0.) (float 0.))) (Printf.sprintf "crossing %d with %d media" id n) expected (io.(0), io.(1));
              Ray_tree.cross media 0 n id)
            0
            [ (0, (1., 1.2)); (1, (1.2, 1.5)); (2, (1.5, 2.)); (2, (2., 1.5)); (1, (1.5, 1.2)); (0, (1.2, 1.)) ]
        in
        Alcotest.(check int) "no medium left" 0 n;
        (* The same medium twice in the stack (a ray that entered it, then
           another, then it again through a second object of the same
           material): [find] returns the innermost, leaving it uncovers
           the medium under it. *)
        let media = [| 0; 1; 0 |] in
        Alcotest.(check int) "find: the innermost of equal ids" 2 (Ray_tree.find media 0 3 0);
        Alcotest.(check int) "find: absent" (-1) (Ray_tree.find media 0 3 2);
        Ray_tree.indices index media 0 3 0 io;
        Alcotest.(check (pair (float 0.) (float 0.))) "leaving the innermost copy" (1.2, 1.5) (io.(0), io.(1)));
    Alcotest.test_case "a full medium stack takes no more: the ray stays in the innermost kept medium" `Quick (fun () ->
        let cap = Ray_tree.media_cap in
        let media = Array.make cap (-1) in
        let n = ref 0 in
        for id = 0 to cap - 1 do
          n := Ray_tree.cross media 0 !n id
        done;
        Alcotest.(check int) "media_cap is 16" 16 cap;
        Alcotest.(check int) "full" cap !n;
        Alcotest.(check int) "one more is not pushed" cap (Ray_tree.cross media 0 !n cap);
        Alcotest.(check (array int)) "the stack unchanged" (Array.init cap Fun.id) media;
        (* Leaving one in the middle closes the gap, in order. *)
        let n = Ray_tree.cross media 0 cap 5 in
        Alcotest.(check int) "one left" (cap - 1) n;
        Alcotest.(check (array int)) "the others in order" (Array.init (cap - 1) (fun k -> if k < 5 then k else k + 1)) (Array.sub media 0 (cap - 1)));
    Alcotest.test_case "the medium stack: nested media refract by the ratio of their indices" `Quick (fun () ->
        (* Materials 0 (water, 1.33) and 1 (glass, 1.5). *)
        let index = [| 1.33; 1.5 |] and media = Array.make Ray_tree.media_cap 0 in
        let io = Array.make Ray_tree.optics_size 0. in
        let sides n id =
          Ray_tree.indices index media 0 n id io;
          (io.(0), io.(1))
        in
        Alcotest.(check (pair (float 0.) (float 0.))) "air into water" (1., 1.33) (sides 0 0);
        let n = Ray_tree.cross media 0 0 0 in
        Alcotest.(check (pair (float 0.) (float 0.))) "water into glass" (1.33, 1.5) (sides n 1);
        let n = Ray_tree.cross media 0 n 1 in
        Alcotest.(check (pair (float 0.) (float 0.))) "glass back to water" (1.5, 1.33) (sides n 1);
        (* Overlapping: leaving the water while in the glass changes nothing. *)
        Alcotest.(check (pair (float 0.) (float 0.))) "out of water, still in glass" (1.5, 1.5) (sides n 0);
        let n = Ray_tree.cross media 0 n 0 in
        Alcotest.(check int) "the glass alone is left" 1 n;
        Alcotest.(check int) "it is the glass" 1 media.(0);
        Alcotest.(check (pair (float 0.) (float 0.))) "glass to air" (1.5, 1.) (sides n 1));
    Alcotest.test_case "an object of transparency 1 and index 1 is invisible: every scene keeps its bytes" `Quick
      (fun () ->
        List.iter
          (fun name ->
            let s = small (Helpers.load_scene name) in
            let f = forward (Scene.camera s) and o = (Scene.camera s).position in
            let at d = Vec3.add o (Vec3.smul d f) in
            (* Glass scenes: a small ball near the camera, in the air; the
               others: a ball, a box and a plane through everything. *)
            let extra =
              if has_glass s then Helpers.with_objects ~spheres:(invisible_ball (at 1.6) 0.4 :: Helpers.scene_spheres s) s
              else
                let c = at 4. in
                Helpers.with_objects
                  ~spheres:(Helpers.scene_spheres s @ [ invisible_ball c 1.2 ])
                  ~shapes:
                    (Shape.Box (Box.v ~min:(Vec3.sub c (Vec3.v 2. 0.5 0.5)) ~max:(Vec3.add c (Vec3.v 0. 1. 3.)) (invisible Color.white))
                    :: Shape.Plane (Plane.v ~point:c ~normal:(Vec3.v 1. 2. 0.5) (invisible Color.white))
                    :: (Scene.shapes s))
                  s
            in
            List.iter
              (fun (mode, epsilon) ->
                let s = Scene.with_overrides ~epsilon s and extra = Scene.with_overrides ~epsilon extra in
                List.iter
                  (fun skips ->
                    same (Printf.sprintf "%s, %s, skips %b" name mode skips) ~expected:(Helpers.image_exn ~skips s)
                      (Helpers.image_exn ~skips extra))
                  [ true; false ])
              [ ("robust", None); ("epsilon", Some 0.001) ])
          (Helpers.scene_names ()));
    Helpers.qcheck ~count:100 "invisible objects anywhere in random opaque scenes change no byte"
      QCheck.(triple Gen_scene.arbitrary (triple float float float) bool)
      (fun (s, (a, b, c), skips) ->
        let s = opaque s in
        let c = Vec3.v (Float.rem a 3.) (Float.rem b 3.) (5. +. Float.rem c 4.) in
        let c = if Float.is_finite (Vec3.norm c) then c else Vec3.v 0. 0. 5. in
        let extra =
          Helpers.with_objects
            ~spheres:(invisible_ball c 1. :: Helpers.scene_spheres s)
            ~shapes:(Scene.shapes s @ [ Shape.Plane (Plane.v ~point:c ~normal:(Vec3.v 0.3 1. (-0.2)) (invisible Color.white)) ])
            s
        in
        Image.equal (Helpers.image_exn ~skips s) (Helpers.image_exn ~skips extra));
    Helpers.qcheck ~count:100 "an invisible ball around camera and scene changes no byte of random glass scenes"
      Gen_scene.arbitrary (fun s ->
        (* Glass planes cut every sphere around the scene: opaque here. *)
        let s =
          Helpers.with_objects
            ~shapes:
              (List.map
                 (function Shape.Plane p -> Shape.Plane (Plane.v ~point:p.point ~normal:p.normal (opaque_material p.material)) | sh -> sh)
                 (Scene.shapes s))
            s
        in
        let extra = Helpers.with_objects ~spheres:(Helpers.scene_spheres s @ [ invisible_ball (Scene.camera s).position 1000. ]) s in
        Image.equal (Helpers.image_exn s) (Helpers.image_exn extra));
    Alcotest.test_case "a glass ball lets through t^2 of the light, one t per surface" `Quick (fun () ->
        (* The camera looks down at the origin of a white floor lit from
           straight above (directional, intensity 1); the shadow ray from
           the origin goes up through a ball of transparency t at (0, 2, 0),
           radius 0.5, which the camera's ray misses (it passes 1.41 from
           its center). Red = 255 * t^2 * <N, L> = 255 * t^2. *)
        let scene t =
          Helpers.scene ~width:3 ~height:3
            ~camera:(ok (Camera.look_at ~position:(Vec3.v 0. 5. (-5.)) Vec3.zero))
            ~spheres:[ Helpers.sphere ~transparency:t ~refractive_index:1.5 ~center:(Vec3.v 0. 2. 0.) ~radius:0.5 Color.white ]
            ~shapes:[ Shape.Plane (Plane.v ~point:Vec3.zero ~normal:up (Material.v (Color.v 255. 255. 255.))) ]
            ~lights:[ Light.directional 1. up ] ()
        in
        List.iter
          (fun (t, expected) ->
            List.iter
              (fun epsilon ->
                let s = (Scene.with_overrides ~epsilon (scene t)) in
                let tr = Trace.create (Helpers.prepare s) in
                Trace.pixel tr 0 0;
                Alcotest.check (Helpers.float_near 1e-9) (Printf.sprintf "t = %g: fast" t) expected (Trace.red tr);
                Alcotest.check (Helpers.float_near 1e-9) (Printf.sprintf "t = %g: oracle" t) expected
                  (Private.Literal.pixel s 0 0).r)
              [ None; Some 0.001 ])
          [ (0.5, 255. *. 0.25); (0.8, 255. *. 0.8 *. 0.8); (1., 255.); (0., 0.) ]);
    Alcotest.test_case "light through two glass slabs 1e-10 apart is scaled by each of their four faces" `Quick
      (fun () ->
        (* The scene of the test above, the ball replaced by two slabs of
           transparency 0.5 across the shadow ray, [-1, 1] x [2, 3] x [-1, 1]
           and the same from y = 3 + 1e-10 to 4: the shadow ray crosses
           four faces, the middle two 1e-10 apart, and each scales the
           light: red = 255 * 0.5^4 = 15.9375. *)
        let slab lo hi = Shape.Box (Box.v ~min:(Vec3.v (-1.) lo (-1.)) ~max:(Vec3.v 1. hi 1.) (Material.v ~transparency:0.5 ~refractive_index:1.5 Color.white)) in
        List.iter
          (fun epsilon ->
            let s =
              Helpers.scene ~width:3 ~height:3 ?epsilon
                ~camera:(ok (Camera.look_at ~position:(Vec3.v 0. 5. (-5.)) Vec3.zero))
                ~spheres:[]
                ~shapes:[ slab 2. 3.; slab (3. +. 1e-10) 4.; Shape.Plane (Plane.v ~point:Vec3.zero ~normal:up (Material.v (Color.v 255. 255. 255.))) ]
                ~lights:[ Light.directional 1. up ] ()
            in
            let tr = Trace.create (Helpers.prepare s) in
            Trace.pixel tr 0 0;
            Alcotest.check (Helpers.float_near 1e-9) (Printf.sprintf "epsilon %b" (epsilon <> None)) 15.9375 (Trace.red tr))
          [ None; Some 1e-12 ]);
    Alcotest.test_case "one depth for both kinds of ray: at depth 0 glass shows its local colour, as a mirror does"
      `Quick (fun () ->
        (* Ambient light alone: no shadow, which glass lets light through. *)
        let s = (Scene.with_overrides ~lights:([ Light.ambient 1. ]) ((small (Helpers.load_scene "glass.scene")))) in
        let s0 = (Scene.with_overrides ~depth:0 s) in
        same "depth 0" ~expected:(Helpers.image_exn (opaque s0)) (Helpers.image_exn s0);
        (* With depth 1, the refracted rays see the scene behind: not so. *)
        let differ = not (Image.equal (Helpers.image_exn (opaque (Scene.with_overrides ~depth:1 s))) (Helpers.image_exn (Scene.with_overrides ~depth:1 s))) in
        Alcotest.(check bool) "depth 1 sees through" true differ);
    Helpers.qcheck ~count:100 "random glass scenes: switching the skips off changes no byte" glass_scenes (fun s ->
        Image.equal (Helpers.image_exn ~skips:false s) (Helpers.image_exn s)
        && Image.equal (Helpers.image_exn ~skips:false ~samples:3 s) (Helpers.image_exn ~samples:3 s));
    Helpers.qcheck ~count:30 "crowds of glass: switching the skips off changes no byte"
      (QCheck.make ~print:Scene_file.to_string (QCheck.Gen.map all_glass Gen_scene.crowd))
      (fun s -> Image.equal (Helpers.image_exn ~skips:false s) (Helpers.image_exn s));
    Helpers.qcheck ~count:100 "random glass scenes in the document's mode render as the oracle does" glass_scenes
      (fun s ->
        let s = (Scene.with_overrides ~epsilon:(Some 0.001) s) in
        Image.equal (Private.Literal.render (Helpers.valid s)) (Helpers.image_exn s));
    Alcotest.test_case "the glass scenes in the document's mode render as the oracle does, byte for byte" `Quick
      (fun () ->
        (* Smooth glass included: where a corner-interpolated normal would
           bend the ray back, both take the flat normal. *)
        List.iter
          (fun name ->
            let s = (Scene.with_overrides ~epsilon:(Some 0.001) ((Scene.with_overrides ~width:48 ~height:36 (Helpers.load_scene name)))) in
            same name ~expected:(Private.Literal.render (Helpers.valid s)) (Helpers.image_exn s))
          [ "glass.scene"; "glass-knot.scene"; "glass-lens.scene" ]);
    Alcotest.test_case "the tree stops early: deep glass traces fewer rays with the skips, for the same bytes"
      `Quick (fun () ->
        (* A ball that reflects 0.4 and lets through 0.4 between mirror
           walls: most paths weigh less than 1 / max_channel after ten
           bounces. *)
        let s = small (Helpers.load_scene "glass.scene") in
        let mirror = function
          | Shape.Plane p -> Shape.Plane (Plane.v ~point:p.point ~normal:p.normal (Material.update ~reflective:0.6 p.material))
          | sh -> sh
        in
        let glass (b : Sphere.t) =
          if b.material.transparency > 0. then Helpers.with_sphere_material b (Material.update ~transparency:0.4 ~reflective:0.4)
          else b
        in
        let s =
          Helpers.with_objects ~spheres:(List.map glass (Helpers.scene_spheres s)) ~shapes:(List.map mirror (Scene.shapes s))
            (Scene.with_overrides ~depth:24 s)
        in
        (* The estimate bounds the full tree, 2^25 - 1 rays a pixel
           (1.55e12 tests): most paths leave the scene long before. *)
        let limits = Limits.with_bound Limits.default `Work 1e13 in
        let stats skips = match Helpers.render ~limits ~skips s with Ok (img, st) -> (img, st) | Error (`Msg m) -> Alcotest.fail m in
        let img, st = stats true and img_off, st_off = stats false in
        same "bytes" ~expected:img_off img;
        if not (st.early_stops > 0 && st.reflection < st_off.reflection) then
          Alcotest.failf "early stops %d, rays %d with skips, %d without" st.early_stops st.reflection st_off.reflection);
    Alcotest.test_case "tracing glass allocates nothing per pixel" `Quick (fun () ->
        List.iter
          (fun name ->
            List.iter
              (fun epsilon ->
                let s = (Scene.with_overrides ~epsilon (small (Helpers.load_scene name))) in
                match Helpers.render s with
                | Ok (_, st) -> Alcotest.(check (float 0.)) name 0. st.minor_words
                | Error (`Msg m) -> Alcotest.fail m)
              [ None; Some 0.001 ])
          [ "glass.scene"; "glass-knot.scene"; "glass-lens.scene" ]);
    Alcotest.test_case "rays grazing glass and rays past the critical angle give finite colours" `Quick (fun () ->
        (* Pixel column 0 of the canvas looks along x = 0: tangent to the
           balls of center x = +-1, radius 1, and along the face x = 0 of
           the box. Inside the dense ball, rays meet its surface past the
           critical angle (sin c = 1/2.4). *)
        let glass = Helpers.sphere ~transparency:0.9 ~refractive_index:2.4 ~fresnel:true Color.white in
        let scene epsilon =
          Helpers.scene ~width:41 ~height:41 ?epsilon ~depth:8
            ~spheres:[ glass ~center:(Vec3.v 1. 0. 5.) ~radius:1.; glass ~center:(Vec3.v (-1.) 0.5 7.) ~radius:1. ]
            ~shapes:
              [
                Shape.Box (Box.v ~min:(Vec3.v 0. (-3.) 9.) ~max:(Vec3.v 2. (-1.) 10.) (Material.v ~transparency:1. ~refractive_index:1.7 Color.white));
                Shape.Plane (Plane.v ~point:(Vec3.v 0. (-2.) 0.) ~normal:up (Material.v ~reflective:0.5 ~transparency:0.5 ~refractive_index:0.7 (Color.v 200. 100. 50.)));
              ]
            ~lights:[ Light.ambient 0.2; Light.point 0.6 (Vec3.v 0. 0. 5.); Light.directional 0.3 (Vec3.v 1. 1. (-1.)) ] ()
        in
        List.iter
          (fun epsilon ->
            let s = scene epsilon in
            let tr = Trace.create (Helpers.prepare s) in
            for gx = Canvas.min_x 41 to Canvas.max_x 41 do
              for gy = Canvas.min_y 41 to Canvas.max_y 41 do
                Trace.pixel tr gx gy;
                if not (Float.is_finite (Trace.red tr) && Float.is_finite (Trace.green tr) && Float.is_finite (Trace.blue tr))
                then Alcotest.failf "pixel (%d, %d) is not finite" gx gy
              done
            done;
            if not (Color.is_finite (Private.Literal.pixel s 0 0)) then Alcotest.fail "the oracle is not finite")
          [ None; Some 0.001 ]);
    Alcotest.test_case
      "nested glass slabs, the inner left before the outer: the edge behind them is where Snell's law puts it with \
       each medium's index"
      `Quick (fun () ->
        (* The camera at the origin looks along z; an outer slab of index
           1.2 fills 2 <= z <= 20, an inner one of index 1.5 (inside it in
           x and y too) 6 <= z <= 16; a red wall at z = 22 begins at x = 6.
           (Not from z = 1: that is the viewport, where camera rays start,
           t_min = 1, and a surface there is not seen.) The ray of angle a
           reaches x = 4 tan a + 8 tan b1 + 10 tan b2 at z = 22, sin bk =
           sin a / nk: in air (2 + 2), inside the outer slab on both sides
           of the inner one (4 + 4), inside the inner one (10). The ray
           leaving the inner slab must be given 1.5 -> 1.2, then 1.2 -> 1
           leaving the outer one; a wrong index on either surface moves
           the edge by several pixels (a ray leaving the inner slab into
           air: column 535.4 instead of 541.4). *)
        let width = 801 and vw = 2. in
        let glass ~lo ~hi ~half n =
          Shape.Box (Box.v ~min:(Vec3.v (-.half) (-.half) lo) ~max:(Vec3.v half half hi) (Material.v ~transparency:1. ~refractive_index:n Color.white))
        in
        let wall = Shape.Box (Box.v ~min:(Vec3.v 6. (-80.) 22.) ~max:(Vec3.v 90. 80. 22.001) (Material.v (Color.v 255. 0. 0.))) in
        let scene ~outer ~inner epsilon =
          Helpers.scene ~width ~height:3 ?epsilon ~viewport:(Viewport.v ~width:vw ~height:(3. *. vw /. float width) ~distance:1.) ~depth:6
            ~shapes:[ glass ~lo:2. ~hi:20. ~half:60. outer; glass ~lo:6. ~hi:16. ~half:50. inner; wall ] ~spheres:[] ~lights:[ Light.ambient 1. ] ()
        in
        let x_at u =
          let sin_a = u /. sqrt (1. +. (u *. u)) in
          let tan_in n = let s = sin_a /. n in s /. sqrt (1. -. (s *. s)) in
          (4. *. u) +. (8. *. tan_in 1.2) +. (10. *. tan_in 1.5)
        in
        let rec solve lo hi k = if k = 0 then (lo +. hi) /. 2. else
            let mid = (lo +. hi) /. 2. in
            if x_at mid < 6. then solve mid hi (k - 1) else solve lo mid (k - 1)
        in
        (* Column c looks at tan a = (c - 400) vw / 801. *)
        let column u = 400. +. (u *. float width /. vw) in
        let expected = column (solve 0. 1. 80) in
        List.iter
          (fun epsilon ->
            let plain = first_bright (Helpers.image_exn (scene ~outer:1. ~inner:1. epsilon)) 1 in
            if Float.abs (Float.of_int plain -. column (6. /. 22.)) > 1. then
              Alcotest.failf "without bending the edge is at column %d, not %.2f" plain (column (6. /. 22.));
            let bent = first_bright (Helpers.image_exn (scene ~outer:1.2 ~inner:1.5 epsilon)) 1 in
            if Float.abs (Float.of_int bent -. expected) > 1. then
              Alcotest.failf "the edge is at column %d; Snell's law puts it at %.2f" bent expected)
          [ None; Some 0.001 ]);
    Alcotest.test_case "the edge seen through a glass slab at an angle is where Snell's law puts it" `Quick
      (fun () ->
        (* The camera at the origin looks along z through a slab of glass
           (index 1.5, transparency 1) between z = 3 and z = 7; behind it, at
           z = 10, a red wall begins at x = X0 = 2. Without the slab its edge
           is seen at tan a = 0.2, 80.2 pixels right of the center (401 pixels
           across a viewport 1 wide at distance 1; the wall is 0.001 thick, so
           that its side is not seen). Through the slab, the ray
           of angle a reaches x = 6 tan a + 4 tan b at z = 10, with
           sin b = sin a / 1.5: the edge is where that is X0, solved by
           bisection. *)
        let width = 401 in
        let wall = Shape.Box (Box.v ~min:(Vec3.v 2. (-50.) 10.) ~max:(Vec3.v 60. 50. 10.001) (Material.v (Color.v 255. 0. 0.))) in
        let slab n = Shape.Box (Box.v ~min:(Vec3.v (-50.) (-50.) 3.) ~max:(Vec3.v 50. 50. 7.) (Material.v ~transparency:1. ~refractive_index:n Color.white)) in
        let scene n epsilon = Helpers.scene ~width ~height:3 ?epsilon ~viewport:(Viewport.v ~width:1. ~height:(3. /. 401.) ~distance:1.) ~depth:4 ~shapes:[ slab n; wall ] ~spheres:[] ~lights:[ Light.ambient 1. ] () in
        let x_at u =
          let sin_a = u /. sqrt (1. +. (u *. u)) in
          let sin_b = sin_a /. 1.5 in
          (6. *. u) +. (4. *. sin_b /. sqrt (1. -. (sin_b *. sin_b)))
        in
        let rec solve lo hi k = if k = 0 then (lo +. hi) /. 2. else
            let mid = (lo +. hi) /. 2. in
            if x_at mid < 2. then solve mid hi (k - 1) else solve lo mid (k - 1)
        in
        let u = solve 0. 1. 80 in
        (* Pixel column c looks at tan a = (c - 200) / 401: the edge is
           between columns, the first red one within 1 of it. *)
        let column u = 200. +. (u *. 401.) in
        let expected = column u in
        List.iter
          (fun epsilon ->
            let plain = first_bright (Helpers.image_exn (scene 1. epsilon)) 1 in
            let bent = first_bright (Helpers.image_exn (scene 1.5 epsilon)) 1 in
            if Float.abs (Float.of_int plain -. column 0.2) > 1. then
              Alcotest.failf "without bending the edge is at column %d, not %.2f" plain (column 0.2);
            if Float.abs (Float.of_int bent -. expected) > 1. then
              Alcotest.failf "the edge is at column %d; Snell's law puts it at %.2f" bent expected)
          [ None; Some 0.001 ]);
  ]
