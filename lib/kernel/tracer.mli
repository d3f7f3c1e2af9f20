(** The tracer's state: what a tracer keeps between rays (its prepared
    scene, the per-ray record, the stacks of the loops, the counters and
    the work budget), at the bottom of the kernel's modules, which all
    read it. Kernel-internal: {!Trace} is the interface.

    Floats cross the kernel's module boundaries only in the per-ray record
    {!Scratch.t} ([s]) and in the arrays here: without flambda, and with
    the dev profile's [-opaque], a float argument or result of a call to
    another module is boxed. *)

(** {1:state The state} *)

type counters = {
  mutable primary : int;  (** Primary rays cast. *)
  mutable shadow : int;  (** Shadow rays cast. *)
  mutable reflection : int;  (** Mirror rays cast, and refracted rays. *)
  mutable tests : int;  (** Ray-object intersection tests. *)
  mutable box_tests : int;  (** Ray-box tests in the object hierarchy. *)
  mutable early_stops : int;  (** Reflections (and refractions) stopped by the weight bound. *)
  mutable decided : int;
      (** Points that an adaptive area light's corners decided lit or
          shadowed, its samples cast no shadow ray. *)
  mutable penumbra : int;  (** Points whose adaptive area light's corners disagreed: all samples traced. *)
  mutable umbra : int;
      (** Area light samples that cast no shadow ray: inside the corner
          cells' samples, all stopped by one convex object (exact). *)
  mutable whole : int;
      (** Points that see an area or sphere light whole (no blocker's box
          meets their hull with it, {!Lighting}): no shadow ray to it (exact). *)
}
(** The type for the work counters ({!Trace.counters}). *)

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
  mutable hit : int;  (** Index of the sphere found by {!Traversal.closest}. *)
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
          (see {!Traversal}). *)
  averaging : bool;  (** Samples are averaged: see {!Byte_exact.settled}. *)
  mutable assumed : int;  (** Sphere the primary ray is assumed to hit, see {!Traversal.primary_hit_spheres}. *)
  mutable budget : int;  (** Most tests {!check_budget} accepts before it calls [refill]. *)
  mutable refill : int -> int;
      (** Called with the work done once it passes [budget]: the next
          budget, or it raises [Limits.Work_exceeded]. *)
  tracer : int;  (** The loop of {!Trace}: {!spheres_chain}, {!objects_chain} or {!tree}. *)
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
          sample being traced, set by {!Trace}'s [pixel], [row] and
          [sample]; the integrals over a light or a lens draw their numbers
          from it, so that they are the same for every [--jobs], tiling and
          order of the pixels. [0] without [p.sampled]. *)
  mutable lens_gx : int;
      (** With [p.sampled], set with [key]: the canvas point [(lens_gx,
          lens_gy)] of the pixel being traced, the side [lens_n] of its grid
          of camera samples and the sample's place [lens_k = j lens_n + i]
          in it ([1] and [0] for a pixel's centre ray): a stratified lens
          ({!Camera_ray}) gives the samples of a pixel one cell each. *)
  mutable lens_gy : int;
  mutable lens_n : int;
  mutable lens_k : int;
  mutable lens_px : int;
      (** A stratified lens's numbers of one pixel, kept from sample to
          sample: the pixel [(lens_px, lens_py)] ([min_int] before the
          first) whose offset is in [s.lens_u0], [s.lens_v0] and whose key
          of the cell permutation, mixed ({!Sample_key.walk}'s [p]), is
          [lens_hc]; the permutation's last domain [lens_m] ([0] before
          the first) and its mask [lens_w]; and the pixel's two sub-cell
          permutations of [0 .. lens_sub_n - 1] ([0]: none yet), the
          first at [lens_sub.(r)], the second at
          [lens_sub.(lens_sub_n + r)] ([2 Limits.max_grid] ints). *)
  mutable lens_py : int;
  mutable lens_hc : int;
  mutable lens_m : int;
  mutable lens_w : int;
  lens_sub : int array;
  mutable lens_sub_n : int;
  light_cells : int array;
      (** An area light's two permutations of its cells' sub-strata, for
          the point being lit ({!Lighting}): of [0 .. v - 1] at
          [light_cells.(b)], of [0 .. u - 1] at [light_cells.(v + a)]
          (as many ints as the largest [u + v] of the scene's area
          lights, at least one). *)
  red : float array;
      (** The colour channels of each material, read by the tracing loops:
          [p.red] itself, or, where some material has a texture
          ([p.texture_of] not empty), this tracer's copy of it, where a
          textured material's entry is its colour at the latest hit on it
          ({!Texturing}). *)
  green : float array;
  blue : float array;
}
(** The type for tracers: one per worker, reused for every ray. *)

val spheres_chain : int
(** [spheres_chain] is the [tracer] of the chain of mirror rays for spheres alone ({!Chain.trace_spheres}). *)

val objects_chain : int
(** [objects_chain] is the [tracer] of the chain of mirror rays for any objects ({!Chain.trace_objects}). *)

val tree : int
(** [tree] is the [tracer] of the ray tree, for scenes with transparency ({!Glass.trace_tree}). *)

val no_assumption : int
(** [no_assumption] is [assumed] when the primary ray searches every object. *)

val lens_rays : int
(** [lens_rays] is [assumed], from {!create} on, when the camera has a
    lens: the primary ray searches every object as any other ray does,
    without the per-frame constants of a ray from the camera's position
    ([Prepared]'s [primary_ocx] ...), since it starts on the lens. *)

val tile : int
(** [tile] is the side, in pixels, of the square tiles by which the document's kernel culls camera rays ({!Textbook}). *)

val block : int
(** [block] is the most pixels of a row traced between two checks of the
    work budget, a multiple of {!tile} ([256]), so that blocks start on
    tiles. *)

(** {1:make Making and reading} *)

val create : ?averaging:bool -> Prepared.t -> t
(** [create ~averaging p] is a tracer of [p]: {!Trace.create}. *)

val prepared : t -> Prepared.t
(** [prepared tr] is [tr]'s scene. *)

val averaging : t -> bool
(** [averaging tr] is [true] iff [tr] was created with [~averaging:true]. *)

val counters : t -> counters
(** [counters tr] is [tr]'s counters, the CSG solids' leaf tests taken into them. *)

val work : t -> int
(** [work tr] is the tests and box tests counted so far. *)

val set_budget : ?refill:(int -> int) -> t -> int -> unit
(** [set_budget ~refill tr n] is {!Trace.set_budget}. *)

val check_budget : t -> unit
(** [check_budget tr] calls [tr]'s [refill] if more than its budget of
    work was done: a sum and a comparison, the call out of line.
    @raise Limits.Work_exceeded as [refill] does. *)

val red : t -> float
(** [red tr] is the red of the last ray traced (unclamped). *)

val green : t -> float
(** [green tr] is its green. *)

val blue : t -> float
(** [blue tr] is its blue. *)

val hit_object : t -> int
(** [hit_object tr] is the scene's number of the object the last primary ray hit, or [-1]. *)
