let pi = 4. *. atan 1.

(* The quad a b c d, whose edges a->b then b->c run clockwise seen from
   its front, as two counter-clockwise triangles (a, d, b) and (b, d, c)
   at [triangles.(k)]. *)
let quad triangles k a b c d =
  triangles.(k) <- a; triangles.(k + 1) <- d; triangles.(k + 2) <- b;
  triangles.(k + 3) <- b; triangles.(k + 4) <- d; triangles.(k + 5) <- c

let torus_knot ~p ~q ~radius ~tube ~segments ~sides =
  let pos_finite x = Float.is_finite x && x > 0. in
  if p < 1 || q < 1 || segments < 3 || sides < 3 || not (pos_finite radius && pos_finite tube) then
    invalid_arg "Mesh_gen.torus_knot";
  let s = radius /. 3. and fp = Float.of_int p and fq = Float.of_int q in
  let n = segments * sides in
  let positions = Array.make (3 * n) 0. and normals = Array.make (3 * n) 0. in
  for i = 0 to segments - 1 do
    let t = 2. *. pi *. Float.of_int i /. Float.of_int segments in
    let r = 2. +. cos (fq *. t) in
    let cx = s *. r *. cos (fp *. t) and cy = s *. r *. sin (fp *. t) and cz = -.s *. sin (fq *. t) in
    (* The derivative of the curve: the tube's axis. *)
    let dr = -.fq *. sin (fq *. t) in
    let tx = s *. ((dr *. cos (fp *. t)) -. (r *. fp *. sin (fp *. t)))
    and ty = s *. ((dr *. sin (fp *. t)) +. (r *. fp *. cos (fp *. t)))
    and tz = -.s *. fq *. cos (fq *. t) in
    (* A frame across the axis: b = t x c (c, from the z axis to the
       curve, is never along t: t has a component r p s around the axis),
       then n = b x t, both normalised. *)
    let bx = (ty *. cz) -. (tz *. cy) and by = (tz *. cx) -. (tx *. cz) and bz = (tx *. cy) -. (ty *. cx) in
    let bl = sqrt ((bx *. bx) +. (by *. by) +. (bz *. bz)) in
    let bx = bx /. bl and by = by /. bl and bz = bz /. bl in
    let nx = (by *. tz) -. (bz *. ty) and ny = (bz *. tx) -. (bx *. tz) and nz = (bx *. ty) -. (by *. tx) in
    let nl = sqrt ((nx *. nx) +. (ny *. ny) +. (nz *. nz)) in
    let nx = nx /. nl and ny = ny /. nl and nz = nz /. nl in
    for j = 0 to sides - 1 do
      let a = 2. *. pi *. Float.of_int j /. Float.of_int sides in
      let c = cos a and sn = sin a in
      let ux = (c *. nx) +. (sn *. bx) and uy = (c *. ny) +. (sn *. by) and uz = (c *. nz) +. (sn *. bz) in
      let ul = sqrt ((ux *. ux) +. (uy *. uy) +. (uz *. uz)) in
      let ux = ux /. ul and uy = uy /. ul and uz = uz /. ul in
      let k = 3 * ((i * sides) + j) in
      positions.(k) <- cx +. (tube *. ux);
      positions.(k + 1) <- cy +. (tube *. uy);
      positions.(k + 2) <- cz +. (tube *. uz);
      normals.(k) <- ux;
      normals.(k + 1) <- uy;
      normals.(k + 2) <- uz
    done
  done;
  let triangles = Array.make (6 * n) 0 in
  for i = 0 to segments - 1 do
    let i' = (i + 1) mod segments in
    for j = 0 to sides - 1 do
      let j' = (j + 1) mod sides in
      let a = (i * sides) + j and b = (i' * sides) + j and c = (i' * sides) + j' and d = (i * sides) + j' in
      (* Along the axis then around it is clockwise seen from outside. *)
      quad triangles (6 * ((i * sides) + j)) a b c d
    done
  done;
  Obj_file.v ~positions ~normals ~triangles ~triangle_normals:(Array.copy triangles)

(* A hash of lattice point (i, j) in octave [o] to [0, 1): integer mixing
   in Int64, which wraps the same way everywhere, JavaScript's 32-bit ints
   included. *)
let lattice seed o i j =
  let open Int64 in
  let ( + ) = add and ( * ) = mul and ( lxor ) = logxor and ( lsr ) = shift_right_logical in
  let h = (of_int seed * 0x2545F491L) + (of_int o * 0x9E3779B1L) + (of_int i * 0x85EBCA6BL) + (of_int j * 0xC2B2AE35L) in
  let h = h lxor (h lsr 29) in
  let h = h * 0x27D4EB2F165667C5L in
  let h = h lxor (h lsr 32) in
  let h = h * 0x165667B19E3779F9L in
  let h = h lxor (h lsr 29) in
  Stdlib.( /. ) (Float.of_int (to_int (logand h 0xFFFFFFL))) 16777216.

let smooth t = t *. t *. (3. -. (2. *. t))

(* Value noise at (u, v) in lattice units: the lattice values blended by a
   smooth step. *)
let value seed o u v =
  let i = Float.to_int (Float.floor u) and j = Float.to_int (Float.floor v) in
  let fu = smooth (u -. Float.floor u) and fv = smooth (v -. Float.floor v) in
  let a = lattice seed o i j and b = lattice seed o (i + 1) j in
  let c = lattice seed o i (j + 1) and d = lattice seed o (i + 1) (j + 1) in
  let lo = a +. (fu *. (b -. a)) and hi = c +. (fu *. (d -. c)) in
  lo +. (fv *. (hi -. lo))

(* Four octaves, each of twice the frequency and half the amplitude; the
   amplitudes sum to 15/16, hence the division, to stay in [0, 1). *)
let noise seed u v =
  let sum = ref 0. and amp = ref 0.5 and freq = ref 4. in
  for o = 0 to 3 do
    sum := !sum +. (!amp *. value seed o (u *. !freq) (v *. !freq));
    amp := !amp /. 2.;
    freq := !freq *. 2.
  done;
  !sum /. 0.9375

let terrain ~seed ~nx ~nz ~size ~height =
  if nx < 1 || nz < 1 || not (Float.is_finite size && size > 0. && Float.is_finite height && height >= 0.) then
    invalid_arg "Mesh_gen.terrain";
  let w = nx + 1 in
  let n = w * (nz + 1) in
  let dx = size /. Float.of_int nx and dz = size /. Float.of_int nz in
  let y = Array.make n 0. in
  for j = 0 to nz do
    for i = 0 to nx do
      y.((j * w) + i) <- height *. noise seed (Float.of_int i /. Float.of_int nx) (Float.of_int j /. Float.of_int nz)
    done
  done;
  let positions = Array.make (3 * n) 0. and normals = Array.make (3 * n) 0. in
  for j = 0 to nz do
    for i = 0 to nx do
      let k = (j * w) + i in
      positions.(3 * k) <- (Float.of_int i *. dx) -. (size /. 2.);
      positions.((3 * k) + 1) <- y.(k);
      positions.((3 * k) + 2) <- (Float.of_int j *. dz) -. (size /. 2.);
      (* Slopes by differences over the neighbours inside the grid. *)
      let i0 = max 0 (i - 1) and i1 = min nx (i + 1) and j0 = max 0 (j - 1) and j1 = min nz (j + 1) in
      let sx = (y.((j * w) + i1) -. y.((j * w) + i0)) /. (Float.of_int (i1 - i0) *. dx) in
      let sz = (y.((j1 * w) + i) -. y.((j0 * w) + i)) /. (Float.of_int (j1 - j0) *. dz) in
      let l = sqrt ((sx *. sx) +. 1. +. (sz *. sz)) in
      normals.(3 * k) <- -.sx /. l;
      normals.((3 * k) + 1) <- 1. /. l;
      normals.((3 * k) + 2) <- -.sz /. l
    done
  done;
  let triangles = Array.make (6 * nx * nz) 0 in
  for j = 0 to nz - 1 do
    for i = 0 to nx - 1 do
      let a = (j * w) + i in
      let b = a + 1 and d = a + w in
      let c = d + 1 in
      (* x then z is clockwise seen from above (+y). *)
      quad triangles (6 * ((j * nx) + i)) a b c d
    done
  done;
  Obj_file.v ~positions ~normals ~triangles ~triangle_normals:(Array.copy triangles)
