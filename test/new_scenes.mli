(** The scenes beyond the document's spheres, for the tests that run the
    farm (tiles, regions, merge, frames) and the window on them. *)

val all : (string * string) list
(** [all] is each scene of [scenes/] with what it brings beyond spheres,
    such as [("checker.scene", "checker patterns")]: one line per scene,
    where the glass and CSG scenes of issue 14 join. *)

val names : string list
(** [names] is the scene file names of {!all}. *)

val copy_models : string -> unit
(** [copy_models dir] copies the OBJ and PPM files of [scenes/] into [dir], so that
    a copy of a scene in [dir] reads its meshes and textures as the original
    does. *)
