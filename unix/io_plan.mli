(** The files a command reads and writes, checked together before any work.

    A command names its inputs (a scene, images, parts) and every path it
    will write (each frame, each part, a merged image; [-] for standard
    output). {!check} refuses the plan when an output is an input, or when
    two outputs are one file, however the names reach it: symbolic links,
    hard links, [..], [/dev/stdout] or [/proc/self/fd/1] for a redirected
    standard output. Existing files are compared by device and inode,
    files still to be created by the real path of their directory and their
    name. Streams (character devices, FIFOs, sockets, and the files that
    standard output and error already write to) may take several outputs:
    they are written to in turn, never replaced ({!File_io.write_atomic}). *)

val check :
  inputs:(string * string) list -> outputs:(string * string) list -> (unit, [> `Msg of string ]) result
(** [check ~inputs ~outputs] is [Ok ()] if no output of [outputs] is the
    same file as an input of [inputs] and no two outputs are the same file
    (streams excepted). Each element is [(what, path)], [what] naming it in
    messages ("scene", "part p.ppm", "frame 3"); the output path [-] is
    standard output. Missing inputs are ignored (reading them fails
    later). [Error] names the output path and what it collides with. *)
