(** The Graphics window: the document's way of showing the picture.

    The window has the canvas size; pixels are drawn with the document's
    centered-origin [plotc] (section 1). *)

val plotc : int -> int -> int * int * int -> unit
(** [plotc x' y' color] plots [color] at canvas coordinates [(x', y')],
    the origin in the middle of the window and [y] up: the document's
    [plotc], verbatim. *)

val show : title:string -> Raytrace.Image.t -> (unit, [ `No_display of string | `Msg of string ]) result
(** [show ~title img] opens a window of [img]'s size titled [title], draws
    [img] pixel by pixel through {!plotc}, and waits until the user presses
    [q] or Escape or closes the window. [`No_display] if no window can be
    opened (no X server), with the reason. *)
