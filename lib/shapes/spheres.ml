(* Blocks of [block] spheres: a sequence grows by a block at a time, and
   never copies what it holds into a bigger array (a million spheres
   would briefly need twice their memory). *)
let bits = 14
let block = 1 lsl bits
let mask = block - 1

type t = {
  length : int;
  x : float array array;
  y : float array array;
  z : float array array;
  r : float array array;
  m : int array array;
  table : Material.t array;
}

let empty = { length = 0; x = [||]; y = [||]; z = [||]; r = [||]; m = [||]; table = [||] }
let length s = s.length

let check s i name = if i < 0 || i >= s.length then invalid_arg ("Spheres." ^ name ^ ": index out of bounds")

let center_x s i = check s i "center_x"; s.x.(i lsr bits).(i land mask)
let center_y s i = check s i "center_y"; s.y.(i lsr bits).(i land mask)
let center_z s i = check s i "center_z"; s.z.(i lsr bits).(i land mask)
let radius s i = check s i "radius"; s.r.(i lsr bits).(i land mask)
let material_index s i = check s i "material_index"; s.m.(i lsr bits).(i land mask)
let materials s = Array.copy s.table

let blit_fields s ~x ~y ~z ~radius ~material =
  let n = s.length in
  if Array.length x < n || Array.length y < n || Array.length z < n || Array.length radius < n
     || Array.length material < n
  then invalid_arg "Spheres.blit_fields: an array is too short";
  Array.iteri
    (fun b xs ->
      let at = b lsl bits and len = Array.length xs in
      Array.blit xs 0 x at len;
      Array.blit s.y.(b) 0 y at len;
      Array.blit s.z.(b) 0 z at len;
      Array.blit s.r.(b) 0 radius at len;
      Array.blit s.m.(b) 0 material at len)
    s.x

let get s i =
  check s i "get";
  let b = i lsr bits and k = i land mask in
  let m = s.table.(s.m.(b).(k)) in
  Sphere.v ~center:(Vec3.v s.x.(b).(k) s.y.(b).(k) s.z.(b).(k)) ~radius:s.r.(b).(k) m

let iteri f s =
  for i = 0 to s.length - 1 do
    f i (get s i)
  done

let iter f s = iteri (fun _ x -> f x) s

let fold f acc s =
  let acc = ref acc in
  iter (fun x -> acc := f !acc x) s;
  !acc

let exists p s =
  let rec go i = i < s.length && (p (get s i) || go (i + 1)) in
  go 0

let to_list s =
  let l = ref [] in
  for i = s.length - 1 downto 0 do
    l := get s i :: !l
  done;
  !l

let equal a b =
  a.length = b.length
  &&
  let rec go i = i >= a.length || (Sphere.equal (get a i) (get b i) && go (i + 1)) in
  go 0

let pp ppf s = iter (fun x -> Format.fprintf ppf "%a\n" Sphere.pp x) s

module Table = Material.Plain

type builder = {
  mutable n : int;
  (* Full blocks, last first; [cur_*] is the block being filled. *)
  mutable full : (float array * float array * float array * float array * int array) list;
  mutable cur_x : float array;
  mutable cur_y : float array;
  mutable cur_z : float array;
  mutable cur_r : float array;
  mutable cur_m : int array;
  known : int Table.t;
  mutable mats : Material.t list;  (** Last first. *)
  mutable n_mats : int;
}

(* The first block grows from 16 spheres by doubling (a scene of four
   spheres allocates 16 of each array, not a block); the next ones are
   made whole. *)
