(** Lighting (sections 7.4 to 7.7 of the document): the total intensity
    of the lights at a hit point, with their shadow rays. *)

val lighting : Tracer.t -> shiny:bool -> specular_of:float array -> int -> unit
(** [lighting tr ~shiny ~specular_of m] leaves in [s.intensity] the total
    intensity at the hit point [s.px..] with unit normal [s.nx..] and view
    vector [s.vx..], for material [m] (its specular exponent
    [specular_of.(m)], used only if [shiny]). Each light's diffuse and
    specular terms are decided before its shadow ray, and with the skips
    ({!Prepared.t}'s [shadow_skip]) a light that would add neither casts
    none; any object stops a shadow ray ({!Traversal.shadowed}). The
    shadow rays reuse the ray fields of [s].

    Area, sphere and spot lights ({!Light}) are summed sample by sample,
    each sample a point light of its own ({!Light}, "Sample points"), the
    numbers drawn from [tr.key]; an adaptive area light first asks its
    corners ({!Light}, "Penumbra-only sampling"). With the skips, an area
    light's samples that lie inside the hull of its four corner cells'
    samples, when one convex object (sphere, plane, box, triangle, disk)
    stops all four of those, cast no shadow ray: that object stops theirs
    too (the proof is at [area] in the implementation), so the sum is the
    same; [tr.counters.umbra] counts them. With the skips, an area or
    sphere light of at least four samples (an area light's stratified, not
    [(sampling uniform)]: the plain Monte Carlo baseline that the
    benchmark measures the others against) casts no shadow ray from a
    point whose hull with the light's rectangle (a sphere light's: the
    square around the disc its samples lie on) meets no plane and no box
    of {!Prepared.t}'s [casters]: nothing can stop those rays, and each
    sample's terms are added as a ray that passes would add them, in the
    same order (the same bytes, adaptive or not: uniform sampling could
    take it too, with the same bytes; exact up to the margins
    stated at [whole_in_view] in the implementation, which cover the
    rounding of the test and of the kernel's hit tests);
    [tr.counters.whole] counts those points. The document's lights take a
    copy of the loop that never asks for the new kinds. *)

val lighting_through : Tracer.t -> shiny:bool -> specular_of:float array -> int -> unit
(** [lighting_through] is {!lighting} with shadow rays that pass through
    transparent objects, the light scaled by the transparency of each
    surface crossed (twice through a ball, once out of the one the ray
    starts in); an opaque object stops them. For the ray tree. *)
