(** The viewport (document section 3).

    The viewport is the frame of [width x height] world units, frontal to the
    camera at [distance] along its orientation, through which the camera
    looks. The document's values [V_w = V_h = d = 1] give a field of view of
    about 53 degrees. *)

type t = private { width : float; height : float; distance : float }
(** The type for viewports: [V_w], [V_h] and [d], all positive. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf vp] prints [vp] as its [viewport] form in the scene-file
    syntax. *)

val show : t -> string
(** [show x] is [x] formatted by {!pp}. *)

val equal : t -> t -> bool
(** [equal a b] is [true] iff [a] and [b] are equal field by field, floats
    compared with [=]. *)

val v : width:float -> height:float -> distance:float -> t
(** [v ~width ~height ~distance] is the viewport with these dimensions. *)

val width : t -> float
(** [width vp] is [V_w], in world units. *)

val height : t -> float
(** [height vp] is [V_h], in world units. *)

val distance : t -> float
(** [distance vp] is [d], the distance from the camera to the viewport,
    in world units. *)

val default : t
(** [default] is the document's viewport, [V_w = V_h = d = 1]. *)

val check_dimension : string -> float -> (float, [> `Msg of string ]) result
(** [check_dimension what x] is {!Limits.check_size} of the viewport's
    [what] ("width", "height", "distance"). *)

val validate : t -> (t, [> `Msg of string ]) result
(** [validate vp] checks the three dimensions with {!check_dimension}. *)

val of_canvas : t -> canvas_width:int -> canvas_height:int -> int -> int -> Vec3.t
(** [of_canvas vp ~canvas_width:gw ~canvas_height:gh gx gy] is the point
    [(V_x, V_y, d)] of the viewport seen through the canvas pixel [(gx, gy)]
    (centered canvas coordinates, {!Raytrace.Private.Canvas}), with [V_x = G_x * V_w / G_w]
    and [V_y = G_y * V_h / G_h], multiplied before dividing as the document
    writes it. *)

val of_canvas_f : t -> canvas_width:int -> canvas_height:int -> float -> float -> Vec3.t
(** [of_canvas_f] is {!of_canvas} at fractional canvas coordinates, for rays
    through points inside a pixel. On integral coordinates it is equal to
    {!of_canvas}. *)
