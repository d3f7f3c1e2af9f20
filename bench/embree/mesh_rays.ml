open Raytrace.Private

let write_floats (a : float array) path =
  let b = Buffer.create (8 * Array.length a) in
  Array.iter (fun f -> Buffer.add_int64_le b (Int64.bits_of_float f)) a;
  let oc = open_out_bin path in
  Buffer.output_buffer oc b;
  close_out oc

let camera_rays (p : Prepared.t) =
  let w = p.width and h = p.height in
  let a = Array.create_float (w * h * 6) in
  let o = p.camera.position and m = p.camera.rotation and d = p.viewport.distance in
  for r = 0 to h - 1 do
    (* Row [r] from the top is the kernel's row [h - 1 - r] (Trace.pixel:
       gy + h / 2 with gy = h - 1 - r - h / 2). *)
    let vy = p.row_vy.(h - 1 - r) in
    for c = 0 to w - 1 do
      let vx = p.column_vx.(c) and k = 6 * ((r * w) + c) in
      a.(k) <- o.x;
      a.(k + 1) <- o.y;
      a.(k + 2) <- o.z;
      (* Camera_ray.set_direction's operations, in its order. *)
      if p.identity_rotation then begin
        a.(k + 3) <- vx;
        a.(k + 4) <- vy;
        a.(k + 5) <- d
      end
      else begin
        a.(k + 3) <- (vx *. m.row0.x) +. (vy *. m.row0.y) +. (d *. m.row0.z);
        a.(k + 4) <- (vx *. m.row1.x) +. (vy *. m.row1.y) +. (d *. m.row1.z);
        a.(k + 5) <- (vx *. m.row2.x) +. (vy *. m.row2.y) +. (d *. m.row2.z)
      end
    done
  done;
  a

let write_rays p path = write_floats (camera_rays p) path

type result = { cpu_s : float; rays : int; hits : int }

let check_mask (p : Prepared.t) mask fn = if Bytes.length mask <> p.width * p.height then invalid_arg (fn ^ ": mask size")

(* The pixels, rows from the top, each row left to right, [f] at each. *)
let over_pixels (p : Prepared.t) mask f =
  let w = p.width and h = p.height in
  let hits = ref 0 in
  let t0 = Sys.time () in
  for r = 0 to h - 1 do
    let gy = h - 1 - r - (h / 2) in
    for c = 0 to w - 1 do
      let hit = f (c - (w / 2)) gy in
      if hit then incr hits;
      Bytes.unsafe_set mask ((r * w) + c) (if hit then '\001' else '\000')
    done
  done;
  { cpu_s = Sys.time () -. t0; rays = w * h; hits = !hits }

let cast (p : Prepared.t) mask =
  check_mask p mask "Mesh_rays.cast";
  let tr = Trace.create p in
  over_pixels p mask (fun gx gy ->
      Trace.pixel tr gx gy;
      Trace.hit_object tr >= 0)

let cast_camera (p : Prepared.t) mask =
  check_mask p mask "Mesh_rays.cast_camera";
  let tr = Trace.create p in
  over_pixels p mask (fun gx gy -> Trace.camera_hit tr gx gy >= 0)

(* The hit's [t] scaled by this: a point in front of the surface by about
   a thousandth of its distance from the camera. *)
let short = 1. -. 0x1p-10

let shadow_rays (p : Prepared.t) ~(light : Raytrace.Vec3.t) =
  let tr = Trace.create p in
  let cam = camera_rays p in
  let out = ref [] and n = ref 0 in
  for k = (p.width * p.height) - 1 downto 0 do
    let r = k / p.width and c = k mod p.width in
    let hit = Trace.camera_hit tr (c - (p.width / 2)) (p.height - 1 - r - (p.height / 2)) in
    if hit >= 0 then begin
      let o = Raytrace.Vec3.v cam.(6 * k) cam.((6 * k) + 1) cam.((6 * k) + 2)
      and d = Raytrace.Vec3.v cam.((6 * k) + 3) cam.((6 * k) + 4) cam.((6 * k) + 5) in
      let near, _ = Trace.roots tr hit o d in
      let t = near *. short in
      let x = o.x +. (t *. d.x) and y = o.y +. (t *. d.y) and z = o.z +. (t *. d.z) in
      out := [| x; y; z; light.x -. x; light.y -. y; light.z -. z |] :: !out;
      incr n
    end
  done;
  Array.concat !out

let rounds ~camera ~shadow = if shadow <= 0 then 1 else max 1 (camera / shadow)

let cast_shadows (p : Prepared.t) rays ~rounds mask =
  let n = Array.length rays / 6 in
  if Array.length rays <> 6 * n then invalid_arg "Mesh_rays.cast_shadows: not six floats a ray";
  if Bytes.length mask <> n then invalid_arg "Mesh_rays.cast_shadows: mask size";
  let tr = Trace.create p in
  let blocked = ref 0 in
  let t0 = Sys.time () in
  for round = 1 to rounds do
    for k = 0 to n - 1 do
      let b = Trace.shadow_blocked tr rays k in
      if round = 1 then begin
        if b then incr blocked;
        Bytes.unsafe_set mask k (if b then '\001' else '\000')
      end
    done
  done;
  { cpu_s = Sys.time () -. t0; rays = n * rounds; hits = !blocked }

let build_alone (p : Prepared.t) =
  let n = p.n_scene_objects in
  let f () = Array.create_float n in
  let x0 = f () and y0 = f () and z0 = f () and x1 = f () and y1 = f () and z1 = f () in
  let v = p.vertex in
  for k = 0 to n - 1 do
    let i = p.slot.(k) in
    let a = p.at0.(i) and b = p.at1.(i) and c = p.at2.(i) in
    let lo j = Float.min v.(a + j) (Float.min v.(b + j) v.(c + j)) and hi j = Float.max v.(a + j) (Float.max v.(b + j) v.(c + j)) in
    x0.(k) <- lo 0;
    y0.(k) <- lo 1;
    z0.(k) <- lo 2;
    x1.(k) <- hi 0;
    y1.(k) <- hi 1;
    z1.(k) <- hi 2
  done;
  let t0 = Sys.time () in
  let b = Bvh.build_boxes ~leaf_size:16 ~x0 ~y0 ~z0 ~x1 ~y1 ~z1 () in
  let s = Sys.time () -. t0 in
  ignore (Sys.opaque_identity b);
  s
