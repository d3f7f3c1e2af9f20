let diffuse ~intensity ~l ~n =
  let n_dot_l = Vec3.dot n l in
  if n_dot_l > 0. then intensity *. n_dot_l /. (Vec3.norm n *. Vec3.norm l) else 0.

let reflect l n = Vec3.sub (Vec3.smul (2. *. Vec3.dot l n) n) l

let specular ~intensity ~s ~r ~v =
  let r_dot_v = Vec3.dot r v in
  if r_dot_v > 0. then intensity *. ((r_dot_v /. (Vec3.norm r *. Vec3.norm v)) ** s) else 0.
