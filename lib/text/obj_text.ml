type t = {
  positions : float array;
  normals : float array;
  triangles : int array;
  triangle_normals : int array;
  texcoords : float array;
  triangle_texcoords : int array;
  skipped : (string * int) list;
}

let max_line_bytes = 1 lsl 20

(* The kinds of skipped statements, in the order [skipped] lists them;
   "other" last. Matched against the line's bytes, so that a skipped line
   allocates nothing. *)
let kinds = [| "#"; "vt"; "vp"; "o"; "g"; "s"; "usemtl"; "mtllib"; "l"; "p"; "other" |]
let kind_comment = 0
let kind_vt = 1
let kind_other = Array.length kinds - 1

let vertex_count m = Array.length m.positions / 3
let triangle_count m = Array.length m.triangles / 3
let skipped_total m = List.fold_left (fun acc (_, n) -> acc + n) 0 m.skipped

let equal a b =
  let floats x y = Array.length x = Array.length y && Array.for_all2 Float.equal x y in
  floats a.positions b.positions && floats a.normals b.normals
  && a.triangles = b.triangles && a.triangle_normals = b.triangle_normals
  && floats a.texcoords b.texcoords && a.triangle_texcoords = b.triangle_texcoords
  && a.skipped = b.skipped

let v ~positions ~normals ~triangles ~triangle_normals =
  let bad what = invalid_arg ("Obj_file.v: " ^ what) in
  if Array.length positions mod 3 <> 0 then bad "positions not 3 per vertex";
  if Array.length normals mod 3 <> 0 then bad "normals not 3 per normal";
  if Array.length triangles mod 3 <> 0 then bad "triangles not 3 per triangle";
  if Array.length triangle_normals <> Array.length triangles then bad "triangle_normals and triangles differ in length";
  let nv = Array.length positions / 3 and nn = Array.length normals / 3 in
  Array.iter (fun i -> if i < 0 || i >= nv then bad "vertex number out of range") triangles;
  Array.iter (fun i -> if i < -1 || i >= nn then bad "normal number out of range") triangle_normals;
  { positions; normals; triangles; triangle_normals; texcoords = [||]; triangle_texcoords = [||]; skipped = [] }

let with_texcoords ~texcoords ~triangle_texcoords m =
  let bad what = invalid_arg ("Obj_file.with_texcoords: " ^ what) in
  if Array.length texcoords mod 2 <> 0 then bad "texcoords not 2 per coordinate";
  if triangle_texcoords <> [||] && Array.length triangle_texcoords <> Array.length m.triangles then
    bad "triangle_texcoords and triangles differ in length";
  let nt = Array.length texcoords / 2 in
  Array.iter (fun i -> if i < -1 || i >= nt then bad "texture number out of range") triangle_texcoords;
  { m with texcoords; triangle_texcoords }

let texcoord_count m = Array.length m.texcoords / 2

(* The arrays of the mesh are built in blocks of [block] elements (the
   first grows to that size by doubling, for small meshes) and
   concatenated once by [finish]: the peak is the result twice over (the
   blocks, then the result), where doubling arrays would leave up to
   twice the result in capacity plus the garbage of each growth. Two
   types rather than one polymorphic: a [float array] known as such
   stores and loads unboxed floats. The current block is an array, a
   full block is copied out of the collector's heap into a bigarray
   ([fblock], [iblock]): the system's memory, given back once the
   collector finds the blocks garbage, where blocks in the heap (48 MB
   for a million triangles) stayed resident, and the compaction after a
   big mesh's loading moved its arrays into pages never touched beside
   them (docs/performance.md, "Issue 28, round 3: build and memory"). *)
type fblock = (float, Bigarray.float64_elt, Bigarray.c_layout) Bigarray.Array1.t
type iblock = (int, Bigarray.int_elt, Bigarray.c_layout) Bigarray.Array1.t

