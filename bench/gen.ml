(* Writes a generated test mesh (lib/text/mesh_gen.ml) as Wavefront OBJ, so
   that tests and benchmarks make their meshes rather than ship them.

   dune exec bench/gen.exe -- knot --segments 31250 --sides 16 -o knot.obj   (1M triangles)
   dune exec bench/gen.exe -- terrain --seed 1 --nx 100 --nz 100 -o terrain.obj *)

open Raytrace

let usage =
  "gen knot [--p P] [--q Q] [--radius R] [--tube T] [--segments N] [--sides M] [--digits D] [-o FILE]\n\
   gen terrain [--seed S] [--nx N] [--nz M] [--size L] [--height H] [--digits D] [-o FILE]\n\
   Writes a torus knot (2 N M triangles) or a terrain (2 N M triangles) as OBJ text, to stdout \
   without -o."

let () =
  let p = ref 2 and q = ref 3 and radius = ref 2. and tube = ref 0.3 and segments = ref 256 and sides = ref 16 in
  let seed = ref 1 and nx = ref 64 and nz = ref 64 and size = ref 10. and height = ref 1. in
  let out = ref "-" and kind = ref "" and digits = ref 0 in
  let spec =
    [
      ("--p", Arg.Set_int p, "P  turns around the axis (knot, 2)");
      ("--q", Arg.Set_int q, "Q  turns through the hole (knot, 3)");
      ("--radius", Arg.Set_float radius, "R  size of the knot (2)");
      ("--tube", Arg.Set_float tube, "T  radius of the tube (0.3)");
      ("--segments", Arg.Set_int segments, "N  rings along the knot (256)");
      ("--sides", Arg.Set_int sides, "M  vertices per ring (16)");
      ("--seed", Arg.Set_int seed, "S  seed of the terrain's noise (1)");
      ("--nx", Arg.Set_int nx, "N  cells along x (64)");
      ("--nz", Arg.Set_int nz, "M  cells along z (64)");
      ("--size", Arg.Set_float size, "L  side of the terrain (10)");
      ("--height", Arg.Set_float height, "H  highest point of the terrain (1)");
      ("--digits", Arg.Set_int digits, "D  significant digits of the numbers (exact by default)");
      ("-o", Arg.Set_string out, "FILE  output file (- for stdout)");
    ]
  in
  Arg.parse spec (fun k -> kind := k) usage;
  let mesh =
    try
      match !kind with
      | "knot" -> Mesh.Gen.torus_knot ~p:!p ~q:!q ~radius:!radius ~tube:!tube ~segments:!segments ~sides:!sides
      | "terrain" -> Mesh.Gen.terrain ~seed:!seed ~nx:!nx ~nz:!nz ~size:!size ~height:!height
      | _ -> prerr_endline usage; exit 2
    with Invalid_argument _ -> prerr_endline ("gen: invalid arguments\n" ^ usage); exit 2
  in
  let b = Buffer.create (1 lsl 20) in
  Mesh.Obj.to_buffer ~digits:!digits b mesh;
  let oc = if !out = "-" then stdout else open_out_bin !out in
  Buffer.output_buffer oc b;
  close_out oc
