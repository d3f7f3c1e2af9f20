(* The per-ray state (ray, roots, hit point, colour) is [Scratch.t], at
   the bottom of the kernel, so that the shapes' root routines read the ray
   without depending on the tracer. *)
open Scratch

type counters = {
  mutable primary : int;
  mutable shadow : int;
  mutable reflection : int;
  mutable tests : int;
  mutable box_tests : int;
  mutable early_stops : int;
  mutable decided : int;
  mutable penumbra : int;
  mutable umbra : int;
}


type t = {
  p : Prepared.t;
  s : Scratch.t;
  stack : float array;  (** Per reflection level: local r, g, b and reflectivity. *)
  last_blocker : int array;  (** Per light: the sphere that last shadowed it. *)
  blockers : float array;
      (** The document's kernel: per light [l], from [4 n l] on ([n] =
          [n_objects]), a copy of [sphere4] in the order its shadow rays
          try the spheres: the last blocker found first. One array read per
          sphere, not an index then the sphere. *)
  blockers_first : int array;  (** Per light [l]: [4 n l], read rather than multiplied per shadow ray. *)
  counters : counters;
  nodes : int array;  (** Stack of hierarchy nodes still to visit: their offsets in [Bvh.t]'s [nodes]. *)
  entries : float array;
      (** Beside [nodes], the closest-hit search's: each node's entry
          distance along the ray, found when its parent tested its box. *)
  csg : Csg.work;  (** Room for the intervals of the CSG solids. *)
  mutable hit : int;  (** Index of the sphere found by [closest]. *)
  mutable origin_sphere : int;
      (** The slot of the sphere the current secondary ray leaves, or
          [-1]: in the robust mode that sphere is handled exactly. (An
          identical sphere has no slot of its own: {!Prepared.prepare}.) *)
  mutable first_hit : int;
  triangles : bool;
      (** Every object in the hierarchy is a triangle (a mesh, maybe on
          planes, which are outside it): the traversals then read no
          object's kind, one array (and a cache miss a leaf) less. *)
  mutable kx : int;
      (** The axes of the ray in [s] for the triangle test
          ({!Triangle.shear}), [kz = -1] until a traversal's first triangle
          finds them (a traversal of a hierarchy of triangles alone finds
          them before its first box): once a ray, not once a triangle. *)
  mutable ky : int;
  mutable kz : int;
  mutable order : int;
      (** [kx], [ky], [kz] as one of the six orders of the axes, 0 to 5
          (see [triangle_hit]). *)
  averaging : bool;  (** Samples are averaged: see [settled]. *)
  mutable assumed : int;  (** Sphere the primary ray is assumed to hit, see [primary_hit]. *)
  mutable budget : int;  (** Most tests [check_budget] accepts before it calls [refill]. *)
  mutable refill : int -> int;
      (** Called with the work done once it passes [budget]: the next
          budget, or it raises [Limits.Work_exceeded]. *)
  tracer : int;  (** The loop of [trace]: [spheres_chain], [objects_chain] or [tree]. *)
  tree : Ray_tree.t;  (** The ray tree's levels: transparent scenes only. *)
  cand : int array;
      (** The document's kernel: per tile column, the spheres (slots, in
          scene order) that the camera rays of its current tile may meet,
          [n_objects] places each; then every slot, for rays of no tile. *)
  tile_row : int array;  (** Per tile column: the tile row [cand] holds, or [-1]. *)
  tile_count : int array;  (** Per tile column: how many spheres [cand] holds. *)
  corners : float array;  (** Scratch: the four corner directions of a tile. *)
  mutable cand_first : int;  (** The next camera ray tests [cand] from here on... *)
  mutable cand_count : int;  (** ...this many spheres. *)
  inner : t array;
      (** Per bottom level of the scene's instances ([Prepared.instances]'s
          [bottoms]): a tracer of its own, whose per-ray record holds the
          ray carried into an instance's frame. *)
  mutable inner_material : int;
      (** The material, in the bottom level's numbering, of the surface
          last hit in an instance ({!Surface}). *)
  mutable inner_slot : int;
      (** The slot of the instance whose closest hit the last closest
          search found last ([-1] before any), and that hit's slot in its
          bottom level, [inner_hit]: where the search kept that hit, the
          normal takes it from here rather than from a second walk of the
          bottom level ({!Traversal.instance_hit}). *)
  mutable inner_hit : int;
  mutable key : int;
      (** With [p.sampled]: the {!Sample_key.camera} key of the camera
          sample being traced, from which the integrals over a light or a
          lens draw their numbers. An int of the tracer, not of [Scratch]:
          an int field would unflatten that all-float record. *)
  mutable lens_gx : int;  (** With [p.sampled]: the sample's pixel and place, for a stratified lens. *)
  mutable lens_gy : int;
  mutable lens_n : int;
  mutable lens_k : int;
  mutable lens_px : int;  (** The pixel whose lens numbers are cached: [s.lens_u0], [lens_hc]. *)
  mutable lens_py : int;
  mutable lens_hc : int;
  mutable lens_m : int;  (** The cell permutation's domain whose mask is [lens_w]. *)
  mutable lens_w : int;
  lens_sub : int array;  (** The pixel's sub-cell permutations, for [lens_sub_n]. *)
  mutable lens_sub_n : int;
  light_cells : int array;
  red : float array;
  green : float array;
  blue : float array;
}

(* The tracing loops, chosen once per tracer. *)
let spheres_chain = 0
let objects_chain = 1
let tree = 2

(* [assumed] when the primary ray searches every sphere. *)
let no_assumption = -2

(* [assumed] for good with a lens: its camera rays start off the
   camera's position, where the per-frame constants of the primary
   search do not hold. Tested where an assumption is, so that the
   pinhole's rays take no new instruction. *)
let lens_rays = -3

(* Camera rays are culled by square tiles of this many pixels a side. *)
let tile = 8

(* The pixels of a row traced between two checks of the budget: a multiple
   of [tile], so that blocks start on tiles. *)
let block = 32 * tile

(* The tile columns of the canvas, where culling applies. *)
let tiles_across (p : Prepared.t) = if p.cull && p.textbook_all then (p.width + tile - 1) / tile else 0

(* Whether [p] has a hierarchy and every object in it is a triangle:
   every object is one, or a plane (planes are not in the hierarchy). *)
let hierarchy_of_triangles (p : Prepared.t) =
  p.bvh <> None && Array.for_all (fun k -> Kind.is_triangle k || not (Kind.bounded k)) p.kind

let exhausted w = raise (Limits.Work_exceeded w)

let rec create ?(averaging = false) (p : Prepared.t) =
  {
    p;
    s = Scratch.create ();
    stack = Array.make (4 * (p.depth + 1)) 0.;
    last_blocker = Array.make (max 1 p.n_lights) (-1);
    blockers =
      (let n4 = Array.length p.sphere4 in
       Array.init (p.n_lights * n4) (fun k -> p.sphere4.(k mod n4)));
    blockers_first = Array.init p.n_lights (fun l -> l * Array.length p.sphere4);
    counters = { primary = 0; shadow = 0; reflection = 0; tests = 0; box_tests = 0; early_stops = 0; decided = 0; penumbra = 0; umbra = 0 };
    nodes =
      Array.make (match p.bvh with Some b -> (2 * b.depth) + 2 | None -> 1) 0;
    entries = Array.make (match p.bvh with Some b -> (2 * b.depth) + 2 | None -> 1) 0.;
    csg = Csg.work p.csg;
    hit = -1;
    origin_sphere = -1;
    first_hit = -1;
    triangles = hierarchy_of_triangles p;
    kx = 0;
    ky = 0;
    kz = -1;
    order = 0;
    averaging;
    assumed = (if Camera.has_lens p.camera then lens_rays else no_assumption);
    budget = Limits.work_budget Limits.default;
    refill = exhausted;
    tracer = (if p.transparent then tree else if p.all_spheres then spheres_chain else objects_chain);
    tree = (if p.transparent then Ray_tree.create ~depth:p.depth else Ray_tree.empty);
    (* Read by the document's kernel alone ([textbook_all]): other scenes,
       a million objects in a hierarchy, would make an int per object and
       per tile column, per tracer (per worker), for nothing. *)
    cand = (let n = if p.textbook_all then p.n_objects else 0 and tiles = tiles_across p in
            Array.init ((tiles * n) + n) (fun k -> if k >= tiles * n then k - (tiles * n) else 0));
    tile_row = Array.make (tiles_across p) (-1);
    tile_count = Array.make (tiles_across p) 0;
    corners = Array.make 12 0.;
    cand_first = (if p.cull && p.textbook_all then tiles_across p * p.n_objects else 0);
    cand_count = p.n_objects;
    (* No closure made where there is no instance. *)
    inner = (if Array.length p.instances.bottoms = 0 then [||] else Array.map (fun b -> create ~averaging b) p.instances.bottoms);
    inner_material = 0;
    inner_slot = -1;
    inner_hit = -1;
    key = 0;
    lens_gx = 0;
    lens_gy = 0;
    lens_n = 1;
    lens_k = 0;
    lens_px = min_int;
    lens_py = min_int;
    lens_hc = 0;
    lens_m = 0;
    lens_w = 0;
    lens_sub = Array.make (2 * Limits.max_grid) 0;
    lens_sub_n = 0;
    light_cells =
      Array.make
        (Array.fold_left max 1
           (Array.init p.n_lights (fun l ->
                if p.light_kind.(l) = Prepared.area then p.light_su.(l) + p.light_sv.(l) else 0)))
        0;
    (* A copy only where a texture writes in it: the other scenes read the
       prepared scene's own arrays. *)
    red = (if Array.length p.texture_of = 0 then p.red else Array.copy p.red);
    green = (if Array.length p.texture_of = 0 then p.green else Array.copy p.green);
    blue = (if Array.length p.texture_of = 0 then p.blue else Array.copy p.blue);
  }

let prepared tr = tr.p
let averaging tr = tr.averaging
(* A CSG solid's leaf tests are counted in its work room, and taken into
   the counters whenever they are read: nothing per ray. *)
let rec counters tr =
  let c = tr.counters in
  c.tests <- c.tests + Csg.take_tests tr.csg;
  c.box_tests <- c.box_tests + Csg.take_boxes tr.csg;
  (* The instances' tests, counted by their bottom levels' tracers: a
     loop, not [Array.iter] (its closure would be allocated at each read,
     once a row). *)
  for k = 0 to Array.length tr.inner - 1 do
    let i = counters (Array.unsafe_get tr.inner k) in
    c.tests <- c.tests + i.tests;
    c.box_tests <- c.box_tests + i.box_tests;
    i.tests <- 0;
    i.box_tests <- 0
  done;
  c

let work tr =
  let c = counters tr in
  c.tests + c.box_tests

let set_budget ?(refill = exhausted) tr n =
  tr.budget <- n;
  tr.refill <- refill

(* Out of line: the check itself is a sum and a comparison, made once a
   pixel; the CSG leaves' tests not yet taken into the counters count too. *)
let[@inline never] over_budget tr = tr.budget <- tr.refill (work tr)

let[@inline] check_budget tr =
  if tr.counters.tests + tr.counters.box_tests + Csg.pending tr.csg > tr.budget then over_budget tr

let red tr = tr.s.r
let green tr = tr.s.g
let blue tr = tr.s.b
let hit_object tr = if tr.first_hit < 0 then -1 else Array.unsafe_get tr.p.index tr.first_hit
