type mode = Always | Madvise | Never | Unknown

let mode_of_setting s =
  match (String.index_opt s '[', String.index_opt s ']') with
  | Some i, Some j when j > i -> (
      match String.sub s (i + 1) (j - i - 1) with
      | "always" -> Always
      | "madvise" -> Madvise
      | "never" -> Never
      | _ -> Unknown)
  | _ -> Unknown

let mode () =
  match open_in "/sys/kernel/mm/transparent_hugepage/enabled" with
  | exception Sys_error _ -> Unknown
  | ic ->
      let m = match input_line ic with line -> mode_of_setting line | exception End_of_file -> Unknown in
      close_in_noerr ic;
      m

let variable = "RAYTRACE_HUGE_PAGES"

external wrapped : unit -> bool = "raytrace_huge_pages_wrapped"
external enabled : unit -> bool = "raytrace_huge_pages_enabled"
external asked : unit -> int = "raytrace_huge_pages_asked"

let resident_mb () = Option.map (fun kb -> Float.of_int kb /. 1024.) (Proc_self.kb "smaps_rollup" "AnonHugePages")

let status () =
  let held () = match resident_mb () with Some mb -> Printf.sprintf ", %.1f MB" mb | None -> "" in
  match mode () with
  | Always -> "on (the kernel's mode is always)" ^ held ()
  | Never -> "off (the kernel's transparent huge pages are never)"
  | Unknown -> "off (no transparent huge pages here)"
  | Madvise when not (wrapped ()) -> "off (this program is not linked to ask for them)"
  | Madvise when not (enabled ()) -> "off (" ^ variable ^ "=0)"
  | Madvise -> "on" ^ held ()
