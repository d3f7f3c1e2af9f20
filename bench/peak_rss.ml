(* The peak resident memory of this process, from Linux's /proc. *)
let mb () = match Raytrace_unix.Proc_self.kb "status" "VmHWM" with Some kb -> Float.of_int kb /. 1024. | None -> nan
