(** The texture images of the example scenes ([scenes/earth.ppm] and
    [scenes/tiles.ppm], made by [scenes/textures.ml]), built into the
    page: a web page reads no files, so these are the textures a scene
    typed into it can name. *)

val files : (string * string) list
(** [files] is each image's file name as the example scenes write it
    ([(file "earth.ppm")]) and its contents, a plain-text PPM. *)
