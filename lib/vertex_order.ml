(* The new offset of each old vertex, [-1] until a slot names it: an int
   array of a third of [vertex]'s length (4 MB for the 1M-triangle knot),
   read as the slots walk the mesh, which keeps it mostly in cache. *)

(* The reads below are unchecked: a corner's offset is checked to lie in
   [vertex] first. (That it is a multiple of 3 is [Prepared]'s invariant,
   not checked: a division per corner, and a wrong one reads in bounds.) *)
let check_corner vertex o =
  if o < 0 || o + 2 >= Array.length vertex then
    invalid_arg (Printf.sprintf "Vertex_order.gather: %d is not a vertex's offset" o)

let gather ~kind ~vertex ~normals at0 at1 at2 =
  let n = Array.length kind in
  if Array.length at0 <> n || Array.length at1 <> n || Array.length at2 <> n then
    invalid_arg "Vertex_order.gather: arrays of different lengths";
  let with_normals = Array.length normals > 0 in
  if with_normals && Array.length normals <> Array.length vertex then
    invalid_arg "Vertex_order.gather: normals not parallel to the vertices";
  let fresh = Array.make (Array.length vertex / 3) (-1) in
  (* Written in order, never read before: no zeroing. *)
  let out = Array.create_float (Array.length vertex) in
  let nout = if with_normals then Array.create_float (Array.length vertex) else [||] in
  let next = ref 0 in
  let place o =
    let v = o / 3 in
    let placed = Array.unsafe_get fresh v in
    if placed >= 0 then placed
    else begin
      let p = !next in
      Array.unsafe_set out p (Array.unsafe_get vertex o);
      Array.unsafe_set out (p + 1) (Array.unsafe_get vertex (o + 1));
      Array.unsafe_set out (p + 2) (Array.unsafe_get vertex (o + 2));
      if with_normals then begin
        Array.unsafe_set nout p (Array.unsafe_get normals o);
        Array.unsafe_set nout (p + 1) (Array.unsafe_get normals (o + 1));
        Array.unsafe_set nout (p + 2) (Array.unsafe_get normals (o + 2))
      end;
      Array.unsafe_set fresh v p;
      next := p + 3;
      p
    end
  in
  for i = 0 to n - 1 do
    let k = Array.unsafe_get kind i in
    if k = Shape.triangle || k = Shape.smooth_triangle then begin
      let o0 = Array.unsafe_get at0 i and o1 = Array.unsafe_get at1 i and o2 = Array.unsafe_get at2 i in
      check_corner vertex o0;
      check_corner vertex o1;
      check_corner vertex o2;
      Array.unsafe_set at0 i (place o0);
      Array.unsafe_set at1 i (place o1);
      Array.unsafe_set at2 i (place o2)
    end
  done;
  let used = !next in
  if used = Array.length vertex then (out, nout)
  else (Array.sub out 0 used, if with_normals then Array.sub nout 0 used else [||])
