type t = {
  frames : int;
  after : float;  (** Seconds of work before the line appears. *)
  start : float;
  mutable frame : int;  (** Frames finished. *)
  mutable rays_before : int;  (** Rays of the frames finished. *)
  mutable rays : int;  (** Rays of the current frame, as last updated. *)
  mutable drawn_at : float;
  mutable width : int;  (** Characters of the line shown, 0 if none. *)
}

let create ?(after = 1.) ~frames () =
  let start = Unix.gettimeofday () in
  { frames = max 1 frames; after; start; frame = 0; rays_before = 0; rays = 0; drawn_at = start; width = 0 }

let wanted ~quiet = (not quiet) && Unix.isatty Unix.stderr

(* Whole seconds, as a person reads a countdown. *)
let duration s =
  let s = Float.to_int (Float.round s) in
  if s < 60 then Printf.sprintf "%d s" s
  else if s < 3600 then Printf.sprintf "%d min %02d s" (s / 60) (s mod 60)
  else Printf.sprintf "%d h %02d min" (s / 3600) (s / 60 mod 60)

let line m ~fraction ~elapsed =
  let rays = Float.of_int (m.rays_before + m.rays) in
  let speed = if elapsed > 0. then Printf.sprintf ", %.1f M rays/s" (rays /. elapsed /. 1e6) else "" in
  (* The time left if the rest goes as fast as the work so far. *)
  let left = if fraction > 0. then Printf.sprintf ", %s left" (duration (elapsed *. (1. -. fraction) /. fraction)) else "" in
  let frame = if m.frames > 1 then Printf.sprintf " (frame %d of %d)" (min m.frames (m.frame + 1)) m.frames else "" in
  Printf.sprintf "raytrace: %d%%%s%s%s" (Float.to_int (100. *. fraction)) speed left frame

let draw m text =
  (* Spaces over what is left of a longer previous line. *)
  let pad = String.make (max 0 (m.width - String.length text)) ' ' in
  (* A terminal that went away (EIO) loses the line, not the render. *)
  (try
     prerr_string ("\r" ^ text ^ pad);
     flush stderr
   with Sys_error _ -> ());
  m.width <- String.length text

let update m ~rows ~total ~rays =
  m.rays <- rays;
  let now = Unix.gettimeofday () in
  let elapsed = now -. m.start in
  if elapsed >= m.after && (m.width = 0 || now -. m.drawn_at >= 0.25) then begin
    let in_frame = if total > 0 then Float.of_int (min rows total) /. Float.of_int total else 0. in
    let fraction = Float.min 1. ((Float.of_int m.frame +. in_frame) /. Float.of_int m.frames) in
    draw m (line m ~fraction ~elapsed);
    m.drawn_at <- now
  end

let next_frame m =
  m.frame <- m.frame + 1;
  m.rays_before <- m.rays_before + m.rays;
  m.rays <- 0

let clear m =
  if m.width > 0 then begin
    (try
       prerr_string ("\r" ^ String.make m.width ' ' ^ "\r");
       flush stderr
     with Sys_error _ -> ());
    m.width <- 0
  end
