let media_cap = 16
let pending_stride = 6
let node_stride = 9
let optics_size = 12

type t = {
  levels : int;
  pending : float array;
  pending_leaving : int array;
  media : int array;
  n_media : int array;
  pending_media : int array;
  pending_n_media : int array;
  node : float array;
  weight : float array;
  tracing : int array;
  attenuation : float array;
  optics : float array;
}

let create ~depth =
  let levels = depth + 2 in
  {
    levels;
    pending = Array.make (pending_stride * levels) 0.;
    pending_leaving = Array.make levels (-1);
    media = Array.make (media_cap * levels) 0;
    n_media = Array.make levels 0;
    pending_media = Array.make (media_cap * levels) 0;
    pending_n_media = Array.make levels 0;
    node = Array.make (node_stride * levels) 0.;
    weight = Array.make levels 0.;
    tracing = Array.make levels 0;
    attenuation = Array.make 1 1.;
    optics = Array.make optics_size 0.;
  }

let empty = create ~depth:(-2)

(* The medium stack: ids (material numbers), the innermost last. *)

let find media base n id =
  let k = ref (n - 1) in
  while !k >= 0 && Array.unsafe_get media (base + !k) <> id do
    decr k
  done;
  !k

let top_index (index : float array) media base n =
  if n = 0 then 1. else Array.unsafe_get index (Array.unsafe_get media (base + n - 1))
let copy_media src sbase n dst dbase =
  for k = 0 to n - 1 do
    Array.unsafe_set dst (dbase + k) (Array.unsafe_get src (sbase + k))
  done

(* Crossing the surface of [id]: entering it pushes it (when there is
   room), leaving it removes it wherever it is; the new count. *)
let cross media base n id =
  let k = find media base n id in
  if k < 0 then
    if n < media_cap then begin
      Array.unsafe_set media (base + n) id;
      n + 1
    end
    else n
  else begin
    for j = k to n - 2 do
      Array.unsafe_set media (base + j) (Array.unsafe_get media (base + j + 1))
    done;
    n - 1
  end

(* The index on each side; the far side's: the object's own when the ray
   enters it, when it leaves it the one under it, if it was innermost,
   else the innermost's (overlapping objects). *)
let indices (index : float array) media base n id (io : float array) =
  let k = find media base n id in
  let near = top_index index media base n in
  io.(0) <- near;
  io.(1) <- (if k < 0 then index.(id) else if k = n - 1 then top_index index media base (n - 1) else near)

(* Snell's law and Schlick's approximation. With [c = cos i] (the unit
   direction against the unit normal) and [eta = n1 / n2],
   [sin^2 t = eta^2 (1 - c^2)]; total internal reflection when it exceeds
   1. The transmitted direction is [eta d + (eta c - cos t) n] (unit
   length for a unit [d]). Schlick: [R0 + (1 - R0) (1 - c)^5] with
   [R0 = ((n1 - n2) / (n1 + n2))^2], and [c] the cosine on the side of the
   lower index (the transmitted one when leaving a denser medium), so
   that the reflectance reaches 1 at the critical angle. *)
let split (io : float array) ~fresnel =
  let n1 = io.(0) and n2 = io.(1) in
  let dx = io.(2) and dy = io.(3) and dz = io.(4) and nx = io.(5) and ny = io.(6) and nz = io.(7) in
  if n1 = n2 then begin
    io.(8) <- dx;
    io.(9) <- dy;
    io.(10) <- dz;
    io.(11) <- 0.
  end
  else begin
    (* Scaled by its largest coordinate first, so that no square
       underflows or overflows, whatever the scene's scale. *)
    let big = Float.max (Float.abs dx) (Float.max (Float.abs dy) (Float.abs dz)) in
    let dx = dx /. big and dy = dy /. big and dz = dz /. big in
    let len = sqrt ((dx *. dx) +. (dy *. dy) +. (dz *. dz)) in
    let inv = 1. /. len in
    let c = -.((dx *. nx) +. (dy *. ny) +. (dz *. nz)) *. inv in
    (* Rounding may take the cosine a hair above 1, or below 0 at grazing
       incidence: clamped, so that no square root sees a negative. *)
    let c = if c > 1. then 1. else if c > 0. then c else 0. in
    let eta = n1 /. n2 in
    let sin2_t = eta *. eta *. ((1. -. c) *. (1. +. c)) in
    if sin2_t >= 1. then io.(11) <- 1.
    else begin
      let cos_t = sqrt (1. -. sin2_t) in
      let e = eta *. inv and k = (eta *. c) -. cos_t in
      io.(8) <- (e *. dx) +. (k *. nx);
      io.(9) <- (e *. dy) +. (k *. ny);
      io.(10) <- (e *. dz) +. (k *. nz);
      io.(11) <-
        (if not fresnel then 0.
         else
           let r0 = (n1 -. n2) /. (n1 +. n2) in
           let r0 = r0 *. r0 in
           let x = 1. -. if n1 > n2 then cos_t else c in
           let x2 = x *. x in
           r0 +. ((1. -. r0) *. (x2 *. x2 *. x)))
    end
  end
