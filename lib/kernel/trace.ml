open Scratch
open Tracer

type counters = Tracer.counters = {
  mutable primary : int;
  mutable shadow : int;
  mutable reflection : int;
  mutable tests : int;
  mutable box_tests : int;
  mutable early_stops : int;
  mutable decided : int;
  mutable penumbra : int;
  mutable umbra : int;
  mutable whole : int;
}

type t = Tracer.t

let create = Tracer.create
let prepared = Tracer.prepared
let counters = Tracer.counters
let work = Tracer.work
let set_budget = Tracer.set_budget
let check_budget = Tracer.check_budget
let red = Tracer.red
let green = Tracer.green
let blue = Tracer.blue
let hit_object = Tracer.hit_object
let averaging = Tracer.averaging
let to_byte = Byte_exact.to_byte
let store = Byte_exact.store
let store_average = Byte_exact.store_average
let roots = Traversal.roots

(* The ray in [s], by the loop chosen once per tracer: the document's
   kernel, the chain of mirror rays, or the ray tree. *)
let[@inline] trace tr =
  let p = tr.p in
  if p.textbook_all && p.skips then Textbook.trace tr
  else
    let k = tr.tracer in
    if k = spheres_chain then Chain.trace_spheres tr else if k = objects_chain then Chain.trace_objects tr else Glass.trace_tree tr

(* The primary ray through canvas point [s.gx, s.gy]. *)
let primary tr =
  Textbook.untiled tr;
  Camera_ray.set_point tr;
  tr.counters.primary <- tr.counters.primary + 1;
  trace tr

(* [primary] for a scene that samples ([p.sampled]): the ray from the
   lens point of the camera sample [tr.key], if the camera has a lens. A
   copy, not a test in [primary]: the pinhole's rays take no new
   instruction. *)
let primary_sampled tr =
  Textbook.untiled tr;
  Camera_ray.set_lens_point tr;
  tr.counters.primary <- tr.counters.primary + 1;
  trace tr

(* The camera sample [(i, j)] of an [n x n] grid in the pixel at canvas
   point [(gx, gy)], for a scene that samples: its key, and its pixel and
   place for a stratified lens. A pixel's centre ray is the sample [(0, 0)]
   of a [1 x 1] grid, whose key and lens point are those of the centre
   sample of any odd grid (Sample_key.camera, Camera_ray). *)
let[@inline] set_sample tr gx gy ~i ~j ~n =
  tr.key <- Sample_key.camera ~gx ~gy ~di:((2 * i) + 1 - n) ~dj:((2 * j) + 1 - n);
  tr.lens_gx <- gx;
  tr.lens_gy <- gy;
  tr.lens_n <- n;
  tr.lens_k <- (j * n) + i

