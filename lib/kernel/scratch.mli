(** The per-ray state of the fast tracer.

    One mutable record of floats per tracer holds the ray being traced, the
    roots of the last intersection test, the hit point and its normal, and
    the colour being computed. Every part of the kernel reads and writes
    it: the traversal ({!Trace}), and the root and normal routines of each
    shape ({!Sphere}, {!Plane}, {!Triangle}, {!Box}). It sits below them
    all, so that none of them needs another to reach the ray.

    All its fields are floats, so OCaml stores the record flat and reads
    and writes its fields without boxing: this is how floats cross
    function calls on the per-ray path without allocating (OCaml 4.13 has
    no flambda, and boxes a float returned by a call that is not
    inlined).

    @canonical Raytrace.Private.Scratch *)

type t = {
  mutable ox : float;  (** Ray origin [O]. *)
  mutable oy : float;
  mutable oz : float;
  mutable dx : float;  (** Ray direction [D], not necessarily unit length. *)
  mutable dy : float;
  mutable dz : float;
  mutable t_min : float;  (** The ray sees hits with [t_min < t < t_max]. *)
  mutable t_max : float;
  mutable t : float;  (** Root of the best hit so far, [infinity] for none. *)
  mutable near : float;
      (** Roots of the last intersection test, [near <= far]; a flat shape
          gives [near = far]. *)
  mutable far : float;
  mutable gx : float;  (** Canvas point of the primary ray. *)
  mutable gy : float;
  mutable px : float;  (** Hit point. *)
  mutable py : float;
  mutable pz : float;
  mutable nx : float;  (** Unit normal at the hit point. *)
  mutable ny : float;
  mutable nz : float;
  mutable vx : float;  (** View vector, [-D]. *)
  mutable vy : float;
  mutable vz : float;
  mutable intensity : float;  (** Light received at the hit point. *)
  mutable r : float;  (** Colour of the ray, unclamped. *)
  mutable g : float;
  mutable b : float;
  mutable acc_r : float;  (** Sum of clamped sample colours. *)
  mutable acc_g : float;
  mutable acc_b : float;
  mutable offset : float;
      (** Robust mode: how far secondary rays start off the surface they
          leave, along its normal (a bound on the rounding error of the
          hit point; see {!Trace}). *)
  mutable sx : float;
      (** The ray in the frame of the triangle test ([Triangle.shear]):
          the shear [sx], [sy], [sz] and the origin's coordinates [okx],
          [oky], [okz] on its axes. Found once per ray, not per
          triangle. *)
  mutable sy : float;
  mutable sz : float;
  mutable okx : float;
  mutable oky : float;
  mutable okz : float;
  mutable tu : float;
      (** The texture coordinates [(u, v)] of the hit point on a
          textured surface ({!Texturing}), written by its mapping and read
          by its lookup. *)
  mutable tv : float;
  mutable first_t : float;
      (** The distance parameter of the primary ray's hit (along the ray
          as set, [t = 1] on the viewport plane), written by the tracing
          loops with the first hit; meaningless when the ray hit nothing.
          Adaptive sampling reads it for the lens's circle of confusion. *)
  mutable lens_u0 : float;
      (** A stratified lens's offset [(lens_u0, lens_v0)] on the unit square
          for the pixel whose lens numbers the tracer holds
          ({!Tracer.t}'s [lens_px]): computed once per pixel. *)
  mutable lens_v0 : float;
}
(** The type for per-ray state. *)

val create : unit -> t
(** [create ()] is a state with every field [0.]. *)

val set_ray : t -> Vec3.t -> Vec3.t -> unit
(** [set_ray s o d] sets the ray of [s] to [O = o], [D = d]. *)

val normal_to_world : t -> float array -> int -> unit
(** [normal_to_world s m o] turns the normal in [s], found in an object's
    frame, into the world's: by the transpose of the world-to-object
    matrix [m] stored at [m.(o)] (12 floats, 3 rows of [a b c t]), which
    is the inverse transpose of the object's transform, then to unit
    length. Reads and writes [s] alone: nothing boxed crosses the call. *)
