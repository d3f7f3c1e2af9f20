open Raytrace_view

let to_char = function
  | "ArrowLeft" -> Some View.arrow_left
  | "ArrowUp" -> Some View.arrow_up
  | "ArrowRight" -> Some View.arrow_right
  | "ArrowDown" -> Some View.arrow_down
  | "Escape" -> Some '\027'
  | k when String.length k = 1 && Char.code k.[0] >= 32 && Char.code k.[0] < 127 -> Some k.[0]
  | _ -> None
