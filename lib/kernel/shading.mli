(** The lighting formulas (document sections 7.5 to 7.8).

    The total intensity at a point is
    [I_a + sum_i I_i (<L_i, N> / (|L_i| |N|) + (<R_i, V> / (|R_i| |V|))^s)],
    each term counted only when positive, and each light counted only when
    no object shadows it (7.7). These functions are the terms of that sum;
    {!Literal} adds them up as the document does.

    @canonical Raytrace.Private.Shading *)

val diffuse : intensity:float -> l:Vec3.t -> n:Vec3.t -> float
(** [diffuse ~intensity:i ~l ~n] is the diffuse term [i <L, N> / (|L| |N|)]
    (7.5) if [<L, N> > 0], and [0.] when the light is behind the surface. It
    is computed as [i * <N, L> / (|N| * |L|)], the order of CGFS. *)

val reflect : Vec3.t -> Vec3.t -> Vec3.t
(** [reflect l n] is [R = 2 <L, N> N - L] (7.6), the mirror image of [l]
    about the unit normal [n]; computed as [N (2 <L, N>) - L]. It is used
    both for the light's reflection and for the mirror ray, [reflect V N]
    (7.8). *)

val specular : intensity:float -> s:float -> r:Vec3.t -> v:Vec3.t -> float
(** [specular ~intensity:i ~s ~r ~v] is the specular term
    [i (<R, V> / (|R| |V|))^s] (7.6) if [<R, V> > 0], and [0.] otherwise.
    The caller skips it for matte objects ([s = -1], {!Sphere.matte}); for
    [s = 0] it is [i] whenever [<R, V> > 0]. *)