(* A pixel's centre: its viewport point is the frame's (the same
   operations as [primary]'s), and its tile's spheres are the candidates. *)
let[@inline] pixel tr gx gy =
  let p = tr.p in
  check_budget tr;
  let col = gx + (p.width / 2) and row = gy + (p.height / 2) in
  if col >= 0 && col < p.width && row >= 0 && row < p.height then begin
    if p.cull && p.textbook_all then Textbook.use_tile tr col row;
    if p.sampled then begin
      set_sample tr gx gy ~i:0 ~j:0 ~n:1;
      Camera_ray.set_lens_pixel tr col row
    end
    else Camera_ray.set_pixel tr col row;
    tr.counters.primary <- tr.counters.primary + 1;
    trace tr
  end
  else begin
    tr.s.gx <- Float.of_int gx;
    tr.s.gy <- Float.of_int gy;
    if p.sampled then begin
      set_sample tr gx gy ~i:0 ~j:0 ~n:1;
      primary_sampled tr
    end
    else primary tr
  end

(* Probe [k] of pixel [(gx, gy)], a canvas pixel: its centre ray from a
   fixed point of the lens's rim ([Camera_ray.set_probe]); its lights'
   numbers are those of the pixel's centre sample. Counted as a primary
   ray: it is one. *)
let probe tr gx gy k =
  let p = tr.p in
  check_budget tr;
  let col = gx + (p.width / 2) and row = gy + (p.height / 2) in
  if col < 0 || col >= p.width || row < 0 || row >= p.height || k < 0 || k > 3 then
    invalid_arg "Trace.probe: no such pixel or probe";
  if p.cull && p.textbook_all then Textbook.use_tile tr col row;
  if p.sampled then set_sample tr gx gy ~i:0 ~j:0 ~n:1;
  Camera_ray.set_probe tr col row k;
  tr.counters.primary <- tr.counters.primary + 1;
  trace tr

(* Pixel [col] of a row whose first is [col0]: its camera ray (from the
   lens point of [tr.key] if [sampled]), traced and stored. *)
let[@inline] row_pixel tr buffer k col0 col r ~sampled =
  check_budget tr;
  if sampled then Camera_ray.set_lens_pixel tr col r else Camera_ray.set_pixel tr col r;
  tr.counters.primary <- tr.counters.primary + 1;
  trace tr;
  store tr buffer (k + (3 * (col - col0)))

let row tr buffer k gx gy count =
  let p = tr.p in
  let col0 = gx + (p.width / 2) and r = gy + (p.height / 2) in
  if r >= 0 && r < p.height && col0 >= 0 && count >= 0 && col0 + count <= p.width then begin
    (* The kernel's row copy takes no assumed sphere (see [Textbook]). *)
    if p.textbook_all && p.skips && tr.assumed = no_assumption then Textbook.row tr buffer k col0 count r
    (* [pixel], the row's checks made once; [p.sampled] too, outside the
       loop, whose copy for other scenes has no test of it. *)
    else if p.sampled then
      for col = col0 to col0 + count - 1 do
        set_sample tr (gx + col - col0) gy ~i:0 ~j:0 ~n:1;
        row_pixel tr buffer k col0 col r ~sampled:true
      done
    else for col = col0 to col0 + count - 1 do row_pixel tr buffer k col0 col r ~sampled:false done
  end
  else
    for c = 0 to count - 1 do
      pixel tr (gx + c) gy;
      store tr buffer (k + (3 * c))
    done

let sample tr gx gy ~i ~j ~n =
  let fn = Float.of_int n in
  (* For n = 1 the offsets are 0.5 /. 1. -. 0.5 = 0 exactly: [pixel]. *)
  tr.s.gx <- Float.of_int gx +. (((Float.of_int i +. 0.5) /. fn) -. 0.5);
  tr.s.gy <- Float.of_int gy +. (((Float.of_int j +. 0.5) /. fn) -. 0.5);
  if tr.p.sampled then begin
    set_sample tr gx gy ~i ~j ~n;
    primary_sampled tr
  end
  else primary tr

let cast tr ~from (o : Vec3.t) (d : Vec3.t) =
  let s = tr.s in
  s.ox <- o.x;
  s.oy <- o.y;
  s.oz <- o.z;
  s.dx <- d.x;
  s.dy <- d.y;
  s.dz <- d.z;
  s.t_min <- tr.p.epsilon;
  s.t_max <- infinity;
  tr.origin_sphere <-
    (if from < 0 || tr.p.kind.(tr.p.slot.(from)) <> Kind.Sphere then -1 else tr.p.slot.(from));
  let hit = Traversal.closest tr in
  if hit < 0 then -1 else tr.p.index.(hit)

(* The benchmark's rays (issue 28): the traversals alone, no shading. *)
let camera_hit tr gx gy =
  let p = tr.p in
  let col = gx + (p.width / 2) and row = gy + (p.height / 2) in
  if col < 0 || col >= p.width || row < 0 || row >= p.height then invalid_arg "Trace.camera_hit: no such pixel";
  Camera_ray.set_pixel tr col row;
  tr.counters.primary <- tr.counters.primary + 1;
  tr.origin_sphere <- -1;
  let i = if p.all_spheres then Traversal.primary_hit_spheres tr else Traversal.primary_hit_objects tr in
  tr.first_hit <- i;
  if i < 0 then -1 else Array.unsafe_get p.index i

let shadow_blocked tr (rays : float array) k =
  if k < 0 || (6 * k) + 5 >= Array.length rays then invalid_arg "Trace.shadow_blocked: no such ray";
  let s = tr.s and o = 6 * k in
  s.ox <- Array.unsafe_get rays o;
  s.oy <- Array.unsafe_get rays (o + 1);
  s.oz <- Array.unsafe_get rays (o + 2);
  s.dx <- Array.unsafe_get rays (o + 3);
  s.dy <- Array.unsafe_get rays (o + 4);
  s.dz <- Array.unsafe_get rays (o + 5);
  s.t_min <- tr.p.epsilon;
  s.t_max <- 1.;
  tr.origin_sphere <- -1;
  Traversal.shadowed tr 0

(* Several rays per pixel. The colours are summed here, in the scratch
   record, so that no float crosses a module boundary per sample. *)

type samples = (float, Bigarray.float64_elt, Bigarray.c_layout) Bigarray.Array1.t


let pixel_assuming tr gx gy k =
  if k < -1 || k >= tr.p.n_scene_objects then invalid_arg "Trace.pixel_assuming: no such object";
  (* A lens's rays assume nothing: an assumed sphere's test reads the
     per-frame constants of rays from the camera's position. *)
  if tr.assumed = lens_rays then pixel tr gx gy
  else begin
    tr.assumed <- k;
    pixel tr gx gy;
    tr.assumed <- no_assumption
  end

(* [Color.clamp] without the NaN case (no NaN reaches a colour here). *)
let[@inline] clamp x = if x >= 255. then 255. else if x > 0. then x else 0.

let check_averaging tr fn =
  if not tr.averaging then
    invalid_arg (Printf.sprintf "Trace.%s: the tracer was not created with ~averaging:true" fn)

let clear tr =
  let s = tr.s in
  s.acc_r <- 0.;
  s.acc_g <- 0.;
  s.acc_b <- 0.

let[@inline] add_clamped s =
  s.acc_r <- s.acc_r +. clamp s.r;
  s.acc_g <- s.acc_g +. clamp s.g;
  s.acc_b <- s.acc_b +. clamp s.b

let accumulate tr =
  check_averaging tr "accumulate";
  add_clamped tr.s

(* The samples of the grid in one fixed order, rows [j] then columns [i]:
   [average] and [average_reusing] add the same floats in the same order,
   so they give the same sums. *)
let grid tr gx gy n ~reuse (saved : samples) k =
  let c = n / 2 in
  let s = tr.s in
  clear tr;
  for j = 0 to n - 1 do
    for i = 0 to n - 1 do
      if reuse && i = c && j = c then begin
        s.acc_r <- s.acc_r +. Bigarray.Array1.get saved k;
        s.acc_g <- s.acc_g +. Bigarray.Array1.get saved (k + 1);
        s.acc_b <- s.acc_b +. Bigarray.Array1.get saved (k + 2)
      end
      else begin
        sample tr gx gy ~i ~j ~n;
        add_clamped s
      end
    done
  done

(* A 0-element array for [grid ~reuse:false], which never reads it. *)
let no_samples : samples = Bigarray.Array1.create Bigarray.float64 Bigarray.c_layout 0

let average tr gx gy ~n =
  check_averaging tr "average";
  if n < 1 then invalid_arg "Trace.average: n < 1";
  check_budget tr;
  grid tr gx gy n ~reuse:false no_samples 0

(* For an odd [n], the centre sample [(n / 2, n / 2)] has offsets
   [(n / 2 + 0.5) / n - 0.5 = 0.5 - 0.5 = 0] exactly ([n / 2 + 0.5] is
   [n / 2] exactly in floats), so it is the ray of [pixel]. *)
let save tr (saved : samples) k =
  let s = tr.s in
  Bigarray.Array1.set saved k (clamp s.r);
  Bigarray.Array1.set saved (k + 1) (clamp s.g);
  Bigarray.Array1.set saved (k + 2) (clamp s.b)

let average_reusing tr saved k gx gy ~n =
  check_averaging tr "average_reusing";
  if n < 1 || n land 1 = 0 then invalid_arg "Trace.average_reusing: n is not odd and positive";
  check_budget tr;
  grid tr gx gy n ~reuse:true saved k


(* The circle of confusion of the last primary ray's hit, in pixels: a
   point at depth [z] along the view axis spreads over a circle of
   diameter [A |z - f| / z] on the plane of focus, whose pixels are
   [w f / (W d)] wide ([w], [W]: the viewport's width and the canvas's).
   The ray from the lens (its direction's axial part is [d], for an
   orthonormal matrix) meets its hit at depth [z = t d]. A miss shows the
   background, the same colour everywhere: [0]. *)
let save_blur tr (blur : samples) k =
  let p = tr.p in
  let cam = p.camera in
  let c =
    if tr.first_hit < 0 || not (Camera.has_lens cam) then 0.
    else
      let t = tr.s.first_t and d = p.viewport.distance and f = cam.focal_distance in
      cam.aperture *. Float.of_int p.width *. Float.abs ((t *. d) -. f) /. (t *. p.viewport.width *. f)
  in
  Bigarray.Array1.set blur k c
