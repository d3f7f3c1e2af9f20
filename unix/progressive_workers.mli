(** Worker processes for the coarse-first renderer of the window
    ([Raytrace_view.Progressive]): its full-resolution rows traced by
    forked processes into shared memory ({!Parallel}). *)

val v : jobs:int -> width:int -> height:int -> Raytrace_view.Progressive.workers
(** [v ~jobs ~width ~height] is [jobs] workers rendering [width x height]
    images, over memory shared with them: the image and their counters.
    @raise Invalid_argument if [jobs < 2].
    @raise Failure or [Unix.Unix_error] if no shared memory can be
    mapped. *)
