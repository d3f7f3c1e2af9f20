(* The work is in [Render_region], whose [?beside] names a kernel type
   that this public module does not show. *)
let region_image ?limits ?clock ?skips ?samples ?adaptive ?subsample ?progress scene region =
  Render_region.region_image ?limits ?clock ?skips ?samples ?adaptive ?subsample ?progress scene region

let image ?limits ?clock ?skips ?samples ?adaptive ?subsample ?progress scene =
  let s = Scene.view (Scene.of_valid scene) in
  region_image ?limits ?clock ?skips ?samples ?adaptive ?subsample ?progress scene
    (Region.full ~width:s.width ~height:s.height)
