(** The benchmark against Embree's instrument: the C driver builds and finds
    raytrace's hit masks on small meshes (issue 28). *)

val tests : unit Alcotest.test_case list
(** The cases of the suite [embree]. *)
