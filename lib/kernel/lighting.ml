open Scratch
open Tracer

(* Light through transparent objects: the shadow ray in [s] (its range
   set by [lighting]) is followed from surface to surface, nearest first
   (the same order for every traversal, so the product rounds alike),
   and the light it carries is scaled by the transparency of each surface
   it crosses: twice through a ball, once out of the one it starts in; an
   opaque one stops it. The factor is left in [tr.tree.attenuation.(0)]
   (a float returned by a call is boxed). *)
let[@inline never] transmit tr =
  let p = tr.p and s = tr.s in
  tr.counters.shadow <- tr.counters.shadow + 1;
  let f = ref 1. and go = ref true in
  while !go do
    let i = Traversal.closest tr in
    if i < 0 then go := false
    else begin
      f := !f *. Array.unsafe_get p.transparency (Array.unsafe_get p.material i);
      if !f > 0. then begin
        s.t_min <- s.t;
        (* A shadow ray may cross every transparent surface: each further
           crossing is a search, checked against the budget like a hit of
           the tree (the first one is the hit's, checked there). *)
        check_budget tr
      end
      else go := false
    end
  done;
  Array.unsafe_set tr.tree.attenuation 0 !f

(* Adds light [l]'s terms, of intensity [li] and unnormalised direction
   [s.dx..], to [s.intensity]: the diffuse one if [n_dot_l > 0], the
   specular one of cosine [cos] if [cos > 0] (see [lighting_with]). *)
let[@inline] add_terms s ~specular_of m li n_dot_l cos length_n =
  if n_dot_l > 0. then begin
    let lx = s.dx and ly = s.dy and lz = s.dz in
    s.intensity <- s.intensity +. (li *. n_dot_l /. (length_n *. sqrt ((lx *. lx) +. (ly *. ly) +. (lz *. lz))))
  end;
  if cos > 0. then s.intensity <- s.intensity +. (li *. Float.pow cos (Array.unsafe_get specular_of m))

(* The total intensity at the hit point [s.px..] with unit normal [s.nx..]
   and view vector [s.vx..] (sections 7.4 to 7.7), left in [s.intensity].
   The shadow rays reuse [s]'s ray fields. [through]: shadow rays pass
   through transparent objects ([transmit]); otherwise any object stops
   them. Both terms of a light are decided before its shadow ray: with
   [p.shadow_skip], a light that would add neither casts none (lit or
   not, it leaves the sum as it is), as in the document's kernel. *)
let[@inline] lighting_with tr ~through ~shiny ~specular_of m =
  let p = tr.p and s = tr.s in
  let px = s.px and py = s.py and pz = s.pz in
  let nx = s.nx and ny = s.ny and nz = s.nz in
  let vx = s.vx and vy = s.vy and vz = s.vz in
  let shadow_skip = p.shadow_skip and cut = p.specular_cut and mo = m * p.n_lights in
  s.intensity <- 0.;
  let length_n = sqrt ((nx *. nx) +. (ny *. ny) +. (nz *. nz)) in
  let length_v = sqrt ((vx *. vx) +. (vy *. vy) +. (vz *. vz)) in
  for l = 0 to p.n_lights - 1 do
    let li = Array.unsafe_get p.light_intensity l in
    if Array.unsafe_get p.light_kind l = Prepared.ambient then s.intensity <- s.intensity +. li
    else begin
      let point = Array.unsafe_get p.light_kind l = Prepared.point in
      if point then begin
        s.dx <- Array.unsafe_get p.lx l -. px;
        s.dy <- Array.unsafe_get p.ly l -. py;
        s.dz <- Array.unsafe_get p.lz l -. pz;
        s.t_max <- 1.
      end
      else begin
        s.dx <- Array.unsafe_get p.lx l;
        s.dy <- Array.unsafe_get p.ly l;
        s.dz <- Array.unsafe_get p.lz l;
        s.t_max <- infinity
      end;
      s.ox <- px;
      s.oy <- py;
      s.oz <- pz;
      s.t_min <- p.epsilon;
      let lx = s.dx and ly = s.dy and lz = s.dz in
      let n_dot_l = (nx *. lx) +. (ny *. ly) +. (nz *. lz) in
      (* The specular cosine, or [0.] where no term is added: matte,
         <R, V> <= 0, or a cosine at or below the cut, where cos^s is 0 or
         too small to change the sum (Prepared.specular_cut, never below
         0): the sum is what it would be with the term. *)
      let cos =
        if shiny then begin
          (* R = 2 <L, N> N - L (section 7.6). *)
          let k = 2. *. n_dot_l in
          let rx = (nx *. k) -. lx and ry = (ny *. k) -. ly and rz = (nz *. k) -. lz in
          let r_dot_v = (rx *. vx) +. (ry *. vy) +. (rz *. vz) in
          let cos = if r_dot_v > 0. then r_dot_v /. (sqrt ((rx *. rx) +. (ry *. ry) +. (rz *. rz)) *. length_v) else 0. in
          if cos > Array.unsafe_get cut (mo + l) then cos else 0.
        end
        else 0.
      in
      (* A point light on the lit point itself gives no direction, L = 0:
         it is skipped (as Literal does), not divided by zero; with the
         skip, it adds no term (n_dot_l = 0 and R = 0). *)
      if
        if shadow_skip then n_dot_l > 0. || cos > 0.
        else (not point) || lx <> 0. || ly <> 0. || lz <> 0.
      then begin
        if through then begin
          (* [transmit] moves [s.t_min]; the direction stays. *)
          transmit tr;
          let f = Array.unsafe_get tr.tree.attenuation 0 in
          if f > 0. then add_terms s ~specular_of m (li *. f) n_dot_l cos length_n
        end
        else if not (Traversal.shadowed tr l) then add_terms s ~specular_of m li n_dot_l cos length_n
      end
    end
  done

let lighting tr ~shiny ~specular_of m = lighting_with tr ~through:false ~shiny ~specular_of m
let lighting_through tr ~shiny ~specular_of m = lighting_with tr ~through:true ~shiny ~specular_of m

