(** A scene prepared for fast tracing.

    {!prepare} turns a {!Scene.t} into flat float arrays (structure of
    arrays), drops what cannot change a pixel (lights of zero intensity),
    and precomputes the constants that the tracer would otherwise
    recompute for every ray. The fields are read by {!Raytrace.Private.Trace}; they are
    exposed for it and for tests, not for building by hand.

    @canonical Raytrace.Private.Prepared *)

type t = private {
  n_spheres : int;  (** The number of spheres. *)
  n_objects : int;  (** The number of slots: spheres and other shapes. *)
  all_spheres : bool;
      (** Every object is a sphere ([n_spheres = n_objects]) and none has a
          pattern: the tracer's loops for spheres alone, which ask no
          object its kind nor its pattern. *)
  patterned : bool;
      (** Some material has a {!Pattern} or a texture ({!Texture_map}):
          the tracer looks it up at each hit (the loop for spheres alone
          never asks; the other asks this field once per hit). *)
  alternate : int array;
      (** Per material (second colours included): the material (an index
          into [red] to [reflective]) of its pattern's second colour, or
          [-1] if it has no pattern in the world's frame, or
          {!textured_material} if it has a texture; empty when no
          material has a pattern or a texture. The second colours' materials
          follow the scene's, each a copy of its own with the pattern's
          colour. *)
  pattern : float array;
      (** Per material [m], at [Pattern.stride * m], its pattern as
          [Pattern.store] writes it, on its object's {!Shape.pattern_frame}
          (zeros where [alternate] is [-1]; empty when no material has a
          pattern). A bottom level of instances keeps every material's
          frame there (its size [0] where it has no pattern of its own):
          its instances' patterns lie on it. *)
  textbook_all : bool;
      (** Spheres only, of plain materials (no pattern, no texture, no
          transparency), no hierarchy, the document's mode, a pinhole
          camera, the document's lights: the
          tracer's fastest loop (the reference scene). *)
  index : int array;
      (** The index of the object in each slot, objects counted in the
          order of the scene's list ({!Scene.objects}, a mesh one object per
          triangle): the per-object arrays below are in slot order (the
          hierarchy's leaf order, then the planes). *)
  slot : int array;
      (** The slot of each object: the inverse of [index], but for the
          identical spheres of [n_scene_objects], which share a slot. *)
  bvh : Bvh.t option;
      (** The hierarchy over the bounded objects (all but planes), when the
          skips are enabled and there are more than {!bvh_threshold} of them;
          its leaves hold slots [0 .. n - 1], the planes follow. *)
  unbounded : int array;  (** The slots of the planes, in scene order. *)
  kind : Kind.t array;  (** The slot's kind, by which the kernel dispatches ({!Kind}). *)
  geom : float array;
      (** The geometry of the shapes other than spheres and triangles:
          shape [g]'s at [Kind.stride * g], as the shape module's [store]
          writes it; a slot's [g] is in [at0]. *)
  vertex : float array;
      (** The triangles' vertices, 3 floats each, a vertex stored once
          however many triangles share it. Without a hierarchy, in the
          scene's order: each mesh's placed positions (a scene's one
          mesh's own array, not a copy), then the lone triangles' corners.
          With one, those copied in the order in which the slots first
          name them ([Vertex_order]), so that a leaf's triangles read
          their corners close together. *)
  at0 : int array;
      (** Per slot of a shape (empty when the scene has spheres alone): a
          triangle's first corner, as its offset in [vertex]; another
          shape's number [g] in [geom] and [extent]. With [at1] and
          [at2], 24 bytes a triangle where its 9 floats were 72. *)
  at1 : int array;  (** Per slot: a triangle's second corner in [vertex]. *)
  at2 : int array;  (** Per slot: a triangle's third corner in [vertex]. *)
  vnormal : float array;
      (** The normals of the smooth meshes, 3 floats each, each divided by
          its length ({!Mesh.unit_normal}; [nan] for one that cannot be,
          which no smooth triangle uses): a corner's normal once, however
          many triangles share it (empty if the scene has no smooth
          triangle). When every smooth mesh names its corners' normals by
          their vertices' numbers ([vcorner] empty), parallel to the
          vertices in the scene's order: the normal of the corner at
          offset [o] in [vertex] is at [o], or at [vsource.(o / 3)] if
          [vsource] is not empty. *)
  vsource : int array;
      (** Where [vertex] is a copy in the slots' order: per vertex of
          [vertex] (the one at offset [o] at [o / 3]), its offset in the
          scene's order; empty where [vertex] is in the scene's order,
          and where the scene has no smooth triangle (no normal is
          read). *)
  vcorner : int array;
      (** Smooth triangles whose corners' normals are not their vertices'
          numbers: the offsets in [vnormal] of the normals of the three
          corners of the object in slot [k], at [3 k] to [3 k + 2] (empty
          if the scene has no smooth triangle, or none of those). *)
  extent : float array;
      (** Per shape [g] of [geom], the largest magnitude of a coordinate of
          its geometry (a triangle's is found from its corners when a hit
          needs it). *)
  csg : Csg.table;
      (** The CSG solids: the [geom] of a slot of kind {!Kind.Csg} holds
          the number of its root node in this table. *)
  n_scene_objects : int;
      (** The objects of the scene, [>= n_objects]: a sphere identical (same
          center and radius) to an earlier one has no slot of its own, its
          [slot] is the earlier one's. It would never be seen first, nor
          block a ray the earlier one does not block, and identical spheres
          are one surface, which a ray leaves at once. *)
  material : int array;
      (** The material of the object in each slot: an index into the
          material arrays [red] to [reflective]. *)
  cx : float array;
      (** Sphere centers, x coordinates, by slot ([0] for other shapes;
          empty when the scene has no sphere). *)
  cy : float array;
  cz : float array;
  radius : float array;
  r2 : float array;  (** [radius *. radius]. *)
  red : float array;  (** Colour channels of each material, 0-255. *)
  green : float array;
  blue : float array;
  specular : float array;  (** Exponent, or {!Sphere.matte}. *)
  specular_zero : float array;
      (** Below this cosine, [cosine ** specular] is exactly [0.] (it lies
          under the smallest subnormal float), so the specular term adds
          nothing; [0.] when no cosine in [(0, 1\]] qualifies. *)
  reflective : float array;
  n_lights : int;
  light_kind : int array;  (** {!ambient}, {!point}, {!directional}, {!area}, {!sphere} or {!spot}. *)
  light_intensity : float array;
  lx : float array;
      (** Position (point, sphere, spot), direction (directional) or
          corner (area). *)
  ly : float array;
  lz : float array;
  robust : bool;  (** The robust mode: the scene gives no epsilon. *)
  epsilon : float;
      (** Lower bound of [t] for secondary rays: the scene's epsilon, or [0.]
          in the robust mode, where the tracer handles the sphere a ray
          leaves exactly instead. *)
  depth : int;  (** Recursion depth; [0] when no material reflects or is transparent. *)
  width : int;  (** Canvas size. *)
  height : int;
  viewport : Viewport.t;
  camera : Camera.t;
  identity_rotation : bool;  (** The camera matrix is exactly the identity. *)
  background : Color.t;
  primary_ocx : float array;
      (** [camera - center], per sphere: the rays of a pinhole. (A lens's
          rays start elsewhere: the tracer never reads these for them, its
          primary search being every other ray's: [Tracer.lens_rays].) *)
  primary_ocy : float array;
  primary_ocz : float array;
  primary_k3 : float array;  (** [<CO, CO> - r^2] for the camera origin. *)
  max_channel : float;
      (** An upper bound of every colour channel a ray can return (a
          material's colour, its pattern's, its texture's brightest
          channel), used to stop reflections that can no longer change an
          8-bit value;
          [infinity] if a huge specular exponent leaves none (the cosine,
          rounded, may exceed 1 by a few ulps, and its power explodes). *)
  early_stop : bool;  (** The skips are on and [max_channel] is finite. *)
  skips : bool;  (** Whether the exact skips are enabled. *)
  transparency : float array;  (** Per material, in [\[0, 1\]]. *)
  refractive_index : float array;  (** Per material, [> 0]. *)
  fresnel : bool array;  (** Per material: Schlick's approximation splits the transparency. *)
  transparent : bool;
      (** Some material has [transparency > 0]: the tracer follows the ray
          tree (reflected and refracted rays) instead of the reflection
          chain, and shadow rays pass through transparent objects. *)
  behind : bool;
      (** The skips are on: the document's kernel rejects a sphere whose
          two roots are certainly [<= 0] ([k2 > 0] and [k3 > 0]) without
          computing them. *)
  shadow_skip : bool;
      (** The skips are on: the tracer casts a shadow ray only when the
          light would add a term. *)
  cull : bool;
      (** The skips are on: the document's kernel tests a camera ray only
          against the spheres that can meet some ray of its 8 x 8 tile. *)
  light_number : int array;
      (** Per light: its place in the scene's list of lights (from 0, every
          light counted, the dropped ones too), which keys its samples
          ({!Light}, "Sample points"). *)
  light_geom : float array;
      (** Per light [l], at [light_stride * l]: an area light's corner,
          edge1 and edge2 (9 floats); a sphere light's position and
          radius; a spotlight's position, unit direction, the cosine of
          its angle and its falloff; zeros otherwise. *)
  light_su : int array;
      (** Per light: an area light's samples along edge1, a sphere
          light's samples, [1] otherwise. *)
  light_sv : int array;  (** Per light: an area light's samples along edge2, [1] otherwise. *)
  light_adaptive : bool array;
      (** Per light: an area light samples only the points its corners
          leave in doubt ({!Light.corners_first}: adaptive, at least four
          samples; {!Light}, "Penumbra-only sampling"). *)
  light_uniform : bool array;
      (** Per light: an area light's samples are drawn independently over
          its whole rectangle ([Light.Uniform]), not one per cell. *)
  soft_lights : bool;
      (** Some light is an area, sphere or spot light: the lighting loop
          that asks each light's kind for them (the other never asks). *)
  umbra_skip : bool;
      (** The skips are on: an area light's samples inside the hull of its
          corner cells' samples, all four stopped by one convex object,
          cast no shadow ray (the kernel's [Lighting], exact). *)
  casters : float array;
      (** With the skips and an area or sphere light, boxes that together
          hold every bounded object: each object's own where the scene has
          at most 16 (a sphere's cube, an axis-aligned box itself, another
          object's {!Shape.box_bounds}, each grown by the margin of
          {!Bvh.ray_box_margin} for its largest half side, as the
          hierarchy's boxes are), else the hierarchy's nodes at depth 4 and
          its leaves above it; none for a scene of at most 16 objects with
          an instance and no hierarchy. [casters.(0)] is [M], the largest
          magnitude of a coordinate of their corners; box [i] is at [1 + 6
          i]: its centre, then its half sides, each grown by [2^-30 (M +
          1)] (far more than the rounding of the centre and half sides).
          The kernel's [Lighting] tests a lit point's hull with a
          stratified area light or a sphere light against them and the
          planes ([unbounded]): a point whose hull meets none sees the
          light whole and casts no shadow ray to it. Empty otherwise, and
          with the skip [Whole_light] off. *)
  sampled : bool;
      (** Some pixel is an integral that draws numbers (an area light, a
          lens): the tracer keeps the key of each camera sample
          ([Tracer.key]). [false] keeps the loops of other scenes as they
          were. *)
  specular_cut : float array;
      (** With the skips, per
          material [m] and light [l] at [m * n_lights + l]: the cosine at or below which the specular
          term of [l] adds nothing to the intensity it joins, because
          [cos ** s] is 0 ([specular_zero]) or below half an ulp of the
          intensity already summed (at least the ambient lights listed
          before [l]); [0.] without the skips; [infinity] for a matte
          material, which has no specular term. *)
  ambient_lead : float;
      (** The sum of the ambient lights that come first in [light_kind],
          added from [0.] in order. *)
  first_light : int;  (** The index of the first light that is not one of those. *)
  sphere4 : float array;
      (** With [textbook_all]: per slot [i], [cx, cy, cz, r2] at [4 i] to
          [4 i + 3]; otherwise empty. *)
  primary4 : float array;
      (** With [textbook_all]: per slot [i], [primary_ocx, primary_ocy,
          primary_ocz, primary_k3] at [4 i] to [4 i + 3]; otherwise empty. *)
  light6 : float array;
      (** Per light [l], at [6 l] to [6 l + 5]: the range of its shadow
          rays ([1.] point, [infinity] directional, [0.] ambient),
          intensity, vector x, y, z and [|L|]. *)
  column_vx : float array;
      (** The viewport x of the pixel centres of each canvas column, left to right. *)
  row_vy : float array;
      (** The viewport y of the pixel centres whose [gy] is [r - height / 2], for [r] from [0]. *)
  instances : instances;  (** The transformed objects ({!Kind.Instance}). *)
  materials : Material.t array;  (** The materials by number, for the scenes that instance this one. *)
  texture_of : int array;
      (** Per material: the number of its texture in [texture_table], or
          [-1] if it has none; empty when no material has one. *)
  texture_table : int array;
      (** Per texture [k], at [texture_stride * k]: the number of its
          image in [texels], its width, its height and its mapping
          ([spherical], [planar], [box_mapping] or [uv_mapping]). A texture
          that several materials share is one; an image that several
          textures show (one file, read once) is one. *)
  texture_size : float array;  (** Per texture: the side of one copy of a planar mapping's image. *)
  texels : Image.buffer array;
      (** Each image's channels, {!Texture.channels}: the scene's own
          buffers, not copies (a float per channel would take eight times
          their memory, for a conversion saved per channel read). *)
  uv : float array;
      (** Per slot [i], at [6 i], the [vt] coordinates [u0 v0 u1 v1 u2
          v2] of the corners [at0], [at1], [at2] of a triangle whose
          material has a [uv] texture (zeros for the other slots); empty
          when no material has one. *)
}
(** The type for prepared scenes. *)

and instances = {
  bottoms : t array;
      (** The bottom level: one prepared scene per object that instances
          place (physically one value, shared by any number of them: a
          mesh's triangles and hierarchy are there once), with no lights. *)
  bottom : int array;  (** Per instance: its number in [bottoms]. *)
  to_object : float array;
      (** Per instance [n], at [12 n]: the world-to-object matrix
          ({!Transform.to_object}), rows [[a00 a01 a02 b0; ...]]. *)
  material_map : int array array;
      (** Per instance: the material, in this scene's numbering, of each
          material of its bottom level (all one where the instance gives
          its own; one per material of the bottom level where its own
          has a pattern). *)
  placed_alternate : int array;
      (** Per material of this scene (second colours included): the
          material of its pattern's second colour where that pattern lies
          in an instance's object frame, or [-1]; empty when no instance
          shows a pattern. Such a pattern is stored in [pattern] on the
          frame of the bottom level's surface (its material's
          [Shape.pattern_frame]) and looked up on the ray carried into the
          object's frame; [alternate] gives these materials [-1]. *)
}
(** The type for the table of instances. A slot of kind {!Kind.Instance}
    stores its instance's number in [geom]. *)

val instance_box : t -> Shape.instance -> Vec3.t * Vec3.t
(** [instance_box bottom i] is the box, in the world, of instance [i]
    whose bottom level is [bottom]: the root box [B] of [bottom]'s
    hierarchy (where it has none, {!Shape.box_bounds} of [i]'s object),
    its eight corners carried by [i]'s transform, their extremes taken,
    and moved outward by {!Transform.bounds}'s room and by [8 e S]
    ([e = 2^-52], [S] the largest of [|a_r0 x| + |a_r1 y| + |a_r2 z| +
    |b_r|] over the rows [r] of the object-to-world matrix and the
    corners [(x, y, z)]). The top level's box of the instance is this
    box, not the cube around it, padded by the margin of a cube of its
    largest half side ({!Bvh.margin}) times the transform's
    {!Transform.stretch}.

    Why it holds every hit the bottom level reports. (1) The bottom
    level reports a hit only where the carried ray meets [B]: its walk
    starts with [B]'s slab test, and [B] holds every node's box below
    it, each padded so that no test reports a hit outside it
    ({!Bvh.ray_box_margin}); a bottom level without a hierarchy is its
    one object, inside its box. (2) The map [q -> A q + b] is affine, so
    the image of [B] is the convex hull of its eight corners' images,
    inside the box of their extremes. Each corner's image is computed
    with three products and three sums per coordinate, an error of at
    most [3u/(1 - 3u)] ([u = e / 2]) times that coordinate's [|a_r0 x| +
    |a_r1 y| + |a_r2 z| + |b_r|] <= [S] (Higham's bound for a dot
    product): [2 e S] covers it, and the rest of [8 e S] covers the
    rounding of the room and of the corners moved by it (each at most
    half an ulp of a coordinate, itself at most [S]). So the box holds
    [A B + b] exactly. (3) The kernel carries the world ray into the
    object's frame by the world-to-object matrix (each operation's exact
    inverse, composed), not by an inverse of [A]: the carried point at a
    root [t] is the exact preimage of a world point within a few [u]
    times [stretch] of the ray's point at [t], with [u] relative to the
    ray's origin and the distance it travelled, both at most the
    world's largest coordinate [M] and diameter [D] (rays start at the
    camera or on a surface of the scene). The margin [64 u (D^2 / r +
    M)] ([r <= D] the half side) times [stretch] exceeds that by a
    factor of ten or more for up to a dozen operations: the world ray
    meets the padded box at every [t] where the carried ray's hit lies
    in [B]. *)

val bvh_threshold : int
(** [bvh_threshold] is [8]: with at most this many spheres, testing every
    one is cheaper than walking a hierarchy. *)

val ambient : int
(** [ambient] is the [light_kind] of ambient lights. *)

val point : int
(** [point] is the [light_kind] of point lights. *)

val directional : int
(** [directional] is the [light_kind] of directional lights. *)

val area : int
(** [area] is the [light_kind] of area lights; [area > directional]. *)

val sphere : int
(** [sphere] is the [light_kind] of sphere lights; [sphere > directional]. *)

val spot : int
(** [spot] is the [light_kind] of spotlights; [spot > directional]. *)

val light_stride : int
(** [light_stride] is [10], the floats per light in [light_geom]. *)
val textured_material : int
(** [textured_material] is [-2], the [alternate] of a textured material. *)

val texture_stride : int
(** [texture_stride] is [4], the ints of a texture in [texture_table]. *)

val spherical : int
(** [spherical] is the mapping code of {!Texture_map.Spherical} in [texture_table]. *)

val planar : int
(** [planar] is the mapping code of {!Texture_map.Planar}. *)

val box_mapping : int
(** [box_mapping] is the mapping code of {!Texture_map.Box}. *)

val uv_mapping : int
(** [uv_mapping] is the mapping code of {!Texture_map.Uv}. *)

val prepare : ?skips:bool -> ?cut:bool -> ?beside:Bvh.beside -> Scene.valid -> t
(** [prepare ~skips ~cut ~beside scene] is [scene] prepared for {!Raytrace.Private.Trace}. With [skips]
    (default [true]) the tracer skips work that provably cannot change an
    output byte: lights of zero intensity are dropped here, shadow rays stop
    at the first blocker and try the last blocker first, and reflections
    stop once their remaining weight cannot change an 8-bit channel, and
    rays are tested only against spheres whose (conservatively padded,
    {!Raytrace.Private.Bvh.ray_box_margin}) boxes they meet. With
    [~skips:false] it does everything the document does, for tests that
    prove the skips exact. [beside] builds a part of the hierarchy on
    another core ({!Raytrace.Private.Bvh.build_boxes}) and, from its
    [min_objects] spheres on, finds the identical spheres there while
    this process makes the hierarchy's boxes: the same result. With
    [cut] (default [false]), a mesh's leaves are cut by planes where the
    surface area heuristic finds it pays ({!Raytrace.Private.Bvh.split_leaves},
    prices by default): the same image, fewer triangle tests a ray on meshes of long
    thin triangles (the 1M-triangle knot: camera rays 17% and shadow rays
    23% fewer instructions), for a slower prepare (the 1M knot's cut:
    about 1 G instructions, a sixth of a second) and twice the nodes
    (docs/performance.md, "Issue 28, round 3: the tree" and "Issue 28,
    round 3: the cut made cheap").
    For a scene of more than 2{^18} objects, the garbage collector's
    [major_heap_increment] is 256 MB while it runs (then set back): the
    heap's free pieces between the default's smaller chunks do not fit
    arrays of a million floats. *)

(** The skips of the tracer's kernel, each exact on its own: [Behind] and
    [Culling] for the document's scenes (spheres alone, an epsilon, no
    hierarchy), [Shadow_rays] and [Negligible_terms] for every scene,
    [Umbra] and [Whole_light] for scenes with area (and, [Whole_light],
    sphere) lights. *)
type kernel_skip =
  | Behind  (** [behind]: no roots computed for a sphere behind the ray. *)
  | Shadow_rays  (** [shadow_skip]: no shadow ray for a light that adds nothing. *)
  | Culling  (** [cull]: camera rays test only their tile's spheres. *)
  | Negligible_terms  (** [specular_cut]: no specular term too small to count. *)
  | Umbra  (** [umbra_skip]: no shadow ray for an area light's samples in one convex object's umbra. *)
  | Whole_light  (** [casters]: no shadow ray to an area or sphere light that no blocker can hide from the point. *)

val without : kernel_skip -> t -> t
(** [without k p] is [p] with the skip [k] off and the others as they
    are: for the tests that show each skip exact. *)
