(** Raytrace's side of the benchmark against Embree (issue 28): the camera
    rays of a prepared scene, written as a file that the C driver
    [embree_rays.c] casts unchanged, and raytrace's own hit mask of the
    same rays, timed. Shared by [raytrace_rays.exe] and the test suite
    [embree]. *)

open Raytrace.Private

val write_rays : Prepared.t -> string -> unit
(** [write_rays p path] writes to [path] the camera ray of every pixel of
    [p]'s canvas, rows from the top, each row left to right: six
    little-endian float64s per pixel, origin then direction, computed from
    [p]'s per-column and per-row viewport coordinates and camera by the
    operations of the kernel's camera rays (so the very doubles the tracer
    casts, whose range is [(1, inf)]). *)

type result = {
  cpu_s : float;  (** CPU time of the loop over the pixels. *)
  rays : int;  (** Pixels, one camera ray each. *)
  hits : int;  (** Pixels whose camera ray hit an object. *)
}
(** The type for the measures of {!cast}. *)

val cast : Prepared.t -> Bytes.t -> result
(** [cast p mask] traces every pixel of [p]'s canvas ({!Trace.pixel}, in
    the order of {!write_rays}) and sets byte [row * width + col] of
    [mask] to [1] where the camera ray hit an object, [0] elsewhere.
    [mask] has [width * height] bytes. The scene should be the mesh alone,
    an ambient light and recursion depth 0, so that the time is the camera
    ray's.
    @raise Invalid_argument if [mask] does not have [width * height] bytes. *)
