open Scratch
open Tracer

(* The direction of the camera ray through viewport point [(vx, vy, vz)],
   turned by the camera's matrix [m] unless it is the identity. *)
let[@inline] set_direction s identity (m : Camera.rotation) vx vy vz =
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

(* The camera ray through viewport point [(vx, vy, d)], in [s]. *)
let[@inline] through tr vx vy =
  let p = tr.p and s = tr.s in
  let cam = p.camera in
  set_direction s p.identity_rotation cam.rotation vx vy p.viewport.distance;
  s.ox <- cam.position.x;
  s.oy <- cam.position.y;
  s.oz <- cam.position.z;
  s.t_min <- 1.;
  s.t_max <- infinity

let[@inline] set_pixel tr col row =
  let p = tr.p in
  through tr (Array.unsafe_get p.column_vx col) (Array.unsafe_get p.row_vy row)

let set_point tr =
  let p = tr.p and s = tr.s in
  let vp = p.viewport in
  (* Viewport point (section 3), multiplied before dividing as written. *)
  let vx = s.gx *. vp.width /. Float.of_int p.width in
  let vy = s.gy *. vp.height /. Float.of_int p.height in
  through tr vx vy

(* {1 The thin lens} *)

(* The lens's numbers hang off the camera sample's key by a tag of their
   own: the lights chain their index ([>= 0]) there. *)
let lens_tag = -1

(* [Sample_key.unit], written here: a float returned from another module
   is boxed, and this runs per camera ray. *)
let[@inline] unit h = Float.of_int (Sample_key.mix h) *. 0x1p-31

(* Pairs tried before the disc's centre is taken: the chance that all of
   them miss the disc is [(1 - pi/4)^32], below [1e-21]. *)
let tries = 32

(* Moves the pinhole ray in [s] to lens point [(x, y)] of the unit disc:
   its origin to [O + L], with [L = M (r x, r y, 0)], and its direction to
   [D - (d / f) L], so that it still meets the pinhole ray's point at
   [t = f / d] (the focal plane) and the viewport plane at [t = 1].
   Inlined: its floats are arguments. *)
let[@inline] move tr x y =
  let p = tr.p and s = tr.s in
  let cam = p.camera in
  let r = 0.5 *. cam.aperture in
  let lx = r *. x and ly = r *. y in
  let q = p.viewport.distance /. cam.focal_distance in
  if p.identity_rotation then begin
    s.ox <- s.ox +. lx;
    s.oy <- s.oy +. ly;
    s.dx <- s.dx -. (q *. lx);
    s.dy <- s.dy -. (q *. ly)
  end
  else begin
    let m = cam.rotation in
    let ex = (lx *. m.row0.x) +. (ly *. m.row0.y)
    and ey = (lx *. m.row1.x) +. (ly *. m.row1.y)
    and ez = (lx *. m.row2.x) +. (ly *. m.row2.y) in
    s.ox <- s.ox +. ex;
    s.oy <- s.oy +. ey;
    s.oz <- s.oz +. ez;
    s.dx <- s.dx -. (q *. ex);
    s.dy <- s.dy -. (q *. ey);
    s.dz <- s.dz -. (q *. ez)
  end

(* The sine and cosine of an angle in [\[-pi/4, pi/4\]] for the
   concentric map: their Taylor polynomials (to [t^13] and [t^14], whose
   first omitted terms are below [3e-14] there), evaluated by Horner's
   rule with products and sums alone, which are correctly rounded in C and
   in JavaScript alike, where libm's [sin] and [cos] are not: the web page
   gives the same bytes. *)
let s3 = -1. /. 6.
let s5 = 1. /. 120.
let s7 = -1. /. 5040.
let s9 = 1. /. 362880.
let s11 = -1. /. 39916800.
let s13 = 1. /. 6227020800.
let c2 = -1. /. 2.
let c4 = 1. /. 24.
let c6 = -1. /. 720.
let c8 = 1. /. 40320.
let c10 = -1. /. 3628800.
let c12 = 1. /. 479001600.
let c14 = -1. /. 87178291200.
let quarter_pi = Float.pi /. 4.

let[@inline] sin_q t =
  let t2 = t *. t in
  t *. (1. +. (t2 *. (s3 +. (t2 *. (s5 +. (t2 *. (s7 +. (t2 *. (s9 +. (t2 *. (s11 +. (t2 *. s13))))))))))))

let[@inline] cos_q t =
  let t2 = t *. t in
  1. +. (t2 *. (c2 +. (t2 *. (c4 +. (t2 *. (c6 +. (t2 *. (c8 +. (t2 *. (c10 +. (t2 *. (c12 +. (t2 *. c14)))))))))))))

(* The lens point of the camera sample whose key is [tr.key], on the unit
   disc, moves the pinhole ray in [s] (see [move]).

   [Uniform]: the first of the points [(2 unit (key h 2k) - 1,
   2 unit (key h (2k+1)) - 1)], [h = key tr.key (-1)], [k = 0, 1, ...],
   that lies inside the unit disc: uniform over the disc, independent
   from sample to sample. Rejection: a product, a sum and a comparison
   are the same everywhere.

   [Stratified]: the pixel's own numbers ([hp], the chain of the pixel
   with sample [-1], which no camera key uses) give an offset [u0] on the
   unit square and a permutation of the cells of its [n x n] cut. Sample
   [k] of the grid takes cell [pi k], [(ci, cj)], and in it the sub-cell
   [(sx, sy)] of the cell's own [n x n] cut, where [sx = sigma cj] and
   [sy = tau ci] for two more permutations of the pixel's, of [0 .. n - 1]
   fixing 0 (Kensler's correlated multi-jittered sampling, 2013: each
   column of cells takes every column of sub-cells once, each row every
   row), a jittered point in it (from its own key), plus [u0] modulo 1:
   each point is uniform over the square (the offset is), the [n^2]
   points of a pixel are one to a cell of the shifted cut, and their
   abscissae (ordinates) one to each of the [n^2] columns (rows) of
   sub-cells: an edge across the lens parallel to one of its axes is
   crossed as by [n^2] strata, not [n]. The centre sample of an odd grid takes cell 0 without
   jitter, the point [u0] itself, which is also the point of the pixel's
   centre ray ([n = 1]): adaptive sampling's first ray is both the
   one-sample render's and the full grid's centre sample. The square goes
   onto the disc by Shirley and Chiu's concentric map, which keeps areas,
   with the polynomials above for its sine and cosine. *)
