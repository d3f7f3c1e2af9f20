(* The reads below are unchecked: a corner's offset is checked to lie in
   [vertex] first. (That it is a multiple of 3 is [Prepared]'s invariant,
   not checked: a division per corner, and a wrong one reads in bounds.) *)
let check_corner vertex o =
  if o < 0 || o + 2 >= Array.length vertex then
    invalid_arg (Printf.sprintf "Vertex_order.gather: %d is not a vertex's offset" o)

let gather ?(sources = true) ~kind ~vertex at0 at1 at2 =
  let n = Array.length kind in
  if Array.length at0 <> n || Array.length at1 <> n || Array.length at2 <> n then
    invalid_arg "Vertex_order.gather: arrays of different lengths";
  let n_vertices = Array.length vertex / 3 in
  (* Per old vertex, its new offset, or [-1] until a slot names it: read
     as the slots walk the mesh, mostly near the last reads. *)
  let fresh = Array.make n_vertices (-1) in
  (* Written in order before any read: no zeroing. *)
  let out = Array.create_float (Array.length vertex) in
  let source = Array.make (if sources then n_vertices else 0) 0 in
  let placed = ref 0 in
  let place o =
    let v = o / 3 in
    let p = Array.unsafe_get fresh v in
    if p >= 0 then p
    else begin
      let j = !placed in
      let p = 3 * j in
      Array.unsafe_set out p (Array.unsafe_get vertex o);
      Array.unsafe_set out (p + 1) (Array.unsafe_get vertex (o + 1));
      Array.unsafe_set out (p + 2) (Array.unsafe_get vertex (o + 2));
      if sources then Array.unsafe_set source j o;
      Array.unsafe_set fresh v p;
      placed := j + 1;
      p
    end
  in
  for i = 0 to n - 1 do
    let k = Array.unsafe_get kind i in
    if Kind.is_triangle k then begin
      let o0 = Array.unsafe_get at0 i and o1 = Array.unsafe_get at1 i and o2 = Array.unsafe_get at2 i in
      check_corner vertex o0;
      check_corner vertex o1;
      check_corner vertex o2;
      Array.unsafe_set at0 i (place o0);
      Array.unsafe_set at1 i (place o1);
      Array.unsafe_set at2 i (place o2)
    end
  done;
  let used = !placed in
  if used = n_vertices then (out, source) else (Array.sub out 0 (3 * used), if sources then Array.sub source 0 used else source)
