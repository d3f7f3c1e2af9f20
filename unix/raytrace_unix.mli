(** The system parts of raytrace: files, processes, signals, the limits
    read from the environment, tiles and parts for farms.

    The core library [Raytrace] is pure; a program that reads scene files
    and renders them on the cores of a machine starts here:
{[
let () =
  match Raytrace_unix.Limits_env.read () with
  | Error (`Msg m) -> prerr_endline m
  | Ok limits -> (
      match Raytrace_unix.Files.render_file ~limits ~jobs:4 "scenes/cgfs.scene" with
      | Ok img -> ignore (Raytrace_unix.Files.write_ppm "cgfs.ppm" img)
      | Error (`Msg m) -> prerr_endline m)
]}
    Errors follow the core's convention: [Error (`Msg m)], messages that
    start with the path of the file at fault. *)

module Limits_env = Limits_env
module File_io = File_io
module Files = Files
module Io_plan = Io_plan
module Parallel = Parallel
module Render_jobs = Render_jobs
module Ppm_stream = Ppm_stream
module Progressive_workers = Progressive_workers
module Signals = Signals
module Part = Part
module Proc_self = Proc_self
