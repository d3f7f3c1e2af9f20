open Scratch
open Tracer

(* Section 7.8 as a loop: each level traces one ray; a reflective hit pushes
   its local colour and reflectivity and continues with the mirror ray; then
   the stack is folded back from the deepest colour, blend by blend, in the
   same order as the recursion. The ray to trace is in [s]. *)
let[@inline] trace_in tr ~spheres =
  let p = tr.p and s = tr.s in
  let levels = ref 0 and tracing = ref true in
  (* The weight of the colour still to be traced: the product of the
     reflectivities on the stack. *)
  let weight = ref 1. in
  tr.first_hit <- -1;
  tr.origin_sphere <- -1;
  while !tracing do
    let i = if !levels = 0 then (if spheres then Traversal.primary_hit_spheres tr else Traversal.primary_hit_objects tr)
      else Traversal.closest_in tr ~spheres in
    if !levels = 0 then begin
      tr.first_hit <- i;
      (* For adaptive sampling's circle of confusion (Trace.save_blur). *)
      s.first_t <- s.t
    end;
    if i < 0 then begin
      s.r <- p.background.r;
      s.g <- p.background.g;
      s.b <- p.background.b;
      tracing := false
    end
    else begin
      let t = s.t in
      let dx = s.dx and dy = s.dy and dz = s.dz in
      let px = s.ox +. (dx *. t) and py = s.oy +. (dy *. t) and pz = s.oz +. (dz *. t) in
      let m =
      if spheres || Array.unsafe_get p.kind i = Kind.Sphere then begin
        s.px <- px;
        s.py <- py;
        s.pz <- pz;
        Surface.sphere_hit tr i;
        Array.unsafe_get p.material i
      end
      else begin
        (* The point goes in [s], not as arguments: floats passed to a
           function that is not inlined are boxed. *)
        s.px <- px;
        s.py <- py;
        s.pz <- pz;
        Surface.shape_hit tr i
      end
      in
      (* A pattern's second colour is a material that differs from the
         object's in its colour alone. Looked up before the lighting, whose
         shadow rays reuse [s]'s ray. *)
      let m = if (not spheres) && p.patterned then Surface.local_material tr i m else m
      in
      Lighting.lighting tr ~shiny:(Array.unsafe_get p.specular m <> Sphere.matte) ~specular_of:p.specular m;
      let light = s.intensity in
      let lr = Array.unsafe_get tr.red m *. light and lg = Array.unsafe_get tr.green m *. light and lb = Array.unsafe_get tr.blue m *. light in
      let refl = Array.unsafe_get p.reflective m in
      if refl <= 0. || !levels >= p.depth then begin
        s.r <- lr;
        s.g <- lg;
        s.b <- lb;
        tracing := false
      end
      else begin
        let k = 4 * !levels in
        Array.unsafe_set tr.stack k lr;
        Array.unsafe_set tr.stack (k + 1) lg;
        Array.unsafe_set tr.stack (k + 2) lb;
        Array.unsafe_set tr.stack (k + 3) refl;
        incr levels;
        weight := !weight *. refl;
        (* Checking costs two folds of the stack: worth it only when what is
           left weighs less than a unit, or this colour saturates. Skipping
           the check is always exact. *)
        if p.early_stop
           && (!weight *. p.max_channel < 1. || (lr >= 255. && lg >= 255. && lb >= 255.))
           && Byte_exact.settled tr !levels
        then begin
          tr.counters.early_stops <- tr.counters.early_stops + 1;
          s.r <- 0.;
          s.g <- 0.;
          s.b <- 0.;
          tracing := false
        end
        else begin
          Surface.mirror_ray p s;
          tr.counters.reflection <- tr.counters.reflection + 1
        end
      end
    end
  done;
  for l = !levels - 1 downto 0 do
    let refl = Array.unsafe_get tr.stack ((4 * l) + 3) in
    let keep = 1. -. refl in
    s.r <- (Array.unsafe_get tr.stack (4 * l) *. keep) +. (s.r *. refl);
    s.g <- (Array.unsafe_get tr.stack ((4 * l) + 1) *. keep) +. (s.g *. refl);
    s.b <- (Array.unsafe_get tr.stack ((4 * l) + 2) *. keep) +. (s.b *. refl)
  done

(* One copy per kind of scene: spheres alone ask no object its kind, nor
   its pattern ({!Prepared.all_spheres}); the other scenes test per hit
   whether any material has a pattern. (A copy of the loop for patterns
   made [trace_objects] too big for OCaml to inline into the render loop
   it is called from, which cost more than the test: docs/performance.md,
   "Round 3: the kernel's modules".) *)
let trace_spheres tr = trace_in tr ~spheres:true
let trace_objects tr = trace_in tr ~spheres:false

