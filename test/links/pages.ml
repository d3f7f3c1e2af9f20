(* What the two checks share: the pages (README.md and docs/*.md) and
   their prose, the lines outside fenced code blocks. *)

let read path =
  let ic = open_in_bin path in
  Fun.protect ~finally:(fun () -> close_in_noerr ic) (fun () -> really_input_string ic (in_channel_length ic))

let lines path = String.split_on_char '\n' (read path)

let is_fence line =
  let l = String.trim line in
  String.length l >= 3 && String.sub l 0 3 = "```"

(* The lines of a page outside fenced code blocks, with their numbers. *)
let prose path =
  let fenced = ref false in
  lines path
  |> List.mapi (fun i l -> (i + 1, l))
  |> List.filter (fun (_, l) ->
         if is_fence l then begin
           fenced := not !fenced;
           false
         end
         else not !fenced)

(* README.md and docs/*.md, relative to [root], in a fixed order. *)
let all root =
  let docs = Filename.concat root "docs" in
  "README.md"
  :: (Sys.readdir docs |> Array.to_list |> List.filter (fun f -> Filename.check_suffix f ".md") |> List.sort compare
     |> List.map (Filename.concat "docs"))
