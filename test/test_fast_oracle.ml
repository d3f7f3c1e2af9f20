(* The fast tracer, with its skips on (the default: first-blocker shadow
   rays, the last blocker first, culling, the hierarchy, the early stop)
   and off, against the literal oracle, on the scenes of Gen_placed:
   every kind of object on every side of every light, touching and
   coinciding surfaces, the camera inside solids and glass, rays exactly
   through edges and vertices. In the document's mode, which these scenes
   use, the fast tracer does the oracle's arithmetic, so the images must
   be equal byte for byte (as in Test_render's random scenes): no
   tolerance. In the robust mode it uses other formulas, and there the
   skips alone are held to bytes, on and off. *)
open Raytrace

let show_pixel (r, g, b) = Printf.sprintf "(%d, %d, %d)" r g b

(* [None] if [actual] is [expected] byte for byte; otherwise how many
   pixels differ, by how much, and the first of them. *)
let difference what ~expected actual =
  match Image_diff.compare expected actual with
  | Error (`Msg m) -> Some (what ^ ": " ^ m)
  | Ok d when d.differing = 0 -> None
  | Ok d ->
      let first = ref None in
      for y = Image.height expected - 1 downto 0 do
        for x = Image.width expected - 1 downto 0 do
          if Image.get expected x y <> Image.get actual x y then first := Some (x, y)
        done
      done;
      let x, y = Option.get !first in
      Some
        (Printf.sprintf "%s: %d of %d pixels differ (%d by more than 1), by up to %d per channel, mean %.4f; the first at column %d, row %d: %s where the oracle has %s"
           what d.differing d.pixels d.differing_gt1 d.max_abs d.mean_abs x y
           (show_pixel (Image.get actual x y))
           (show_pixel (Image.get expected x y)))

let fail_with = function
  | [] -> true
  | l -> QCheck.Test.fail_reportf "%s\n(the scene above is Gen_placed.print's: its meshes' files follow it)" (String.concat "\n" l)

(* The fast tracer with the skips on and off, each against the oracle. *)
let as_the_oracle (s : Scene.t) =
  let expected = Literal.render (Helpers.valid s) in
  fail_with
    (List.filter_map
       (fun (what, skips) -> difference what ~expected (Helpers.image_exn ~skips s))
       [ ("with the skips on", true); ("with the skips off", false) ])

let robust (s : Scene.t) = { s with epsilon = None }

let skips_exact (s : Scene.t) =
  let s = robust s in
  fail_with
    (Option.to_list
       (difference "in the robust mode (the scene above without its epsilon), skips on against skips off" ~expected:(Helpers.image_exn ~skips:false s)
          (Helpers.image_exn ~skips:true s)))

let tests =
  [
    Helpers.qcheck ~count:500 "every kind of object, placed around the lights, touching and grazed, renders as the oracle does with the skips on and off"
      Gen_placed.arbitrary as_the_oracle;
    Helpers.qcheck ~count:300 "spheres alone, placed around the lights, touching and around the camera, render as the oracle does with the skips on and off"
      Gen_placed.arbitrary_spheres as_the_oracle;
    Helpers.qcheck ~count:300 "in the robust mode the skips change no byte of such scenes" Gen_placed.arbitrary skips_exact;
  ]
