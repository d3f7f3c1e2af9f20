(** What a render cost: rays by kind, intersection tests, time, allocation.

    @canonical Raytrace.Render.Stats *)

type t = {
  pixels : int;  (** Pixels rendered. *)
  primary : int;  (** Primary rays, from the camera. *)
  shadow : int;  (** Shadow rays, toward lights (section 7.7). *)
  reflection : int;  (** Mirror rays (section 7.8). *)
  tests : int;  (** Ray-sphere intersection tests. *)
  box_tests : int;  (** Ray-box tests in the sphere hierarchy. *)
  early_stops : int;  (** Reflections stopped by the exact weight bound. *)
  decided : int;
      (** Lit points where an adaptive area light's four corners agreed
          (all seen or all hidden): its samples cast no shadow ray there
          (an estimate, {!Light}, "Penumbra-only sampling"). *)
  penumbra : int;  (** Lit points where they disagreed: every sample traced. *)
  umbra : int;
      (** Area light samples that cast no shadow ray because one convex
          object stops the rays of the corner cells' samples around them
          (exact: the kernel's [Lighting] (lib/kernel/lighting.mli)). *)
  whole : int;
      (** Lit points that see an area or sphere light whole: no blocker's
          box meets the hull of the point and the light, and no shadow ray
          is cast to it (exact: the kernel's [Lighting]
          (lib/kernel/lighting.mli)). *)
  jobs : int;  (** Processes that traced. *)
  prepare_s : float;  (** Seconds spent preparing the scene, by the render's clock (below). *)
  trace_s : float;
      (** Seconds spent tracing, by the render's clock: {!Render.image}'s [clock],
          processor time ([Sys.time]) unless the caller gives another; the
          command line's renders (all their processes together) read the wall clock. *)
  minor_words : float;  (** Minor-heap words allocated by the tracing loops. *)
}
(** The type for render statistics.

    @canonical Raytrace.Render.Stats.t *)

val pp : Format.formatter -> t -> unit
(** [pp ppf x] prints [x] as an OCaml record (derived). *)

val show : t -> string
(** [show x] is [x] formatted by {!pp}. *)

val rays : t -> int
(** [rays s] is [s.primary + s.shadow + s.reflection]. *)

val pp_table : Format.formatter -> t -> unit
(** [pp_table ppf s] prints [s] as a small table, one figure per line, with
    rays per second and allocation per pixel. *)
