let read () = Limits.of_lookup Sys.getenv_opt
