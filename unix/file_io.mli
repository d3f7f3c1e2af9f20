(** Whole-file reads and atomic writes.

    Every file the program writes goes through {!write_atomic}: the data go
    to a temporary file in the target's directory, which is renamed over the
    target only once it is complete, so a failed or interrupted write never
    leaves a truncated file behind, and an existing file keeps its contents
    unless the new ones are complete. Errors are values whose message starts
    with the path. *)

val read : ?check_size:(int -> (int, [ `Msg of string ]) result) -> string -> (string, [> `Msg of string ]) result
(** [read ~check_size path] is the contents of the file [path], read until
    its end (so pipes and [/proc] files work too), opened by {!open_read}.
    [check_size] (default: accept all) is called on the file's length in
    bytes before anything is read, and on the bytes read so far for files
    of unknown length; an [Error m] of it is returned as [path: m], so that
    an oversized file costs no memory. *)

(** {1:opening Opening without blocking} *)

type opened = {
  channel : in_channel;  (** Binary, blocking, at the file's start (after [first]). *)
  stats : Unix.stats;  (** The file's, when it was opened. *)
  first : string;  (** The text's first bytes, already read from a FIFO; [""] for other files. *)
}
(** The type for files opened for reading. *)

val fifo_wait : float
(** [fifo_wait] is [5.]: the seconds {!open_read} waits for a program to
    write to a FIFO. *)

val open_read : ?regular:bool -> string -> (opened, [> `Msg of string ]) result
(** [open_read ~regular path] opens [path] for reading, never waiting
    without end: the open itself does not wait for a FIFO's writer
    ([O_NONBLOCK], cleared once open). A FIFO that no program has open for
    writing (or whose writer wrote nothing) within {!fifo_wait} seconds is
    an [Error]; one that a program writes is read as it comes, as before.
    A directory is an [Error] ([path: is a directory]); with [regular]
    (default [false]), so is anything but a regular file ([path: is a
    FIFO, not a regular file]). Errors start with [path]. *)

val read_opened :
  ?check_size:(int -> (int, [ `Msg of string ]) result) -> string -> opened -> (string, [> `Msg of string ]) result
(** [read_opened ~check_size path o] is {!read} of the file [o] opened at
    [path], which it closes. *)

val write_atomic : string -> (out_channel -> unit) -> (unit, [> `Msg of string ]) result
(** [write_atomic path f] calls [f oc] on a channel to a new temporary file
    beside [path], then flushes it to disk and renames it to [path]. If
    [path] is the file that standard output or error writes to
    ([/dev/stdout], [/dev/fd/2], the file of a redirection), [f] writes to
    that channel, at its position (appending after a [>>] redirection). If
    [path] exists and is not a regular file (a character device such as
    [/dev/full], a FIFO), [f] writes to it directly.
    [Error] if the directory is missing or not writable, [path] is a
    directory, the disk is full, or [f] raises [Sys_error]; then [path] is
    left as it was and the temporary file is removed. Exceptions other than
    [Sys_error] and [Unix.Unix_error] raised by [f] are re-raised after the
    temporary file is removed. *)

val replaces : string -> bool
(** [replaces path] is [true] iff {!write_atomic} [path] writes a temporary
    file that it renames to [path] (or fails before it calls its function):
    [path] is not the file of a standard channel nor a special file. *)

(** {1:atomic Atomic writes in steps}

    What {!write_atomic} does, for a caller that writes the file a part at
    a time while it does other work (and handles signals meanwhile, with
    {!Signals.protect} and {!remove_temporaries}). *)

type atomic
(** The type for files being written beside the path they will replace. *)

val open_atomic : string -> (atomic, [> `Msg of string ]) result
(** [open_atomic path] is a new temporary file beside [path], with the
    errors of {!write_atomic} before it writes.
    @raise Invalid_argument if [replaces path] is [false]. *)

val channel : atomic -> out_channel
(** [channel a] is the channel to [a]'s temporary file (binary). *)

val commit : atomic -> (unit, [> `Msg of string ]) result
(** [commit a] flushes [a] to disk and renames it to its path. [Error] as
    for {!write_atomic}: then the temporary file is removed. *)

val discard : atomic -> unit
(** [discard a] closes and removes [a]'s temporary file: its path is left
    as it was. *)

val standard_channel : string -> out_channel option
(** [standard_channel path] is [Some stdout] (or [Some stderr]) if [path]
    names the file that standard output (error) writes to: the same device
    and inode, as [/dev/stdout] or the file of a [>] or [>>] redirection
    are; [None] otherwise, or if [path] does not exist. *)

val remove_temporaries : unit -> unit
(** [remove_temporaries ()] removes the temporary files of writes in
    progress. A signal handler calls it before exiting, so that an
    interrupted write leaves nothing behind. *)
