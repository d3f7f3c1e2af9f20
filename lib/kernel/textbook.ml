open Scratch
open Tracer

(* The buffer of the kernel's one-ray copies, which store nothing. *)
let no_buffer : Image.buffer = Bigarray.Array1.create Bigarray.int8_unsigned Bigarray.c_layout 0

(* Does sphere [k] of [sph] block the ray? With [behind], a sphere with
   [k2 > 0] and [k3 > 0] does not, without its roots (the proof is in the
   .mli). *)
let[@inline] blocks_unless_behind sph ox oy oz dx dy dz t_min t_max two_k1 k1x4 zero ~behind k =
  let fx = ox -. Array.unsafe_get sph k
  and fy = oy -. Array.unsafe_get sph (k + 1)
  and fz = oz -. Array.unsafe_get sph (k + 2) in
  let h = (fx *. dx) +. (fy *. dy) +. (fz *. dz) in
  let k2 = h +. h in
  let k3 = ((fx *. fx) +. (fy *. fy) +. (fz *. fz)) -. Array.unsafe_get sph (k + 3) in
  (not (behind && k2 > zero && k3 > zero))
  &&
  let disc = (k2 *. k2) -. (k1x4 *. k3) in
  disc >= zero
  &&
  let sq = sqrt disc in
  let t2 = (-.k2 -. sq) /. two_k1 in
  (t_min < t2 && t2 < t_max)
  ||
  let t1 = (-.k2 +. sq) /. two_k1 in
  t_min < t1 && t1 < t_max

(* The candidates of tile [(tx, ty)]: the spheres that may meet its
   camera rays, in scene order (the culling and its proof: the .mli). *)
let[@inline never] tile_candidates tr tx ty =
  let p = tr.p and c = tr.corners in
  let n = p.n_objects and vz = p.viewport.distance and m = p.camera.rotation in
  let col0 = tx * tile and row0 = ty * tile in
  let col1 = Int.min (p.width - 1) (col0 + tile - 1) and row1 = Int.min (p.height - 1) (row0 + tile - 1) in
  for k = 0 to 3 do
    let vx = Array.unsafe_get p.column_vx (if k land 1 = 0 then col0 else col1) in
    let vy = Array.unsafe_get p.row_vy (if k land 2 = 0 then row0 else row1) in
    let x = (vx *. m.row0.x) +. (vy *. m.row0.y) +. (vz *. m.row0.z) in
    let y = (vx *. m.row1.x) +. (vy *. m.row1.y) +. (vz *. m.row1.z) in
    let z = (vx *. m.row2.x) +. (vy *. m.row2.y) +. (vz *. m.row2.z) in
    let len = sqrt ((x *. x) +. (y *. y) +. (z *. z)) in
    c.(3 * k) <- x /. len;
    c.((3 * k) + 1) <- y /. len;
    c.((3 * k) + 2) <- z /. len
  done;
  let ax = c.(0) +. c.(3) +. c.(6) +. c.(9) in
  let ay = c.(1) +. c.(4) +. c.(7) +. c.(10) in
  let az = c.(2) +. c.(5) +. c.(8) +. c.(11) in
  let al = sqrt ((ax *. ax) +. (ay *. ay) +. (az *. az)) in
  let ax = ax /. al and ay = ay /. al and az = az /. al in
  let cos_min = ref 1. in
  for k = 0 to 3 do
    let cs = (ax *. c.(3 * k)) +. (ay *. c.((3 * k) + 1)) +. (az *. c.((3 * k) + 2)) in
    if not (cs >= !cos_min) then cos_min := cs
  done;
  let theta = Float.acos (Float.min 1. (Float.max (-1.) !cos_min)) in
  let margin = 1e-6 in
  let base = tx * n and count = ref 0 in
  for i = 0 to n - 1 do
    let qx = -.Array.unsafe_get p.primary_ocx i
    and qy = -.Array.unsafe_get p.primary_ocy i
    and qz = -.Array.unsafe_get p.primary_ocz i in
    let dist = sqrt ((qx *. qx) +. (qy *. qy) +. (qz *. qz)) in
    let re = (Array.unsafe_get p.radius i *. (1. +. margin)) +. (margin *. dist) in
    let keep =
      (not (dist > 2. *. re && theta <= 1.))
      ||
      let alpha = Float.asin (re /. dist) in
      let beta = Float.acos (Float.min 1. (Float.max (-1.) (((ax *. qx) +. (ay *. qy) +. (az *. qz)) /. dist))) in
      not (beta > theta +. alpha +. margin)
    in
    if keep then begin
      Array.unsafe_set tr.cand (base + !count) i;
      incr count
    end
  done;
  tr.tile_row.(tx) <- ty;
  tr.tile_count.(tx) <- !count

(* [Camera_ray]'s direction of the camera ray through viewport point
   [(vx, vy, vz)], the same operations, here so that the kernel's row
   computes it from values read once a row: a call of another module's
   function with these floats would box them (in the dev profile), and
   with the row's values read again at each pixel the kernel's loop is
   slower (docs/performance.md, "Round 3: the kernel's modules"). *)
let[@inline] camera_direction s identity (m : Camera.rotation) vx vy vz =
  if identity then begin
    s.dx <- vx;
    s.dy <- vy;
    s.dz <- vz
  end
  else begin
    s.dx <- (vx *. m.row0.x) +. (vy *. m.row0.y) +. (vz *. m.row0.z);
    s.dy <- (vx *. m.row1.x) +. (vy *. m.row1.y) +. (vz *. m.row1.z);
    s.dz <- (vx *. m.row2.x) +. (vy *. m.row2.y) +. (vz *. m.row2.z)
  end

(* The camera rays of the tile of pixel [(col, row)] test its tile's
   candidates, found when the tile's row changes. *)
let[@inline] use_tile tr col row =
  let tx = col / tile and ty = row / tile in
  if Array.unsafe_get tr.tile_row tx <> ty then tile_candidates tr tx ty;
  tr.cand_first <- tx * tr.p.n_objects;
  tr.cand_count <- Array.unsafe_get tr.tile_count tx

(* The camera ray of no tile tests every sphere. *)
let untiled tr =
  tr.cand_first <- Array.length tr.cand - tr.p.n_objects;
  tr.cand_count <- tr.p.n_objects

(* The whole ray tree of a pixel, or of each pixel of a row (the .mli
   says what it promises). One function, though longer than a screen: its
   locals (the ray, the hit point, the level loop's state, the row's
   counts) live in registers across its steps, and helpers, even inlined,
   change what OCaml keeps there: the closest-hit loops or the shadow
   search cut out as functions of their own each cost more instructions
   per pixel than the slack of the speed gate (docs/performance.md,
   "Round 3: the kernel's modules"). *)
let[@inline] textbook_kernel tr ~behind ~row (buffer : Image.buffer) k0 col0 count r =
  let p = tr.p and s = tr.s in
  let sph = p.sphere4 in
  (* Floats computed, not read: a float field or [infinity] bound as is
     stays a pointer to a boxed float, read through once more at every use
     (eps >= 0, so adding 0. changes no comparison). *)
  let n = p.n_objects and eps = p.epsilon +. 0. and inf = 1. /. 0. in
  (* A zero the compiler does not know: compared in a register (or the
     stack), not made afresh with an instruction before every test. *)
  let zero = Float.of_int (Sys.opaque_identity 0) in
  let n4 = 4 * n in
  let n_lights = p.n_lights and light6 = p.light6 and kinds = p.light_kind in
  let blockers = tr.blockers and blockers_first = tr.blockers_first and shadow_skip = p.shadow_skip in
  (* With [row], the camera rays of columns [col0] to [col0 + count - 1] of
     canvas row [r], set up as [row] would, with what is constant along the
     row read once, and each pixel stored at [k0 + 3 (col - col0)];
     without, the one ray in [s] ([count] = 1). Its setup is then once per
     row, not once per pixel. *)
  let c = tr.counters and cull = row && p.cull and ty = r / tile in
  let vx = p.column_vx and vy = if row then Array.unsafe_get p.row_vy r else 0. in
  let vz = p.viewport.distance and m = p.camera.rotation and o = p.camera.position in
  let identity = p.identity_rotation in
  (* The counts of the whole row, added to the counters once. *)
  let tests = ref 0 and shadows = ref 0 and reflections = ref 0 in
  tr.origin_sphere <- -1;
  for col = col0 to col0 + count - 1 do
    if row then begin
      if cull && (col = col0 || col land (tile - 1) = 0) then begin
        let tx = col / tile in
        if Array.unsafe_get tr.tile_row tx <> ty then tile_candidates tr tx ty;
        tr.cand_first <- tx * n;
        tr.cand_count <- Array.unsafe_get tr.tile_count tx
      end;
      camera_direction s identity m (Array.unsafe_get vx col) vy vz;
      s.ox <- o.x;
      s.oy <- o.y;
      s.oz <- o.z;
      (* No [t_max]: the kernel's camera and mirror rays reach infinity,
         which [t < best] already implies, and it reads none. *)
      s.t_min <- 1.
    end;
    let levels = ref 0 and tracing = ref true in
    (* The weight of the colour still to be traced: the product of the
       reflectivities on the stack. *)
    let weight = ref 1. in
    while !tracing do
      (* The ray of this level is in [s]: read once, into registers.
         Doublings are written [x +. x]: the same bits as [2. *. x] (both
         exact, or both infinite), one instruction, no constant to load. *)
      let ox' = s.ox and oy' = s.oy and oz' = s.oz and dx' = s.dx and dy' = s.dy and dz' = s.dz in
      let t_min' = s.t_min in
      let a = (dx' *. dx') +. (dy' *. dy') +. (dz' *. dz') in
      let two_k1 = a +. a and k1x4 = 4. *. a in
      (* The closest hit, as [closest_textbook_all] finds it: the t_max of
         camera and mirror rays is infinity, which [t < best] already
         implies. *)
      let best = ref inf and hit = ref (-1) in
      if !levels > 0 then begin
        tests := !tests + n;
        (* Fresh names for what the loop reads: values live across the calls
           (pow, settled) stay on the stack, reloaded at every use otherwise. *)
        let sph = Sys.opaque_identity sph and n4 = Sys.opaque_identity n4 in
        let k = ref 0 in
        while !k < n4 do
          let i = !k in
          let fx = ox' -. Array.unsafe_get sph i and fy = oy' -. Array.unsafe_get sph (i + 1) and fz = oz' -. Array.unsafe_get sph (i + 2) in
          let h = (fx *. dx') +. (fy *. dy') +. (fz *. dz') in
          let k2 = h +. h in
          let k3 = ((fx *. fx) +. (fy *. fy) +. (fz *. fz)) -. Array.unsafe_get sph (i + 3) in
          if not (behind && k2 > zero && k3 > zero) then begin
            let disc = (k2 *. k2) -. (k1x4 *. k3) in
            if disc >= zero then begin
              let sq = sqrt disc in
              let t2 = (-.k2 -. sq) /. two_k1 in
              if t2 < !best && t_min' < t2 then begin
                best := t2;
                hit := i
              end
              else
                let t1 = (-.k2 +. sq) /. two_k1 in
                if t1 < !best && t_min' < t1 then begin
                  best := t1;
                  hit := i
                end
            end
          end;
          k := i + 4
        done;
        (* Slots, not places in [sph]. *)
        if !hit >= 0 then hit := !hit / 4
      end
      else if (not row) && tr.assumed <> no_assumption then begin
        (* Not in a row: [row] leaves an assumed sphere to [pixel], so the
           row's copy calls nothing here, and the ray's values need not be
           saved on the stack around a call at every level. *)
        hit := Traversal.primary_hit_spheres tr;
        best := s.t;
        tr.first_hit <- !hit
      end
      else begin
        (* From the camera, CO and k3 are per-frame constants; only the
           tile's spheres are tested. *)
        let pr = p.primary4 in
        let cand = tr.cand and first = tr.cand_first and count = tr.cand_count in
        tests := !tests + count;
        for j = first to first + count - 1 do
          let i = Array.unsafe_get cand j in
          let k = 4 * i in
          let fx = Array.unsafe_get pr k and fy = Array.unsafe_get pr (k + 1) and fz = Array.unsafe_get pr (k + 2) in
          let h = (fx *. dx') +. (fy *. dy') +. (fz *. dz') in
          let k2 = h +. h in
          let k3 = Array.unsafe_get pr (k + 3) in
          if not (behind && k2 > zero && k3 > zero) then begin
            let disc = (k2 *. k2) -. (k1x4 *. k3) in
            if disc >= zero then begin
              let sq = sqrt disc in
              let t2 = (-.k2 -. sq) /. two_k1 in
              if t2 < !best && t_min' < t2 then begin
                best := t2;
                hit := i
              end
              else
                let t1 = (-.k2 +. sq) /. two_k1 in
                if t1 < !best && t_min' < t1 then begin
                  best := t1;
                  hit := i
                end
            end
          end
        done;
        tr.first_hit <- !hit
      end;
      let i = !hit in
      if i < 0 then begin
        s.r <- p.background.r;
        s.g <- p.background.g;
        s.b <- p.background.b;
        tracing := false
      end
      else begin
        let t = !best in
        let px = ox' +. (dx' *. t) and py = oy' +. (dy' *. t) and pz = oz' +. (dz' *. t) in
        let nx = px -. Array.unsafe_get sph (4 * i) and ny = py -. Array.unsafe_get sph ((4 * i) + 1) and nz = pz -. Array.unsafe_get sph ((4 * i) + 2) in
        let inv = 1. /. sqrt ((nx *. nx) +. (ny *. ny) +. (nz *. nz)) in
        let nx = nx *. inv and ny = ny *. inv and nz = nz *. inv in
        let vx = -.dx' and vy = -.dy' and vz = -.dz' in
        let m = Array.unsafe_get p.material i in
        (* [lighting], with the shadow ray inlined. *)
        let specular = Array.unsafe_get p.specular m and cut = p.specular_cut and mo = m * n_lights in
        (* The ambient lights that come first add up to the same sum in any
           case: it starts from their total (Prepared.ambient_lead). *)
        let intensity = ref p.ambient_lead in
        let length_n = sqrt ((nx *. nx) +. (ny *. ny) +. (nz *. nz)) in
        (* |V| = |D|: negating changes no square, [a] sums them alike. *)
        let length_v = sqrt a in
        for l = p.first_light to n_lights - 1 do
          let o = 6 * l in
          let kind = Array.unsafe_get kinds l and li = Array.unsafe_get light6 (o + 1) in
          if kind = Prepared.ambient then intensity := !intensity +. li
          else begin
            let lx = ref (Array.unsafe_get light6 (o + 2))
            and ly = ref (Array.unsafe_get light6 (o + 3))
            and lz = ref (Array.unsafe_get light6 (o + 4)) in
            if kind = Prepared.point then begin
              lx := !lx -. px;
              ly := !ly -. py;
              lz := !lz -. pz
            end;
            let lx = !lx and ly = !ly and lz = !lz in
            let n_dot_l = (nx *. lx) +. (ny *. ly) +. (nz *. lz) in
            let add_diffuse = n_dot_l > zero in
            (* The specular term's cosine, as [lighting] computes it
               (its 2 <L, N> is 2 n_dot_l: the same products, summed in the
               same order); computed for matte spheres too, whose cut is
               infinite, rather than asking the material at every light. *)
            let k = n_dot_l +. n_dot_l in
            let rx = (nx *. k) -. lx and ry = (ny *. k) -. ly and rz = (nz *. k) -. lz in
            let r_dot_v = (rx *. vx) +. (ry *. vy) +. (rz *. vz) in
            let cos = if r_dot_v > zero then r_dot_v /. (sqrt ((rx *. rx) +. (ry *. ry) +. (rz *. rz)) *. length_v) else zero in
            (* At or below the cut, li cos^s is 0 or too small to change
               the sum (Prepared.specular_cut): the sum is what it would be
               with the term, and pow is not called. *)
            let add_specular = cos > Array.unsafe_get cut (mo + l) in
            (* The shadow ray only matters if a term would be added: a light
               that adds nothing leaves the sum as it is, lit or not. (A
               point light on the point itself, L = 0, adds nothing:
               n_dot_l = 0 and R = 0. Without the skip it is left out, as
               [lighting] does.) *)
            if
              (if shadow_skip then add_diffuse || add_specular
               else kind <> Prepared.point || lx <> 0. || ly <> 0. || lz <> 0.)
              &&
              (* [shadowed] with the skips: any blocker will do, so the
                 spheres are tried in this light's order of [blockers],
                 where the last one found was swapped to the front. *)
              let a = (lx *. lx) +. (ly *. ly) +. (lz *. lz) in
              let two_k1 = a +. a and k1x4 = 4. *. a in
              incr shadows;
              let first = Array.unsafe_get blockers_first l in
              let stop = first + n4 in
              let q = ref first in
              (* Its range: 1 for a point light, infinity for a directional one. *)
              let t_max = Array.unsafe_get light6 o in
              while !q < stop && not (blocks_unless_behind blockers px py pz lx ly lz eps t_max two_k1 k1x4 zero ~behind !q) do
                q := !q + 4
              done;
              let q = !q in
              if q < stop then begin
                tests := !tests + ((q - first) / 4) + 1;
                if q > first then
                  for c = 0 to 3 do
                    let x = Array.unsafe_get blockers (q + c) in
                    Array.unsafe_set blockers (q + c) (Array.unsafe_get blockers (first + c));
                    Array.unsafe_set blockers (first + c) x
                  done;
                false
              end
              else begin
                tests := !tests + n;
                true
              end
            then begin
              if add_diffuse then begin
                let len = if kind = Prepared.point then sqrt ((lx *. lx) +. (ly *. ly) +. (lz *. lz)) else Array.unsafe_get light6 (o + 5) in
                intensity := !intensity +. (li *. n_dot_l /. (length_n *. len))
              end;
              if add_specular then intensity := !intensity +. (li *. Float.pow cos specular)
            end
          end
        done;
        let light = !intensity in
        let lr = Array.unsafe_get p.red m *. light and lg = Array.unsafe_get p.green m *. light and lb = Array.unsafe_get p.blue m *. light in
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
          (* As in [trace_in]. *)
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
            (* The mirror ray R = 2 <V, N> N - V from the hit point. *)
            let h = (vx *. nx) +. (vy *. ny) +. (vz *. nz) in
            let k = h +. h in
            s.ox <- px;
            s.oy <- py;
            s.oz <- pz;
            s.dx <- (nx *. k) -. vx;
            s.dy <- (ny *. k) -. vy;
            s.dz <- (nz *. k) -. vz;
            s.t_min <- eps;
            incr reflections
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
    done;
    if row then Byte_exact.store tr buffer (k0 + (3 * (col - col0)))
  done;
  if row then c.primary <- c.primary + count;
  c.tests <- c.tests + !tests;
  c.shadow <- c.shadow + !shadows;
  c.reflection <- c.reflection + !reflections

(* One copy with the rejection of spheres behind, one without (for the
   tests of its exactness); each for one ray and for a row of camera rays. *)
let[@inline never] trace_textbook_behind tr = textbook_kernel tr ~behind:true ~row:false no_buffer 0 0 1 0
let[@inline never] trace_textbook_all_roots tr = textbook_kernel tr ~behind:false ~row:false no_buffer 0 0 1 0
let[@inline never] row_textbook_behind tr buffer k col0 count r = textbook_kernel tr ~behind:true ~row:true buffer k col0 count r
let[@inline never] row_textbook_all_roots tr buffer k col0 count r = textbook_kernel tr ~behind:false ~row:true buffer k col0 count r

let trace tr = if tr.p.behind then trace_textbook_behind tr else trace_textbook_all_roots tr

let row tr buffer k col0 count r =
  (* In blocks of pixels, with the budget checked before each: a single
     wide row cannot run far past it. *)
  let c = ref 0 in
  while !c < count do
    let n = if count - !c < block then count - !c else block in
    check_budget tr;
    if tr.p.behind then row_textbook_behind tr buffer (k + (3 * !c)) (col0 + !c) n r
    else row_textbook_all_roots tr buffer (k + (3 * !c)) (col0 + !c) n r;
    c := !c + n
  done

