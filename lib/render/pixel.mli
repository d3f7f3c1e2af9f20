(** One pixel at a time: the colour the renderer computes for a pixel,
    without rendering the image (for tests, games and teaching).

    A value of type {!t} holds the prepared scene and a tracer, made once;
    each {!color} then traces one pixel with the renderer's own code, in
    the scene's mode (the document's epsilon, or robust without one).

    @canonical Raytrace.Render.Pixel *)

type t
(** The type for tracers of single pixels of one scene. *)

val v : ?skips:bool -> ?samples:int -> Scene.valid -> t
(** [v ~skips ~samples scene] prepares [scene] for tracing single pixels
    with [samples x samples] rays each ([samples] defaults to [1]); [skips]
    and [samples] are as for {!Render.image} ([skips] changes no colour
    byte; [samples] as [raytrace render --samples], full sampling, not
    adaptive).
    @raise Invalid_argument if {!Sampling.v} refuses [samples] (it is not
    in [\[1, ]{!Sampling.max_samples}[\]]). *)

val scene : t -> Scene.valid
(** [scene p] is the scene of [p]. *)

val samples : t -> int
(** [samples p] is the side of [p]'s grid of samples: [p] traces
    [samples p * samples p] rays per pixel. *)

val color : t -> int -> int -> Color.t
(** [color p x y] is the colour of the pixel at column [x] (from the left)
    and row [y] (from the top) of the image of [p]'s scene: with one
    sample, the colour of the ray through the pixel's centre, unclamped
    (channels may exceed [255]); with [n x n] samples ({!v}), the mean of
    the samples' colours each clamped to [\[0, 255\]] first, as
    the tracer sums them. Either way {!Color.to_byte} of its
    channels ({!Color.to_rgb8} of it) are the bytes that {!Render.image}
    with the same [samples] stores there.
    @raise Invalid_argument if [(x, y)] is outside the canvas. *)
