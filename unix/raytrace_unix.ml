module Limits_env = Limits_env
module File_io = File_io
module Files = Files
module Parallel = Parallel
module Render_jobs = Render_jobs
module Progressive_workers = Progressive_workers
module Signals = Signals
module Part = Part
