(** Raytrace's side of the benchmark against Embree (issue 28): the camera
    rays of a prepared scene and shadow rays from their hits, written as
    files that the C driver [embree_rays.c] casts unchanged, and
    raytrace's own hit masks of the same rays, timed. Shared by
    [raytrace_rays.exe] and the test suite [embree]. The scene should be
    a mesh alone (every object a triangle), an ambient light and
    recursion depth 0. *)

open Raytrace.Private

val camera_rays : Prepared.t -> float array
(** [camera_rays p] is the camera ray of every pixel of [p]'s canvas, rows
    from the top, each row left to right: six floats per pixel, origin
    then direction, computed from [p]'s per-column and per-row viewport
    coordinates and camera by the operations of the kernel's camera rays
    (so the very doubles the tracer casts, whose range is [(1, inf)]). *)

val write_floats : float array -> string -> unit
(** [write_floats a path] writes [a] to [path], little-endian float64s. *)

val write_rays : Prepared.t -> string -> unit
(** [write_rays p path] is [write_floats (camera_rays p) path]. *)

type result = {
  cpu_s : float;  (** CPU time of the loop over the rays. *)
  rays : int;  (** Rays cast. *)
  hits : int;  (** Rays that hit an object (shadow rays: that are blocked), counted once. *)
}
(** The type for the measures of the casts. *)

val cast : Prepared.t -> Bytes.t -> result
(** [cast p mask] traces every pixel of [p]'s canvas ({!Trace.pixel}: the
    camera ray and the pixel's shading, in the order of {!camera_rays})
    and sets byte [row * width + col] of [mask] to [1] where the camera
    ray hit an object, [0] elsewhere.
    @raise Invalid_argument if [mask] does not have [width * height] bytes. *)

val cast_camera : Prepared.t -> Bytes.t -> result
(** [cast_camera p mask] is {!cast} by {!Trace.camera_hit}: the search for
    the camera ray's first hit alone, without the pixel's shading. The
    same mask. *)

val shadow_rays : Prepared.t -> light:Raytrace.Vec3.t -> float array
(** [shadow_rays p ~light] is, for every pixel whose camera ray hits an
    object (in the order of {!camera_rays}), the shadow ray toward the
    point [light] from the point of the camera ray at [t (1 - 2^-10)],
    where [t] is its hit's ({!Trace.roots}): in front of the surface by
    about a thousandth of its distance from the camera. Six floats a ray,
    origin then direction (the light minus the origin), range [(0, 1)]. *)

val rounds : camera:int -> shadow:int -> int
(** [rounds ~camera ~shadow] is how many times the [shadow] shadow rays
    are cast so that they are about as many as the [camera] camera rays:
    [camera / shadow], at least 1 (the C driver computes the same). *)

val cast_shadows : Prepared.t -> float array -> rounds:int -> Bytes.t -> result
(** [cast_shadows p rays ~rounds mask] casts the shadow rays [rays] (six
    floats each, {!Trace.shadow_blocked}) [rounds] times over and sets
    byte [k] of [mask] to [1] where ray [k] is blocked, [0] elsewhere.
    @raise Invalid_argument if [rays] is not six floats a ray or [mask]
    has not one byte per ray. *)

val build_alone : Prepared.t -> float
(** [build_alone p] is the CPU seconds of {!Bvh.build_boxes} (leaves of
    16, as {!Prepared.prepare}'s for a mesh) over the bounds of the
    triangles of [p], in object order: the hierarchy's build alone, made
    again after [p]'s, beside prepare's whole time. *)
