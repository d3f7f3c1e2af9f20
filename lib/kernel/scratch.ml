type t = {
  mutable ox : float;
  mutable oy : float;
  mutable oz : float;
  mutable dx : float;
  mutable dy : float;
  mutable dz : float;
  mutable t_min : float;
  mutable t_max : float;
  mutable t : float;
  mutable near : float;
  mutable far : float;
  mutable gx : float;
  mutable gy : float;
  mutable px : float;
  mutable py : float;
  mutable pz : float;
  mutable nx : float;
  mutable ny : float;
  mutable nz : float;
  mutable vx : float;
  mutable vy : float;
  mutable vz : float;
  mutable intensity : float;
  mutable r : float;
  mutable g : float;
  mutable b : float;
  mutable acc_r : float;
  mutable acc_g : float;
  mutable acc_b : float;
  mutable offset : float;
  mutable sx : float;
  mutable sy : float;
  mutable sz : float;
  mutable okx : float;
  mutable oky : float;
  mutable okz : float;
  mutable tu : float;
  mutable tv : float;
  mutable first_t : float;
  mutable lens_u0 : float;
  mutable lens_v0 : float;
}

let create () =
  {
    ox = 0.; oy = 0.; oz = 0.; dx = 0.; dy = 0.; dz = 0.; t_min = 0.; t_max = 0.; t = 0.;
    near = 0.; far = 0.; gx = 0.; gy = 0.; px = 0.; py = 0.; pz = 0.; nx = 0.; ny = 0.;
    nz = 0.; vx = 0.; vy = 0.; vz = 0.; intensity = 0.; r = 0.; g = 0.; b = 0.; acc_r = 0.;
    acc_g = 0.; acc_b = 0.; offset = 0.; sx = 0.; sy = 0.; sz = 0.;
    okx = 0.; oky = 0.; okz = 0.; tu = 0.; tv = 0.; first_t = 0.; lens_u0 = 0.; lens_v0 = 0.;
  }

let set_ray s (o : Vec3.t) (d : Vec3.t) =
  s.ox <- o.x;
  s.oy <- o.y;
  s.oz <- o.z;
  s.dx <- d.x;
  s.dy <- d.y;
  s.dz <- d.z

let normal_to_world s (m : float array) o =
  let nx = s.nx and ny = s.ny and nz = s.nz in
  let wx = (Array.unsafe_get m o *. nx) +. (Array.unsafe_get m (o + 4) *. ny) +. (Array.unsafe_get m (o + 8) *. nz) in
  let wy = (Array.unsafe_get m (o + 1) *. nx) +. (Array.unsafe_get m (o + 5) *. ny) +. (Array.unsafe_get m (o + 9) *. nz) in
  let wz = (Array.unsafe_get m (o + 2) *. nx) +. (Array.unsafe_get m (o + 6) *. ny) +. (Array.unsafe_get m (o + 10) *. nz) in
  let inv = 1. /. sqrt ((wx *. wx) +. (wy *. wy) +. (wz *. wz)) in
  s.nx <- wx *. inv;
  s.ny <- wy *. inv;
  s.nz <- wz *. inv