(* The pixel's two permutations of the sub-cells' columns and rows, of
   [0 .. n - 1] fixing 0, from its keys [key hp 3] and [key hp 4]
   ([Sample_key.permute] of the [n - 1] others), into [tr.lens_sub]. *)
let sub_cells tr n =
  let hp = Sample_key.pixel ~col:tr.lens_gx ~row:tr.lens_gy ~sample:lens_tag in
  let px = Sample_key.mix (Sample_key.key hp 3) and py = Sample_key.mix (Sample_key.key hp 4) in
  let t = tr.lens_sub in
  t.(0) <- 0;
  Sample_key.fill t ~at:1 ~shift:1 ~p:px ~n:(n - 1);
  t.(n) <- 0;
  Sample_key.fill t ~at:(n + 1) ~shift:1 ~p:py ~n:(n - 1);
  tr.lens_sub_n <- n

let lens tr =
  let p = tr.p in
  let cam = p.camera in
  let x = ref 0. and y = ref 0. in
  if cam.lens_sampling = Camera.Uniform then begin
    let h = Sample_key.key tr.key lens_tag in
    let k = ref 0 in
    while !k < tries do
      let u = (2. *. unit (Sample_key.key h (2 * !k))) -. 1. in
      let v = (2. *. unit (Sample_key.key h ((2 * !k) + 1))) -. 1. in
      if (u *. u) +. (v *. v) < 1. then begin
        x := u;
        y := v;
        k := tries
      end
      else incr k
    done
  end
  else begin
    let n = tr.lens_n and k = tr.lens_k and s = tr.s in
    (* The pixel's numbers, once per pixel: a pixel's samples are traced
       one after the other. *)
    if tr.lens_gx <> tr.lens_px || tr.lens_gy <> tr.lens_py then begin
      let hp = Sample_key.pixel ~col:tr.lens_gx ~row:tr.lens_gy ~sample:lens_tag in
      s.lens_u0 <- unit (Sample_key.key hp 0);
      s.lens_v0 <- unit (Sample_key.key hp 1);
      tr.lens_hc <- Sample_key.mix (Sample_key.key hp 2);
      tr.lens_sub_n <- 0;
      tr.lens_px <- tr.lens_gx;
      tr.lens_py <- tr.lens_gy
    end;
    let x0 = s.lens_u0 and y0 = s.lens_v0 in
    let centre = if n land 1 = 1 then ((n / 2) * n) + (n / 2) else -1 in
    let u = ref x0 and v = ref y0 in
    if k <> centre then begin
      (* The centre keeps cell 0: the others share the rest, by
         [Sample_key.permute (key hp 2)] of that many, its mixed key and
         mask kept from sample to sample. *)
      let m = if centre >= 0 then (n * n) - 1 else n * n in
      if m <> tr.lens_m then begin
        tr.lens_m <- m;
        tr.lens_w <- Sample_key.mask m
      end;
      (* The sub-cell permutations, once per pixel and grid: [n - 1]
         walks each, not two a sample. *)
      if n <> tr.lens_sub_n then sub_cells tr n;
      let c =
        if centre >= 0 then 1 + Sample_key.walk ~p:tr.lens_hc ~w:tr.lens_w ~n:m (if k < centre then k else k - 1)
        else Sample_key.walk ~p:tr.lens_hc ~w:tr.lens_w ~n:m k
      in
      (* The sub-cell: the cell's column [ci] and row [cj] are the coarse
         strata; [sx], the row's place in the pixel's first sub-cell
         permutation, and [sy], the column's in its second, the fine ones
         (both fix 0: cell 0's sub-cell is its corner's, the centre
         sample's point); the jitter, two numbers chained from the
         sample's lens key, inside it. *)
      let ci = c mod n and cj = c / n in
      let sx = Array.unsafe_get tr.lens_sub cj and sy = Array.unsafe_get tr.lens_sub (n + ci) in
      let h = Sample_key.key tr.key lens_tag and fn2 = Float.of_int (n * n) in
      let a = ((Float.of_int ((ci * n) + sx) +. unit h) /. fn2) +. x0 in
      let b = ((Float.of_int ((cj * n) + sy) +. unit (Sample_key.mix h)) /. fn2) +. y0 in
      u := if a >= 1. then a -. 1. else a;
      v := if b >= 1. then b -. 1. else b
    end;
    (* The concentric map, from [\[0, 1\]^2] onto the unit disc. *)
    let a = (2. *. !u) -. 1. and b = (2. *. !v) -. 1. in
    if a = 0. && b = 0. then ()
    else if Float.abs a > Float.abs b then begin
      let t = quarter_pi *. (b /. a) in
      x := a *. cos_q t;
      y := a *. sin_q t
    end
    else begin
      let t = quarter_pi *. (a /. b) in
      x := b *. sin_q t;
      y := b *. cos_q t
    end
  end;
  move tr !x !y

let set_lens_pixel tr col row =
  set_pixel tr col row;
  if tr.p.camera.aperture > 0. then lens tr

let set_lens_point tr =
  set_point tr;
  if tr.p.camera.aperture > 0. then lens tr

(* Probe [k] of adaptive sampling ([k] in [0, 3]): the pixel's centre ray
   moved to the rim point [(1, 0)], [(-1, 0)], [(0, 1)] or [(0, -1)] of the
   unit disc. Fixed points, no key: the same ray for every process, tile
   and region. *)
let set_probe tr col row k =
  set_pixel tr col row;
  if tr.p.camera.aperture > 0. then
    if k = 0 then move tr 1. 0. else if k = 1 then move tr (-1.) 0. else if k = 2 then move tr 0. 1. else move tr 0. (-1.)
