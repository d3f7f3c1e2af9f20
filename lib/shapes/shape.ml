type t = Sphere of Sphere.t | Plane of Plane.t | Triangle of Triangle.t | Box of Box.t | Mesh of Mesh.t | Csg of Csg.t
  | Primitive of Shape_desc.primitive
  | Instance of instance

and instance = {
  transform : Transform.t;
  shape : t;
  own_material : Material.t option;
  name : string option;
}
[@@deriving eq]

(* A plane stays a plane when transformed (it is unbounded: no box of the
   hierarchy holds it): its point mapped, its normal by the inverse
   transpose. *)
let rec instance ?material ?name transform shape =
  match shape with
  | Plane p ->
      let m = Option.value material ~default:p.material in
      Plane (Plane.v ~point:(Transform.point transform p.point) ~normal:(Transform.normal_to_world transform p.normal) m)
  | Instance { transform = inner; shape; own_material; name = _ } ->
      (* A transform of a transform: one transform, the inner's first. *)
      let material = match material with Some _ -> material | None -> own_material in
      instance ?material ?name (Transform.compose inner transform) shape
  | _ -> Instance { transform; shape; own_material = material; name }

let rec material = function
  | Instance { own_material = Some m; _ } -> m
  | Instance { shape; _ } -> material shape
  | Sphere s -> s.material
  | Plane p -> p.material
  | Triangle t -> t.material
  | Box b -> b.material
  | Mesh m -> m.material
  | Csg c -> List.hd (Csg.materials c)
  | Primitive p -> Shape_desc.material p

let rec materials = function
  | Csg c -> Csg.materials c
  | Instance { own_material = Some m; _ } -> [ m ]
  | Instance { shape; _ } -> materials shape
  | s -> [ material s ]

let name = function Instance _ -> "transform" | Sphere _ -> "sphere" | Plane _ -> "plane" | Triangle _ -> "triangle" | Box _ -> "box" | Mesh _ -> "mesh" | Csg _ -> "csg" | Primitive p -> Shape_desc.name p

(* Whether an object of kind [name] takes texture [t]: its kind has the
   mapping [t] has ({!Texture_map.mapping_for}). *)
let fits name (t : Texture_map.t) =
  match Texture_map.mapping_for name with
  | None -> Error (`Msg (Printf.sprintf "a %s takes no texture; textures map onto spheres, planes, boxes and meshes" name))
  | Some m when m <> t.mapping ->
      Error
        (`Msg
          (Printf.sprintf "%s texture mapping must be %s, got %s" name (Texture_map.mapping_name m)
             (Texture_map.mapping_name t.mapping)))
  | Some _ -> Ok ()

(* A transform's or use's own texture [t] lies on every surface of its
   object, in the object's frame: each must take [t]'s mapping (a mesh's
   uv needs its [vt], which a bottom level keeps for every mesh that has
   them). *)
let rec own_texture t = function
  | Instance { shape; _ } -> own_texture t shape
  | Csg c -> Csg.check_textures ~texture:t c
  | Mesh m when t.mapping = Texture_map.Uv && not (Mesh.has_texcoords m) ->
      Error (`Msg "mesh texture mapping uv needs the mesh's texture coordinates (vt), which it has none of")
  | s -> fits (name s) t

(* The kernel draws a texture on an object of a kind that has a mapping
   ({!Texture_map.mapping_for}), placed as written or through a transform
   or an instance (the object's own texture, in its frame), on an
   instance's own material (on every surface of the object, in its
   frame), and on a CSG solid's sphere, box and mesh operands ({!Csg.check_textures}). *)
let check_texture s =
  let name = name s in
  match s with
  | Instance { own_material = Some { texture = Some t; _ }; shape; _ } ->
      Result.map_error (fun (`Msg m) -> `Msg ("its texture lies on its object's surfaces: " ^ m)) (own_texture t shape)
  | Csg c -> Csg.check_textures c
  | Instance _ -> Ok ()
  | s -> (
      match (material s).texture with
      | None -> Ok ()
      | Some t -> (
          match (fits name t, s) with
          | (Error _ as e), _ -> e
          | Ok (), Mesh m when not (Mesh.has_texcoords m) ->
              Error (`Msg "mesh texture mapping uv needs the mesh's texture coordinates (vt), which it has none of")
          | Ok (), _ -> Ok ()))

