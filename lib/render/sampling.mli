(** Rays per pixel: supersampling, adaptive supersampling and CGFS's
    subsampling, the knobs that trade run time for error (with the
    recursion depth of {!Scene.t}).

    - {e Supersampling} with [samples = n] traces the [n x n] regular grid
      of sample points in every pixel and averages it; deterministic.
      Each sample is clamped to [\[0, 255\]] (as a float) before the
      average and the mean is rounded once: a pixel is the mean of what the
      document would display at its sample points, and one overexposed
      sample cannot brighten a whole pixel. [n = 1] is exactly the
      document's image.
    - {e Adaptive} supersampling with threshold [th] and an odd [n] first
      traces one ray per pixel, through its centre, then traces the rest
      of the [n x n] grid only in pixels whose first ray hit another
      sphere than, or whose bytes differ by more than [th] in some channel
      from, those of a pixel above, below, left or right (CGFS's
      suggestion; POV-Ray's adaptive method 1 is the peer). The grid of an
      odd [n] has the centre as its middle sample, so a refined pixel
      reuses its first ray and is exactly the pixel of full supersampling,
      and an unrefined one is exactly the document's pixel: without a
      lens, adaptive sampling never traces more rays than full
      supersampling (under one, at most the four probes of a pixel more). (An even
      [n] has no centre sample: the first ray would be wasted or taken off
      centre, which measurably raises the error; without a lens the
      renderers refuse it. Under a lens an even [n] is accepted: a refined
      pixel traces the whole [n x n] grid, exactly [--samples n]'s, and
      its first ray is not reused, one ray more than an odd grid's
      [n^2 - 1]; it fills the ladder between odd sides, see
      docs/run-time-against-error.md.)
      Under a thin lens ({!Camera.has_lens}), where one ray per pixel of a
      blurred region is noise and the neighbour test refines it at random,
      a pixel the neighbour test leaves is {e probed} when it is
      {e blurred}: when the circle of confusion of its first ray's hit, or
      of a first ray's within 4 pixels whose circle reaches it, is wider
      than half a pixel (the circle's diameter in pixels: [A |z - f| / z]
      on the plane of focus, for a lens of diameter [A] focused at [f] and
      the hit at depth [z], over a pixel's width there). Its probes are
      four rays from fixed points of the lens's rim, [(+-A/2, 0)] and
      [(0, +-A/2)] in lens coordinates, through the point of its centre on
      the plane of focus, the widest
      rays of the cone whose average the pixel is; it is refined when one
      of them hits another object than its first ray, or gives bytes more
      than [th] apart from its first ray's in some channel (the neighbour
      test's rule), and keeps its first ray when all four agree: inside
      one object's blurred interior, or one checker cell, every lens point
      sees the same. The probes are not samples (nothing averages them),
      are counted as primary rays, take no key (the same rays for every
      process, tile and region) and stop at the first that disagrees.
      What is exact: an unrefined pixel is the one-sample render's, a
      refined one [--samples n]'s, the same for every [--jobs] and tiling.
      What is an estimate: the circle is that of the first ray's hit alone
      (its depth [t d], exact for an orthonormal camera matrix; a
      reflection of a blurred object, or a blurred object that no first
      ray within 4 pixels hits, is not seen); an edge or a small object
      can lie inside the cone between the probes and the centre ray (a
      pixel that sees it in some of its [n x n] samples then keeps its
      first ray, as an area light's corners can miss a small blocker);
      and a pixel whose first ray and neighbourhood are in focus keeps one
      ray (or the full grid at an edge, as for a pinhole). A pinhole's
      circle is 0: its pixels are decided as without a lens, and nothing
      is probed.
    - {e Subsampling} (CGFS, "Performance Optimizations") traces one ray
      per pixel but skips the search for the primary ray's sphere where
      the two neighbours on either side (left and right on even rows, above
      and below on odd rows) hit the same sphere, and assumes it hits that
      one. Approximate, opt-in, measured by the
      benchmark.

    Every mode gives the same image whatever the number of processes: the
    renderers trace it in passes, and a pass reads only what earlier
    passes wrote.

    @canonical Raytrace.Render.Sampling *)

(** {1:settings Settings} *)

type t = private {
  samples : int;  (** [n]: at most [n x n] rays per pixel, [1 <= n <= max_samples]. *)
  adaptive : int option;
      (** Adaptive threshold, in [\[0, 255\]] (then [samples >= 2]; an even
          [samples] only under a lens, which the renderers check), or full
          sampling. *)
  subsample : bool;  (** CGFS's subsampling (then [samples = 1], not adaptive). *)
}
(** The type for sampling settings.

    @canonical Raytrace.Render.Sampling.t *)

val max_samples : int
(** [max_samples] is [64]: the largest grid side, 4096 rays per pixel. *)

val v : ?samples:int -> ?adaptive:int -> ?subsample:bool -> unit -> (t, [> `Msg of string ]) result
(** [v ~samples ~adaptive ~subsample ()] is the settings, or [Error] with a
    one-line message if [samples] (default 1) is outside
    [\[1, max_samples\]], [adaptive] is outside [\[0, 255\]] or given with
    [samples = 1] ({!even_message}), or [subsample] (default [false]) is
    combined with [samples > 1]. *)

val even_message : int -> string
(** [even_message n] is the one-line message of an adaptive [n] refused:
    [n < 2], or an even [n] without a lens (which the renderers refuse,
    {!Raytrace.Render.image}). *)

val one : t
(** [one] is one ray per pixel through its centre: the document's image. *)

val is_one : t -> bool
(** [is_one s] is [true] iff [s] is {!one}. *)

val averaging : t -> bool
(** [averaging s] is [true] iff [s] averages samples, so that tracers must
    average too ({!Raytrace.Render.Pixel} and the renderers see to it). *)

val to_string : t -> string
(** [to_string s] is a short description, e.g. ["1x1"], ["4x4"],
    ["adaptive 5x5 t=8"], ["subsampled"]. *)
