(** Image textures on objects: which image, and how a surface point finds
    its place in it.

    A material's texture ([(texture (file "earth.png") (mapping spherical))]
    in scene text, DESIGN.md "Round 3: soft light, lenses, textures")
    replaces the material's colour by the image's colour at the hit point.
    The mappings below turn a point of an object's surface into texture
    coordinates [(u, v)] ({!Texture}: [u] left to right, [v] bottom to
    top, the image over [\[0, 1\] x \[0, 1\]]). They are pure functions of
    the object's geometry and the point, written for the scene's
    coordinates: [x] to the right, [y] up, [z] away from a camera at the
    origin that looks along [+z] (a left-handed frame, as in CGFS), so
    that an image seen from the front of a surface reads left to right,
    not mirrored.

    The renderer draws them on objects placed as written, on
    transformed and instanced ones (in the object's own frame), as a
    transform's or instance's own material (on every surface of its
    object, in the object's frame) and on a CSG solid's sphere, box and
    mesh operands, placed or transformed (a mesh's [uv] through its
    [vt]): the kernel's own copy of these mappings
    and of {!Texture}'s lookup is [Texturing], and the executable
    specification [Literal] calls the functions below.

    @canonical Raytrace.Material.Texture *)

(** {1:mappings Mappings} *)

type mapping =
  | Spherical  (** A sphere's point by its longitude and latitude. *)
  | Planar  (** A plane's point by its coordinates along two axes of the plane. *)
  | Box  (** A box's point by its place on its face, the whole image on each face. *)
  | Uv  (** A mesh's point by its triangle's [vt] coordinates. *)
(** The type for the ways an image is laid on a surface. *)

val mapping_name : mapping -> string
(** [mapping_name m] is the scene-text name of [m]: ["spherical"],
    ["planar"], ["box"] or ["uv"]. *)

val mapping_of_string : string -> mapping option
(** [mapping_of_string s] is the mapping named [s] by {!mapping_name}, if
    any. *)

val mapping_names : string list
(** [mapping_names] is the names of every mapping, in the order above. *)

val wraps : mapping -> Texture.wrap * Texture.wrap
(** [wraps m] is what the lookups of [m] do beyond the image's edges, in
    [u] then [v]: [Repeat, Clamp] for [Spherical] (the image closes
    around the sphere at its seam; the poles are its top and bottom
    rows), [Repeat, Repeat] for [Planar] (the plane is tiled) and [Uv]
    (as OBJ's [vt] coordinates outside [\[0, 1\]] mean), [Clamp, Clamp]
    for [Box] (each face holds one whole copy, whose edges must not take
    the colour of the opposite edge). *)

val spherical : center:Vec3.t -> Vec3.t -> float * float
(** [spherical ~center p] is the [(u, v)] of point [p] of a sphere of
    centre [center], from the direction [d = p - center] (of any
    length [> 0]): [u = 0.5 + atan2 d.x (-. d.z) / (2 pi)] and
    [v = 0.5 + asin (d.y / |d|) / pi]. The point facing the camera,
    [d = (0, 0, -1)], is the image's centre [(0.5, 0.5)]; [u] grows
    eastward, to the camera's right ([d = (1, 0, 0)] gives [u = 0.75]);
    the seam [u = 0 = 1] is at the back, [d = (0, 0, 1)]; the north pole
    [d = (0, 1, 0)] is [v = 1], the top row. [u] is in [\[0, 1\]], [v]
    in [\[0, 1\]]. At [d = 0] it is [(0.5, 0.5)]. *)

val planar_axes : Vec3.t -> Vec3.t * Vec3.t
(** [planar_axes n] is the unit axes [(e_u, e_v)] of a plane of normal
    [n] ([n <> 0], any length): [e_u = unit (n x r)] and
    [e_v = e_u x unit n], where the reference [r] is [(0, 0, 1)] when
    [y] is [n]'s largest component in magnitude (a floor or a ceiling),
    and [(0, 1, 0)] otherwise (a wall, which then stands upright:
    [e_v] is the plane's steepest way up). A floor [n = (0, 1, 0)] gets
    [e_u = (1, 0, 0)], [e_v = (0, 0, 1)] (the image upright, seen from
    above by a camera that looks along [+z]); a wall facing the camera,
    [n = (0, 0, -1)], gets [e_u = (1, 0, 0)], [e_v = (0, 1, 0)].
    @raise Invalid_argument if [n] is zero or not finite. *)

val planar : point:Vec3.t -> normal:Vec3.t -> size:float -> Vec3.t -> float * float
(** [planar ~point ~normal ~size p] is the [(u, v)] of point [p] of the
    plane through [point] of normal [normal]:
    [u = ((p - point) . e_u) / size], [v = ((p - point) . e_v) / size]
    with the axes of {!planar_axes}: one copy of the image on each square
    of side [size] (world units), the plane's [point] at a corner of one.
    @raise Invalid_argument as {!planar_axes}, or if [size] is not
    finite and [> 0]. *)

type face = Min_x | Max_x | Min_y | Max_y | Min_z | Max_z
(** The type for a box's faces: [Min_x] is the face [x = min.x], and so
    on. *)

val box_face : min:Vec3.t -> max:Vec3.t -> Vec3.t -> face
(** [box_face ~min ~max p] is the face of the box [\[min, max\]] nearest
    to [p] (of a hit on the box's surface: the face it lies on), the
    distance to a face being [|p.x - min.x|] and so on; on an edge or a
    corner the first face in the order of {!face}'s constructors. *)

val box : min:Vec3.t -> max:Vec3.t -> Vec3.t -> face * float * float
(** [box ~min ~max p] is the face of [p] ({!box_face}) and the [(u, v)]
    of [p] on it: the whole image on each face, upright and read left to
    right as seen from outside the box. With [sx = (p.x - min.x) /
    (max.x - min.x)], [sy], [sz] likewise:
    - [Min_z] (the front, facing a camera that looks along [+z]):
      [(sx, sy)]; [Max_z] (the back): [(1 - sx, sy)];
    - [Min_x] (the left side): [(1 - sz, sy)]; [Max_x]: [(sz, sy)];
    - [Max_y] (the top, seen from above with [+z] up the image):
      [(sx, sz)]; [Min_y] (the bottom): [(sx, 1 - sz)].
    A box of zero extent along an axis gives [0] for that axis's
    [s]. *)

val barycentric : Vec3.t -> Vec3.t -> Vec3.t -> Vec3.t -> float * float
(** [barycentric a b c p] is [(b1, b2)], the weights of corners [b] and
    [c] of the point [p] of the plane of the triangle [a b c]: [p = a +
    b1 (b - a) + b2 (c - a)] (the weight of [a] is [1 - b1 - b2]), from
    the least-squares formula with the dot products of the edges, as in
    Ericson's Real-Time Collision Detection, 3.4. A degenerate triangle
    gives [(0, 0)]. *)

val interpolate : b1:float -> b2:float -> float * float -> float * float -> float * float -> float * float
(** [interpolate ~b1 ~b2 t0 t1 t2] is the texture coordinates at the
    point of barycentric weights [(1 - b1 - b2, b1, b2)] of a triangle
    whose corners have the coordinates [t0], [t1], [t2] (its [vt]):
    [t0 + b1 (t1 - t0) + b2 (t2 - t0)], component by component. *)

(** {1:textures A material's texture} *)

type t = private {
  file : string;  (** The image file as the scene names it, for printing back. *)
  mapping : mapping;
  size : float;  (** The side of one copy of the image, for [Planar]: [> 0], finite. *)
  image : Texture.t;  (** The decoded pixels. *)
}
(** The type for a material's texture. *)

val v : ?size:float -> file:string -> mapping -> Texture.t -> t
(** [v ~size ~file mapping image] is the texture [image], read from
    [file], laid by [mapping]; [size] defaults to [1]. Not validated:
    see {!validate}. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff the fields are equal (the size with [=],
    the images by {!Texture.equal}). *)

val pp : Format.formatter -> t -> unit
(** [pp ppf t] prints [t] as the field of an object's form:
    [(texture (file "F") (mapping M))], then [ (size S)] when it is not
    [1]; the file name is written as an OCaml string literal, which the
    scene reader reads back. *)

val pp_optional : Format.formatter -> t option -> unit
(** [pp_optional ppf t] prints nothing for [None], and a space then {!pp}
    for [Some t]. *)

val validate : form:string -> t -> (t, [> `Msg of string ]) result
(** [validate ~form t] is [Ok t] if [t.size] is finite and [> 0], and
    otherwise an error naming [form] (["plane texture size must be > 0,
    got 0"]). *)

val mapping_for : string -> mapping option
(** [mapping_for kind] is the mapping an object of the scene-text form
    [kind] takes: [Spherical] for ["sphere"], [Planar] for ["plane"],
    [Box] for ["box"], [Uv] for ["mesh"], and [None] for the others,
    which take no texture. *)
