type ints = (int64, Bigarray.int64_elt, Bigarray.c_layout) Bigarray.Array1.t

type memory = {
  bytes : int -> Image.buffer;
  floats : int -> Trace.samples;
  ints : int -> ints;
  at_row : unit -> unit;
}

let local =
  {
    bytes = (fun n -> Bigarray.Array1.create Bigarray.int8_unsigned Bigarray.c_layout n);
    floats = (fun n -> Bigarray.Array1.create Bigarray.float64 Bigarray.c_layout n);
    ints = (fun n -> Bigarray.Array1.create Bigarray.int64 Bigarray.c_layout n);
    at_row = ignore;
  }

(* A plan renders the [w x h] rectangle of the canvas at [(x, y)] into
   [img]. Adaptive sampling and subsampling decide a pixel from its
   neighbours' first rays, so their first pass also traces a margin around
   the rectangle (clipped to the canvas): the rectangle [(mx, my)],
   [mw x mh], whose pixels the buffers hold, row by row. The margin is one
   pixel wide, or [reach] for adaptive sampling, whose buffers leave room
   for a lens's blur; its first pass traces that wider margin only under a
   lens (see [first_rays]). *)
type plan = {
  s : Sampling.t;
  img : Image.t;
  cw : int;  (** Canvas size. *)
  ch : int;
  x : int;
  y : int;
  w : int;
  h : int;
  mx : int;
  my : int;
  mw : int;
  mh : int;
  first : Image.buffer;  (** Adaptive: the bytes of each pixel's first ray. *)
  saved : Trace.samples;  (** Adaptive: its clamped colour. *)
  hits : ints;  (** The sphere each pixel's (first) ray hit, [-1] for none. *)
  blur : Trace.samples;  (** Adaptive: the circle of confusion of each first ray, in pixels. *)
  probe : Image.buffer;  (** Adaptive: the bytes of the last probe. *)
  at_row : unit -> unit;
}

(* How far, in pixels, adaptive sampling looks for a blurred first ray
   whose circle of confusion covers a pixel: a wider circle than
   [2 (reach - 1)] pixels across is seen up to [reach] only (see
   [blurred]). *)
let reach = 4

let plan ?(memory = local) (s : Sampling.t) img ~canvas:(cw, ch) ~at:(x, y) =
  let w = Image.width img and h = Image.height img in
  if x < 0 || y < 0 || x + w > cw || y + h > ch then invalid_arg "Sampling_rows.plan: rectangle outside the canvas";
  let adaptive = s.adaptive <> None in
  let r = if adaptive then reach else 1 in
  let mx = max 0 (x - r) and my = max 0 (y - r) in
  let mw = min cw (x + w + r) - mx and mh = min ch (y + h + r) - my in
  let margin = if adaptive || s.subsample then mw * mh else 0 in
  (* Empty buffers need no shared memory. *)
  let bytes n = if n > 0 then memory.bytes n else local.bytes 0 in
  let floats n = if n > 0 then memory.floats n else local.floats 0 in
  let ints n = if n > 0 then memory.ints n else local.ints 0 in
  (* Every element a pass reads was written by an earlier pass. *)
  {
    s;
    img;
    cw;
    ch;
    x;
    y;
    w;
    h;
    mx;
    my;
    mw;
    mh;
    first = bytes (if adaptive then 3 * margin else 0);
    saved = floats (if adaptive then 3 * margin else 0);
    hits = ints margin;
    blur = floats (if adaptive then margin else 0);
    probe = local.bytes (if adaptive then 3 else 0);
    at_row = memory.at_row;
  }

let passes pl = if pl.s.adaptive <> None || pl.s.subsample then 2 else 1

(* Indices: [out] of canvas pixel [(cx, cy)] in [img] (times 3 for its
   bytes), [m] in the margin buffers. *)
let[@inline] out pl cx cy = ((cy - pl.y) * pl.w) + (cx - pl.x)
let[@inline] m pl cx cy = ((cy - pl.my) * pl.mw) + (cx - pl.mx)
let[@inline] inside pl cx cy = cx >= pl.x && cx < pl.x + pl.w && cy >= pl.y && cy < pl.y + pl.h
let[@inline] gx pl cx = Canvas.x_of_column ~width:pl.cw cx
let[@inline] gy pl cy = Canvas.y_of_row ~height:pl.ch cy

(* One ray per pixel, or the full grid: the [count] pixels of canvas row
   [cy] from column [x0] on. *)
let full_span pl tr cy x0 count =
  let buffer = Image.buffer pl.img and n = pl.s.samples in
  let gy = gy pl cy in
  if n = 1 then Trace.row tr buffer (3 * out pl x0 cy) (gx pl x0) gy count
  else
    for cx = x0 to x0 + count - 1 do
      Trace.average tr (gx pl cx) gy ~n;
      Trace.store_average tr buffer (3 * out pl cx cy) ~count:(n * n)
    done

(* Canvas row [cy] of the rectangle. *)
let full pl tr cy = full_span pl tr cy pl.x pl.w

(* The side, in pixels, of the squares in which [full_tiles] traces: the
   rays of a square meet the same few objects, and walk the same nodes
   of their hierarchies while these are still in the cache; a row of 1,920
   pixels crosses 48 small knots before it comes back to the first
   (docs/performance.md, "Third pass"). *)
let square = 64

(* Canvas rows [r0 .. r1 - 1] of the rectangle, one [square] wide column of
   them after the other. Each pixel is computed alone ([full] has no
   neighbour to read), so the order changes no byte. The work budget is
   checked after each row of a square, as often as after each row. *)
let full_tiles pl tr r0 r1 =
  let x1 = pl.x + pl.w in
  let x = ref pl.x in
  while !x < x1 do
    pl.at_row ();
    let count = if !x + square < x1 then square else x1 - !x in
    for cy = r0 to r1 - 1 do
      full_span pl tr cy !x count;
      Trace.check_budget tr
    done;
    x := !x + square
  done

(* Per pixel, not per ray: these accesses keep their bounds checks, so that
   a wrong neighbour index fails loudly rather than reading past a mapped
   buffer. *)
let set_hit (hits : ints) i tr = Bigarray.Array1.set hits i (Int64.of_int (Trace.hit_object tr))
let hit (hits : ints) i = Int64.to_int (Bigarray.Array1.get hits i)

let[@inline] has_lens tr = Camera.has_lens (Trace.prepared tr).camera

(* Adaptive, pass 0: the first ray of each pixel of canvas row [cy] of the
   margin, kept three ways (four under a lens: its circle of confusion).
   A pinhole decides from the four neighbours: only the pixels within one
   of the rectangle are traced, as the margin of one pixel was. *)
let first_rays pl tr cy =
  let gy = gy pl cy in
  let lens = has_lens tr in
  let x0 = if lens then pl.mx else max pl.mx (pl.x - 1) in
  let x1 = if lens then pl.mx + pl.mw - 1 else min (pl.mx + pl.mw - 1) (pl.x + pl.w) in
  if lens || (cy >= pl.y - 1 && cy <= pl.y + pl.h) then
    for cx = x0 to x1 do
      let i = m pl cx cy in
      Trace.pixel tr (gx pl cx) gy;
      Trace.store tr pl.first (3 * i);
      Trace.save tr pl.saved (3 * i);
      set_hit pl.hits i tr;
      if lens then Trace.save_blur tr pl.blur i
    done

(* Do the first rays of margin pixels [p] and [q] differ: another sphere,
   or a channel more than [th] apart? *)
let[@inline] apart (f : Image.buffer) th p q c =
  abs (Bigarray.Array1.get f ((3 * p) + c) - Bigarray.Array1.get f ((3 * q) + c)) > th

let differ pl th p q =
  hit pl.hits p <> hit pl.hits q || apart pl.first th p q 0 || apart pl.first th p q 1 || apart pl.first th p q 2

(* Below this circle of confusion, in pixels, a first ray counts as in
   focus: its blur stays inside its pixel. *)
let sharp = 0.5

(* Under a lens, is pixel [(cx, cy)] (margin index [i]) blurred: is its
   own first ray's circle of confusion wider than [sharp], or that of a
   first ray [q] within [reach] whose circle, around [q], reaches the
   pixel ([|q - p| <= c/2 + 1] pixels, the pixels' own extent included)?
   A blurred foreground spreads over the sharp pixels around it. *)
let blurred pl i cx cy =
  Bigarray.Array1.get pl.blur i > sharp
  ||
  let found = ref false in
  (* Integer bounds by hand: [min] and [max] are polymorphic calls. *)
  let y1 = if cy + reach < pl.my + pl.mh - 1 then cy + reach else pl.my + pl.mh - 1 in
  let x0 = if cx - reach > pl.mx then cx - reach else pl.mx in
  let x1 = if cx + reach < pl.mx + pl.mw - 1 then cx + reach else pl.mx + pl.mw - 1 in
  let qy = ref (if cy - reach > pl.my then cy - reach else pl.my) in
  while (not !found) && !qy <= y1 do
    let dy = !qy - cy and row = m pl 0 !qy in
    for qx = x0 to x1 do
      let c = Bigarray.Array1.get pl.blur (row + qx) in
      if c > sharp then begin
        let dx = qx - cx in
        let r = (0.5 *. c) +. 1. in
        if Float.of_int ((dx * dx) + (dy * dy)) <= r *. r then found := true
      end
    done;
    incr qy
  done;
  !found

(* Under a lens, does a probe of pixel [(cx, cy)] (margin index [i]) see
   another object than its first ray, or a colour more than [th] apart in
   some channel? The probes go from the four rim points of the lens
   through the pixel centre's point on the plane of focus, the widest
   rays of its cone: where all four see what the centre saw, the cone is
   taken to lie inside one object and one colour. An estimate: an edge
   can pass between them. *)
let probes_differ pl th tr i cx cy =
  let gx = gx pl cx and gy = gy pl cy and h = hit pl.hits i in
  let found = ref false and k = ref 0 in
  while (not !found) && !k < 4 do
    Trace.probe tr gx gy !k;
    if Trace.hit_object tr <> h then found := true
    else begin
      Trace.store tr pl.probe 0;
      for c = 0 to 2 do
        if abs (Bigarray.Array1.get pl.probe c - Bigarray.Array1.get pl.first ((3 * i) + c)) > th then found := true
      done
    end;
    incr k
  done;
  !found

(* Adaptive, pass 1: refine the pixels of canvas row [cy] that differ from a
   neighbour in the canvas, or under a lens are blurred and a probe of
   their lens sees something else: the full grid; copy the others' first
   bytes. Reads only what pass 0 wrote. *)
let refine pl th tr cy =
  let buffer = Image.buffer pl.img and n = pl.s.samples and mw = pl.mw in
  let lens = has_lens tr in
  let gy = gy pl cy in
  for cx = pl.x to pl.x + pl.w - 1 do
    let i = m pl cx cy and k = 3 * out pl cx cy in
    if
      (cx > 0 && differ pl th i (i - 1))
      || (cx < pl.cw - 1 && differ pl th i (i + 1))
      || (cy > 0 && differ pl th i (i - mw))
      || (cy < pl.ch - 1 && differ pl th i (i + mw))
      || (lens && blurred pl i cx cy && probes_differ pl th tr i cx cy)
    then begin
      (* An even grid, under a lens only, has no centre sample to reuse. *)
      if n land 1 = 1 then Trace.average_reusing tr pl.saved (3 * i) (gx pl cx) gy ~n
      else Trace.average tr (gx pl cx) gy ~n;
      Trace.store_average tr buffer k ~count:(n * n)
    end
    else
      for c = 0 to 2 do
        Bigarray.Array1.set buffer (k + c) (Bigarray.Array1.get pl.first ((3 * i) + c))
      done
  done

(* Subsampling: the pixel at margin index [i] from its neighbours [a] and
   [b], when both exist ([both]) and hit the same sphere; traced in full
   otherwise. Stored if it lies in the rectangle. *)
let subsampled pl tr cx cy i a b ~both =
  (* [a] and [b] may lie outside the margin when not [both]: read only then
     (an unchecked read before a mapped buffer can fault). *)
  if both && hit pl.hits a = hit pl.hits b then
    Trace.pixel_assuming tr (gx pl cx) (gy pl cy) (hit pl.hits a)
  else Trace.pixel tr (gx pl cx) (gy pl cy);
  if inside pl cx cy then Trace.store tr (Image.buffer pl.img) (3 * out pl cx cy);
  set_hit pl.hits i tr

(* Subsampling, pass 0, even canvas rows of the margin: even columns
   traced, odd ones from their left and right neighbours. An odd column at
   the margin's edge lacks a neighbour that the whole canvas has; it is
   traced in full, and only ever read by nobody: pass 1 reads the columns
   of the rectangle only. *)
let even_row pl tr cy =
  let x0 = pl.mx and x1 = pl.mx + pl.mw in
  let cx = ref (x0 + (x0 land 1)) in
  while !cx < x1 do
    let i = m pl !cx cy in
    Trace.pixel tr (gx pl !cx) (gy pl cy);
    if inside pl !cx cy then Trace.store tr (Image.buffer pl.img) (3 * out pl !cx cy);
    set_hit pl.hits i tr;
    cx := !cx + 2
  done;
  let cx = ref (x0 + 1 - (x0 land 1)) in
  while !cx < x1 do
    let i = m pl !cx cy in
    subsampled pl tr !cx cy i (i - 1) (i + 1) ~both:(!cx > x0 && !cx + 1 < x1);
    cx := !cx + 2
  done

(* Subsampling, pass 1, odd canvas rows of the rectangle: every pixel from
   the pixels above and below, written by pass 0. *)
let odd_row pl tr cy =
  for cx = pl.x to pl.x + pl.w - 1 do
    let i = m pl cx cy in
    subsampled pl tr cx cy i (i - pl.mw) (i + pl.mw) ~both:(cy + 1 < pl.ch)
  done

(* The canvas rows pass [i] works on are [start], [start + every], ...
   below [stop]: the rectangle's, or the margin's for the first rays of
   adaptive sampling, every other one for subsampling. Three functions, not
   a tuple: [rows] may run once per row, and must not allocate. *)
let[@inline] on_margin pl i = i = 0 && (pl.s.adaptive <> None || pl.s.subsample)
let[@inline] stop pl i = if on_margin pl i then pl.my + pl.mh else pl.y + pl.h
let[@inline] every pl = if pl.s.subsample then 2 else 1

let[@inline] start pl i =
  let lo = if on_margin pl i then pl.my else pl.y in
  (* Subsampling: even canvas rows in pass 0, odd ones in pass 1. *)
  if pl.s.subsample && lo land 1 <> i then lo + 1 else lo

let pass_rows pl i =
  if i < 0 || i >= passes pl then invalid_arg "Sampling_rows.pass_rows: no such pass";
  let span = stop pl i - start pl i in
  if span <= 0 then 0 else (span + every pl - 1) / every pl

let check pl i tr fn =
  let p = Trace.prepared tr in
  if p.width <> pl.cw || p.height <> pl.ch then invalid_arg ("Sampling_rows." ^ fn ^ ": the canvas sizes differ");
  if Trace.averaging tr <> Sampling.averaging pl.s then
    invalid_arg ("Sampling_rows." ^ fn ^ ": the tracer's averaging differs");
  if i < 0 || i >= passes pl then invalid_arg ("Sampling_rows." ^ fn ^ ": no such pass")

(* A pass whose pixels read no neighbour's ray ([full]), in a scene with
   a hierarchy: one that [full_tiles] traces in squares. Its rows are the
   rectangle's: [start pl 0 = pl.y], [every pl = 1]. A scene without a
   hierarchy has no nodes to keep in the cache, and the document's
   kernel ([Textbook]) culls its spheres per column of its own tiles,
   once a row: its squares' shorter rows cost it 0.6% more instructions
   (cgfs.scene). *)
let[@inline] plain pl tr = pl.s.adaptive = None && (not pl.s.subsample) && (Trace.prepared tr).bvh <> None

(* Pass [i]'s rows [first, first + step, ...], one after the other. *)
let each_row pl i tr ~first ~step =
  (* A plain loop: a closure per pass would show in the allocation test. *)
  let stop = stop pl i and every = every pl in
  let r = ref (start pl i + (every * first)) in
  while !r < stop do
    (* A worker whose parent was killed stops here, within one row. *)
    pl.at_row ();
    (match pl.s.adaptive with
    | Some _ when i = 0 -> first_rays pl tr !r
    | Some th -> refine pl th tr !r
    | None -> if not pl.s.subsample then full pl tr !r else if i = 0 then even_row pl tr !r else odd_row pl tr !r);
    Trace.check_budget tr;
    r := !r + (every * step)
  done

(* A plain pass's rows [first .. last - 1], [square] rows at a time, each
   such band square by square. *)
let plain_band pl tr ~first ~last =
  let r = ref (pl.y + first) and stop = pl.y + last in
  while !r < stop do
    let r1 = if !r + square < stop then !r + square else stop in
    full_tiles pl tr !r r1;
    r := r1
  done

let rows pl i tr ~first ~step =
  check pl i tr "rows";
  if step < 1 then invalid_arg "Sampling_rows.rows: step < 1";
  if step = 1 && plain pl tr then plain_band pl tr ~first ~last:(pass_rows pl i) else each_row pl i tr ~first ~step

let band_rows pl tr = if plain pl tr then square else 1

let band pl i tr ~first ~last =
  check pl i tr "band";
  if first < 0 || last > pass_rows pl i then invalid_arg "Sampling_rows.band: rows outside the pass";
  if plain pl tr then plain_band pl tr ~first ~last
  else
    let n = pass_rows pl i in
    for r = first to last - 1 do
      each_row pl i tr ~first:r ~step:n
    done
