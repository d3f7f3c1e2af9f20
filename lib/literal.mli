(** The document's algorithm, transcribed literally: the executable
    specification.

    This module follows the document (and, where it is silent, the CGFS
    demos that it summarises) step by step, with lists, boxed vectors and
    options, and no shortcut: every sphere is tested for every ray, every
    light casts a shadow ray, reflection recurses. It is slow on purpose and
    is kept as the oracle that the fast renderer ({!Render}) is tested
    against. The arithmetic is done in the same order as the CGFS demos,
    so that on the reference scene it reproduces their images byte for
    byte.

    It always uses the document's semantics: a scene without an epsilon is
    traced with {!Scene.document_epsilon}. *)

val closest_intersection :
  Sphere.t list -> origin:Vec3.t -> direction:Vec3.t -> t_min:float -> t_max:float ->
  (Sphere.t * float) option
(** [closest_intersection spheres ~origin ~direction ~t_min ~t_max] is the
    sphere hit first by the ray [P = O + t D] with [t_min < t < t_max], and
    its [t] (section 6.1, roots by {!Sphere.textbook_roots}); [None] if the
    ray hits nothing in that range. Of two spheres hit at the same [t], the
    first in the list wins. *)

type obj =
  | Sphere of Sphere.t
  | Shape of Shape.t  (** A plane, a triangle or a box. *)
  | Mesh_triangle of Mesh.t * int  (** Triangle [k] of a mesh. *)
  | Csg_surface of Csg.t * Csg.solid * Vec3.t
      (** The point hit on a CSG solid: the solid, the leaf whose surface it is and the
          solid's outward normal there ({!Csg.literal_hit}). *)
(** The type for the objects of a scene: a mesh is one object per
    triangle, less its degenerate ones. *)

val closest_hit :
  Scene.t -> origin:Vec3.t -> direction:Vec3.t -> t_min:float -> t_max:float -> (obj * float) option
(** [closest_hit scene ~origin ~direction ~t_min ~t_max] is the object of
    [scene] hit first by the ray [P = O + t D] with [t_min < t < t_max],
    and its [t]: the spheres by {!closest_intersection}, then the other
    shapes by {!Shape.roots}, the nearer of its two roots that is in range,
    a CSG solid by {!Csg.literal_hit}.
    Of objects hit at the same [t], the first wins, spheres before shapes. *)

val normal : obj -> point:Vec3.t -> direction:Vec3.t -> Vec3.t
(** [normal obj ~point ~direction] is the unit normal of [obj] at [point]
    for a ray along [direction]: {!Sphere.normal} for a sphere (outward, as
    in the document), and for the other shapes {!Shape.normal} turned
    toward the ray ([-n] when [<n, D> > 0]); a mesh's smooth triangle
    gives its corners' normals interpolated ({!Triangle.smooth_normal}),
    turned as its flat normal is. *)

val compute_lighting :
  Scene.t -> epsilon:float -> point:Vec3.t -> normal:Vec3.t -> view:Vec3.t -> specular:float ->
  float
(** [compute_lighting scene ~epsilon ~point ~normal ~view ~specular] is the
    total intensity [I_total] at [point] (sections 7.4 to 7.7): the ambient
    intensities plus, for each point or directional light that no object
    shadows, its diffuse term and (unless [specular] is {!Sphere.matte}) its
    specular term. A sphere shadows a light if it meets the shadow ray
    [P + t L] with [epsilon < t < Light.shadow_t_max]. A point light
    located exactly at [point] ([L = 0]) is skipped: it has no direction. *)

val trace_ray :
  Scene.t -> epsilon:float -> origin:Vec3.t -> direction:Vec3.t -> t_min:float -> t_max:float ->
  depth:int -> Color.t
(** [trace_ray scene ~epsilon ~origin ~direction ~t_min ~t_max ~depth] is the
    unclamped colour seen along the ray: the background if it hits nothing,
    else the hit sphere's colour times the lighting at the hit point,
    blended with the colour seen along the mirror ray (section 7.8,
    [t > epsilon], [depth - 1]) when the sphere is reflective and
    [depth > 0]. *)

val pixel : Scene.t -> int -> int -> Color.t
(** [pixel scene gx gy] is the unclamped colour of canvas pixel [(gx, gy)]
    (centered coordinates, {!Raytrace.Private.Canvas}): the primary ray from the camera
    through the viewport point of the pixel, [t > 1] (section 8), by
    {!trace_ray}; or, when some object has [transparency > 0], by the
    ray tree of the book's chapter "Extending the Raytracer", as a
    recursion: at each hit [local (1 - r - t) + reflected wr +
    refracted wt] with [wr = r + t R], [wt = t (1 - R)] and the reflectance
    [R] and refracted direction of {!Raytrace.Private.Ray_tree.split}
    (Snell's law; [R = 1] on total internal reflection; Schlick's when
    [fresnel]), the indices those of the media the ray is in and enters
    (the objects it is inside, innermost first), one depth for both kinds
    of ray; shadow rays scaled by the transparency of every surface they
    cross, nearest first; a surface of transparency 1 between equal
    indices crossed on the same ray. docs/scene-format.md states the
    rules. *)

val render : ?limits:Limits.t -> Scene.valid -> Image.t
(** [render ~limits scene] is the image of [scene]: every pixel of the canvas
    (section 8), clamped and rounded by {!Color.to_byte}. Reflections are
    followed in a loop, not by recursion: any depth fits in the stack, and
    memory grows with the reflections of one ray (a few words a level).
    @raise Limits.Work_exceeded once the ray-sphere tests counted so far
    pass the work bound of [limits] (default {!Limits.default};
    {!Limits.work_budget}), checked after each column of pixels, and at
    every hit of a ray tree (a scene with transparency). *)
