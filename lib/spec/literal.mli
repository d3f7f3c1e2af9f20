(** The document's algorithm, transcribed literally: the executable
    specification.

    This module follows the document (and, where it is silent, the CGFS
    demos that it summarises) step by step, with lists, boxed vectors and
    options, and no shortcut: every object is tested for every ray, every
    light casts a shadow ray, reflection recurses. It is slow on purpose and
    is kept as the oracle that the fast renderer ({!Render}) is tested
    against. The spheres' arithmetic is done in the same order as the CGFS
    demos, so that on the reference scene it reproduces their images byte
    for byte.

    {b Independent of the kernel.} Every shape's hit, normal, inside test,
    CSG membership and mesh parity, the refraction and Fresnel split of
    glass and the pattern cells are computed here and in
    {!Raytrace.Private.Literal_geometry}, from the definitions, by code
    that shares nothing with the kernel's shape modules ({!module-Sphere},
    {!Plane}, {!Triangle}, {!Box}, {!Mesh}, {!Csg}, {!module-Shape},
    {!Pattern} are read for their data only; the ray tree's
    {!Raytrace.Private.Ray_tree} is not used): a mistake in the kernel's shape
    code cannot also be here. Every comparison that decides whether a ray
    meets a triangle, a plane or a box, and the order of the crossings of
    a CSG solid's boxes and meshes, is exact ({!Raytrace.Private.Exact_float}):

    - a triangle (alone or in a mesh) is closed: a line through its edge or
      vertex meets it, decided by the exact signs of its three edge
      functions [det\[P - O, Q - O, D\]];
    - a closed mesh as a CSG operand is inside after an odd number of
      crossings, each counted by the same exact edge functions with a
      consistent tie rule (the line moved by an infinitesimal, fixed per
      ray, off every edge and vertex), so that a line through a shared
      edge or vertex crosses the surface once, and one that touches it at
      a fold crosses it twice or not at all;
    - a box is the closed set [min <= P <= max]: a line touching an edge
      or a corner meets it, and as a CSG operand, a line that only touches
      it does not go in;
    - a CSG solid's surface along a ray is found by classifying each
      crossing of each leaf: the boolean expression on the leaves just
      before and just after it (a leaf is inside between its entry and
      exit, a mesh after an odd number of crossings); touching and
      coincident intervals (two boxes sharing a face, seen from inside
      their union) thus make no surface, and of two crossings at the
      same parameter the leaf further left gives the surface.

    A sphere's roots are the document's textbook formula; a sphere leaf of
    a CSG solid uses the cancellation-free roots of Ray Tracing Gems,
    chapter 7, as docs/numerics.md states for CSG solids; the
    parameters [t] of hits are floats.

    It always uses the document's semantics: a scene without an epsilon is
    traced with {!Scene.document_epsilon}.

    {b Work.} Every ray-object test (a sphere, plane, triangle, box, a
    described kind's shape (cylinder, disk, cone, torus), a mesh's
    triangle, a CSG solid's leaf or mesh triangle) is counted as it
    is done and checked against the work bound of {!val-render}: a render
    stops within one test of its bound. *)

val closest_intersection :
  Sphere.t list -> origin:Vec3.t -> direction:Vec3.t -> t_min:float -> t_max:float ->
  (Sphere.t * float) option
(** [closest_intersection spheres ~origin ~direction ~t_min ~t_max] is the
    sphere hit first by the ray [P = O + t D] with [t_min < t < t_max], and
    its [t] (section 6.1, [t1,2 = (-b +- sqrt (b^2 - 4ac)) / 2a]); [None] if
    the ray hits nothing in that range. Of two spheres hit at the same [t],
    the first in the list wins. *)

