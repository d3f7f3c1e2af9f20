(** The progress line of a long render on a terminal.

    [raytrace render] shows, on stderr, how far the work has gone, how fast
    it goes and how long it should still take, on one line rewritten in
    place ([\r]) a few times a second:
    [raytrace: 42%, 12.3 M rays/s, 1 min 05 s left (frame 3 of 48)].
    The line appears only once the work has taken a second (a quick render
    shows nothing), and only on a terminal: a redirected stderr (a log, a
    pipe, a test) gets nothing at all. *)

type t
(** The type for progress lines. *)

val wanted : quiet:bool -> bool
(** [wanted ~quiet] is [true] iff not [quiet] and stderr is a terminal:
    whether to {!create} a line at all. *)

val create : ?after:float -> frames:int -> unit -> t
(** [create ~after ~frames ()] is a line for work of [frames] (at least 1)
    frames, starting now, that appears once the work has taken [after]
    seconds (default 1). *)

val update : t -> rows:int -> total:int -> rays:int -> unit
(** [update m ~rows ~total ~rays] says that [rows] of the [total] rows of
    the current frame are finished, after [rays] rays in that frame (the
    arguments of {!Raytrace.Render.image}'s [progress]). It redraws the
    line if the work started at least [after] seconds ago and the line was last
    drawn at least a quarter of a second ago. *)

val next_frame : t -> unit
(** [next_frame m] says that the current frame is finished and the next
    one starts. *)

val clear : t -> unit
(** [clear m] erases the line, if it is shown, so that a message can be
    printed; the next {!update} draws it again. *)
