(** One pixel at a time: the colour the renderer computes for a pixel,
    without rendering the image (for tests, games and teaching).

    A value of type {!t} holds the prepared scene and a tracer, made once;
    each {!color} then traces one pixel with the renderer's own code, in
    the scene's mode (the document's epsilon, or robust without one). *)

type t
(** The type for tracers of single pixels of one scene. *)

val v : ?skips:bool -> Scene.valid -> t
(** [v ~skips scene] prepares [scene] for tracing single pixels; [skips]
    is as for {!Render.image} (it changes no colour byte). *)

val scene : t -> Scene.valid
(** [scene p] is the scene of [p]. *)

val color : t -> int -> int -> Color.t
(** [color p x y] is the colour of the pixel at column [x] (from the left)
    and row [y] (from the top) of the image of [p]'s scene, one ray per
    pixel, unclamped (channels may exceed [255]): {!Color.to_byte} of its
    channels are the bytes that {!Render.image} stores there.
    @raise Invalid_argument if [(x, y)] is outside the canvas. *)