let new_block b size =
  (* Not [Array.init] with a closure: a call per element, measurable on
     loading a big scene (docs/performance.md, "Numbers moved out of the
     library's comments"). *)
  let grow a zero =
    let a' = Array.make size zero in
    Array.blit a 0 a' 0 (min size (Array.length a));
    a'
  in
  b.cur_x <- grow b.cur_x 0.;
  b.cur_y <- grow b.cur_y 0.;
  b.cur_z <- grow b.cur_z 0.;
  b.cur_r <- grow b.cur_r 0.;
  b.cur_m <- grow b.cur_m 0

let builder () =
  {
    n = 0;
    full = [];
    cur_x = [||];
    cur_y = [||];
    cur_z = [||];
    cur_r = [||];
    cur_m = [||];
    known = Table.create 16;
    mats = [];
    n_mats = 0;
  }

let builder_length b = b.n

let material b (m : Material.t) =
  let add () =
    b.mats <- m :: b.mats;
    b.n_mats <- b.n_mats + 1;
    b.n_mats - 1
  in
  if Option.is_some m.pattern then add ()
  else
    match Table.find_opt b.known m with
    | Some i -> i
    | None ->
        let i = add () in
        Table.add b.known m i;
        i

let add_fields b ~x ~y ~z ~radius m =
  if m < 0 || m >= b.n_mats then invalid_arg "Spheres.add_fields: no such material";
  let k = b.n land mask in
  if k = 0 && b.n > 0 then begin
    b.full <- (b.cur_x, b.cur_y, b.cur_z, b.cur_r, b.cur_m) :: b.full;
    b.cur_x <- [||];
    b.cur_y <- [||];
    b.cur_z <- [||];
    b.cur_r <- [||];
    b.cur_m <- [||];
    new_block b block
  end
  else if k >= Array.length b.cur_x then new_block b (max 16 (2 * k));
  b.cur_x.(k) <- x;
  b.cur_y.(k) <- y;
  b.cur_z.(k) <- z;
  b.cur_r.(k) <- radius;
  b.cur_m.(k) <- m;
  b.n <- b.n + 1

let add b s =
  let c = Sphere.center s in
  add_fields b ~x:c.x ~y:c.y ~z:c.z ~radius:(Sphere.radius s) (material b (Sphere.material s))

(* A block at a time where it can: appending the half million spheres of
   a file's second half a sphere at a time was slow (docs/performance.md,
   "Numbers moved out of the library's comments"). The sphere that
   [add_fields] puts in opens a block if need be; as many as fit follow
   it. *)
let append_fields b ~x ~y ~z ~radius ~material n =
  if Array.length x < n || Array.length y < n || Array.length z < n || Array.length radius < n
     || Array.length material < n
  then invalid_arg "Spheres.append_fields: an array is too short";
  for i = 0 to n - 1 do
    if material.(i) < 0 || material.(i) >= b.n_mats then invalid_arg "Spheres.append_fields: no such material"
  done;
  let at = ref 0 in
  while !at < n do
    let j = !at in
    add_fields b ~x:x.(j) ~y:y.(j) ~z:z.(j) ~radius:radius.(j) material.(j);
    let c = b.n land mask in
    let room = if c = 0 || Array.length b.cur_x < block then 0 else min (block - c) (n - j - 1) in
    Array.blit x (j + 1) b.cur_x c room;
    Array.blit y (j + 1) b.cur_y c room;
    Array.blit z (j + 1) b.cur_z c room;
    Array.blit radius (j + 1) b.cur_r c room;
    Array.blit material (j + 1) b.cur_m c room;
    b.n <- b.n + room;
    at := j + 1 + room
  done

let append b s =
  let index = Array.map (material b) s.table in
  Array.iteri
    (fun k xs ->
      let n = Array.length xs in
      append_fields b ~x:xs ~y:s.y.(k) ~z:s.z.(k) ~radius:s.r.(k) ~material:(Array.map (Array.get index) s.m.(k)) n)
    s.x

let build b =
  (* The last block cut to its spheres: a small scene takes no more than
     its own. *)
  let blocks =
    if b.n = 0 then []
    else
      let used = ((b.n - 1) land mask) + 1 in
      let cut a = Array.sub a 0 used in
      List.rev ((cut b.cur_x, cut b.cur_y, cut b.cur_z, cut b.cur_r, cut b.cur_m) :: b.full)
  in
  let blocks = Array.of_list blocks in
  {
    length = b.n;
    x = Array.map (fun (x, _, _, _, _) -> x) blocks;
    y = Array.map (fun (_, y, _, _, _) -> y) blocks;
    z = Array.map (fun (_, _, z, _, _) -> z) blocks;
    r = Array.map (fun (_, _, _, r, _) -> r) blocks;
    m = Array.map (fun (_, _, _, _, m) -> m) blocks;
    table = Array.of_list (List.rev b.mats);
  }

let of_list l =
  let b = builder () in
  List.iter (add b) l;
  build b
