open Raytrace
module Desc = Private.Shape_desc

let map_primitive ~point ~length ~material (Desc.Primitive (d, x)) =
  match (Desc.same d.witness Private.Cylinder.desc.witness, Desc.same d.witness Private.Disk.desc.witness) with
  | Some Desc.Equal, _ ->
      let c : Private.Cylinder.t = x in
      Desc.Primitive
        ( d,
          Private.Cylinder.v ~capped:c.capped ~base:(point c.base) ~top:(point c.top) ~radius:(length c.radius)
            (material c.material) )
  | _, Some Desc.Equal ->
      let k : Private.Disk.t = x in
      Desc.Primitive
        (d, Private.Disk.v ~center:(point k.center) ~normal:k.normal ~radius:(length k.radius) (material k.material))
  | None, None -> invalid_arg ("Shape_kinds.map_primitive: a " ^ d.name)
