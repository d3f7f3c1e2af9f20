open Raytrace.Private

let write_rays (p : Prepared.t) path =
  let w = p.width and h = p.height in
  let b = Buffer.create (w * h * 48) in
  let o = p.camera.position and m = p.camera.rotation and d = p.viewport.distance in
  let add f = Buffer.add_int64_le b (Int64.bits_of_float f) in
  for r = 0 to h - 1 do
    (* Row [r] from the top is the kernel's row [h - 1 - r] (Trace.pixel:
       gy + h / 2 with gy = h - 1 - r - h / 2). *)
    let vy = p.row_vy.(h - 1 - r) in
    for c = 0 to w - 1 do
      let vx = p.column_vx.(c) in
      add o.x;
      add o.y;
      add o.z;
      (* Camera_ray.set_direction's operations, in its order. *)
      if p.identity_rotation then begin
        add vx;
        add vy;
        add d
      end
      else begin
        add ((vx *. m.row0.x) +. (vy *. m.row0.y) +. (d *. m.row0.z));
        add ((vx *. m.row1.x) +. (vy *. m.row1.y) +. (d *. m.row1.z));
        add ((vx *. m.row2.x) +. (vy *. m.row2.y) +. (d *. m.row2.z))
      end
    done
  done;
  let oc = open_out_bin path in
  Buffer.output_buffer oc b;
  close_out oc

type result = { cpu_s : float; rays : int; hits : int }

let cast (p : Prepared.t) mask =
  let w = p.width and h = p.height in
  if Bytes.length mask <> w * h then invalid_arg "Mesh_rays.cast: mask size";
  let tr = Trace.create p in
  let hits = ref 0 in
  let t0 = Sys.time () in
  for r = 0 to h - 1 do
    let gy = h - 1 - r - (h / 2) in
    for c = 0 to w - 1 do
      Trace.pixel tr (c - (w / 2)) gy;
      let hit = Trace.hit_object tr >= 0 in
      if hit then incr hits;
      Bytes.unsafe_set mask ((r * w) + c) (if hit then '\001' else '\000')
    done
  done;
  { cpu_s = Sys.time () -. t0; rays = w * h; hits = !hits }
