open Raytrace
module Desc = Private.Shape_desc

(* One arm per described kind: each is told by its own fields. *)
let map_primitive ~point ~length ~material (Desc.Primitive (d, x) as prim) =
  let is (type a) (d' : a Desc.t) = Desc.same d.witness d'.witness in
  match (is Private.Cylinder.desc, is Private.Disk.desc, is Private.Cone.desc, is Private.Torus.desc) with
  | Some Desc.Equal, _, _, _ ->
      let c : Private.Cylinder.t = x in
      Desc.Primitive
        ( d,
          Private.Cylinder.v ~capped:c.capped ~base:(point c.base) ~top:(point c.top) ~radius:(length c.radius)
            (material c.material) )
  | _, Some Desc.Equal, _, _ ->
      let k : Private.Disk.t = x in
      Desc.Primitive
        (d, Private.Disk.v ~center:(point k.center) ~normal:k.normal ~radius:(length k.radius) (material k.material))
  | _, _, Some Desc.Equal, _ ->
      let c : Private.Cone.t = x in
      Desc.Primitive
        ( d,
          Private.Cone.v ~capped:c.capped ~base:(point c.base) ~top:(point c.top) ~radius:(length c.radius)
            ~top_radius:(length c.top_radius) (material c.material) )
  | _, _, _, Some Desc.Equal ->
      let t : Private.Torus.t = x in
      Desc.Primitive
        ( d,
          Private.Torus.v ~center:(point t.center) ~axis:t.axis ~major:(length t.major) ~minor:(length t.minor)
            (material t.material) )
  | None, None, None, None -> invalid_arg ("Shape_kinds.map_primitive: a " ^ Desc.name prim)
