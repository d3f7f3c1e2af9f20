(** Writing a PPM file while its image is being rendered.

    With several jobs the parent process only waits while the workers
    trace: it can write the rows that are done, and flush them to disk, so
    that what is left to write when the last row is traced is the last few
    rows, not the whole file. The file is still written atomically
    ({!File_io.write_atomic}): a render that fails leaves no file. *)

val render_to :
  string ->
  (rows_done:(Image.t -> int -> unit) -> ('a, [ `Msg of string ]) result) ->
  ('a * float, [> `Msg of string ]) result
(** [render_to path render] is [Ok (x, s)] where [Ok x] is
    [render ~rows_done], whose image has been written to [path] as a PPM
    file ({!Raytrace.Image.Ppm.output}) and [s] is the seconds the writing took
    after [render] returned. [render] must call [rows_done img r] as
    {!Render_jobs.image} does: whenever the first [r] rows of [img] are
    final, the last time with [r] its height, before it returns [Ok]. Where
    [path] is replaced by a temporary file ({!File_io.replaces}), the rows
    are written as they come; elsewhere (standard output, a FIFO, a device)
    the image is written after [render], so that a failed render writes
    nothing there either. [Error] is [render]'s, or {!File_io.write_atomic}'s
    (then [render] may not have been called); [path] is then left as it
    was. *)
