(** The version of raytrace. *)

val v : string
(** [v] is the version of raytrace, from [dune-project] (e.g. ["0.2.0"]). *)
