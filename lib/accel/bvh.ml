type t = { order : int array; n_nodes : int; nodes : float array; root : int; depth : int }

(* A node's 8 floats, at [root + 8 k]: lower corner, upper corner, link,
   tag. A node visit of the tracer reads one 64-byte block, not 8 arrays
   (8 cache lines); link and tag as floats are exact (below 2^53) and
   converted by one instruction each. *)
let node_floats = 8

(* The address of [a]'s first float modulo 64, read from the pointer that
   [a] is: [Obj.magic a] as an int is [(p - 1) / 2] in OCaml's tagged
   arithmetic, so that [2 v + 1] is [p] (every intermediate word odd, a
   valid int for the collector). Where there is no address (JavaScript),
   any number: it only places the nodes. *)
let line_offset (a : float array) = (((Obj.magic a : int) * 2) + 1) land 63

(* The offset in [a] of its first float on a 64-byte boundary, from 0 to
   7, where node 0 goes so that every node is one cache line: a big
   array's data starts 8 bytes after a header, wherever its chunk of the
   heap put it (16 and 48 bytes past a line for grid:1000000 and the
   1M-triangle knot). The collector does not move it afterwards unless it
   compacts the heap, which costs speed then, not correctness. *)
let aligned_root (a : float array) = ((64 - line_offset a) / 8) land 7

(* The offset of node [k] where node 0 is at [root]. *)
let[@inline] at root k = root + (k lsl 3)
let[@inline] offset t k = at t.root k
let[@inline] lo_at (nodes : float array) o a = Array.unsafe_get nodes (o + a)
let[@inline] hi_at (nodes : float array) o a = Array.unsafe_get nodes (o + 3 + a)
let[@inline] link_at (nodes : float array) o = truncate (Array.unsafe_get nodes (o + 6))
let[@inline] tag_at (nodes : float array) o = truncate (Array.unsafe_get nodes (o + 7))

let check_node t k =
  if k < 0 || k >= t.n_nodes then invalid_arg (Printf.sprintf "Bvh: node %d of %d" k t.n_nodes)

let lo t k a =
  check_node t k;
  if a < 0 || a > 2 then invalid_arg "Bvh.lo: axis";
  lo_at t.nodes (offset t k) a

let hi t k a =
  check_node t k;
  if a < 0 || a > 2 then invalid_arg "Bvh.hi: axis";
  hi_at t.nodes (offset t k) a

let link t k =
  check_node t k;
  let o = offset t k in
  let l = link_at t.nodes o in
  if tag_at t.nodes o > 0 then l else (l - t.root) / node_floats

let tag t k =
  check_node t k;
  tag_at t.nodes (offset t k)

let[@inline] fmin (a : float) b = if a < b then a else b
let[@inline] fmax (a : float) b = if a > b then a else b

(* Half the surface area of a box: the surface area heuristic (SAH) takes
   the chance that a ray meets a box to grow with its area. *)
let[@inline] half_area x0 y0 z0 x1 y1 z1 =
  let dx = x1 -. x0 and dy = y1 -. y0 and dz = z1 -. z0 in
  (dx *. dy) +. (dy *. dz) +. (dz *. dx)

let bins = 16

(* The tree's shape while it is built, 16 bytes a node, grown as the
   tree is: the ten node arrays are made once the number of nodes is
   known, and their boxes filled in from the leaves up (a box is the min
   and max of its objects' boxes, whichever way they are grouped). Node
   [k]'s [link] is its right child (inner node) or first slot (leaf), its
   [tag] its split axis 0 to 2 (inner node) or minus its count (leaf).
   Out of the collector's heap, in bigarrays (malloc'd, their pages
   taken from the system only where written, and given back once the
   build lets them go): room for [1.06 n] nodes takes memory only where
   nodes are written (a mesh's leaves of 16 make about [0.19 n]), and
   the arrays made after the build find no room in the heap that no
   node ever used (int arrays, zeroed, took 17 MB for a million
   triangles, 14 of them never read). A link is a node's or a slot's
   number, below [2^31] (checked at the start), in 32 bits; a tag is at
   least [-max_leaf], in 16: 6 bytes a node, not 16. A wall of spheres
   writes all of its [1.04 n] nodes, and the collector frees these
   arrays only at a later cycle, while prepare makes its next arrays: a
   million spheres' peak had grown by 7 MB when they left the heap as
   ints. *)
type links = (int32, Bigarray.int32_elt, Bigarray.c_layout) Bigarray.Array1.t

type tags = (int, Bigarray.int16_signed_elt, Bigarray.c_layout) Bigarray.Array1.t

type shape = { mutable size : int; mutable link : links; mutable tag : tags }

(* The most objects a leaf holds: its count's negation is a tag. *)
let max_leaf = 0x7fff

(* Made with the collector's pace for memory out of its heap relaxed: it
   counts a bigarray's bytes as a reason to mark the heap sooner, where
   these are let go at the build's end (as [Obj_text]'s blocks). *)
let out_of_heap kind n =
  let gc = Gc.get () in
  Gc.set { gc with custom_major_ratio = 1_000_000 };
  let a = Bigarray.Array1.create kind Bigarray.c_layout n in
  Gc.set gc;
  a

let[@inline] link_of t k = Int32.to_int (Bigarray.Array1.get t.link k)
let[@inline] tag_of t k = Bigarray.Array1.get t.tag k
let[@inline] set_link t k v = Bigarray.Array1.set t.link k (Int32.of_int v)
let[@inline] set_tag t k v = Bigarray.Array1.set t.tag k v

let add_node t =
  if t.size = Bigarray.Array1.dim t.link then begin
    let grow kind a =
      let b = out_of_heap kind (2 * t.size) in
      Bigarray.Array1.blit a (Bigarray.Array1.sub b 0 t.size);
      b
    in
    t.link <- grow Bigarray.int32 t.link;
    t.tag <- grow Bigarray.int16_signed t.tag
  end;
  t.size <- t.size + 1;
  t.size - 1

let[@inline] swap_float (a : float array) i j =
  let x = Array.unsafe_get a i in
  Array.unsafe_set a i (Array.unsafe_get a j);
  Array.unsafe_set a j x

(* Exchanges slots [i] and [j]: their boxes move with them. *)
let[@inline] swap_slots x0 y0 z0 x1 y1 z1 (order : int array) i j =
  swap_float x0 i j;
  swap_float y0 i j;
  swap_float z0 i j;
  swap_float x1 i j;
  swap_float y1 i j;
  swap_float z1 i j;
  let o = Array.unsafe_get order i in
  Array.unsafe_set order i (Array.unsafe_get order j);
  Array.unsafe_set order j o

(* The bin of a doubled center [c] among [bins] over [c0 .. c0 + bins / scale]. *)
let[@inline] bin_of c c0 scale bins =
  let b = truncate ((c -. c0) *. scale) in
  if b < 0 then 0 else if b >= bins then bins - 1 else b

(* [merge box o ...] grows the box of 6 floats at [o] in [box] by the box
   given: each bound [fmin box.(o + i) v] or [fmax box.(o + i) v], bit for
   bit, stored only where it is [v] (most objects leave a bin's box as it
   is). The offsets written out at each access, not bound once: the
   compiler then folds them into the addressing. *)
let[@inline] merge (box : float array) o x0 y0 z0 x1 y1 z1 =
  if not (Array.unsafe_get box o < x0) then Array.unsafe_set box o x0;
  if not (Array.unsafe_get box (o + 1) < y0) then Array.unsafe_set box (o + 1) y0;
  if not (Array.unsafe_get box (o + 2) < z0) then Array.unsafe_set box (o + 2) z0;
  if not (Array.unsafe_get box (o + 3) > x1) then Array.unsafe_set box (o + 3) x1;
  if not (Array.unsafe_get box (o + 4) > y1) then Array.unsafe_set box (o + 4) y1;
  if not (Array.unsafe_get box (o + 5) > z1) then Array.unsafe_set box (o + 5) z1

(* A node waiting to be built has a block of [block] floats: its bounds
   (12 floats: its objects' box, lower corner then upper, then the box of
   their doubled centers), the boxes of its bins (6 floats a bin, at
   [boxes_at]), the boxes of each bin's doubled centers (at
   [centers_at]); and [bins] ints of another array, its bins' counts.
   Its parent fills the bins as it moves each object to its side (see
   {!partition_bins}): a level of the tree is one pass over its objects,
   where it was two (bin, then partition). The bins' boxes of centers
   give the children's bounds of centers, which the binning of the
   children needs before that pass. *)
let block = 12 + (12 * bins)
let boxes_at = 12
let centers_at = 12 + (6 * bins)

