(** The properties that every input must satisfy, whatever its bytes.

    Shared by the coverage-guided fuzz target ([fuzz/fuzz_raytrace.ml],
    crowbar under AFL++) and the normal tests, which replay the regression
    corpus ([test/corpus/]) and mutate the example files with QCheck. Each
    property runs the code under test, catches every exception (stack
    overflow and out of memory included) and checks the outcome; [Error]
    says what went wrong, for the fuzzer to report. *)

val scene_file : string
(** [scene_file] is ["fuzz.scene"], the file name given to the parser. *)

val scene : ?files:(string * string) list -> string -> (unit, string) result
(** [scene ~files text] is [Ok ()] if {!Raytrace.Scene_file.of_string} on
    [text] returns without raising, and either
    - [Ok s] where [s] passes {!Raytrace.Scene.validate}, prints back
      ({!Raytrace.Scene_file.to_string}) to text that parses to an equal
      scene, and renders at 3 x 2 pixels with {!Raytrace.Render.image}
      under a work budget of {!work_budget} tests, to an image or to one
      line: the estimate's refusal, or a render stopped after at most
      twice the budget; and under a budget of 100 tests, to an image or
      one line, stopped (if it is) after at most 20100 tests; or
    - [Error m] where [m] is one line that starts with
      [fuzz.scene:LINE:COLUMN: ] (a line and a column that exist in
      [text], 1-based) or, for a text beyond the size bound, with
      [fuzz.scene: ].
    Its mesh forms and textures read the files of [files] (name, text;
    default none) as the command line reads them: meshes with its OBJ
    parser and bounds, textures with its PPM reader and pixel bound and
    its ["cannot read texture file: "] prefix; another name is a file
    that cannot be read. *)

val work_budget : int
(** [work_budget] is [1_000_000]: the [`Work] bound of the renders of
    {!scene}. *)

val random_scene : Random.State.t -> string * (string * string) list
(** [random_scene rand] is a scene text of every form (spheres, planes,
    triangles, boxes, meshes, capped and open cylinders and cones (pointed
    or not), disks, tori, CSG solids nested up to 4 deep with every
    operation on every closed kind (and, now and then, an open one), glass with transparency, refractive index and the Fresnel
    term, mirrors, checker patterns, image textures with every mapping,
    every light (issue 27's area, sphere and spot lights with all their
    fields among them), a camera with a lens now and then) with its files
    (name, text): its meshes (OBJ text: a closed tetrahedron, with
    texture coordinates or not, or loose triangles, now and then a broken
    line) and its textures (small P6 and P3 images, and files that are
    empty, truncated, huge in declared size or of another format),
    most of it valid, with values at or beyond the edges
    of their domains now and then; for {!scene}. *)

val ppm : string -> (unit, string) result
(** [ppm bytes] is [Ok ()] if {!Raytrace.Image.Ppm.of_string} on [bytes] returns
    without raising, and either [Ok img] where [img] written as P6 reads
    back equal, or [Error m] where [m] is one non-empty line; and if
    {!Raytrace.Image.Ppm.header_comments} does not raise, and
    {!Raytrace.Part.of_string} (the parts that [raytrace merge] reads)
    returns a part that reads back once written, or one line of error. *)

val scene_tokens : string array
(** [scene_tokens] are fragments of scene files, valid and hostile (form
    and field names, every shape's and light's form among them, the
    lens's and textures' fields, numbers at and beyond every bound, NaN, comments,
    strings, parentheses), from which fuzzers and mutators build inputs. *)

val ppm_tokens : string array
(** [ppm_tokens] are fragments of PPM files (magic numbers, sizes and
    maxvals at and beyond their bounds, comments, whitespace). *)

val mutate : Random.State.t -> tokens:string array -> string -> string
(** [mutate rand ~tokens s] is [s] after 1 to 8 random edits: bytes
    deleted, replaced or inserted, a token of [tokens] inserted, a span
    duplicated or wrapped in up to 10000 parentheses, the text truncated. *)
