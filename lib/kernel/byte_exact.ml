open Scratch
open Tracer

(* [Color.to_byte], copied so that no float crosses a module boundary on the
   per-ray path: in dev builds (-opaque) such a call boxes its argument. A
   test checks the two agree. *)
let to_byte x =
  if not (x > 0.) then 0
  else if x >= 255. then 255
  else
    (* In [2^52, 2^53) the floats are the integers: adding 2^52 rounds
       [x] to an integer, half to even (the default rounding), exactly. *)
    truncate ((x +. 0x1p52) -. 0x1p52)
[@@inline]

let store tr (buffer : Image.buffer) k =
  let s = tr.s in
  Bigarray.Array1.unsafe_set buffer k (to_byte s.r);
  Bigarray.Array1.unsafe_set buffer (k + 1) (to_byte s.g);
  Bigarray.Array1.unsafe_set buffer (k + 2) (to_byte s.b)

(* When samples are averaged, a pixel is the mean of the samples' clamped
   floats, not of their bytes: a reflection may stop only if it cannot
   change the clamped float itself. Clamping is monotonic, so that holds
   when both extremes clamp alike: both [>= 255], both [<= 0], or equal. *)
let[@inline] same_clamped (lo : float) (hi : float) = hi <= 0. || lo >= 255. || lo = hi

(* Byte-exact early stop of reflection: the pixel's colour is a
   non-decreasing function of the colour [rc] still to be traced (each blend
   is local (1 - r) + rc r with r >= 0, and rounding is monotonic), and
   0 <= rc <= max_channel. If the blend of the stack gives the same bytes
   for rc = 0 and rc = max_channel, it gives them for the true rc too. *)
let settled tr levels =
  let stack = tr.stack and hi = tr.p.max_channel in
  let lo_r = ref 0. and lo_g = ref 0. and lo_b = ref 0. in
  let hi_r = ref hi and hi_g = ref hi and hi_b = ref hi in
  for l = levels - 1 downto 0 do
    let refl = Array.unsafe_get stack ((4 * l) + 3) in
    let keep = 1. -. refl in
    let r = Array.unsafe_get stack (4 * l) *. keep
    and g = Array.unsafe_get stack ((4 * l) + 1) *. keep
    and b = Array.unsafe_get stack ((4 * l) + 2) *. keep in
    lo_r := r +. (!lo_r *. refl);
    lo_g := g +. (!lo_g *. refl);
    lo_b := b +. (!lo_b *. refl);
    hi_r := r +. (!hi_r *. refl);
    hi_g := g +. (!hi_g *. refl);
    hi_b := b +. (!hi_b *. refl)
  done;
  if tr.averaging then same_clamped !lo_r !hi_r && same_clamped !lo_g !hi_g && same_clamped !lo_b !hi_b
  else to_byte !lo_r = to_byte !hi_r && to_byte !lo_g = to_byte !hi_g && to_byte !lo_b = to_byte !hi_b

(* Byte-exact early stop in the tree: before level [l] traces the child
   [tree.tracing.(l)] names, the pixel is a non-decreasing function of the
   colours still unknown (that child, and the refracted children still
   pending on the way up), each in [\[0, max_channel\]], evaluated with the
   operations of [shade]: if both extremes give the same bytes, so does the
   truth, whatever the children are (the argument of [settled]). *)
let settled_tree tr l =
  let tree = tr.tree and hi = tr.p.max_channel in
  let node = tree.node in
  let lo_r = ref 0. and lo_g = ref 0. and lo_b = ref 0. in
  let hi_r = ref hi and hi_g = ref hi and hi_b = ref hi in
  for k = l downto 0 do
    let o = Ray_tree.node_stride * k in
    let lr = Array.unsafe_get node o and lg = Array.unsafe_get node (o + 1) and lb = Array.unsafe_get node (o + 2) in
    let wr = Array.unsafe_get node (o + 3) and wt = Array.unsafe_get node (o + 4) in
    if Array.unsafe_get tree.tracing k = 0 then begin
      (* The reflected child is the unknown one; the refracted one, if
         any, is still to come: 0 at least, max_channel at most. *)
      lo_r := lr +. (!lo_r *. wr);
      lo_g := lg +. (!lo_g *. wr);
      lo_b := lb +. (!lo_b *. wr);
      hi_r := lr +. (!hi_r *. wr);
      hi_g := lg +. (!hi_g *. wr);
      hi_b := lb +. (!hi_b *. wr);
      if wt > 0. then begin
        lo_r := !lo_r +. (0. *. wt);
        lo_g := !lo_g +. (0. *. wt);
        lo_b := !lo_b +. (0. *. wt);
        hi_r := !hi_r +. (hi *. wt);
        hi_g := !hi_g +. (hi *. wt);
        hi_b := !hi_b +. (hi *. wt)
      end
    end
    else begin
      let br = ref lr and bg = ref lg and bb = ref lb in
      if wr > 0. then begin
        br := lr +. (Array.unsafe_get node (o + 5) *. wr);
        bg := lg +. (Array.unsafe_get node (o + 6) *. wr);
        bb := lb +. (Array.unsafe_get node (o + 7) *. wr)
      end;
      lo_r := !br +. (!lo_r *. wt);
      lo_g := !bg +. (!lo_g *. wt);
      lo_b := !bb +. (!lo_b *. wt);
      hi_r := !br +. (!hi_r *. wt);
      hi_g := !bg +. (!hi_g *. wt);
      hi_b := !bb +. (!hi_b *. wt)
    end
  done;
  if tr.averaging then same_clamped !lo_r !hi_r && same_clamped !lo_g !hi_g && same_clamped !lo_b !hi_b
  else to_byte !lo_r = to_byte !hi_r && to_byte !lo_g = to_byte !hi_g && to_byte !lo_b = to_byte !hi_b

let store_average tr (buffer : Image.buffer) k ~count =
  let s = tr.s and c = Float.of_int count in
  Bigarray.Array1.unsafe_set buffer k (to_byte (s.acc_r /. c));
  Bigarray.Array1.unsafe_set buffer (k + 1) (to_byte (s.acc_g /. c));
  Bigarray.Array1.unsafe_set buffer (k + 2) (to_byte (s.acc_b /. c))

