type t = { x : int; y : int; w : int; h : int } [@@deriving show, eq]

let msg fmt = Printf.ksprintf (fun m -> Error (`Msg m)) fmt
let v ~x ~y ~w ~h = { x; y; w; h }
let x r = r.x
let y r = r.y
let w r = r.w
let h r = r.h
let full ~width ~height = { x = 0; y = 0; w = width; h = height }
let pixels r = r.w * r.h

let contains r ~width ~height =
  r.w >= 1 && r.h >= 1 && r.x >= 0 && r.y >= 0 && r.x + r.w <= width && r.y + r.h <= height

let of_corners ~width ~height x0 y0 x1 y1 =
  if x0 < 0 || x1 > width || x0 >= x1 then
    msg "region columns %d to %d: need 0 <= x0 < x1 <= %d (the canvas width)" x0 x1 width
  else if y0 < 0 || y1 > height || y0 >= y1 then
    msg "region rows %d to %d: need 0 <= y0 < y1 <= %d (the canvas height)" y0 y1 height
  else Ok { x = x0; y = y0; w = x1 - x0; h = y1 - y0 }

let tile ~width ~height ~index ~count =
  if count < 1 then msg "tile %d/%d: the number of tiles must be at least 1" index count
  else if index < 1 || index > count then
    msg "tile %d/%d: the tile number must lie in [1, %d]" index count count
  else if count > height then
    msg "tile %d/%d: the canvas has only %d rows, fewer than %d tiles" index count height count
  else
    (* Products first, then division: the bands meet exactly, and the last
       one ends at [height]. *)
    let y0 = (index - 1) * height / count and y1 = index * height / count in
    Ok { x = 0; y = y0; w = width; h = y1 - y0 }

let parse_tile s =
  let decimal t = t <> "" && String.length t <= 9 && String.for_all (fun c -> c >= '0' && c <= '9') t in
  match String.split_on_char '/' s with
  | [ i; n ] when decimal i && decimal n -> Ok (int_of_string i, int_of_string n)
  | _ -> msg "tile %S: expected I/N, tile I of N, e.g. 3/16" s

let parse_corners s =
  let words = List.filter (( <> ) "") (String.split_on_char ' ' (String.map (fun c -> if c = ',' then ' ' else c) s)) in
  let int w = if String.length w <= 9 then int_of_string_opt w else None in
  match List.map int words with
  | [ Some x0; Some y0; Some x1; Some y1 ] -> Ok (x0, y0, x1, y1)
  | _ -> msg "region %S: expected four integers X0,Y0,X1,Y1, e.g. 0,0,300,200" s

let pp_corners ppf r = Format.fprintf ppf "%d %d %d %d" r.x r.y (r.x + r.w) (r.y + r.h)