(* [check_block fr cn p] checks that block [p] is in [fr] and [cn]: one
   check for the unchecked reads and writes of the block's bins. *)
let check_block (fr : float array) (cn : int array) p =
  if p < 0 || ((p + 1) * block) > Array.length fr || ((p + 1) * bins) > Array.length cn then
    invalid_arg "Bvh: block"

(* [reset_bins fr cn p nb] empties the first [nb] bins of block [p]: their
   counts (a bin's boxes are written by its first object, {!add_to}, and
   read only if it has one). *)
let reset_bins (fr : float array) (cn : int array) p nb =
  check_block fr cn p;
  if nb > bins then invalid_arg "Bvh.reset_bins";
  let co = p * bins in
  for b = 0 to nb - 1 do
    Array.unsafe_set cn (co + b) 0
  done

(* Adds the box [x0 .. z1] of doubled center [(cx, cy, cz)] to bin [b]
   of the block at [bo] in [fr], counts at [co] in [cn]: the first
   object's boxes are the bin's (the min of infinity and [x] is [x]), the
   others grow them. Min and max are exact in any order: a bin's boxes
   are the same in whatever order its objects come. *)
let[@inline] add_to (fr : float array) (cn : int array) bo co b x0 y0 z0 x1 y1 z1 cx cy cz =
  let c = Array.unsafe_get cn (co + b) in
  Array.unsafe_set cn (co + b) (c + 1);
  let o = bo + boxes_at + (6 * b) and oc = bo + centers_at + (6 * b) in
  if c = 0 then begin
    Array.unsafe_set fr o x0;
    Array.unsafe_set fr (o + 1) y0;
    Array.unsafe_set fr (o + 2) z0;
    Array.unsafe_set fr (o + 3) x1;
    Array.unsafe_set fr (o + 4) y1;
    Array.unsafe_set fr (o + 5) z1;
    Array.unsafe_set fr oc cx;
    Array.unsafe_set fr (oc + 1) cy;
    Array.unsafe_set fr (oc + 2) cz;
    Array.unsafe_set fr (oc + 3) cx;
    Array.unsafe_set fr (oc + 4) cy;
    Array.unsafe_set fr (oc + 5) cz
  end
  else begin
    merge fr o x0 y0 z0 x1 y1 z1;
    merge fr oc cx cy cz cx cy cz
  end

(* Bins slot [s], of box [x0 .. z1] and doubled center [(cx, cy, cz)],
   among the [nb] bins along axis [a] of the block at [bo] in [fr]
   (counts at [co] in [cn]) that start at [c0], [scale] bins a unit;
   its bin to [bin_at]. *)
let[@inline] bin_one (fr : float array) (cn : int array) bo co bin_at s a c0 scale nb x0 y0 z0 x1 y1 z1 cx cy cz =
  let b = bin_of (if a = 0 then cx else if a = 1 then cy else cz) c0 scale nb in
  Bytes.unsafe_set bin_at s (Char.unsafe_chr b);
  add_to fr cn bo co b x0 y0 z0 x1 y1 z1 cx cy cz

(* [binning fr p n params i] is [a + 4 nb] for the node of [n] objects
   whose bounds are in block [p]: [a] the axis 0 to 2 along which its
   centers spread most, [nb] its number of bins, 0 if it is not binned
   (one object, or its centers all at the same place along [a]). It
   writes the bins' first center and scale to [params] at [i] and [i +
   1] (bin [b] holds the doubled centers from [c0 + b / scale]). *)
let binning (fr : float array) p n (params : float array) i =
  let o = (p * block) + 6 in
  let ex = fr.(o + 3) -. fr.(o) and ey = fr.(o + 4) -. fr.(o + 1) and ez = fr.(o + 5) -. fr.(o + 2) in
  let a = if ex >= ey && ex >= ez then 0 else if ey >= ez then 1 else 2 in
  let ext = match a with 0 -> ex | 1 -> ey | _ -> ez in
  let nb = if n < bins then n else bins in
  if n <= 1 || not (ext > 0.) then a
  else begin
    params.(i) <- fr.(o + a);
    params.(i + 1) <- Float.of_int nb /. ext;
    a + (4 * nb)
  end

(* [bin_slots x0 y0 z0 x1 y1 z1 bin_at lo hi params fr cn p] bins slots
   [lo .. hi - 1] into block [p], as {!binning} found it ([params] at 0
   and 1), each slot's bin in [bin_at]: for the nodes that no partition
   binned, the root and the children of a split at the median. *)
let bin_slots (x0 : float array) (y0 : float array) (z0 : float array) (x1 : float array) (y1 : float array)
    (z1 : float array) bin_at lo hi (params : float array) (fr : float array) (cn : int array) p =
  let n = hi - lo in
  let g = binning fr p n params 0 in
  let a = g land 3 and nb = g lsr 2 in
  if nb > 0 then begin
    reset_bins fr cn p nb;
    if lo < 0 || hi > Array.length x0 || hi > Bytes.length bin_at then invalid_arg "Bvh.bin_slots";
    let c0 = Array.unsafe_get params 0 and scale = Array.unsafe_get params 1 in
    let bo = p * block and co = p * bins in
    for s = lo to hi - 1 do
      let vx0 = Array.unsafe_get x0 s and vy0 = Array.unsafe_get y0 s and vz0 = Array.unsafe_get z0 s in
      let vx1 = Array.unsafe_get x1 s and vy1 = Array.unsafe_get y1 s and vz1 = Array.unsafe_get z1 s in
      let cx = vx0 +. vx1 and cy = vy0 +. vy1 and cz = vz0 +. vz1 in
      bin_one fr cn bo co bin_at s a c0 scale nb vx0 vy0 vz0 vx1 vy1 vz1 cx cy cz
    done
  end

(* [partition_bins x0 y0 z0 x1 y1 z1 order bin_at best lo hi params l r
   fr cn] moves slots [lo .. hi - 1] whose bin is at most [best] first
   (their boxes and objects with them), the others after, and is the
   first of the others. Each object is read once: as it goes to its side,
   it is binned into that child's block, [l] or [r] ([g] of {!binning}
   at [params] 0 and 2, bins reset; a child of no bins is not binned),
   its bin for the child left in [bin_at]. The order of the slots is that
   of the partition that was once a pass of its own: slot [i] kept if on
   the left, else exchanged with the last slot not yet placed. *)
let partition_bins (x0 : float array) (y0 : float array) (z0 : float array) (x1 : float array)
    (y1 : float array) (z1 : float array) (order : int array) bin_at best lo hi (params : float array) lg rg
    l r (fr : float array) (cn : int array) =
  check_block fr cn l;
  check_block fr cn r;
  let n = Array.length x0 in
  if lo < 0 || hi > n || hi > Bytes.length bin_at || Array.length params < 4 || Array.length order <> n || Array.length y0 <> n
     || Array.length z0 <> n || Array.length x1 <> n || Array.length y1 <> n || Array.length z1 <> n
  then invalid_arg "Bvh.partition_bins";
  let la = lg land 3 and lnb = lg lsr 2 and ra = rg land 3 and rnb = rg lsr 2 in
  let lc0 = Array.unsafe_get params 0 and ls = Array.unsafe_get params 1 in
  let rc0 = Array.unsafe_get params 2 and rs = Array.unsafe_get params 3 in
  let lbo = l * block and lco = l * bins and rbo = r * block and rco = r * bins in
  let i = ref lo and j = ref (hi - 1) in
  while !i <= !j do
    let s = !i in
    let vx0 = Array.unsafe_get x0 s and vy0 = Array.unsafe_get y0 s and vz0 = Array.unsafe_get z0 s in
    let vx1 = Array.unsafe_get x1 s and vy1 = Array.unsafe_get y1 s and vz1 = Array.unsafe_get z1 s in
    let cx = vx0 +. vx1 and cy = vy0 +. vy1 and cz = vz0 +. vz1 in
    if Char.code (Bytes.unsafe_get bin_at s) <= best then begin
      if lnb > 0 then bin_one fr cn lbo lco bin_at s la lc0 ls lnb vx0 vy0 vz0 vx1 vy1 vz1 cx cy cz;
      incr i
    end
    else begin
      let d = !j in
      Array.unsafe_set x0 s (Array.unsafe_get x0 d);
      Array.unsafe_set y0 s (Array.unsafe_get y0 d);
      Array.unsafe_set z0 s (Array.unsafe_get z0 d);
      Array.unsafe_set x1 s (Array.unsafe_get x1 d);
      Array.unsafe_set y1 s (Array.unsafe_get y1 d);
      Array.unsafe_set z1 s (Array.unsafe_get z1 d);
      Array.unsafe_set x0 d vx0;
      Array.unsafe_set y0 d vy0;
      Array.unsafe_set z0 d vz0;
      Array.unsafe_set x1 d vx1;
      Array.unsafe_set y1 d vy1;
      Array.unsafe_set z1 d vz1;
      let o = Array.unsafe_get order s in
      Array.unsafe_set order s (Array.unsafe_get order d);
      Array.unsafe_set order d o;
      Bytes.unsafe_set bin_at s (Bytes.unsafe_get bin_at d);
      if rnb > 0 then bin_one fr cn rbo rco bin_at d ra rc0 rs rnb vx0 vy0 vz0 vx1 vy1 vz1 cx cy cz;
      decr j
    end
  done;
  !i

(* [copy6 a i b j] copies [a.(i) .. a.(i + 5)] to [b.(j) .. b.(j + 5)],
   in place of [Array.blit], a call into C, for the 2 boxes of every node. *)
