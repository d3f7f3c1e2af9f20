type t = {
  order : int array;
  n_nodes : int;
  lo_x : float array;
  lo_y : float array;
  lo_z : float array;
  hi_x : float array;
  hi_y : float array;
  hi_z : float array;
  right : int array;
  first : int array;
  count : int array;
  axis : int array;
  depth : int;
}

(* Rearranges [order.(lo .. hi - 1)] so that the element of rank [k] (by
   [key]) is at [k], smaller ones before, larger ones after: Hoare's
   selection, linear on average. *)
let select order (key : float array) lo hi k =
  let lo = ref lo and hi = ref (hi - 1) in
  while !lo < !hi do
    let pivot = key.(order.((!lo + !hi) / 2)) in
    let i = ref !lo and j = ref !hi in
    while !i <= !j do
      while key.(order.(!i)) < pivot do incr i done;
      while key.(order.(!j)) > pivot do decr j done;
      if !i <= !j then begin
        let x = order.(!i) in
        order.(!i) <- order.(!j);
        order.(!j) <- x;
        incr i;
        decr j
      end
    done;
    if k <= !j then hi := !j else if k >= !i then lo := !i else lo := !hi
  done

let[@inline] fmin (a : float) b = if a < b then a else b
let[@inline] fmax (a : float) b = if a > b then a else b

(* Half the surface area of a box: the surface area heuristic (SAH) takes
   the chance that a ray meets a box to grow with its area. *)
let[@inline] half_area x0 y0 z0 x1 y1 z1 =
  let dx = x1 -. x0 and dy = y1 -. y0 and dz = z1 -. z0 in
  (dx *. dy) +. (dy *. dz) +. (dz *. dx)

let bins = 16