type obj =
  | Sphere of Sphere.t
  | Shape of Shape.t * Vec3.t
      (** A plane, a triangle or a box, and its unit normal at the hit: the
          plane's and the triangle's as given ([(v1 - v0) x (v2 - v0)]), the
          outward normal of the box's face that the ray crosses there. *)
  | Mesh_triangle of Mesh.t * int  (** Triangle [k] of a mesh. *)
  | Csg_surface of Csg.t * Csg.solid * Vec3.t
      (** The point hit on a CSG solid: the solid, the leaf whose surface it is and the
          solid's outward normal there. *)
  | Placed of Shape.instance * obj * Vec3.t
      (** The point hit on a transformed object: the instance, the surface
          hit in the object's frame (the ray carried there by this module's
          own inverse of the transform's matrix, its adjugate over its
          determinant) and the unit normal in the world (the object's by
          the inverse transpose). *)
(** The type for the objects of a scene: a mesh is one object per
    triangle. *)

val rounding_dependent : unit -> int
(** [rounding_dependent ()] is the number of ray-object searches so far
    whose answer the rounding of floats may decide, in the oracle as in
    the kernel: those where exact arithmetic had to decide whether a ray
    passes a boundary (a triangle's edge or vertex, another root) it is
    within rounding of but off ({!Literal_geometry.undecided}'s [near]),
    those of a ray from a computed hit point (a shadow, mirror or
    refracted ray) through a triangle's edge or within what that point's
    rounding can move it of the edge ({!Literal_geometry.from_origin}), since that point
    and the ray's direction are rounded, by the oracle's arithmetic and
    the kernel's each its own way; those of any ray where two objects
    whose parameters different formulas find (a box's face and a mesh's
    triangle in it) tie exactly, as each formula rounds the parameter its
    own way; those where a root's enclosure holds the ray's end (a plane
    through a light, met at the shadow ray's [t = 1]); those of a ray within rounding of parallel to a plane
    (met very far away, or, where its denominator rounds to 0, not at
    all); and the checker cells of points within rounding of a cell's
    boundary. A camera ray exactly through an edge or a vertex, and other
    exact ties of two roots (touching CSG operands, coinciding surfaces
    of one kind, a box's edge), are not counted: their answer is exact. *)

val closest_hit :
  Scene.t -> origin:Vec3.t -> direction:Vec3.t -> t_min:float -> t_max:float -> (obj * float) option
(** [closest_hit scene ~origin ~direction ~t_min ~t_max] is the object of
    [scene] hit first by the ray [P = O + t D] with [t_min < t < t_max],
    and its [t]: the spheres by {!closest_intersection}, then the other
    shapes in order, the nearer of a box's two roots that is in range.
    The range is strict and decided on the exact [t]
    ({!Literal_geometry.in_range}): a plane met at exactly [t = t_min] is
    not hit, whatever its rounded [t]; the hits are ordered by
    their exact parameters (a sphere's is its rounded root): of objects hit
    at the same [t], the first wins, spheres before shapes. *)

val normal : obj -> point:Vec3.t -> direction:Vec3.t -> Vec3.t
(** [normal obj ~point ~direction] is the unit normal of [obj] at [point]
    for a ray along [direction]: for a sphere [(P - C) * (1 / |P - C|)]
    (outward, as in the document), for the other shapes their normal
    turned toward the ray ([-n] when [<n, D> > 0]); a mesh's smooth
    triangle gives its corners' normals weighted by the barycentric
    coordinates of [point] (ratios of signed areas), turned as its flat
    normal is. *)

val compute_lighting :
  ?key:int -> Scene.t -> epsilon:float -> point:Vec3.t -> normal:Vec3.t -> view:Vec3.t -> specular:float ->
  float
(** [compute_lighting scene ~epsilon ~point ~normal ~view ~specular] is the
    total intensity [I_total] at [point] (sections 7.4 to 7.7): the ambient
    intensities plus, for each point or directional light that no object
    shadows, its diffuse term and (unless [specular] is {!Sphere.matte}) its
    specular term. An object shadows a light if it meets the shadow ray
    [P + t L] with [epsilon < t < Light.shadow_t_max]. A point light
    located exactly at [point] ([L = 0]) is skipped: it has no direction.
    An area or sphere light is its samples, each a point light at a
    point of its own, numbered by [key] (default [0]; the camera sample's
    {!Raytrace.Private.Sample_key.camera} key) and the light's place in the list ({!Light},
    "Sample points"); a spotlight is a point light scaled by its cone. *)

val trace_ray :
  ?key:int -> Scene.t -> epsilon:float -> origin:Vec3.t -> direction:Vec3.t -> t_min:float -> t_max:float ->
  depth:int -> Color.t
(** [trace_ray scene ~epsilon ~origin ~direction ~t_min ~t_max ~depth] is the
    unclamped colour seen along the ray: the background if it hits nothing,
    else the hit object's colour times the lighting at the hit point,
    blended with the colour seen along the mirror ray (section 7.8,
    [t > epsilon], [depth - 1]) when the object is reflective and
    [depth > 0]. [key] numbers the samples of area and sphere lights as in
    {!compute_lighting}. *)

val pixel : Scene.t -> int -> int -> Color.t
(** [pixel scene gx gy] is the unclamped colour of canvas pixel [(gx, gy)],
    its area and sphere lights sampled with the key of the pixel's centre
    ray, [Sample_key.camera ~gx ~gy ~di:0 ~dj:0]
    (centered coordinates, {!Raytrace.Private.Canvas}): the primary ray from the camera
    through the viewport point of the pixel, [t > 1] (section 8), by
    {!trace_ray}; or, when some object has [transparency > 0], by the
    ray tree of the book's chapter "Extending the Raytracer", as a
    recursion: at each hit [local (1 - r - t) + reflected wr +
    refracted wt] with [wr = r + t R], [wt = t (1 - R)], the refracted
    direction by Snell's law [eta d + (eta c - cos t) n] and the
    reflectance [R] ([R = 1] on total internal reflection; Schlick's
    [R0 + (1 - R0) (1 - cos)^5] when [fresnel], the cosine on the side of
    the lower index), the indices those of the media the ray is in and
    enters (the objects it is inside, innermost first), one depth for both
    kinds of ray; shadow rays scaled by the transparency of every surface
    they cross, nearest first; a surface of transparency 1 between equal
    indices crossed on the same ray. docs/scene-format.md states the
    rules. With a lens ({!Camera.has_lens}), the ray of the pixel's centre
    sample ({!sample} with [n = 1]). *)

val sample : Scene.t -> int -> int -> i:int -> j:int -> n:int -> Color.t
(** [sample scene gx gy ~i ~j ~n] is {!pixel} for camera sample [(i, j)]
    of the [n x n] grid of pixel [(gx, gy)]: the ray through canvas point
    [(gx + (i + 1/2) / n - 1/2, gy + (j + 1/2) / n - 1/2)]. With a lens of
    diameter [a] focused at [f], a viewport at distance [d] and the
    camera's matrix [M], the ray leaves [O' = O + M (a u / 2, a w / 2, 0)]
    for the point [F = O + (f / d) M V] of the plane of focus, in
    direction [(d / f) (F - O')] ([t = 1] on the viewport plane, as the
    pinhole's), where [(u, w)] is {!lens_point} [~lens:(gx, gy, n, i, j)]
    of the camera sample's key [camera ~gx ~gy ~di:(2i+1-n) ~dj:(2j+1-n)]
    ({!Sample_key}). Written from that
    definition, not with the kernel's camera rays. *)

val lens_point : Camera.t -> key:int -> lens:int * int * int * int * int -> float * float
(** [lens_point cam ~key ~lens:(gx, gy, n, i, j)] is the point [(u, w)] of
    the unit disc from which camera sample [(i, j)] of the [n x n] grid of
    pixel [(gx, gy)], keyed [key], leaves the lens. With [Uniform]
    sampling ({!Camera.lens_sampling}), the first pair
    [(2 unit (key h 2k) - 1, 2 unit (key h (2k+1)) - 1)], [k = 0 .. 31],
    inside the disc ([(0, 0)] if none), [h = key key (-1)]. With
    [Stratified], from the pixel's key [hp = pixel ~col:gx ~row:gy
    ~sample:(-1)]: the offset [u0 = (unit (key hp 0), unit (key hp 1))]; for
    the centre [k = (n/2) n + n/2] of an odd grid the point [u0]; for the
    other samples [k = j n + i], the cell [c = 1 + permute (key hp 2)
    ~n:(n^2 - 1) k'] ([k'] = [k] less one past the centre; for an even
    grid [permute (key hp 2) ~n:(n^2) k]) of the [n x n] cut of the unit
    square, [(ci, cj) = (c mod n, c / n)], and in it the sub-cell
    [(sx, sy) = (s3 cj, s4 ci)], where [sK 0 = 0] and
    [sK r = 1 + permute (key hp K) ~n:(n - 1) (r - 1)]: the point
    [((ci n + sx + unit h) / n^2, (cj n + sy + unit (mix h)) / n^2)
    + u0] modulo 1 ([h = key key (-1)]); then Shirley and Chiu's concentric map onto
    the disc, with the library's [sin] and [cos]. *)

val render : ?limits:Limits.t -> Scene.valid -> Image.t
(** [render ~limits scene] is the image of [scene]: every pixel of the canvas
    (section 8), clamped and rounded by {!Color.to_byte}. Reflections are
    followed in a loop, not by recursion: any depth fits in the stack, and
    memory grows with the reflections of one ray (a few words a level).
    @raise Limits.Work_exceeded as soon as the ray-object tests counted so
    far pass the work bound of [limits] (default {!Limits.default};
    {!Limits.work_budget}): each test is counted and checked as it is done,
    in every ray of every pixel. *)