let[@inline] copy6 (a : float array) i (b : float array) j =
  if i < 0 || j < 0 || i + 6 > Array.length a || j + 6 > Array.length b then invalid_arg "Bvh.copy6";
  Array.unsafe_set b j (Array.unsafe_get a i);
  Array.unsafe_set b (j + 1) (Array.unsafe_get a (i + 1));
  Array.unsafe_set b (j + 2) (Array.unsafe_get a (i + 2));
  Array.unsafe_set b (j + 3) (Array.unsafe_get a (i + 3));
  Array.unsafe_set b (j + 4) (Array.unsafe_get a (i + 4));
  Array.unsafe_set b (j + 5) (Array.unsafe_get a (i + 5))

(* [running_boxes cn co fr bo b0 b1 out] writes at [6 b] in [out], for
   each [b] from [b0] to [b1] (downwards if [b1 < b0]), the box of the
   bins from [b0] to [b] of the block whose counts are at [co] in [cn],
   boxes at [bo] in [fr]: grown in registers, each bin's box read once. *)
let running_boxes (cn : int array) co (fr : float array) bo b0 b1 (out : float array) =
  if co < 0 || bo < 0 || co + bins > Array.length cn || bo + (6 * bins) > Array.length fr || b0 < 0 || b1 < 0
     || b0 >= bins || b1 >= bins || Array.length out < 6 * bins
  then invalid_arg "Bvh.running_boxes";
  let step = if b1 >= b0 then 1 else -1 in
  let bx0 = ref infinity and by0 = ref infinity and bz0 = ref infinity in
  let bx1 = ref neg_infinity and by1 = ref neg_infinity and bz1 = ref neg_infinity in
  for i = 0 to abs (b1 - b0) do
    let b = b0 + (step * i) in
    let o = bo + (6 * b) in
    if Array.unsafe_get cn (co + b) > 0 then begin
      bx0 := fmin !bx0 (Array.unsafe_get fr o);
      by0 := fmin !by0 (Array.unsafe_get fr (o + 1));
      bz0 := fmin !bz0 (Array.unsafe_get fr (o + 2));
      bx1 := fmax !bx1 (Array.unsafe_get fr (o + 3));
      by1 := fmax !by1 (Array.unsafe_get fr (o + 4));
      bz1 := fmax !bz1 (Array.unsafe_get fr (o + 5))
    end;
    let o = 6 * b in
    Array.unsafe_set out o !bx0;
    Array.unsafe_set out (o + 1) !by0;
    Array.unsafe_set out (o + 2) !bz0;
    Array.unsafe_set out (o + 3) !bx1;
    Array.unsafe_set out (o + 4) !by1;
    Array.unsafe_set out (o + 5) !bz1
  done

(* [union cn co fr bo b0 b1 out o] writes to [out] at [o] the union of
   the boxes of bins [b0 .. b1] (6 floats a bin at [bo] in [fr], counts
   at [co] in [cn]; an empty bin holds no box): the box of a side's
   doubled centers. *)
let union (cn : int array) co (fr : float array) bo b0 b1 (out : float array) o =
  let x0 = ref infinity and y0 = ref infinity and z0 = ref infinity in
  let x1 = ref neg_infinity and y1 = ref neg_infinity and z1 = ref neg_infinity in
  for b = b0 to b1 do
    if cn.(co + b) > 0 then begin
      let c = bo + (6 * b) in
      x0 := fmin !x0 fr.(c);
      y0 := fmin !y0 fr.(c + 1);
      z0 := fmin !z0 fr.(c + 2);
      x1 := fmax !x1 fr.(c + 3);
      y1 := fmax !y1 fr.(c + 4);
      z1 := fmax !z1 fr.(c + 5)
    end
  done;
  out.(o) <- !x0;
  out.(o + 1) <- !y0;
  out.(o + 2) <- !z0;
  out.(o + 3) <- !x1;
  out.(o + 4) <- !y1;
  out.(o + 5) <- !z1

type floats = (float, Bigarray.float64_elt, Bigarray.c_layout) Bigarray.Array1.t

(* [leaf_box x0 y0 z0 x1 y1 z1 l c into o] writes the box of slots [l ..
   l + c - 1] to [into] at [o .. o + 5]. *)
let[@inline] leaf_box (x0 : float array) (y0 : float array) (z0 : float array) (x1 : float array)
    (y1 : float array) (z1 : float array) l c (into : float array) o =
  let bx0 = ref infinity and by0 = ref infinity and bz0 = ref infinity in
  let bx1 = ref neg_infinity and by1 = ref neg_infinity and bz1 = ref neg_infinity in
  for s = l to l + c - 1 do
    bx0 := fmin !bx0 (Array.unsafe_get x0 s);
    by0 := fmin !by0 (Array.unsafe_get y0 s);
    bz0 := fmin !bz0 (Array.unsafe_get z0 s);
    bx1 := fmax !bx1 (Array.unsafe_get x1 s);
    by1 := fmax !by1 (Array.unsafe_get y1 s);
    bz1 := fmax !bz1 (Array.unsafe_get z1 s)
  done;
  into.(o) <- !bx0;
  into.(o + 1) <- !by0;
  into.(o + 2) <- !bz0;
  into.(o + 3) <- !bx1;
  into.(o + 4) <- !by1;
  into.(o + 5) <- !bz1

(* The leaves of nodes [first .. last - 1], whose boxes were gathered
   into the six arrays of slot boxes: the [j]th one's box in slot
   [at + j], each one slot ([at + j] is at most its first slot). *)
type gathered = { first : int; last : int; at : int; leaves : int }

let none_gathered = { first = 0; last = 0; at = 0; leaves = 0 }

(* [finish_nodes nodes root link tag x0 y0 z0 x1 y1 z1 lo hi gathered]
   writes nodes [hi - 1] down to [lo] to [nodes], from the shape's [link]
   and [tag] and their children, already written: a leaf's box from its
   slots if [gathered < 0], else the leaves' boxes are gathered in slots
   [.. gathered - 1] (the box of one slot is that slot's box: the min of
   infinity and [x] is [x]). It is where the gathered boxes start. *)
let finish_nodes nodes root (link : links) (tag : tags) x0 y0 z0 x1 y1 z1 lo hi gathered =
  let next = ref gathered in
  for k = hi - 1 downto lo do
    let o = at root k in
    let l = Int32.to_int (Bigarray.Array1.get link k) and g = Bigarray.Array1.get tag k in
    (* An inner node's link is its right child's offset: the tracer's
       stack holds offsets, not indices to multiply. *)
    nodes.(o + 6) <- Float.of_int (if g < 0 then l else at root l);
    if g < 0 then begin
      (* A leaf: its count, [-g], becomes its tag. *)
      nodes.(o + 7) <- Float.of_int (-g);
      if gathered < 0 then leaf_box x0 y0 z0 x1 y1 z1 l (-g) nodes o
      else begin
        decr next;
        leaf_box x0 y0 z0 x1 y1 z1 !next 1 nodes o
      end
    end
    else begin
      (* An inner node: its axis [g] becomes [-1 - g]; [l] is its right child. *)
      nodes.(o + 7) <- Float.of_int (-1 - g);
      (* Both children come after [k], already written. *)
      let c = at root (k + 1) and r = at root l in
      Array.unsafe_set nodes o (fmin (Array.unsafe_get nodes c) (Array.unsafe_get nodes r));
      Array.unsafe_set nodes (o + 1) (fmin (Array.unsafe_get nodes (c + 1)) (Array.unsafe_get nodes (r + 1)));
      Array.unsafe_set nodes (o + 2) (fmin (Array.unsafe_get nodes (c + 2)) (Array.unsafe_get nodes (r + 2)));
      Array.unsafe_set nodes (o + 3) (fmax (Array.unsafe_get nodes (c + 3)) (Array.unsafe_get nodes (r + 3)));
      Array.unsafe_set nodes (o + 4) (fmax (Array.unsafe_get nodes (c + 4)) (Array.unsafe_get nodes (r + 4)));
      Array.unsafe_set nodes (o + 5) (fmax (Array.unsafe_get nodes (c + 5)) (Array.unsafe_get nodes (r + 5)))
    end
  done;
  !next

(* The nodes of the tree [t] over the slots' boxes, the boxes from the
   leaves up: children come after their parent. The shape's arrays (16
   bytes a node) are garbage once read: the nodes (64 bytes a node) are
   the only copy made. The leaves of [mine] and [theirs] have their
   boxes gathered (see {!gathered}): [mine] is this process's left
   subtree, [theirs] the part built beside, right after it. *)
let finish t ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 ?(mine = none_gathered) ?(theirs = none_gathered) order depth =
  let n_nodes = t.size in
  (* Every element is written below. *)
  let nodes = Array.create_float ((node_floats * n_nodes) + node_floats - 1) in
  let root = aligned_root nodes in
  let link = t.link and tag = t.tag in
  let n = Array.length x0 in
  (* Without [theirs] (nothing built beside), an empty range after [mine]. *)
  let theirs = if theirs.leaves = 0 then { none_gathered with first = mine.last; last = mine.last } else theirs in
  if mine.at < 0 || mine.at + mine.leaves > n || theirs.at < 0 || theirs.at + theirs.leaves > n
     || mine.first < 0 || mine.first > mine.last || theirs.first <> mine.last || theirs.last > n_nodes
  then invalid_arg "Bvh.finish: gathered leaves";
  let finish_nodes = finish_nodes nodes root link tag x0 y0 z0 x1 y1 z1 in
  (* Last to first: each node after its children. *)
  ignore (finish_nodes theirs.last n_nodes (-1));
  let t_at = finish_nodes theirs.first theirs.last (theirs.at + theirs.leaves) in
  let m_at = finish_nodes mine.first mine.last (mine.at + mine.leaves) in
  ignore (finish_nodes 0 mine.first (-1));
  if t_at <> theirs.at || m_at <> mine.at then invalid_arg "Bvh.finish: gathered leaves";
  { order; n_nodes; nodes; root; depth }