let build ?(leaf_size = 4) ~cx ~cy ~cz extent =
  let n = Array.length cx in
  if n = 0 then invalid_arg "Bvh.build: no spheres";
  if Array.length cy <> n || Array.length cz <> n || Array.length extent <> n then
    invalid_arg "Bvh.build: arrays of different lengths";
  let leaf_size = max 1 leaf_size in
  let order = Array.init n Fun.id in
  (* A binary tree with leaves of >= 1 sphere has < 2n nodes. *)
  let cap = 2 * n in
  let lo_x = Array.make cap 0. and lo_y = Array.make cap 0. and lo_z = Array.make cap 0. in
  let hi_x = Array.make cap 0. and hi_y = Array.make cap 0. and hi_z = Array.make cap 0. in
  let right = Array.make cap (-1) and first = Array.make cap 0 and count = Array.make cap 0 in
  let axis = Array.make cap 0 in
  (* Per bin: count and bounds; reused by every node. *)
  let bin_n = Array.make bins 0 in
  let bin_box = Array.init 6 (fun _ -> Array.make bins 0.) in
  let left_area = Array.make bins 0. in
  let acc = Array.make 6 0. in
  let next = ref 0 and depth = ref 0 in
  let bin_of key c0 scale i =
    let b = truncate ((key.(i) -. c0) *. scale) in
    if b < 0 then 0 else if b >= bins then bins - 1 else b
  in
  let rec node lo hi level =
    let k = !next in
    incr next;
    if level > !depth then depth := level;
    let bx0 = ref infinity and by0 = ref infinity and bz0 = ref infinity in
    let bx1 = ref neg_infinity and by1 = ref neg_infinity and bz1 = ref neg_infinity in
    let mx0 = ref infinity and my0 = ref infinity and mz0 = ref infinity in
    let mx1 = ref neg_infinity and my1 = ref neg_infinity and mz1 = ref neg_infinity in
    for s = lo to hi - 1 do
      let i = order.(s) in
      let e = extent.(i) in
      bx0 := fmin !bx0 (cx.(i) -. e);
      by0 := fmin !by0 (cy.(i) -. e);
      bz0 := fmin !bz0 (cz.(i) -. e);
      bx1 := fmax !bx1 (cx.(i) +. e);
      by1 := fmax !by1 (cy.(i) +. e);
      bz1 := fmax !bz1 (cz.(i) +. e);
      mx0 := fmin !mx0 cx.(i);
      my0 := fmin !my0 cy.(i);
      mz0 := fmin !mz0 cz.(i);
      mx1 := fmax !mx1 cx.(i);
      my1 := fmax !my1 cy.(i);
      mz1 := fmax !mz1 cz.(i)
    done;
    lo_x.(k) <- !bx0;
    lo_y.(k) <- !by0;
    lo_z.(k) <- !bz0;
    hi_x.(k) <- !bx1;
    hi_y.(k) <- !by1;
    hi_z.(k) <- !bz1;
    let leaf () =
      first.(k) <- lo;
      count.(k) <- hi - lo
    in
    let n = hi - lo in
    let ex = !mx1 -. !mx0 and ey = !my1 -. !my0 and ez = !mz1 -. !mz0 in
    let a = if ex >= ey && ex >= ez then 0 else if ey >= ez then 1 else 2 in
    let key = match a with 0 -> cx | 1 -> cy | _ -> cz in
    let c0 = match a with 0 -> !mx0 | 1 -> !my0 | _ -> !mz0 in
    let ext = match a with 0 -> ex | 1 -> ey | _ -> ez in
    if n <= 1 then leaf ()
    else begin
      (* The split between bins that minimises the SAH cost
         A_left n_left + A_right n_right (in units of this box's area). *)
      let split =
        if ext > 0. then begin
          let scale = Float.of_int bins /. ext in
          Array.fill bin_n 0 bins 0;
          Array.iteri (fun c b -> Array.fill b 0 bins (if c < 3 then infinity else neg_infinity)) bin_box;
          for s = lo to hi - 1 do
            let i = order.(s) in
            let b = bin_of key c0 scale i in
            let e = extent.(i) in
            bin_n.(b) <- bin_n.(b) + 1;
            bin_box.(0).(b) <- fmin bin_box.(0).(b) (cx.(i) -. e);
            bin_box.(1).(b) <- fmin bin_box.(1).(b) (cy.(i) -. e);
            bin_box.(2).(b) <- fmin bin_box.(2).(b) (cz.(i) -. e);
            bin_box.(3).(b) <- fmax bin_box.(3).(b) (cx.(i) +. e);
            bin_box.(4).(b) <- fmax bin_box.(4).(b) (cy.(i) +. e);
            bin_box.(5).(b) <- fmax bin_box.(5).(b) (cz.(i) +. e)
          done;
          (* The growing box of bins, in a float array rather than float
             refs that a closure would box at every update. *)
          let reset () =
            for c = 0 to 5 do
              acc.(c) <- (if c < 3 then infinity else neg_infinity)
            done
          in
          let grow b =
            if bin_n.(b) > 0 then
              for c = 0 to 5 do
                let v = bin_box.(c).(b) in
                acc.(c) <- (if c < 3 then fmin acc.(c) v else fmax acc.(c) v)
              done
          in
          let acc_area () = half_area acc.(0) acc.(1) acc.(2) acc.(3) acc.(4) acc.(5) in
          reset ();
          for b = 0 to bins - 2 do
            grow b;
            left_area.(b) <- acc_area ()
          done;
          reset ();
          let best = ref (-1) and best_cost = ref infinity and right_n = ref 0 and left_n = ref n in
          for b = bins - 1 downto 1 do
            grow b;
            right_n := !right_n + bin_n.(b);
            left_n := !left_n - bin_n.(b);
            if !left_n > 0 && !right_n > 0 then begin
              let cost =
                (left_area.(b - 1) *. Float.of_int !left_n)
                +. (acc_area () *. Float.of_int !right_n)
              in
              if cost < !best_cost then begin
                best_cost := cost;
                best := b - 1
              end
            end
          done;
          let parent = half_area !bx0 !by0 !bz0 !bx1 !by1 !bz1 in
          (* A leaf costs n sphere tests; a split, one box test plus the
             expected tests below it (areas relative to this box's). *)
          if !best < 0 then if n <= leaf_size then `Leaf else `Median
          else if n <= leaf_size && Float.of_int n *. parent <= parent +. !best_cost then `Leaf
          else begin
            (* Partition the slots: bins <= best first. *)
            let i = ref lo and j = ref (hi - 1) in
            while !i <= !j do
              if bin_of key c0 scale order.(!i) <= !best then incr i
              else begin
                let x = order.(!i) in
                order.(!i) <- order.(!j);
                order.(!j) <- x;
                decr j
              end
            done;
            `At !i
          end
        end
        else if n <= leaf_size then `Leaf
        else `Median
      in
      match split with
      | `Leaf -> leaf ()
      | (`Median | `At _) as split ->
        (* Centers all together, in one bin: split at the median. *)
        let mid =
          match split with
          | `At mid when mid > lo && mid < hi -> mid
          | _ ->
              let m = (lo + hi) / 2 in
              select order key lo hi m;
              m
        in
        axis.(k) <- a;
        node lo mid (level + 1);
        right.(k) <- !next;
        node mid hi (level + 1)
    end
  in
  node 0 n 1;
  let n_nodes = !next in
  let sub a = Array.sub a 0 n_nodes in
  {
    order;
    n_nodes;
    lo_x = sub lo_x;
    lo_y = sub lo_y;
    lo_z = sub lo_z;
    hi_x = sub hi_x;
    hi_y = sub hi_y;
    hi_z = sub hi_z;
    right = sub right;
    first = sub first;
    count = sub count;
    axis = sub axis;
    depth = !depth;
  }

let ray_box_margin ~cx ~cy ~cz ~radius (camera : Vec3.t) =
  let n = Array.length cx in
  let x0 = ref camera.x and y0 = ref camera.y and z0 = ref camera.z in
  let x1 = ref camera.x and y1 = ref camera.y and z1 = ref camera.z in
  for i = 0 to n - 1 do
    let r = radius.(i) in
    x0 := fmin !x0 (cx.(i) -. r);
    y0 := fmin !y0 (cy.(i) -. r);
    z0 := fmin !z0 (cz.(i) -. r);
    x1 := fmax !x1 (cx.(i) +. r);
    y1 := fmax !y1 (cy.(i) +. r);
    z1 := fmax !z1 (cz.(i) +. r)
  done;
  let dx = !x1 -. !x0 and dy = !y1 -. !y0 and dz = !z1 -. !z0 in
  let d2 = (dx *. dx) +. (dy *. dy) +. (dz *. dz) in
  let m =
    List.fold_left (fun acc v -> fmax acc (Float.abs v)) 0. [ !x0; !y0; !z0; !x1; !y1; !z1 ]
  in
  let u = epsilon_float /. 2. in
  Array.map (fun r -> 64. *. u *. ((d2 /. r) +. m)) radius