(* A new block, made without hurrying the collector: a bigarray's memory
   counts toward the major collection's speed ([custom_major_ratio]),
   and the reader's 48 MB for a million triangles, all live until
   [finish], set it marking the heap about once more for nothing (30-40
   ms of the 1M knot's preparation). *)
let out_of_heap create =
  let gc = Gc.get () in
  Gc.set { gc with custom_major_ratio = 1_000_000 };
  let b = create () in
  Gc.set gc;
  b

let block = 1 lsl 16

(* A part (the text from a line start on, read without the text before
   it) counts its own vertices, normals and texture coordinates, and adds
   [part_offset] to each count that resolves an index: then no index is
   out of range, a positive index [x] resolves as usual to [x - 1] (below
   2^60: it has at most 18 digits), and a negative one [-x] to
   [own + part_offset - x], at least 2^60, which the join re-bases to
   [before + own - x] once the count [before] of the text before is
   known. *)
let part_offset = 1 lsl 61
let positive_below = 1 lsl 60
let[@inline] rebased r before = if r >= positive_below then r - part_offset + before else r

(* A store's full blocks are newest first; [free] holds blocks already
   sent ({!spill}), reused for the next ones. *)
type floats = {
  mutable fblocks : fblock list;
  mutable fcur : float array;
  mutable fn : int;
  mutable ffull : int;
  mutable ffree : fblock list;
}

type ints = {
  mutable iblocks : iblock list;
  mutable icur : int array;
  mutable inn : int;
  mutable ifull : int;
  mutable ifree : iblock list;
}

let floats () = { fblocks = []; fcur = Array.make 256 0.; fn = 0; ffull = 0; ffree = [] }
let ints () = { iblocks = []; icur = Array.make 256 0; inn = 0; ifull = 0; ifree = [] }

(* The number of elements of a store. *)
let float_length g = g.ffull + g.fn
let int_length g = g.ifull + g.inn

(* Pushes [src.(i)]: read from an array, not passed, since a float
   argument of a function that is not inlined is boxed. *)
let push_float g (src : float array) i =
  if g.fn = Array.length g.fcur then
    if g.fn < block then begin
      let a = Array.make (2 * g.fn) 0. in
      Array.blit g.fcur 0 a 0 g.fn;
      g.fcur <- a
    end
    else begin
      let b =
        match g.ffree with
        | b :: rest ->
            g.ffree <- rest;
            b
        | [] -> out_of_heap (fun () -> Bigarray.Array1.create Bigarray.float64 Bigarray.c_layout block)
      in
      let a = g.fcur in
      for k = 0 to block - 1 do
        Bigarray.Array1.unsafe_set b k (Array.unsafe_get a k)
      done;
      g.fblocks <- b :: g.fblocks;
      g.ffull <- g.ffull + block;
      g.fn <- 0
    end;
  Array.unsafe_set g.fcur g.fn src.(i);
  g.fn <- g.fn + 1

(* [Array.blit] on ints goes through the write barrier, element by
   element, when the target is in the major heap (the C code cannot know
   the elements are not pointers); a loop on an [int array] does not. *)
let blit_ints (src : int array) (dst : int array) at len =
  for k = 0 to len - 1 do
    Array.unsafe_set dst (at + k) (Array.unsafe_get src k)
  done

let push_int g x =
  if g.inn = Array.length g.icur then
    if g.inn < block then begin
      let a = Array.make (2 * g.inn) 0 in
      blit_ints g.icur a 0 g.inn;
      g.icur <- a
    end
    else begin
      let b =
        match g.ifree with
        | b :: rest ->
            g.ifree <- rest;
            b
        | [] -> out_of_heap (fun () -> Bigarray.Array1.create Bigarray.int Bigarray.c_layout block)
      in
      let a = g.icur in
      for k = 0 to block - 1 do
        Bigarray.Array1.unsafe_set b k (Array.unsafe_get a k)
      done;
      g.iblocks <- b :: g.iblocks;
      g.ifull <- g.ifull + block;
      g.inn <- 0
    end;
  Array.unsafe_set g.icur g.inn x;
  g.inn <- g.inn + 1

(* A part's floats and numbers travel as bytes, 8 each, in the machine's
   byte order (a part is read and joined by processes of one program):
   sent a block at a time while the part is read ({!spill}), and read by
   the join straight into the joined arrays. Marshalled, an [int array]
   takes 30 instructions a number each way, and the part two more
   copies. *)
external get64 : Bytes.t -> int -> int64 = "%caml_bytes_get64u"
external set64 : Bytes.t -> int -> int64 -> unit = "%caml_bytes_set64u"

(* Element [k] of [b], which holds at least [k + 1]: callers loop below
   [Bytes.length b / 8]. *)
let[@inline] float_at b k = Int64.float_of_bits (get64 b (8 * k))
let[@inline] int_at b k = Int64.to_int (get64 b (8 * k))

(* The elements of store [g] into [a.(0) ..], the store left as it is. *)
let blit_float_store g (a : float array) =
  Array.blit g.fcur 0 a g.ffull g.fn;
  List.iteri
    (fun k (b : fblock) ->
      let at = g.ffull - ((k + 1) * block) in
      for j = 0 to block - 1 do
        Array.unsafe_set a (at + j) (Bigarray.Array1.unsafe_get b j)
      done)
    g.fblocks

let blit_int_store g (a : int array) =
  blit_ints g.icur a g.ifull g.inn;
  List.iteri
    (fun k (b : iblock) ->
      let at = g.ifull - ((k + 1) * block) in
      for j = 0 to block - 1 do
        Array.unsafe_set a (at + j) (Bigarray.Array1.unsafe_get b j)
      done)
    g.iblocks

(* The elements of store [g] as one array; the store is emptied, so that
   its blocks can be collected while the next store is concatenated. *)
let float_array g =
  let a = Array.create_float (float_length g) in
  blit_float_store g a;
  g.fblocks <- [];
  g.fcur <- [||];
  a

let int_array g =
  let a = Array.make (int_length g) 0 in
  blit_int_store g a;
  g.iblocks <- [];
  g.icur <- [||];
  a

(* Whether stores [g] and [h], filled in step (a push to one is a push
   to the other), hold the same elements. *)
let same_stores g h =
  let same (a : int array) (b : int array) len =
    let r = ref true in
    for k = 0 to len - 1 do
      if Array.unsafe_get a k <> Array.unsafe_get b k then r := false
    done;
    !r
  in
  let same_block (a : iblock) (b : iblock) =
    let r = ref true in
    for k = 0 to block - 1 do
      if Bigarray.Array1.unsafe_get a k <> Bigarray.Array1.unsafe_get b k then r := false
    done;
    !r
  in
  int_length g = int_length h && same g.icur h.icur g.inn && List.for_all2 same_block g.iblocks h.iblocks

(* A face's vertices: a growable array, reused from face to face. *)
type face = { mutable fa : int array; mutable len : int }

let push_face g x =
  if g.len = Array.length g.fa then begin
    let a = Array.make (2 * g.len) 0 in
    Array.blit g.fa 0 a 0 g.len;
    g.fa <- a
  end;
  Array.unsafe_set g.fa g.len x;
  g.len <- g.len + 1

type parser = {
  name : string;
  max_vertices : int;
  max_triangles : int;
  offset : int;  (* [0], or {!part_offset} for a part *)
  needs : int array;  (* a part's needs of the text before it: see [note] *)
  pos : floats;
  nrm : floats;
  tris : ints;
  tri_nrm : ints;  (* only with [nrm_mode = nrm_explicit]: see [keep_normals] *)
  mutable nrm_mode : int;
  tex : floats;  (* u v of each [vt] *)
  tri_tex : ints;  (* empty until a face gives a texture index: see [face] *)
  mutable textured : bool;  (* a face gave a texture index *)
  face_v : face;  (* the vertices, normals and texture numbers of the face being read *)
  face_n : face;
  face_t : face;
  counts : int array;  (* per kind of skipped statement *)
  mutable texcoords : int;
  mutable line : int;  (* the number of the line being read, from 1 *)
  mutable carry : Bytes.t;  (* the start of a line that a chunk cut *)
  mutable carry_len : int;
  mutable error : string option;
  mutable finished : bool;
  num : float array;  (* the numbers just read, unboxed: 3 *)
  output : (Bytes.t -> int -> int -> unit) option;  (* a part's, see [spill] *)
  mutable sent : int;  (* the bytes given to [output] *)
  mutable send_buffer : Bytes.t;
}

exception Error_at of string

(* What a part's indices need of the text before it, per kind (vertex,
   normal, texture), is kept in [needs]: the largest [x - 1 - own] of a
   positive index [x] read when the part had [own] of that kind (the
   index must be below [before + own]), and the smallest [own - x] of a
   negative one (which must resolve to at least 0). *)
let need_vertex = 0
let need_normal = 2
let need_texture = 4
let no_needs () = [| min_int; 0; min_int; 0; min_int; 0 |]

(* The triangles' normal numbers, as exporters write them: each the
   vertex's number ([f 1//1 2//2 3//3]), or none ([f 1 2 3], each [-1]).
   While every triangle so far is one of the two, the reader stores no
   normal numbers ([nrm_same], [nrm_none]: a million triangles' were 24
   MB of blocks, garbage once read); the first triangle that is neither
   makes them explicit ([explicit_normals]). [nrm_unknown]: no triangle
   yet. *)
let nrm_unknown = 0
let nrm_same = 1
let nrm_none = 2
let nrm_explicit = 3

let make ~offset ~output ~name ~max_vertices ~max_triangles =
  {
    name; max_vertices; max_triangles; offset; needs = no_needs ();
    pos = floats (); nrm = floats (); tris = ints (); tri_nrm = ints ();
    (* A part's blocks of normal numbers are sent in step with its
       triangles' ([spill]): kept from the start. *)
    nrm_mode = (if offset > 0 then nrm_explicit else nrm_unknown);
    tex = floats (); tri_tex = ints (); textured = false;
    face_v = { fa = Array.make 16 0; len = 0 }; face_n = { fa = Array.make 16 0; len = 0 };
    face_t = { fa = Array.make 16 0; len = 0 };
    counts = Array.make (Array.length kinds) 0;
    texcoords = 0; line = 1; carry = Bytes.create 256; carry_len = 0;
    error = None; finished = false; num = [| 0.; 0.; 0. |]; output; sent = 0; send_buffer = Bytes.empty;
  }

let create = make ~offset:0 ~output:None
let create_part ~output ~name ~max_vertices ~max_triangles =
  (* [part_offset] is 2^61: JavaScript's 32-bit integers cannot hold it. *)
  if Sys.int_size < 63 then invalid_arg "Obj_parts.create_part: needs 63-bit integers";
  make ~offset:part_offset ~output:(Some output) ~name ~max_vertices ~max_triangles

(* In a part, what resolving [r] (the index read, with [part_offset]
   added to the count [own + part_offset] it was resolved against)
   needs of the text before. *)
let note p kind ~own r =
  if r < positive_below then begin
    if r - own > p.needs.(kind) then p.needs.(kind) <- r - own
  end
  else if r - p.offset < p.needs.(kind + 1) then p.needs.(kind + 1) <- r - p.offset

(* In a part, the needs of the face just read. *)
let note_face p ~nv ~nn =
  for c = 0 to p.face_v.len - 1 do
    note p need_vertex ~own:(nv - p.offset) p.face_v.fa.(c);
    let n = p.face_n.fa.(c) in
    if n >= 0 then note p need_normal ~own:(nn - p.offset) n
  done

(* Errors: [i] is the byte where the line starts, [k] the offending byte. *)
let fail p i k fmt =
  Printf.ksprintf (fun m -> raise (Error_at (Printf.sprintf "%s:%d:%d: %s" p.name p.line (k - i + 1) m))) fmt

(* One comparison for the bytes of numbers and keywords, all above ' '. *)
let[@inline] is_space c = c <= ' ' && (c = ' ' || c = '\t' || c = '\r' || c = '\012' || c = '\011')

let[@inline] skip_spaces b k j =
  let k = ref k in
  while !k < j && is_space (Bytes.unsafe_get b !k) do incr k done;
  !k

(* The end of the token at [k]: the next space or [j]. The bytes of
   numbers and keywords are all above ' ', which one comparison tells. *)
let[@inline] token_end b k j =
  let k = ref k in
  while
    !k < j
    &&
    let c = Bytes.unsafe_get b !k in
    c > ' ' || not (is_space c)
  do
    incr k
  done;
  !k

let shown b k e =
  let s = Bytes.sub_string b k (min (e - k) 24) in
  if e - k > 24 then s ^ "..." else s

(* The number at [k .. e - 1] into [p.num.(0)]. *)
let number p b i k e =
  Float_scan.into b k e p.num 0;
  let x = p.num.(0) in
  if Float.is_finite x then ()
  else if Float.is_nan x then begin
    let s = String.lowercase_ascii (Bytes.sub_string b k (e - k)) in
    let s = if s <> "" && (s.[0] = '-' || s.[0] = '+') then String.sub s 1 (String.length s - 1) else s in
    if s = "nan" || s = "inf" || s = "infinity" then fail p i k "expected a finite number, found %s" (shown b k e)
    else fail p i k "expected a number, found %S" (shown b k e)
  end
  else fail p i k "number %s is too large (infinite as a float)" (shown b k e)

(* [v x y z [w]] or [v x y z r g b] (or [vn x y z]) after the keyword at
   [kw]: pushes x y z. Here and in faces a token that starts with [#]
   starts a comment to the end of the line, as some exporters write. *)
let vertex p b i kw k j ~normal =
  let k = ref k and n = ref 0 in
  let g = if normal then p.nrm else p.pos in
  let count = float_length g / 3 in
  if count >= p.max_vertices then
    fail p i kw "more than %d %s (the limit of vertices)" p.max_vertices (if normal then "normals" else "vertices");
  let most = if normal then 3 else 7 in
  k := skip_spaces b !k j;
  while !k < j && Bytes.unsafe_get b !k <> '#' do
    (* The number read in one pass where a space or the line's end ends
       it (then it is the whole token); else the token is delimited
       first, and its errors told. *)
    let e = Float_scan.scan b !k j p.num 0 in
    let e =
      if e > !k && (e = j || is_space (Bytes.unsafe_get b e)) && !n < most && Float.is_finite p.num.(0) then e
      else begin
        let e = token_end b !k j in
        if !n >= most then
          fail p i !k "expected at most %d numbers (%s), found %S" most
            (if normal then "vn x y z" else "v x y z [w]") (shown b !k e);
        number p b i !k e;
        e
      end
    in
    if !n < 3 then push_float g p.num 0;
    incr n;
    k := skip_spaces b e j
  done;
  if !n < 3 then fail p i !k "expected 3 numbers (%s), found %d" (if normal then "vn x y z" else "v x y z") !n
  else if (not normal) && !n = 5 then fail p i !k "expected x y z [w] or x y z r g b, found 5 numbers"

(* The vertex (or with [normal] the normal) after the keyword [v] at
   [b.[k]], where it is in the layout of every exporter: one space before
   each of 3 numbers, each ended by the next space or the line's end,
   finite, nothing after, the bound not reached. Then it is what [vertex]
   would read, read without its loop and checks, and the result is
   [true]; on anything else nothing is read and the result is [false]:
   [vertex] reads the line, and tells its errors. [j <= Bytes.length b]
   for every line read: the numbers are scanned without bounds checks. *)
let vertex3 p b k j ~normal =
  let g = if normal then p.nrm else p.pos in
  let num = p.num in
  let q = ref k and ok = ref (float_length g / 3 < p.max_vertices) and c = ref 0 in
  while !ok && !c < 3 do
    if !q < j && Bytes.unsafe_get b !q = ' ' then begin
      let e = Float_scan.unsafe_scan b (!q + 1) j num !c in
      if e > !q + 1 && (e = j || Bytes.unsafe_get b e = ' ') && Float.is_finite (Array.unsafe_get num !c) then q := e
      else ok := false
    end
    else ok := false;
    incr c
  done;
  !ok && !q = j
  && begin
       if g.fn + 3 <= Array.length g.fcur then begin
         let a = g.fcur and n = g.fn in
         Array.unsafe_set a n (Array.unsafe_get num 0);
         Array.unsafe_set a (n + 1) (Array.unsafe_get num 1);
         Array.unsafe_set a (n + 2) (Array.unsafe_get num 2);
         g.fn <- n + 3
       end
       else begin
         push_float g num 0; push_float g num 1; push_float g num 2
       end;
       true
     end

(* [vt u [v [w]]] after the keyword at [kw]: pushes u and v ([0] when
   absent); [w] is ignored. Texture coordinates count against the bound
   of vertices. *)
let texcoord p b i kw k j =
  if p.texcoords >= p.max_vertices then
    fail p i kw "more than %d texture coordinates (the limit of vertices)" p.max_vertices;
  let k = ref (skip_spaces b k j) and n = ref 0 in
  p.num.(1) <- 0.;
  while !k < j && Bytes.unsafe_get b !k <> '#' do
    let e = token_end b !k j in
    if !n >= 3 then fail p i !k "expected at most 3 numbers (vt u [v [w]]), found %S" (shown b !k e);
    number p b i !k e;
    (* [number] reads into [num.(0)]: u stays there, v moves to 1. *)
    if !n = 0 then p.num.(2) <- p.num.(0) else if !n = 1 then p.num.(1) <- p.num.(0);
    incr n;
    k := skip_spaces b e j
  done;
  if !n < 1 then fail p i !k "expected 1 to 3 numbers (vt u [v [w]]), found none";
  push_float p.tex p.num 2;
  push_float p.tex p.num 1;
  p.texcoords <- p.texcoords + 1

(* The digits of an index that fit an integer: 63 bits, or the 32 of
   JavaScript's integers. *)
let index_digits = if Sys.int_size >= 63 then 18 else 9

(* An OBJ index at [!k] (1-based or negative), resolved against [count]
   elements of [what] to 0-based. Leaves [!k] after its digits. *)
let index p b i k j ~count ~what =
  let start = !k in
  let neg = !k < j && Bytes.unsafe_get b !k = '-' in
  if neg then incr k;
  let x = ref 0 and digits = ref 0 in
  while !k < j && Bytes.unsafe_get b !k >= '0' && Bytes.unsafe_get b !k <= '9' do
    if !digits < index_digits then x := (!x * 10) + (Char.code (Bytes.unsafe_get b !k) - 48);
    incr digits;
    incr k
  done;
  if !digits = 0 then fail p i start "expected a %s index, found %S" what (shown b start (token_end b start j));
  if !x = 0 then fail p i start "%s index 0 (indices start at 1, or -1 for the last)" what;
  let r = if !digits > index_digits then -1 else if neg then count - !x else !x - 1 in
  if r < 0 || r >= count then
    fail p i start "%s index %s is out of range: %d %s defined so far" what
      (Bytes.sub_string b start (!k - start)) count
      (if count = 1 then what else if what = "vertex" then "vertices" else what ^ "s");
  r

(* The positive number of at most [index_digits] digits at [!k], [!k]
   moved past its digits; [0] (which no index is) where there is none or
   more. *)
let[@inline] positive b k j =
  let start = !k in
  let x = ref 0 in
  while !k < j && Bytes.unsafe_get b !k >= '0' && Bytes.unsafe_get b !k <= '9' do
    x := (!x * 10) + (Char.code (Bytes.unsafe_get b !k) - 48);
    incr k
  done;
  if !k - start <= index_digits then !x else 0

(* [index] where the index at [!k] is a plain positive number within
   [count]: read without a call, the common case of every face. *)
let[@inline] fast_index p b i k j ~count ~what =
  let start = !k in
  let x = positive b k j in
  if x > 0 && x <= count then x - 1
  else begin
    k := start;
    index p b i k j ~count ~what
  end

(* The normal numbers of the triangles read so far, written out in
   [tri_nrm]: the triangles' own numbers, or [-1] each. *)
let explicit_normals p =
  let t = p.tris and m = p.nrm_mode in
  if m = nrm_same then begin
    List.iter (fun (a : iblock) -> for k = 0 to block - 1 do push_int p.tri_nrm (Bigarray.Array1.unsafe_get a k) done) (List.rev t.iblocks);
    for k = 0 to t.inn - 1 do push_int p.tri_nrm (Array.unsafe_get t.icur k) done
  end
  else if m = nrm_none then for _ = 1 to int_length t do push_int p.tri_nrm (-1) done;
  p.nrm_mode <- nrm_explicit

(* Whether the normal numbers [na nb nc] of the triangle [a b c], about
   to be pushed, go to [tri_nrm]: only once some triangle's are neither
   its vertices' numbers nor all [-1]. *)
let keep_normals p a b c na nb nc =
  let m = p.nrm_mode in
  if m = nrm_explicit then true
  else
    let same = na = a && nb = b && nc = c and none = na < 0 && nb < 0 && nc < 0 in
    if (m = nrm_same && same) || (m = nrm_none && none) then false
    else if m = nrm_unknown && (same || none) then begin
      p.nrm_mode <- (if same then nrm_same else nrm_none);
      false
    end
    else begin
      explicit_normals p;
      true
    end

let face p b i f k j =
  p.face_v.len <- 0;
  p.face_n.len <- 0;
  p.face_t.len <- 0;
  let nv = (float_length p.pos / 3) + p.offset and nn = (float_length p.nrm / 3) + p.offset in
  let k = ref (skip_spaces b k j) in
  while !k < j && Bytes.unsafe_get b !k <> '#' do
    push_face p.face_v (fast_index p b i k j ~count:nv ~what:"vertex");
    let n = ref (-1) and tx = ref (-1) in
    if !k < j && Bytes.unsafe_get b !k = '/' then begin
      incr k;
      if !k < j && Bytes.unsafe_get b !k <> '/' && not (is_space (Bytes.unsafe_get b !k)) then begin
        let t = index p b i k j ~count:(p.texcoords + p.offset) ~what:"texture" in
        if p.offset > 0 then note p need_texture ~own:p.texcoords t;
        tx := t
      end;
      if !k < j && Bytes.unsafe_get b !k = '/' then begin
        incr k;
        if !k < j && not (is_space (Bytes.unsafe_get b !k)) then n := fast_index p b i k j ~count:nn ~what:"normal"
      end
    end;
    if !k < j && not (is_space (Bytes.unsafe_get b !k)) then
      fail p i !k "expected a space or the end of the line after a face vertex, found %S"
        (shown b !k (token_end b !k j));
    push_face p.face_n !n;
    push_face p.face_t !tx;
    k := skip_spaces b !k j
  done;
  let n = p.face_v.len in
  if n < 3 then fail p i f "a face needs at least 3 vertices, found %d" n;
  if (int_length p.tris / 3) + (n - 2) > p.max_triangles then
    fail p i f "more than %d triangles (the limit of triangles)" p.max_triangles;
  if p.offset > 0 then note_face p ~nv ~nn;
  let v = p.face_v.fa and vn = p.face_n.fa and vt = p.face_t.fa in
  (* Meshes without texture coordinates (most) keep no texture numbers:
     the first face that gives one gives the triangles before it none. *)
  let any = ref false in
  for c = 0 to n - 1 do if vt.(c) >= 0 then any := true done;
  if (not p.textured) && !any then begin
    for _ = 1 to int_length p.tris do push_int p.tri_tex (-1) done;
    p.textured <- true
  end;
  for t = 1 to n - 2 do
    if keep_normals p v.(0) v.(t) v.(t + 1) vn.(0) vn.(t) vn.(t + 1) then begin
      push_int p.tri_nrm vn.(0); push_int p.tri_nrm vn.(t); push_int p.tri_nrm vn.(t + 1)
    end;
    push_int p.tris v.(0); push_int p.tris v.(t); push_int p.tris v.(t + 1);
    if p.textured then begin
      push_int p.tri_tex vt.(0); push_int p.tri_tex vt.(t); push_int p.tri_tex vt.(t + 1)
    end
  done

let[@inline] push3 g x y z =
  if g.inn + 3 <= Array.length g.icur then begin
    let a = g.icur and n = g.inn in
    Array.unsafe_set a n x;
    Array.unsafe_set a (n + 1) y;
    Array.unsafe_set a (n + 2) z;
    g.inn <- n + 3
  end
  else begin
    push_int g x; push_int g y; push_int g z
  end

(* The face after the keyword [f] at [b.[k]], where it is a triangle in
   the layout of every exporter: one space before each of its 3 corners,
   each [v] or [v//n] with positive indices in range, nothing after.
   Then it is what [face] would read, read without its loop and calls,
   and the result is [true]; on anything else nothing is read and the
   result is [false]: [face] reads the line, and tells its errors. *)
let triangle p b k j =
  let nv = (float_length p.pos / 3) + p.offset and nn = (float_length p.nrm / 3) + p.offset in
  let v = p.face_v.fa and vn = p.face_n.fa in
  let q = ref k and ok = ref true and c = ref 0 in
  while !ok && !c < 3 do
    if !q < j && Bytes.unsafe_get b !q = ' ' then begin
      incr q;
      let x = positive b q j in
      if x <= 0 || x > nv then ok := false
      else begin
        Array.unsafe_set v !c (x - 1);
        if !q + 1 < j && Bytes.unsafe_get b !q = '/' && Bytes.unsafe_get b (!q + 1) = '/' then begin
          q := !q + 2;
          let y = positive b q j in
          if y <= 0 || y > nn then ok := false else Array.unsafe_set vn !c (y - 1)
        end
        else Array.unsafe_set vn !c (-1);
        if !q < j && Bytes.unsafe_get b !q <> ' ' then ok := false
      end
    end
    else ok := false;
    incr c
  done;
  !ok && !q = j
  && (int_length p.tris / 3) + 1 <= p.max_triangles
  && begin
       if p.offset > 0 then begin
         p.face_v.len <- 3;
         p.face_n.len <- 3;
         note_face p ~nv ~nn
       end;
       let a = Array.unsafe_get v 0 and b = Array.unsafe_get v 1 and c = Array.unsafe_get v 2 in
       let na = Array.unsafe_get vn 0 and nb = Array.unsafe_get vn 1 and nc = Array.unsafe_get vn 2 in
       if keep_normals p a b c na nb nc then push3 p.tri_nrm na nb nc;
       push3 p.tris a b c;
       (* This layout has no texture numbers. *)
       if p.textured then push3 p.tri_tex (-1) (-1) (-1);
       true
     end

(* The kind of the skipped keyword [b.[k] .. b.[e-1]]. *)
let kind_of b k e =
  let len = e - k in
  let rec go n =
    if n = kind_other then kind_other
    else
      let s = Array.unsafe_get kinds n in
      if String.length s = len && (let same = ref true in
                                   for x = 0 to len - 1 do
                                     if String.unsafe_get s x <> Bytes.unsafe_get b (k + x) then same := false
                                   done;
                                   !same)
      then n
      else go (n + 1)
  in
  go 0

(* Whether [b.[i] ..] starts with UTF-8's byte order mark, which some
   editors put at the start of a text: read as a keyword, it made the
   first statement an unknown one, skipped, and shifted every index. *)
let byte_order_mark b i j =
  j - i >= 3
  && Bytes.unsafe_get b i = '\xef'
  && Bytes.unsafe_get b (i + 1) = '\xbb'
  && Bytes.unsafe_get b (i + 2) = '\xbf'

(* One line, [b.[i] .. b.[j-1]] without its line end. The text's first
   line (not a part's: a part starts after a line end) may start with a
   byte order mark, skipped; columns still count its bytes. *)
let line p b i j =
  if j - i > max_line_bytes then fail p i j "line longer than %d bytes" max_line_bytes;
  let from = if p.line = 1 && p.offset = 0 && byte_order_mark b i j then i + 3 else i in
  let k = skip_spaces b from j in
  if k < j then begin
    let c = Bytes.unsafe_get b k in
    if c = '#' then p.counts.(kind_comment) <- p.counts.(kind_comment) + 1
    else begin
      let e = token_end b k j in
      let len = e - k in
      if len = 1 && c = 'v' then (if not (vertex3 p b e j ~normal:false) then vertex p b i k e j ~normal:false)
      else if len = 2 && c = 'v' && Bytes.unsafe_get b (k + 1) = 'n' then
        (if not (vertex3 p b e j ~normal:true) then vertex p b i k e j ~normal:true)
      else if len = 1 && c = 'f' then (if not (triangle p b e j) then face p b i k e j)
      else begin
        let kind = kind_of b k e in
        if kind = kind_vt then texcoord p b i k e j else p.counts.(kind) <- p.counts.(kind) + 1
      end
    end
  end;
  p.line <- p.line + 1

let append_carry p b k e =
  let len = e - k in
  if p.carry_len + len > max_line_bytes + 2 then
    fail p 0 max_line_bytes "line longer than %d bytes" max_line_bytes;
  if p.carry_len + len > Bytes.length p.carry then begin
    let c = Bytes.create (max (p.carry_len + len) (2 * Bytes.length p.carry)) in
    Bytes.blit p.carry 0 c 0 p.carry_len;
    p.carry <- c
  end;
  Bytes.blit b k p.carry p.carry_len len;
  p.carry_len <- p.carry_len + len

(* A line without its LF and a CR before it. *)
let[@inline] line_before p b i nl =
  let j = if nl > i && Bytes.unsafe_get b (nl - 1) = '\r' then nl - 1 else nl in
  line p b i j

(* Equality of int64 words as one comparison: [Int64.equal] goes through
   [compare]. *)
let[@inline] eq64 (x : int64) (y : int64) = x = y

(* The first LF at or after [k], or [stop]. Eight bytes at a time: the
   classic test for a zero byte in a word, on the word xor LF in every
   byte, is non-zero iff some byte is LF (it can only mark wrongly the
   bytes after the first LF, which the byte loop then finds). Measured:
   10% fewer instructions for the whole load than a byte loop. *)
let newline b k stop =
  let k = ref k and found = ref false in
  while (not !found) && !k + 8 <= stop do
    (* [!k + 8 <= stop <= Bytes.length b]: no bounds check. *)
    let x = Int64.logxor (get64 b !k) 0x0a0a0a0a0a0a0a0aL in
    if eq64 (Int64.logand (Int64.logand (Int64.sub x 0x0101010101010101L) (Int64.lognot x)) 0x8080808080808080L) 0L
    then k := !k + 8
    else found := true
  done;
  while !k < stop && Bytes.unsafe_get b !k <> '\n' do incr k done;
  !k

(* A part's arrays are sent to its [output] as records, each a header
   (its kind and its number [n] of elements, 8 bytes each) then [n]
   elements (none for [record_same]), a full block at a time as the part
   is read and the rest when it is finished: the reader then holds a block
   or two per array, whatever the part's size, and its collector has
   little to mark. A block of triangle normals equal to the triangles'
   block and without relative indices (then both are final as they are)
   is sent as [record_same]: exporters number a corner's normal as its
   vertex, and the join then reads half as many bytes. *)
let record_positions = 0
let record_normals = 1
let record_triangles = 2
let record_triangle_normals = 3
let record_same = 4
let record_texcoords = 5
let record_triangle_texcoords = 6
let record_header = 16

let send p out kind n =
  set64 p.send_buffer 0 (Int64.of_int kind);
  set64 p.send_buffer 8 (Int64.of_int n);
  let bytes = if kind = record_same then record_header else record_header + (8 * n) in
  out p.send_buffer 0 bytes;
  p.sent <- p.sent + bytes

let send_floats p out kind (a : float array) n =
  for k = 0 to n - 1 do
    set64 p.send_buffer (record_header + (8 * k)) (Int64.bits_of_float (Array.unsafe_get a k))
  done;
  send p out kind n

let send_ints p out kind (a : int array) n =
  for k = 0 to n - 1 do
    set64 p.send_buffer (record_header + (8 * k)) (Int64.of_int (Array.unsafe_get a k))
  done;
  send p out kind n

(* [send_floats] and [send_ints] of a full block. *)
let send_float_block p out kind (b : fblock) =
  for k = 0 to block - 1 do
    set64 p.send_buffer (record_header + (8 * k)) (Int64.bits_of_float (Bigarray.Array1.unsafe_get b k))
  done;
  send p out kind block

let send_int_block p out kind (b : iblock) =
  for k = 0 to block - 1 do
    set64 p.send_buffer (record_header + (8 * k)) (Int64.of_int (Bigarray.Array1.unsafe_get b k))
  done;
  send p out kind block

(* Whether the first [n] numbers of [a] and [b] are equal and none is
   relative (see [part_offset]). *)
let same_plain (a : int array) (b : int array) n =
  let same = ref true in
  for k = 0 to n - 1 do
    let x = Array.unsafe_get a k in
    if x <> Array.unsafe_get b k || x >= positive_below then same := false
  done;
  !same

(* A pair of blocks, of triangles and of their normals: filled in step,
   they are as many at every line start. *)
let send_pair p out (t : int array) (tn : int array) n =
  send_ints p out record_triangles t n;
  if same_plain t tn n then send p out record_same n else send_ints p out record_triangle_normals tn n

let send_block_pair p out (t : iblock) (tn : iblock) =
  send_int_block p out record_triangles t;
  let same = ref true in
  for k = 0 to block - 1 do
    let x = Bigarray.Array1.unsafe_get t k in
    if x <> Bigarray.Array1.unsafe_get tn k || x >= positive_below then same := false
  done;
  if !same then send p out record_same block else send_int_block p out record_triangle_normals tn

(* Sends the full blocks of a part's arrays (at a line start), and with
   [last] the rest; the blocks sent are reused. *)
let spill p ~last =
  match p.output with
  | None -> ()
  | Some out ->
      if Bytes.length p.send_buffer = 0 then p.send_buffer <- Bytes.create (record_header + (8 * block));
      let floats kind g =
        List.iter (fun b -> send_float_block p out kind b) (List.rev g.fblocks);
        g.ffree <- List.rev_append g.fblocks g.ffree;
        g.fblocks <- [];
        if last && g.fn > 0 then send_floats p out kind g.fcur g.fn
      in
      floats record_positions p.pos;
      floats record_normals p.nrm;
      floats record_texcoords p.tex;
      (* A part's texture numbers, once it has any, are as many as its
         triangles' vertex numbers; sent a block at a time likewise. *)
      let tt = p.tri_tex in
      List.iter (fun b -> send_int_block p out record_triangle_texcoords b) (List.rev tt.iblocks);
      tt.ifree <- List.rev_append tt.iblocks tt.ifree;
      tt.iblocks <- [];
      if last && tt.inn > 0 then send_ints p out record_triangle_texcoords tt.icur tt.inn;
      let t = p.tris and tn = p.tri_nrm in
      List.iter2 (fun a b -> send_block_pair p out a b) (List.rev t.iblocks) (List.rev tn.iblocks);
      t.ifree <- List.rev_append t.iblocks t.ifree;
      tn.ifree <- List.rev_append tn.iblocks tn.ifree;
      t.iblocks <- [];
      tn.iblocks <- [];
      if last && t.inn > 0 then send_pair p out t.icur tn.icur t.inn

let feed_bytes p b off len =
  if off < 0 || len < 0 || off > Bytes.length b - len then invalid_arg "Obj_file.feed";
  if p.finished then invalid_arg "Obj_file.feed: after finish";
  match p.error with
  | Some m -> Error (`Msg m)
  | None -> (
      let stop = off + len in
      try
        let k = ref off in
        if p.carry_len > 0 then begin
          let nl = newline b off stop in
          append_carry p b off nl;
          if nl < stop then begin
            let c = p.carry in
            let n = p.carry_len in
            p.carry_len <- 0;
            line_before p c 0 n
          end;
          k := nl + 1
        end;
        while !k < stop do
          let nl = newline b !k stop in
          if nl < stop then line_before p b !k nl else append_carry p b !k nl;
          k := nl + 1
        done;
        if p.pos.fblocks != [] || p.nrm.fblocks != [] || p.tris.iblocks != [] || p.tex.fblocks != []
           || p.tri_tex.iblocks != []
        then spill p ~last:false;
        Ok ()
      with Error_at m ->
        p.error <- Some m;
        Error (`Msg m))

let feed p s off len = feed_bytes p (Bytes.unsafe_of_string s) off len

type part = {
  part_floats : int;  (* the positions' floats *)
  part_normal_floats : int;
  part_numbers : int;  (* the triangles' vertex numbers, as many normal numbers *)
  part_counts : int array;
  part_needs : int array;
  part_bytes : int;  (* sent to the output *)
  part_tex_floats : int;  (* the texture coordinates' floats *)
  part_textured : bool;  (* a face gave a texture number: as many as [part_numbers] were sent *)
}

let skipped_of counts =
  let skipped = ref [] in
  for n = Array.length kinds - 1 downto 0 do
    if counts.(n) > 0 then skipped := (kinds.(n), counts.(n)) :: !skipped
  done;
  !skipped

(* Ends the reading of [p] (which must be [Ok]) with its last line. *)
let last_line p =
  if p.finished then invalid_arg "Obj_file.finish: called twice";
  p.finished <- true;
  match p.error with
  | Some m -> raise (Error_at m)
  | None ->
      if p.carry_len > 0 then begin
        let n = p.carry_len in
        p.carry_len <- 0;
        line_before p p.carry 0 n
      end

(* Exporters mostly number a corner's normal as its vertex
   ([f 1//1 2//2 3//3]): then one array serves both. *)

let finish p =
  match last_line p with
  | exception Error_at m -> Error (`Msg m)
  | () ->
      let positions = float_array p.pos in
      let normals = float_array p.nrm in
      let mode = p.nrm_mode in
      let same = mode = nrm_unknown || mode = nrm_same || (mode = nrm_explicit && same_stores p.tri_nrm p.tris) in
      let triangles = int_array p.tris in
      let triangle_normals =
        if same then triangles else if mode = nrm_none then Array.make (Array.length triangles) (-1) else int_array p.tri_nrm
      in
      let texcoords = float_array p.tex in
      let triangle_texcoords = if p.textured then int_array p.tri_tex else [||] in
      Ok { positions; normals; triangles; triangle_normals; texcoords; triangle_texcoords; skipped = skipped_of p.counts }

let finish_part p =
  if p.offset = 0 then invalid_arg "Obj_parts.finish_part: not a part";
  match last_line p with
  | exception Error_at m -> Error (`Msg m)
  | () ->
      spill p ~last:true;
      Ok
        { part_floats = float_length p.pos; part_normal_floats = float_length p.nrm; part_numbers = int_length p.tris;
          part_counts = p.counts; part_needs = p.needs; part_bytes = p.sent;
          part_tex_floats = float_length p.tex; part_textured = p.textured }

let part_triangle_count part = part.part_numbers / 3
let part_bytes part = part.part_bytes

let same_ints (a : int array) (b : int array) =
  Array.length a = Array.length b
  &&
  let same = ref true in
  for k = 0 to Array.length a - 1 do
    if Array.unsafe_get a k <> Array.unsafe_get b k then same := false
  done;
  !same

(* Reads the records of [part] by [input] into the joined arrays, whose
   first elements are the text before's, at [at_p], [at_n] and [at_t];
   [tn] is [[||]] while the triangle normals read are the triangles (the
   text before's and the records' so far): it is made at the first
   record that differs. The result is the triangle normals. *)
let read_records ~input ~nv ~nn ~ntx ~positions ~normals ~triangles ~tn ~texcoords ~ttx ~at_p ~at_n ~at_t ~at_x
    ~at_tt =
  let bad () = failwith "Obj_parts.join: not the part's bytes" in
  let buf = Bytes.create (record_header + (8 * block)) in
  let cp = ref at_p and cn = ref at_n and ct = ref at_t and ctn = ref at_t and tn = ref tn in
  let cx = ref at_x and ctt = ref at_tt in
  let np = Array.length positions and nn_floats = Array.length normals and nt = Array.length triangles in
  let nx = Array.length texcoords and ntt = Array.length ttx in
  while !cp < np || !cn < nn_floats || !ct < nt || !ctn < nt || !cx < nx || !ctt < ntt do
    input buf 0 record_header;
    let kind = int_at buf 0 and n = int_at buf 1 in
    if n <= 0 || n > block then bad ();
    if kind = record_same then begin
      (* The triangles' block comes first. *)
      if !ctn + n > !ct then bad ();
      let a = !tn in
      if a != [||] then
        for k = !ctn to !ctn + n - 1 do
          Array.unsafe_set a k (Array.unsafe_get triangles k)
        done;
      ctn := !ctn + n
    end
    else begin
      let at, length =
        if kind = record_positions then (cp, np)
        else if kind = record_normals then (cn, nn_floats)
        else if kind = record_triangles then (ct, nt)
        else if kind = record_triangle_normals then (ctn, nt)
        else if kind = record_texcoords then (cx, nx)
        else if kind = record_triangle_texcoords then (ctt, ntt)
        else bad ()
      in
      let c = !at in
      if c + n > length then bad ();
      input buf record_header (8 * n);
      if kind = record_positions || kind = record_normals || kind = record_texcoords then begin
        let (dst : float array) =
          if kind = record_positions then positions else if kind = record_normals then normals else texcoords
        in
        for k = 0 to n - 1 do
          Array.unsafe_set dst (c + k) (float_at buf (k + 2))
        done
      end
      else if kind = record_triangles || kind = record_triangle_texcoords then begin
        (* Vertex numbers rebase on the vertices before, texture numbers
           on the texture coordinates before. *)
        let dst, before = if kind = record_triangles then (triangles, nv) else (ttx, ntx) in
        for k = 0 to n - 1 do
          Array.unsafe_set dst (c + k) (rebased (int_at buf (k + 2)) before)
        done
      end
      else begin
        if !tn == [||] then begin
          (* Until here the normals' numbers were the triangles'. *)
          let a = Array.make nt 0 in
          blit_ints triangles a 0 c;
          tn := a
        end;
        let a = !tn in
        for k = 0 to n - 1 do
          Array.unsafe_set a (c + k) (rebased (int_at buf (k + 2)) nn)
        done
      end;
      at := c + n
    end
  done;
  (* One reader's: one array where the two numberings are equal. *)
  if !tn == [||] || same_ints !tn triangles then triangles else !tn

let join p part ~input =
  let nv = float_length p.pos / 3 and nn = float_length p.nrm / 3 in
  let fits kind before = part.part_needs.(kind) < before && before + part.part_needs.(kind + 1) >= 0 in
  if p.offset > 0 || p.finished || p.error <> None || p.carry_len > 0 then None
  else if
    not
      (fits need_vertex nv && fits need_normal nn && fits need_texture p.texcoords
      && part.part_floats mod 3 = 0 && part.part_normal_floats mod 3 = 0 && part.part_numbers mod 3 = 0
      && part.part_floats >= 0 && part.part_normal_floats >= 0 && part.part_numbers >= 0
      && nv + (part.part_floats / 3) <= p.max_vertices
      && nn + (part.part_normal_floats / 3) <= p.max_vertices
      && part.part_tex_floats >= 0 && part.part_tex_floats mod 2 = 0
      && p.texcoords + (part.part_tex_floats / 2) <= p.max_vertices
      && (int_length p.tris / 3) + part_triangle_count part <= p.max_triangles)
  then None
  else begin
    let at_p = float_length p.pos and at_n = float_length p.nrm and at_t = int_length p.tris in
    let positions = Array.create_float (at_p + part.part_floats) in
    blit_float_store p.pos positions;
    let normals = Array.create_float (at_n + part.part_normal_floats) in
    blit_float_store p.nrm normals;
    let triangles = Array.make (at_t + part.part_numbers) 0 in
    blit_int_store p.tris triangles;
    if p.nrm_mode = nrm_none then explicit_normals p;
    let tn =
      if p.nrm_mode <> nrm_explicit || same_stores p.tri_nrm p.tris then [||]
      else begin
        let a = Array.make (Array.length triangles) 0 in
        blit_int_store p.tri_nrm a;
        a
      end
    in
    let at_x = float_length p.tex in
    let texcoords = Array.create_float (at_x + part.part_tex_floats) in
    blit_float_store p.tex texcoords;
    (* The texture numbers, if either text has any: [-1] for the
       triangles of a text without. The part's are read after the text
       before's, at [at_t]. *)
    let textured = p.textured || part.part_textured in
    let ttx = if textured then Array.make (Array.length triangles) (-1) else [||] in
    if p.textured then blit_int_store p.tri_tex ttx;
    let records_ttx = if part.part_textured then ttx else [||] in
    (* The reader is left as it was until the records are read. *)
    let triangle_normals =
      read_records ~input ~nv ~nn ~ntx:p.texcoords ~positions ~normals ~triangles ~tn ~texcoords ~ttx:records_ttx ~at_p
        ~at_n ~at_t ~at_x ~at_tt:at_t
    in
    p.finished <- true;
    p.pos.fblocks <- [];
    p.nrm.fblocks <- [];
    p.tris.iblocks <- [];
    p.tri_nrm.iblocks <- [];
    p.tex.fblocks <- [];
    p.tri_tex.iblocks <- [];
    let counts = Array.map2 ( + ) p.counts part.part_counts in
    Some { positions; normals; triangles; triangle_normals; texcoords; triangle_texcoords = ttx; skipped = skipped_of counts }
  end

let of_string ~name ~max_vertices ~max_triangles s =
  let p = create ~name ~max_vertices ~max_triangles in
  match feed p s 0 (String.length s) with Error _ as e -> e | Ok () -> finish p

(* 15 significant digits suffice for most floats and keep the text short;
   17 always read back exactly. *)
let add_float digits b x =
  if digits > 0 then Printf.bprintf b "%.*g" digits x
  else
    let s = Printf.sprintf "%.15g" x in
    Buffer.add_string b (if float_of_string s = x then s else Printf.sprintf "%.17g" x)

let to_buffer ?(digits = 0) b m =
  let triple kw a n =
    for t = 0 to n - 1 do
      Buffer.add_string b kw;
      for c = 0 to 2 do
        Buffer.add_char b ' ';
        add_float digits b a.((3 * t) + c)
      done;
      Buffer.add_char b '\n'
    done
  in
  triple "v" m.positions (vertex_count m);
  triple "vn" m.normals (Array.length m.normals / 3);
  for t = 0 to (Array.length m.texcoords / 2) - 1 do
    Buffer.add_string b "vt ";
    add_float digits b m.texcoords.(2 * t);
    Buffer.add_char b ' ';
    add_float digits b m.texcoords.((2 * t) + 1);
    Buffer.add_char b '\n'
  done;
  for t = 0 to triangle_count m - 1 do
    Buffer.add_char b 'f';
    for c = 0 to 2 do
      Buffer.add_char b ' ';
      Buffer.add_string b (string_of_int (m.triangles.((3 * t) + c) + 1));
      let n = m.triangle_normals.((3 * t) + c) in
      let x = if m.triangle_texcoords = [||] then -1 else m.triangle_texcoords.((3 * t) + c) in
      if x >= 0 then begin
        Buffer.add_char b '/';
        Buffer.add_string b (string_of_int (x + 1))
      end;
      if n >= 0 then begin
        Buffer.add_string b (if x >= 0 then "/" else "//");
        Buffer.add_string b (string_of_int (n + 1))
      end
    done;
    Buffer.add_char b '\n'
  done

let to_string ?digits m =
  let b = Buffer.create 4096 in
  to_buffer ?digits b m;
  Buffer.contents b