type beside = {
  beside : 'a. (unit -> 'a) -> unit -> 'a option;
  min_objects : int;
  floats : int -> floats * (int -> unit);
  idle : unit -> bool;
}

(* What a subtree built beside sends back on the pipe, small (half a MB
   for half a million objects): its nodes' tags (a byte each: their links
   follow from the tags), the deepest level it reached. Its slots'
   objects, in the order it left them, and its leaves' boxes come in the
   floats shared with the caller ([beside.floats]): read in order from
   there, where the caller once followed a permutation through 7 arrays,
   a cache miss at nearly every step. *)
type part = { tags : Bytes.t; part_depth : int }

(* A build in progress: the slots' boxes and objects, which move together
   (so that every pass over a node's objects reads memory in order), the
   nodes made so far, and the blocks of the nodes being built. *)
type build = {
  x0 : float array;
  y0 : float array;
  z0 : float array;
  x1 : float array;
  y1 : float array;
  z1 : float array;
  order : int array;
  t : shape;
  leaf_size : int;
  beside : beside option;
  n_all : int;
  mutable frames : float array;
  mutable counts : int array;
      (* The blocks of the nodes being built ({!block}): a node's
         children's go at blocks [2 level] and [2 level + 1], the right
         child's waiting there while the left's subtree is built above;
         the root's at 0. *)
  params : float array;
  bin_at : Bytes.t;
      (* Each slot's bin in its node, from the binning to the partition
         that follows; it moves with the slot. *)
  prefix : float array;
  suffix : float array;  (* The boxes of bins [0 .. b] and of bins [b .. bins - 1], at [6 b]. *)
  mutable depth : int;
  mutable alone : bool;  (* No subtree has been sent to be built beside. *)
  mutable built_here : bool;  (* [beside] ran [part] in this process. *)
  mutable mine : gathered;
  mutable theirs : gathered;
}

let start_build ~leaf_size ~beside ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 =
  let n = Array.length x0 in
  (* Made one after the other, not in the record's fields (evaluated in
     no set order): the same order of big allocations as before the build
     was cut into steps, so that the collector's slices fall where they
     fell. *)
  let order = Array.init n Fun.id in
  (* Up to [1.04 n] nodes for a wall of spheres, [0.6 n] for a mesh: room
     for [n + n / 16] from the start, not grown (a copy) in most cases. *)
  let cap = n + (n / 16) + 16 in
  if n > 0x7fff_ffff then invalid_arg "Bvh.build_boxes: more than 2^31 - 1 objects";
  let link = out_of_heap Bigarray.int32 cap in
  let tag = out_of_heap Bigarray.int16_signed cap in
  let frames = Array.make (block * 2 * 48) 0. in
  let counts = Array.make (bins * 2 * 48) 0 in
  let params = Array.make 4 0. in
  let bin_at = Bytes.create n in
  let prefix = Array.make (6 * bins) 0. in
  let suffix = Array.make (6 * bins) 0. in
  {
    x0;
    y0;
    z0;
    x1;
    y1;
    z1;
    order;
    t = { size = 0; link; tag };
    leaf_size = max 1 (min max_leaf leaf_size);
    beside;
    n_all = n;
    frames;
    counts;
    params;
    bin_at;
    prefix;
    suffix;
    depth = 0;
    alone = true;
    built_here = false;
    mine = none_gathered;
    theirs = none_gathered;
  }

(* Hoare's selection on the (doubled) centers [ka + kb]: the slot of rank
   [k] at [k], smaller ones before, larger after. *)
let select b (ka : float array) (kb : float array) lo hi k =
  let x0 = b.x0 and y0 = b.y0 and z0 = b.z0 and x1 = b.x1 and y1 = b.y1 and z1 = b.z1 and order = b.order in
  let[@inline] swap i j = swap_slots x0 y0 z0 x1 y1 z1 order i j in
  let key s = Array.unsafe_get ka s +. Array.unsafe_get kb s in
  let lo = ref lo and hi = ref (hi - 1) in
  while !lo < !hi do
    let pivot = key ((!lo + !hi) / 2) in
    let i = ref !lo and j = ref !hi in
    while !i <= !j do
      while key !i < pivot do incr i done;
      while key !j > pivot do decr j done;
      if !i <= !j then begin
        swap !i !j;
        incr i;
        decr j
      end
    done;
    if k <= !j then hi := !j else if k >= !i then lo := !i else lo := !hi
  done

let grow a z =
  let b = Array.make (2 * Array.length a) z in
  Array.blit a 0 b 0 (Array.length a);
  b

(* The first of the blocks of the children of a node at [level], the
   blocks grown to hold them. *)
let frame b level =
  if (2 * level) + 2 > Array.length b.counts / bins then begin
    b.frames <- grow b.frames 0.;
    b.counts <- grow b.counts 0
  end;
  2 * level

(* [bounds_of b lo hi r o] writes the bounds of slots [lo .. hi - 1] to [r] at [o]. *)
let bounds_of b lo hi (r : float array) o =
  let lows = [| b.x0; b.y0; b.z0 |] and highs = [| b.x1; b.y1; b.z1 |] in
  for a = 0 to 2 do
    let l = lows.(a) and h = highs.(a) in
    let b0 = ref infinity and b1 = ref neg_infinity and m0 = ref infinity and m1 = ref neg_infinity in
    for s = lo to hi - 1 do
      let x = Array.unsafe_get l s and y = Array.unsafe_get h s in
      b0 := fmin !b0 x;
      b1 := fmax !b1 y;
      let c = x +. y in
      m0 := fmin !m0 c;
      m1 := fmax !m1 c
    done;
    r.(o + a) <- !b0;
    r.(o + a + 3) <- !b1;
    r.(o + a + 6) <- !m0;
    r.(o + a + 9) <- !m1
  done

let area (a : float array) b =
  let o = 6 * b in
  half_area (Array.unsafe_get a o) (Array.unsafe_get a (o + 1)) (Array.unsafe_get a (o + 2))
    (Array.unsafe_get a (o + 3)) (Array.unsafe_get a (o + 4)) (Array.unsafe_get a (o + 5))

(* [put_box b box at] writes the box of 6 floats [box] to slot [at]. *)
let put_box b (box : float array) at =
  b.x0.(at) <- box.(0);
  b.y0.(at) <- box.(1);
  b.z0.(at) <- box.(2);
  b.x1.(at) <- box.(3);
  b.y1.(at) <- box.(4);
  b.z1.(at) <- box.(5)

(* Gathers the boxes of the leaves of nodes [first .. t.size - 1], over
   slots from [at], into slots [at ..], in order ({!gathered}): the
   leaves' slots are read before a later leaf's box is written, which
   goes no further than its first slot. *)
let gather b first at =
  let t = b.t in
  let box = Array.make 6 0. and j = ref 0 in
  for c = first to t.size - 1 do
    let g = tag_of t c in
    if g < 0 then begin
      leaf_box b.x0 b.y0 b.z0 b.x1 b.y1 b.z1 (link_of t c) (-g) box 0;
      put_box b box (at + !j);
      incr j
    end
  done;
  { first; last = t.size; at; leaves = !j }

(* The axis of the node whose block is [p] in [fr] along which its
   centers' bounds are longest. *)
let widest_axis (fr : float array) p =
  let o = p * block in
  let ex = Array.unsafe_get fr (o + 9) -. Array.unsafe_get fr (o + 6) in
  let ey = Array.unsafe_get fr (o + 10) -. Array.unsafe_get fr (o + 7) in
  let ez = Array.unsafe_get fr (o + 11) -. Array.unsafe_get fr (o + 8) in
  if ex >= ey && ex >= ez then 0 else if ey >= ez then 1 else 2

(* The split of the node over slots [lo .. hi - 1], whose block is [p] in
   [fr] and [cn], along axis [a], between the [nbins] bins that minimises
   the SAH cost A_left n_left + A_right n_right (in units of this box's
   area): [-2] a leaf, [-1] the median (the centers are together), else
   the first slot of the right child, the children's blocks [f] and
   [f + 1] filled: their boxes from the bins on each side, their centers'
   bounds from the bins' centers, their bins filled as the partition moves
   each object to its side. *)
let sah_split b lo hi (fr : float array) (cn : int array) p a nbins f =
  let o = p * block and co = p * bins in
  let n = hi - lo in
  let ext = Array.unsafe_get fr (o + 9 + a) -. Array.unsafe_get fr (o + 6 + a) in
  let bins = nbins in
  if n <= 1 then -2
  else if ext > 0. then begin
    let prefix = b.prefix and suffix = b.suffix in
    running_boxes cn co fr (o + boxes_at) 0 (bins - 2) prefix;
    running_boxes cn co fr (o + boxes_at) (bins - 1) 1 suffix;
    let best = ref (-1) and best_cost = ref infinity and right_n = ref 0 and left_n = ref n in
    for bin = bins - 1 downto 1 do
      (* [bin < bins <= 16]: in the block's counts (checked by [node]). *)
      right_n := !right_n + Array.unsafe_get cn (co + bin);
      left_n := !left_n - Array.unsafe_get cn (co + bin);
      if !left_n > 0 && !right_n > 0 then begin
        let cost = (area prefix (bin - 1) *. Float.of_int !left_n) +. (area suffix bin *. Float.of_int !right_n) in
        if cost < !best_cost then begin
          best_cost := cost;
          best := bin - 1
        end
      end
    done;
    let parent =
      half_area (Array.unsafe_get fr o) (Array.unsafe_get fr (o + 1)) (Array.unsafe_get fr (o + 2))
        (Array.unsafe_get fr (o + 3)) (Array.unsafe_get fr (o + 4)) (Array.unsafe_get fr (o + 5))
    in
    (* A leaf costs n tests; a split, one box test plus the expected
       tests below it (areas relative to this box's). *)
    if !best < 0 then if n <= b.leaf_size then -2 else -1
    else if n <= b.leaf_size && Float.of_int n *. parent <= parent +. !best_cost then -2
    else begin
      let best = !best in
      let left_n = ref 0 in
      for bin = 0 to best do
        left_n := !left_n + cn.(co + bin)
      done;
      let l = f and r = f + 1 in
      let fr' = b.frames and cn' = b.counts and params = b.params in
      copy6 prefix (6 * best) fr' (l * block);
      union cn co fr (o + centers_at) 0 best fr' ((l * block) + 6);
      copy6 suffix (6 * (best + 1)) fr' (r * block);
      union cn co fr (o + centers_at) (best + 1) (bins - 1) fr' ((r * block) + 6);
      let lg = binning fr' l !left_n params 0 and rg = binning fr' r (n - !left_n) params 2 in
      reset_bins fr' cn' l (lg lsr 2);
      reset_bins fr' cn' r (rg lsr 2);
      partition_bins b.x0 b.y0 b.z0 b.x1 b.y1 b.z1 b.order b.bin_at best lo hi params lg rg l r fr' cn'
    end
  end
  else if n <= b.leaf_size then -2
  else -1

(* The split at the median of the centers along axis [a] (all in one
   bin), the children's blocks [f] and [f + 1] filled. *)
let median_split b a lo hi f =
  let ka = match a with 0 -> b.x0 | 1 -> b.y0 | _ -> b.z0 in
  let kb = match a with 0 -> b.x1 | 1 -> b.y1 | _ -> b.z1 in
  let m = (lo + hi) / 2 in
  select b ka kb lo hi m;
  bounds_of b lo m b.frames (f * block);
  bounds_of b m hi b.frames ((f + 1) * block);
  bin_slots b.x0 b.y0 b.z0 b.x1 b.y1 b.z1 b.bin_at lo m b.params b.frames b.counts f;
  bin_slots b.x0 b.y0 b.z0 b.x1 b.y1 b.z1 b.bin_at m hi b.params b.frames b.counts (f + 1);
  m

(* Whether the right child over slots [split .. hi - 1] of a node over
   [lo .. hi - 1] is built beside, and with what: once, for two children
   of a quarter of the objects or more, so that neither process has much
   more to do than the other. *)
let share_right b lo split hi =
  match b.beside with
  | Some s
    when b.alone && hi - split >= s.min_objects && 4 * (hi - split) >= b.n_all && 4 * (split - lo) >= b.n_all
         && b.leaf_size <= 127 && hi - split <= 0x7fff_ffff -> (
      b.alone <- false;
      (* Asked once, at the node that would be shared: a smaller node
         later is not shared instead (the halves would be uneven). *)
      if not (s.idle ()) then None
      else
      match s.floats (7 * (hi - split)) with
      | sh, reserve -> Some (s, sh, reserve)
      | exception (Failure _ | Out_of_memory) -> (* Built here, as without [beside]. *) None)
  | _ -> None

(* Appends the nodes of the part over slots [lo .. hi - 1] and moves the
   slots' objects as that part's build did, from [sh]: the same tree as if
   it had been built here, its leaves' boxes left in [sh] gathered into
   its slots for [finish]. *)
let graft b lo hi p (sh : floats) =
  let t = b.t in
  let first = t.size and nodes = Bytes.length p.tags in
  for c = 0 to nodes - 1 do
    set_tag t (add_node t) (Bytes.get_int8 p.tags c)
  done;
  (* The nodes are depth first: each subtree's size from the last node
     back (children after their parent), in [link]; then the links, in
     order, an inner node's from its left child's size, not yet
     overwritten, a leaf's from the slots of the leaves before it. *)
  for k = first + nodes - 1 downto first do
    if tag_of t k < 0 then set_link t k 1
    else
      let l = link_of t (k + 1) in
      set_link t k (1 + l + link_of t (k + 1 + l))
  done;
  let slot = ref lo and leaves = ref 0 in
  for k = first to first + nodes - 1 do
    if tag_of t k < 0 then begin
      set_link t k !slot;
      slot := !slot - tag_of t k;
      incr leaves
    end
    else set_link t k (k + 1 + link_of t (k + 1))
  done;
  if p.part_depth > b.depth then b.depth <- p.part_depth;
  let m = hi - lo in
  if Bigarray.Array1.dim sh < 7 * m then invalid_arg "Bvh.build_boxes: beside.floats gave too few floats";
  for j = 0 to m - 1 do
    Array.unsafe_set b.order (lo + j) (Float.to_int (Bigarray.Array1.unsafe_get sh j))
  done;
  (* At most [m] leaves: their boxes fit in [sh] and in the slots. *)
  let box = Array.make 6 0. in
  for j = 0 to !leaves - 1 do
    for i = 0 to 5 do
      box.(i) <- Bigarray.Array1.get sh (m + (6 * j) + i)
    done;
    put_box b box (lo + j)
  done;
  b.theirs <- { first; last = first + nodes; at = lo; leaves = !leaves }

(* The node over slots [lo .. hi - 1], whose block is [p] in [fr] and
   [cn], binned (if {!binning} bins it), and its subtree. *)
let rec node b lo hi level (fr : float array) (cn : int array) p =
  let t = b.t in
  let k = add_node t in
  if level > b.depth then b.depth <- level;
  check_block fr cn p;
  let a = widest_axis fr p in
  let n = hi - lo in
  (* Fewer bins for fewer objects: the bins' fixed cost would otherwise
     dominate the many small nodes near the leaves. *)
  let nbins = if n < bins then n else bins in
  let f = frame b level in
  let split = sah_split b lo hi fr cn p a nbins f in
  if split = -2 then begin
    set_link t k lo;
    set_tag t k (lo - hi)
  end
  else begin
    set_tag t k a;
    let split = if split >= 0 then split else median_split b a lo hi f in
    match share_right b lo split hi with
    | Some (s, sh, reserve) ->
        (* The right subtree built beside while this process builds the
           left one; it goes after the left's nodes. *)
        let right = Array.sub b.frames ((f + 1) * block) block and right_n = Array.sub b.counts ((f + 1) * nbins) nbins in
        let wait = s.beside (fun () -> part b split hi (level + 1) right right_n sh reserve) in
        node b lo split (level + 1) b.frames b.counts f;
        (* Work of [finish], done while the other process may still
           build: the left subtree's leaves' boxes, read once, there. *)
        b.mine <- gather b (k + 1) lo;
        set_link t k t.size;
        (match wait () with
        | Some _ when b.built_here -> (* [beside] ran [part] here: the tree is complete. *) ()
        | Some p -> graft b split hi p sh
        | None -> node b split hi (level + 1) b.frames b.counts (f + 1))
    | None ->
        node b lo split (level + 1) b.frames b.counts f;
        set_link t k t.size;
        (* [frames] may have grown (and moved) meanwhile. *)
        node b split hi (level + 1) b.frames b.counts (f + 1)
  end

(* The subtree over slots [lo .. hi - 1] and what [graft] needs of it:
   run beside (in a copy of this process), after [node lo split] there
   has moved nothing in [lo .. hi - 1]. To [sh]: the [m] slots' objects
   (exact as floats: [m < 2^31]), then the box of each of its leaves in
   order, 6 floats (lower corner, upper), at most [6 m] floats (a leaf
   holds a slot or more). Its boxes, not its slots': this process's
   [finish] reads them once, in order, and the caller needs no copy of
   the slots' boxes. *)
and part b lo hi level block_fr block_cn (sh : floats) reserve =
  let t = b.t in
  b.built_here <- true;
  let m = hi - lo in
  let first = t.size in
  node b lo hi level block_fr block_cn 0;
  let leaves = ref 0 in
  for c = first to t.size - 1 do
    if tag_of t c < 0 then incr leaves
  done;
  (* Only what is sent takes memory: this process writes no zeros
     before the build. *)
  reserve (m + (6 * !leaves));
  for j = 0 to m - 1 do
    Bigarray.Array1.unsafe_set sh j (Float.of_int (Array.unsafe_get b.order (lo + j)))
  done;
  let box = Array.make 6 0. and at = ref m in
  for c = first to t.size - 1 do
    let g = tag_of t c in
    if g < 0 then begin
      leaf_box b.x0 b.y0 b.z0 b.x1 b.y1 b.z1 (link_of t c) (-g) box 0;
      (* [!at + 6 <= 7 m]: at most [m] leaves. *)
      for i = 0 to 5 do
        Bigarray.Array1.unsafe_set sh (!at + i) (Array.unsafe_get box i)
      done;
      at := !at + 6
    end
  done;
  let tags = Bytes.create (t.size - first) in
  for c = 0 to t.size - first - 1 do
    Bytes.set_int8 tags c (tag_of t (first + c))
  done;
  { tags; part_depth = b.depth }

let build_boxes ?(leaf_size = 4) ?beside ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 () =
  let n = Array.length x0 in
  if n = 0 then invalid_arg "Bvh.build_boxes: no boxes";
  if Array.exists (fun a -> Array.length a <> n) [| y0; z0; x1; y1; z1 |] then
    invalid_arg "Bvh.build_boxes: arrays of different lengths";
  let b = start_build ~leaf_size ~beside ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 in
  bounds_of b 0 n b.frames 0;
  bin_slots x0 y0 z0 x1 y1 z1 b.bin_at 0 n b.params b.frames b.counts 0;
  node b 0 n 1 b.frames b.counts 0;
  finish b.t ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 ~mine:b.mine ~theirs:b.theirs b.order b.depth

let build ?leaf_size ~cx ~cy ~cz extent =
  let n = Array.length cx in
  if n = 0 then invalid_arg "Bvh.build: no spheres";
  if Array.length cy <> n || Array.length cz <> n || Array.length extent <> n then
    invalid_arg "Bvh.build: arrays of different lengths";
  let lo c = Array.mapi (fun i x -> x -. extent.(i)) c and hi c = Array.mapi (fun i x -> x +. extent.(i)) c in
  build_boxes ?leaf_size ~x0:(lo cx) ~y0:(lo cy) ~z0:(lo cz) ~x1:(hi cx) ~y1:(hi cy) ~z1:(hi cz) ()

type margin = { d2 : float; m : float }

let margin_of_bounds (b : float array) =
  let dx = b.(3) -. b.(0) and dy = b.(4) -. b.(1) and dz = b.(5) -. b.(2) in
  let d2 = (dx *. dx) +. (dy *. dy) +. (dz *. dz) in
  let m = ref 0. in
  for i = 0 to 5 do
    m := fmax !m (Float.abs b.(i))
  done;
  { d2; m = !m }

let margin_terms ?among ?(reach = 0.) ~cx ~cy ~cz ~radius (camera : Vec3.t) =
  let x0 = ref (camera.x -. reach) and y0 = ref (camera.y -. reach) and z0 = ref (camera.z -. reach) in
  let x1 = ref (camera.x +. reach) and y1 = ref (camera.y +. reach) and z1 = ref (camera.z +. reach) in
  (* A loop, not a function over [among]: the refs would be captured,
     and each float boxed as it changes. *)
  let n = match among with Some a -> Array.length a | None -> Array.length cx in
  for j = 0 to n - 1 do
    let i = match among with Some a -> a.(j) | None -> j in
    let r = radius.(i) in
    x0 := fmin !x0 (cx.(i) -. r);
    y0 := fmin !y0 (cy.(i) -. r);
    z0 := fmin !z0 (cz.(i) -. r);
    x1 := fmax !x1 (cx.(i) +. r);
    y1 := fmax !y1 (cy.(i) +. r);
    z1 := fmax !z1 (cz.(i) +. r)
  done;
  margin_of_bounds [| !x0; !y0; !z0; !x1; !y1; !z1 |]

let[@inline] margin t r =
  let u = epsilon_float /. 2. in
  64. *. u *. ((t.d2 /. r) +. t.m)

let ray_box_margin ?among ~cx ~cy ~cz ~radius camera =
  let t = margin_terms ?among ~cx ~cy ~cz ~radius camera in
  let among = match among with Some a -> a | None -> Array.init (Array.length cx) Fun.id in
  Array.map (fun i -> margin t radius.(i)) among

(* {1 Leaves cut by planes} *)

(* The most triangles of a leaf that is tried. *)
let cut_max_count = 64

(* A region of [parts]: the boxes of the parts of a leaf's triangles, 6
   floats a triangle. *)
let region = 6 * cut_max_count

(* The scratch of [split_leaves], made once for all the leaves, and the
   mesh it reads. [parts]: the padded boxes of the leaf's triangles'
   parts, a region each (an empty part's lower x is [infinity]): region
   0 the leaf's triangles, [2 l + 1] and [2 l + 2] the two sides of a cut
   at level [l]. [pads]: each triangle's pad. [cut]: a triangle's two
   parts' boxes before they are padded and clipped. [sides]: the boxes of
   the two sides of a cut at each level, 12 floats a level. [range]: the
   first and last slot with a part on each side. [sub]: a leaf's subtree,
   8 floats a node as in [nodes] but its inner nodes' links the index of
   their right child in the subtree. *)
type cutter = {
  cost : float;
  cuts : int;
  vertex : float array;
  at0 : int array;
  at1 : int array;
  at2 : int array;
  terms : margin;
  triangle : int -> bool;
  parts : float array;
  pads : float array;
  cut : float array;
  sides : float array;
  range : int array;
  mutable sub : float array;
  mutable len : int;
  mutable depth : int;
}

let cutter ~cost ~cuts ~vertex ~at0 ~at1 ~at2 ~margin ~triangle =
  {
    cost;
    cuts;
    vertex;
    at0;
    at1;
    at2;
    terms = margin;
    triangle;
    parts = Array.create_float (((2 * cuts) + 1) * region);
    pads = Array.create_float cut_max_count;
    cut = Array.create_float 12;
    sides = Array.create_float (12 * (cuts + 1));
    range = Array.make 4 0;
    sub = Array.create_float 64;
    len = 0;
    depth = 0;
  }

(* [halves c s a at] writes to [c.cut] at 0 the box of the part of slot
   [s]'s triangle where coordinate [a] is at most [at], at 6 the box of
   its part where it is at least [at], and is [l + 2 r]: [l] ([r]) is 1 if
   that part is not empty (its box is then written), else 0. A part's box
   is that of its corners on that side and of the points where its edges
   cross the plane (coordinate [a] exactly [at], the others rounded: the
   caller pads). Each corner and edge read once and the boxes grown in
   registers (a bound replaced only by a smaller or larger value, the
   first of equals kept), not through an array. *)
let halves c s a at =
  let v = c.vertex and out = c.cut in
  if s < 0 || s >= Array.length c.at0 || s >= Array.length c.at1 || s >= Array.length c.at2 || a < 0 || a > 2
     || Array.length out < 12
  then invalid_arg "Bvh.halves";
  let i0 = Array.unsafe_get c.at0 s and i1 = Array.unsafe_get c.at1 s and i2 = Array.unsafe_get c.at2 s in
  if i0 < 0 || i1 < 0 || i2 < 0 || i0 + 3 > Array.length v || i1 + 3 > Array.length v || i2 + 3 > Array.length v then
    invalid_arg "Bvh.halves: corners";
  let lx0 = ref infinity and ly0 = ref infinity and lz0 = ref infinity in
  let lx1 = ref neg_infinity and ly1 = ref neg_infinity and lz1 = ref neg_infinity in
  let rx0 = ref infinity and ry0 = ref infinity and rz0 = ref infinity in
  let rx1 = ref neg_infinity and ry1 = ref neg_infinity and rz1 = ref neg_infinity in
  let sides = ref 0 in
  for e = 0 to 2 do
    (* Corner [e] and its edge to the next corner. *)
    let oi = if e = 0 then i0 else if e = 1 then i1 else i2 and oj = if e = 0 then i1 else if e = 1 then i2 else i0 in
    let xi = Array.unsafe_get v oi and yi = Array.unsafe_get v (oi + 1) and zi = Array.unsafe_get v (oi + 2) in
    let ci = if a = 0 then xi else if a = 1 then yi else zi and cj = Array.unsafe_get v (oj + a) in
    if ci <= at then begin
      sides := !sides lor 1;
      if xi < !lx0 then lx0 := xi;
      if yi < !ly0 then ly0 := yi;
      if zi < !lz0 then lz0 := zi;
      if xi > !lx1 then lx1 := xi;
      if yi > !ly1 then ly1 := yi;
      if zi > !lz1 then lz1 := zi
    end;
    if ci >= at then begin
      sides := !sides lor 2;
      if xi < !rx0 then rx0 := xi;
      if yi < !ry0 then ry0 := yi;
      if zi < !rz0 then rz0 := zi;
      if xi > !rx1 then rx1 := xi;
      if yi > !ry1 then ry1 := yi;
      if zi > !rz1 then rz1 := zi
    end;
    if (ci < at && cj > at) || (ci > at && cj < at) then begin
      (* The edge's crossing, on both sides. *)
      let t = (at -. ci) /. (cj -. ci) in
      let x = if a = 0 then at else xi +. (t *. (Array.unsafe_get v oj -. xi)) in
      let y = if a = 1 then at else yi +. (t *. (Array.unsafe_get v (oj + 1) -. yi)) in
      let z = if a = 2 then at else zi +. (t *. (Array.unsafe_get v (oj + 2) -. zi)) in
      if x < !lx0 then lx0 := x;
      if y < !ly0 then ly0 := y;
      if z < !lz0 then lz0 := z;
      if x > !lx1 then lx1 := x;
      if y > !ly1 then ly1 := y;
      if z > !lz1 then lz1 := z;
      if x < !rx0 then rx0 := x;
      if y < !ry0 then ry0 := y;
      if z < !rz0 then rz0 := z;
      if x > !rx1 then rx1 := x;
      if y > !ry1 then ry1 := y;
      if z > !rz1 then rz1 := z
    end
  done;
  Array.unsafe_set out 0 !lx0;
  Array.unsafe_set out 1 !ly0;
  Array.unsafe_set out 2 !lz0;
  Array.unsafe_set out 3 !lx1;
  Array.unsafe_set out 4 !ly1;
  Array.unsafe_set out 5 !lz1;
  Array.unsafe_set out 6 !rx0;
  Array.unsafe_set out 7 !ry0;
  Array.unsafe_set out 8 !rz0;
  Array.unsafe_set out 9 !rx1;
  Array.unsafe_set out 10 !ry1;
  Array.unsafe_set out 11 !rz1;
  !sides

(* [clip parts o f cut b p] writes to [o] in [parts] the part at [f] cut
   to the box at [b] of [cut] padded by [p], or makes it empty (its lower
   x [infinity]). *)
let[@inline] clip (parts : float array) o f (cut : float array) b p =
  let x0 = fmax (Array.unsafe_get parts f) (Array.unsafe_get cut b -. p) in
  let y0 = fmax (Array.unsafe_get parts (f + 1)) (Array.unsafe_get cut (b + 1) -. p) in
  let z0 = fmax (Array.unsafe_get parts (f + 2)) (Array.unsafe_get cut (b + 2) -. p) in
  let x1 = fmin (Array.unsafe_get parts (f + 3)) (Array.unsafe_get cut (b + 3) +. p) in
  let y1 = fmin (Array.unsafe_get parts (f + 4)) (Array.unsafe_get cut (b + 4) +. p) in
  let z1 = fmin (Array.unsafe_get parts (f + 5)) (Array.unsafe_get cut (b + 5) +. p) in
  Array.unsafe_set parts o (if x0 <= x1 && y0 <= y1 && z0 <= z1 then x0 else infinity);
  Array.unsafe_set parts (o + 1) y0;
  Array.unsafe_set parts (o + 2) z0;
  Array.unsafe_set parts (o + 3) x1;
  Array.unsafe_set parts (o + 4) y1;
  Array.unsafe_set parts (o + 5) z1

(* The box at [into] of [parts]' region of the [count] parts of a side to
   [sides] at [sb] (their union, in order), and to [range] at [r] and [r
   + 1] the first and last of their slots from [first] with a part not
   empty ([-1] if none). *)
let side_box c into first count sb r =
  let parts = c.parts in
  if into < 0 || into + (6 * count) > Array.length parts || sb < 0 || sb + 6 > Array.length c.sides then
    invalid_arg "Bvh.side_box";
  let x0 = ref infinity and y0 = ref infinity and z0 = ref infinity in
  let x1 = ref neg_infinity and y1 = ref neg_infinity and z1 = ref neg_infinity in
  let lo = ref (-1) and hi = ref (-1) in
  for j = 0 to count - 1 do
    let o = into + (6 * j) in
    if Array.unsafe_get parts o < infinity then begin
      x0 := fmin !x0 (Array.unsafe_get parts o);
      y0 := fmin !y0 (Array.unsafe_get parts (o + 1));
      z0 := fmin !z0 (Array.unsafe_get parts (o + 2));
      x1 := fmax !x1 (Array.unsafe_get parts (o + 3));
      y1 := fmax !y1 (Array.unsafe_get parts (o + 4));
      z1 := fmax !z1 (Array.unsafe_get parts (o + 5));
      if !lo < 0 then lo := first + j;
      hi := first + j
    end
  done;
  let s = c.sides in
  Array.unsafe_set s sb !x0;
  Array.unsafe_set s (sb + 1) !y0;
  Array.unsafe_set s (sb + 2) !z0;
  Array.unsafe_set s (sb + 3) !x1;
  Array.unsafe_set s (sb + 4) !y1;
  Array.unsafe_set s (sb + 5) !z1;
  c.range.(r) <- !lo;
  c.range.(r + 1) <- !hi

(* The parts at [level + 1] (regions [2 level + 1] and [2 level + 2]) of
   those in region [from] of slots [first .. first + count - 1] of the
   leaf from [leaf_first] on which coordinate [a] is at most [at] and at
   least [at], each the part at this level cut to the triangle's part on
   that side padded by its pad; the boxes of the two sides to [sides] at
   [12 level] and [12 level + 6]; to [range] the first and last slot with
   a part on each side ([-1] if none). *)
let cut_sides c leaf_first from level first count a at =
  let j0 = first - leaf_first in
  let from = (from * region) + (6 * j0) and into_l = (((2 * level) + 1) * region) + (6 * j0) in
  let into_r = (((2 * level) + 2) * region) + (6 * j0) in
  let parts = c.parts and cut = c.cut in
  if j0 < 0 || count < 0 || j0 + count > cut_max_count || from < 0 || into_r + (6 * count) > Array.length parts
     || Array.length cut < 12
  then invalid_arg "Bvh.cut_sides";
  for j = 0 to count - 1 do
    let f = from + (6 * j) and ol = into_l + (6 * j) and or_ = into_r + (6 * j) in
    Array.unsafe_set parts ol infinity;
    Array.unsafe_set parts or_ infinity;
    if Array.unsafe_get parts f < infinity then begin
      let sides = halves c (first + j) a at and p = c.pads.(j0 + j) in
      if sides land 1 <> 0 then clip parts ol f cut 0 p;
      if sides land 2 <> 0 then clip parts or_ f cut 6 p
    end
  done;
  side_box c into_l first count (12 * level) 0;
  side_box c into_r first count ((12 * level) + 6) 2

(* A node appended to [sub], its box the 6 floats at [bo] in [b]: its
   index. *)
let emit c (b : float array) bo =
  if c.len + 8 > Array.length c.sub then begin
    let a = Array.create_float (2 * Array.length c.sub) in
    Array.blit c.sub 0 a 0 c.len;
    c.sub <- a
  end;
  copy6 b bo c.sub c.len;
  c.len <- c.len + 8;
  (c.len / 8) - 1

(* Whether cutting the node of [count] slots and box at [bo] in [b]
   across its longest side pays: the sides' boxes then in [sides] at [12
   level], their slots in [range]. Its axis and plane to [axis] and
   [plane]. *)
let cut_pays c leaf_first src first count (b : float array) bo level a at =
  level < c.cuts
  && begin
       cut_sides c leaf_first src level first count a at;
       let r = c.range in
       r.(0) >= 0 && r.(2) >= 0
       && begin
            let nl = r.(1) - r.(0) + 1 and nr = r.(3) - r.(2) + 1 and sb = 12 * level in
            let area = half_area b.(bo) b.(bo + 1) b.(bo + 2) b.(bo + 3) b.(bo + 4) b.(bo + 5) in
            let s = c.sides in
            let al = half_area s.(sb) s.(sb + 1) s.(sb + 2) s.(sb + 3) s.(sb + 4) s.(sb + 5) in
            let ar = half_area s.(sb + 6) s.(sb + 7) s.(sb + 8) s.(sb + 9) s.(sb + 10) s.(sb + 11) in
            (c.cost *. area) +. (al *. Float.of_int nl) +. (ar *. Float.of_int nr) < Float.of_int count *. area
          end
     end

(* Appends to [sub] the subtree of the parts in region [src] of slots
   [first .. first + count - 1] of the leaf from [leaf_first], their box
   at [bo] in [b], at [level] below the leaf (0: the leaf's node). An
   inner node's box is its children's union. *)
let rec cut_leaf c leaf_first src first count (b : float array) bo level =
  let k = emit c b bo in
  let ex = b.(bo + 3) -. b.(bo) and ey = b.(bo + 4) -. b.(bo + 1) and ez = b.(bo + 5) -. b.(bo + 2) in
  let a = if ex >= ey && ex >= ez then 0 else if ey >= ez then 1 else 2 in
  let at = 0.5 *. (b.(bo + a) +. b.(bo + 3 + a)) in
  if count < 1 || not (cut_pays c leaf_first src first count b bo level a at) then begin
    c.sub.((8 * k) + 6) <- Float.of_int first;
    c.sub.((8 * k) + 7) <- Float.of_int count
  end
  else begin
    let r = c.range and sb = 12 * level in
    let l0 = r.(0) and nl = r.(1) - r.(0) + 1 and r0 = r.(2) and nr = r.(3) - r.(2) + 1 in
    c.sub.((8 * k) + 7) <- Float.of_int (-1 - a);
    (* The sides' boxes at this level are read before a deeper level
       writes its own. *)
    cut_leaf c leaf_first ((2 * level) + 1) l0 nl c.sides sb (level + 1);
    let right = c.len / 8 in
    (* [sub] may have grown (and moved) meanwhile. *)
    c.sub.((8 * k) + 6) <- Float.of_int right;
    cut_leaf c leaf_first ((2 * level) + 2) r0 nr c.sides (sb + 6) (level + 1);
    let sub = c.sub and o = 8 * k in
    let l = o + 8 and rr = 8 * right in
    for i = 0 to 2 do
      sub.(o + i) <- fmin sub.(l + i) sub.(rr + i);
      sub.(o + 3 + i) <- fmax sub.(l + 3 + i) sub.(rr + 3 + i)
    done
  end

(* The least and greatest coordinate [i] of the corners at [a], [b],
   [c] of [v] (checked by the caller). *)
let[@inline] corners_min (v : float array) a b c i =
  fmin (Array.unsafe_get v (a + i)) (fmin (Array.unsafe_get v (b + i)) (Array.unsafe_get v (c + i)))

let[@inline] corners_max (v : float array) a b c i =
  fmax (Array.unsafe_get v (a + i)) (fmax (Array.unsafe_get v (b + i)) (Array.unsafe_get v (c + i)))

(* Region 0: each triangle's box padded by twice its margin, within the
   leaf's box at [bo] in [b]; each triangle's pad; whether every slot is
   a triangle. *)
let cut_start c first count (b : float array) bo =
  let ok = ref true and v = c.vertex and parts = c.parts in
  if bo < 0 || bo + 6 > Array.length b || count > cut_max_count || 6 * count > Array.length parts then
    invalid_arg "Bvh.cut_start";
  for s = first to first + count - 1 do
    if !ok && c.triangle s then begin
      let ia = c.at0.(s) and ib = c.at1.(s) and ic = c.at2.(s) in
      if ia < 0 || ib < 0 || ic < 0 || ia + 3 > Array.length v || ib + 3 > Array.length v || ic + 3 > Array.length v then
        invalid_arg "Bvh.cut_start: corners";
      let x0 = corners_min v ia ib ic 0 and y0 = corners_min v ia ib ic 1 and z0 = corners_min v ia ib ic 2 in
      let x1 = corners_max v ia ib ic 0 and y1 = corners_max v ia ib ic 1 and z1 = corners_max v ia ib ic 2 in
      (* The margin of a sphere of the triangle's largest half side, as
         [Prepared]'s boxes. *)
      let h = fmax (fmax (fmax 0. (0.5 *. (x1 -. x0))) (0.5 *. (y1 -. y0))) (0.5 *. (z1 -. z0)) in
      let p = 2. *. margin c.terms h in
      let j = s - first in
      c.pads.(j) <- p;
      let o = 6 * j in
      Array.unsafe_set parts o (fmax (Array.unsafe_get b bo) (x0 -. p));
      Array.unsafe_set parts (o + 1) (fmax (Array.unsafe_get b (bo + 1)) (y0 -. p));
      Array.unsafe_set parts (o + 2) (fmax (Array.unsafe_get b (bo + 2)) (z0 -. p));
      Array.unsafe_set parts (o + 3) (fmin (Array.unsafe_get b (bo + 3)) (x1 +. p));
      Array.unsafe_set parts (o + 4) (fmin (Array.unsafe_get b (bo + 4)) (y1 +. p));
      Array.unsafe_set parts (o + 5) (fmin (Array.unsafe_get b (bo + 5)) (z1 +. p))
    end
    else ok := false
  done;
  !ok

(* The subtree of the leaf at offset [o] of [nodes], tried, in [sub]
   (from 0), and its number of nodes: 1 (not cut, not written) or
   more. *)
let leaf_subtree c (nodes : float array) o =
  let g = tag_at nodes o and first = link_at nodes o in
  if cut_start c first g nodes o then begin
    c.len <- 0;
    cut_leaf c first 0 first g nodes o 0;
    c.len / 8
  end
  else 1

(* Whether leaf [g] slots is tried. A cut costs [cost] tests of the
   leaf's area before its sides' tests: never less than a leaf of [cost]
   triangles or fewer, which is not tried. *)
let[@inline] tried c g = Float.of_int g > c.cost && g <= cut_max_count

(* The new tree's nodes while they are written: room for [n] nodes or
   more, node 0 at [root]. Inner nodes' links are node numbers until
   [offsets]. *)
type written = { mutable out : float array; mutable root : int; mutable used : int }

let node_array n =
  let out = Array.create_float ((node_floats * n) + node_floats - 1) in
  { out; root = aligned_root out; used = 0 }

(* [room w m] is the first of [m] more nodes of [w], made room for: where
   the nodes do not fit (more than one cut a leaf), the array is
   doubled, its nodes copied to the new one's aligned place. *)
let room w m =
  let d = w.used in
  if at w.root (d + m) + node_floats - 1 > Array.length w.out then begin
    let bigger = node_array (2 * (d + m)) in
    Array.blit w.out w.root bigger.out bigger.root (node_floats * d);
    w.out <- bigger.out;
    w.root <- bigger.root
  end;
  w.used <- d + m;
  d

(* [copy c t w k level] writes node [k] of [t] and its subtree to [w],
   its leaves cut, at [level] of the new tree; it is the new node's
   number. Boxes of inner nodes are their children's union, from the
   leaves up. *)
let rec copy c t w k level =
  let o = offset t k and nodes = t.nodes in
  let g = tag_at nodes o in
  if g > 0 then begin
    let m = if tried c g then leaf_subtree c nodes o else 1 in
    let d = room w m in
    if m = 1 then begin
      Array.blit nodes o w.out (at w.root d) node_floats;
      if level > c.depth then c.depth <- level
    end
    else place_subtree c w d m level;
    d
  end
  else begin
    let d = room w 1 in
    w.out.(at w.root d + 7) <- nodes.(o + 7);
    ignore (copy c t w (k + 1) (level + 1));
    let right = copy c t w ((link_at nodes o - t.root) / node_floats) (level + 1) in
    (* [w.out] may have grown (and moved) meanwhile. *)
    let out = w.out and od = at w.root d in
    out.(od + 6) <- Float.of_int right;
    let l = od + node_floats and r = at w.root right in
    for i = 0 to 2 do
      out.(od + i) <- fmin out.(l + i) out.(r + i);
      out.(od + 3 + i) <- fmax out.(l + 3 + i) out.(r + 3 + i)
    done;
    d
  end

(* The [m] nodes of [sub] to [w] from node [d] on, their links node
   numbers, the depth reached counted. *)
and place_subtree c w d m level =
  let sub = c.sub and out = w.out in
  (* Each node's level: its parent's and one, children after parents. *)
  let lv = Array.make m level in
  for j = 0 to m - 1 do
    let so = 8 * j and dj = at w.root (d + j) in
    Array.blit sub so out dj node_floats;
    if lv.(j) > c.depth then c.depth <- lv.(j);
    if sub.(so + 7) < 0. then begin
      let r = truncate sub.(so + 6) in
      out.(dj + 6) <- Float.of_int (d + r);
      lv.(j + 1) <- lv.(j) + 1;
      lv.(r) <- lv.(j) + 1
    end
  done

(* The inner nodes' links of [w] made offsets, for the tracer. *)
let offsets w =
  let out = w.out in
  for k = 0 to w.used - 1 do
    let o = at w.root k in
    if out.(o + 7) < 0. then out.(o + 6) <- Float.of_int (at w.root (truncate out.(o + 6)))
  done

(* The number of [t]'s nodes and two more a leaf tried: room for one cut
   a leaf, written once (a count of the nodes first would cut every leaf
   twice). *)
let room_for c t =
  let n = ref t.n_nodes in
  for k = 0 to t.n_nodes - 1 do
    let g = tag_at t.nodes (offset t k) in
    if g > 0 && tried c g then n := !n + 2
  done;
  !n

(* [w], or an exact copy of its nodes where more than an eighth of its
   room went unused (few leaves cut). *)
let fitted w =
  let n = w.used in
  if 8 * n >= 7 * (Array.length w.out / node_floats) then w
  else begin
    let exact = node_array n in
    Array.blit w.out w.root exact.out exact.root (node_floats * n);
    { exact with used = n }
  end

(* [t] with its leaves cut, written into room for [room] nodes. *)
let cut_tree c t room =
  let w = node_array room in
  ignore (copy c t w 0 1);
  if w.used = t.n_nodes then t
  else begin
    let w = fitted w in
    offsets w;
    { t with n_nodes = w.used; nodes = w.out; root = w.root; depth = c.depth }
  end

let split_leaves ?(cost = 3.) ?(cuts = 1) t ~triangle ~vertex ~at0 ~at1 ~at2 ~margin =
  if cuts < 0 || not (cost >= 0.) then invalid_arg "Bvh.split_leaves";
  let c = cutter ~cost ~cuts ~vertex ~at0 ~at1 ~at2 ~margin ~triangle in
  let room = room_for c t in
  (* No leaf tried (a terrain's leaves of one or two triangles): no copy. *)
  if room = t.n_nodes then t else cut_tree c t room