let rec validate s =
  let ( let* ) = Result.bind in
  let* () = check_texture s in
  match s with
  | Instance i ->
      let* () = match i.shape with Plane _ -> Error (`Msg "a plane is transformed as a plane (Shape.instance), not an instance") | _ -> Ok () in
      let* () = match i.own_material with Some m -> Result.map ignore (Material.validate ~form:"transform" m) | None -> Ok () in
      (* Checked, not rebuilt: the object stays the value its instances
         share (one bottom level). *)
      let* _ = validate i.shape in
      Ok s
  | Sphere sp ->
      let* sp = Sphere.validate sp in
      Ok (Sphere sp)
  | Plane p ->
      let* p = Plane.validate p in
      Ok (Plane p)
  | Triangle t ->
      let* t = Triangle.validate t in
      Ok (Triangle t)
  | Box b ->
      let* b = Box.validate b in
      Ok (Box b)
  | Mesh m ->
      (* Its arrays and placement were checked by [Mesh.v]. *)
      let* _ = Material.validate ~form:"mesh" m.material in
      Ok (Mesh m)
  | Csg c ->
      let* c = Csg.validate c in
      Ok (Csg c)
  | Primitive p ->
      let* p = Shape_desc.validate p in
      Ok (Primitive p)

let one fn = invalid_arg (Printf.sprintf "Shape.%s: a mesh is many objects" fn)
let own fn = invalid_arg (Printf.sprintf "Shape.%s: a CSG solid is in the kernel's CSG table" fn)
let kind = function Instance _ -> Kind.Instance | Sphere _ -> Kind.Sphere | Plane _ -> Kind.Plane | Triangle _ -> Kind.Triangle | Box _ -> Kind.Box | Mesh _ -> one "kind" | Csg _ -> Kind.Csg | Primitive p -> Shape_desc.kind p

let store s g o =
  match s with
  | Sphere sp ->
      g.(o) <- sp.center.x;
      g.(o + 1) <- sp.center.y;
      g.(o + 2) <- sp.center.z;
      g.(o + 3) <- sp.radius
  | Plane p -> Plane.store p g o
  | Triangle t -> Triangle.store t g o
  | Box b -> Box.store b g o
  | Primitive p -> Shape_desc.store p g o
  | Mesh _ -> one "store"
  | Csg _ -> own "store"
  | Instance _ -> invalid_arg "Shape.store: an instance is in the kernel's table of instances"

let bounded = function
  | Plane _ -> false
  | Sphere _ | Triangle _ | Box _ | Mesh _ | Csg _ | Instance _ -> true
  | Primitive p -> Kind.bounded (Shape_desc.kind p)

(* [sub_le a b x] is [true] iff the exact [a - b <= x]: the rounded
   difference and its rounding error, recovered exactly by Knuth's
   two-sum, decide. *)
let sub_le a b x =
  let s = a -. b in
  let bb = s -. a in
  let e = (a -. (s -. bb)) +. (-.b -. bb) in
  s < x || (s = x && e <= 0.)

let cube (lo : Vec3.t) (hi : Vec3.t) =
  let c = Vec3.smul 0.5 (Vec3.add lo hi) in
  let h = Float.max (hi.x -. lo.x) (Float.max (hi.y -. lo.y) (hi.z -. lo.z)) *. 0.5 in
  (* Rounded, [c] and [h] may leave a corner outside the cube by an ulp of
     [c], which may be many of [h] (a small shape far from the origin):
     [h] is first the largest distance from [c] to a corner, rounded, then
     grows an ulp at a time (a step or two) until the exact cube holds
     [lo] and [hi]. *)
  let far (c : float) lo hi = Float.max (c -. lo) (hi -. c) in
  let h = Float.max h (Float.max (far c.x lo.x hi.x) (Float.max (far c.y lo.y hi.y) (far c.z lo.z hi.z))) in
  let holds h (c : float) lo hi = sub_le c h lo && sub_le hi c h in
  let rec grow h = if holds h c.x lo.x hi.x && holds h c.y lo.y hi.y && holds h c.z lo.z hi.z then h else grow (Float.succ h) in
  (c, grow h)

(* The last mesh's box: the instances of one mesh, a thousand of a
   million triangles, ask for it once each (a mesh's positions are not
   changed once it is made). *)
let last_mesh_box = ref None

let rec box_bounds = function
  | Mesh m -> (
      match !last_mesh_box with
      | Some (m', box) when m' == m -> box
      | _ ->
          let box = mesh_box m in
          last_mesh_box := Some (m, box);
          box)
  | Instance i -> Transform.bounds i.transform (box_bounds i.shape)
  | s ->
      let (c : Vec3.t), h = bounds s in
      (Vec3.v (c.x -. h) (c.y -. h) (c.z -. h), Vec3.v (c.x +. h) (c.y +. h) (c.z +. h))

and mesh_box (m : Mesh.t) =
      let p = m.positions in
      let lo = Array.make 3 infinity and hi = Array.make 3 neg_infinity in
      for k = 0 to (Array.length p / 3) - 1 do
        for a = 0 to 2 do
          (* The positions are placed already ([Mesh.t]): their own scale
             and translation are not applied twice. *)
          let x = p.((3 * k) + a) in
          lo.(a) <- Float.min lo.(a) x;
          hi.(a) <- Float.max hi.(a) x
        done
      done;
      (Vec3.v (Float.pred lo.(0)) (Float.pred lo.(1)) (Float.pred lo.(2)), Vec3.v (Float.succ hi.(0)) (Float.succ hi.(1)) (Float.succ hi.(2)))

and bounds = function
  | Plane _ -> invalid_arg "Shape.bounds: a plane is unbounded"
  | Mesh _ -> one "bounds"
  | Instance _ as s ->
      let lo, hi = box_bounds s in
      cube lo hi
  | Box b -> cube b.min b.max
  | Primitive p ->
      if not (Kind.bounded (Shape_desc.kind p)) then invalid_arg ("Shape.bounds: a " ^ Shape_desc.name p ^ " is unbounded");
      let lo, hi = Shape_desc.bounds p in
      cube lo hi
  | Sphere sp ->
      (* An ulp outward: the rounded [c - r] may lie inside the sphere. *)
      let c = sp.center and r = sp.radius in
      cube
        (Vec3.v (Float.pred (c.x -. r)) (Float.pred (c.y -. r)) (Float.pred (c.z -. r)))
        (Vec3.v (Float.succ (c.x +. r)) (Float.succ (c.y +. r)) (Float.succ (c.z +. r)))
  | Csg c ->
      let lo, hi = Csg.bounds c in
      cube lo hi
  | Triangle t ->
      let lo = Vec3.v (Float.min t.v0.x (Float.min t.v1.x t.v2.x)) (Float.min t.v0.y (Float.min t.v1.y t.v2.y))
          (Float.min t.v0.z (Float.min t.v1.z t.v2.z)) in
      let hi = Vec3.v (Float.max t.v0.x (Float.max t.v1.x t.v2.x)) (Float.max t.v0.y (Float.max t.v1.y t.v2.y))
          (Float.max t.v0.z (Float.max t.v1.z t.v2.z)) in
      cube lo hi

let with_table s f =
  let g = Array.make Kind.stride 0. and sc = Scratch.create () in
  store s g 0;
  f sc g

let roots s ~origin ~direction =
  match s with
  | Sphere sp -> Sphere.roots sp ~origin ~direction
  | _ ->
  with_table s (fun sc g ->
      Scratch.set_ray sc origin direction;
      let hit =
        match s with
        | Sphere _ -> assert false
        | Triangle _ -> Triangle.roots sc g 0
        | Plane _ | Box _ | Primitive _ -> Kind_dispatch.roots (kind s) sc g 0
        | Mesh _ -> one "roots"
        | Csg _ | Instance _ -> own "roots"
      in
      if hit then (sc.near, sc.far) else (infinity, infinity))

let normal s (p : Vec3.t) =
  match s with
  | Sphere sp -> Sphere.normal sp p
  | _ ->
  with_table s (fun sc g ->
      sc.px <- p.x;
      sc.py <- p.y;
      sc.pz <- p.z;
      (match s with
      | Sphere _ -> assert false
      | Plane _ -> Plane.normal sc g 0
      | Triangle _ -> Triangle.normal sc g 0
      | Box _ -> Box.normal sc g 0
      | Primitive p -> Kind_dispatch.normal (Shape_desc.kind p) sc g 0
      | Mesh _ -> one "normal"
      | Csg _ | Instance _ -> own "normal");
      Vec3.v sc.nx sc.ny sc.nz)

let rec pp ppf = function
  | Instance { transform; shape; own_material; name } ->
      (* A named instance prints as the [use] of its definition, which
         {!Scene.pp} prints before the first; an anonymous one as its
         [transform] form. A material given to the instance follows. *)
      let pp_material ppf = function Some m -> Format.fprintf ppf " %a" Material.pp m | None -> () in
      (match name with
      | Some n -> Format.fprintf ppf "(use %s (transform %a)%a)" n Transform.pp transform pp_material own_material
      | None -> Format.fprintf ppf "(transform %a %a%a)" Transform.pp transform pp shape pp_material own_material)
  | Sphere s -> Sphere.pp ppf s
  | Plane p -> Plane.pp ppf p
  | Triangle t -> Triangle.pp ppf t
  | Box b -> Box.pp ppf b
  | Mesh m -> Mesh.pp_form ppf m
  | Csg c -> Csg.pp ppf c
  | Primitive p -> Shape_desc.pp_primitive ppf p

let show s = Format.asprintf "%a" pp s

(* The largest coordinate of the stored geometry, as {!Prepared} bounds a
   shape's hit point's rounding. *)
let stored_extent sh =
  let g = Array.make Kind.stride 0. in
  store sh g 0;
  Array.fold_left (fun e x -> Float.max e (Float.abs x)) 0. g

let pattern_frame = function
  | Sphere s -> (Vec3.zero, 1., Sphere.extent s)
  | (Plane _ | Triangle _ | Primitive _) as sh -> (Vec3.zero, 1., stored_extent sh)
  | Box b as sh -> (b.min, 1., stored_extent sh)
  | Mesh m -> (m.translate, m.scale, Array.fold_left (fun e x -> Float.max e (Float.abs x)) 0. m.positions)
  | Csg _ -> invalid_arg "Shape.pattern_frame: a CSG solid's patterns are its leaves' (Shape.leaf_pattern_frame)"
  | Instance _ -> invalid_arg "Shape.pattern_frame: a transformed object's pattern lies in its object's frame (Prepared)"

let leaf_pattern_frame = function
  | Csg.Sphere s -> (Vec3.zero, 1., Sphere.extent s)
  | Csg.Box b -> pattern_frame (Box b)
  | Csg.Mesh m -> pattern_frame (Mesh m)
  | Csg.Primitive p -> pattern_frame (Primitive p)
  | Csg.Csg _ | Csg.Transformed _ -> invalid_arg "Shape.leaf_pattern_frame: a CSG node is not a leaf"
