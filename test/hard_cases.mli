(** Rays and spheres where the textbook quadratic loses its digits, across
    many orders of magnitude (scales 1e-6 to 1e6, translations up to 1e6). *)

type case = { sphere : Raytrace.Sphere.t; origin : Raytrace.Vec3.t; direction : Raytrace.Vec3.t }
(** A ray [origin + t direction] and a sphere. *)

val families : (string * case QCheck.Gen.t) list
(** The families of hard cases, by name: far tiny spheres (radius down to
    1e-9 of the distance), grazing rays (within 1e-12 of tangent), huge
    spheres seen from just above their surface, rays leaving a surface
    point, and general position. *)

val pp : Format.formatter -> case -> unit
(** [pp] prints a case with every float in full. *)
