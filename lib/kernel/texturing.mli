(** Image textures in the kernel: a textured material's colour at a hit.

    The mappings of {!Texture_map} (spherical, planar, box, uv), written
    again for the per-ray path: they read the prepared scene's flat arrays
    ({!Prepared.t}'s [texture_table], [texels], [uv] and the shapes'
    geometry), write the texture coordinates to the per-ray record's [tu]
    and [tv] ({!Scratch}), and look the image up with {!Texture}'s
    bilinear filter on [texels]. Nothing is allocated and no float crosses
    a call: the colour is left in the tracer's own colour arrays. *)

val colour : Tracer.t -> int -> int -> unit
(** [colour tr i m] writes to [tr.red.(m)], [tr.green.(m)] and
    [tr.blue.(m)] the colour, channels in [\[0, 255\]], of the texture of
    material [m] ([tr.p.texture_of.(m) >= 0]) at the hit of the ray in
    [tr.s] at [tr.s.t] on the object in slot [i], whose kind fits the
    texture's mapping (a sphere for [spherical], a plane for [planar], a
    box for [box], a mesh's triangle for [uv]; a CSG solid whose leaf
    there is a sphere or a box, the one or the other, mapped in the frame
    of the transformed operands around it): the point is taken as
    [O + t D], before the robust mode moves it off the surface. The
    colour stays there until the next call for [m]: the tracer reads it
    at once, before tracing any other ray that may meet [m]. *)

val colour_at : Tracer.t -> int -> Tracer.t -> int -> unit
(** [colour_at tr m g i] is [colour] for the material [m] of [tr]'s
    scene, on the surface that tracer [g] found in its slot [i] (a CSG
    solid's slot: the leaf it hit), at [g.s.t] on the ray in [g.s]: an
    instance's hit, whose surface its bottom level's tracer [g] found
    on the ray carried into the object's frame, takes the texture of the
    world's material [m] (the object's own texture, or the instance's own
    material's), laid in that frame. [colour tr i m] is
    [colour_at tr m tr i]. *)
