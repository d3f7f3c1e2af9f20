(** Differences between two images of the same size.

    The figures of [raytrace diff] and of the image tests: how many pixels
    differ, and by how much. A channel difference is the absolute
    difference of two bytes, in [\[0, 255\]].

    @canonical Raytrace.Image.Diff *)

type t = {
  pixels : int;  (** Pixels compared: [width * height]. *)
  differing : int;  (** Pixels with any channel differing at all. *)
  differing_gt1 : int;  (** Pixels with any channel differing by more than 1. *)
  max_abs : int;  (** Largest channel difference. *)
  mean_abs : float;  (** Mean channel difference over all [3 * pixels] channels. *)
  psnr : float;
      (** Peak signal-to-noise ratio in decibels, [10 log10 (255^2 / MSE)]
          over all channels; [infinity] for identical images. *)
}
(** The type for difference figures. *)

val pp : Format.formatter -> t -> unit
(** [pp ppf x] prints [x] as an OCaml record (derived). *)

val show : t -> string
(** [show x] is [x] formatted by {!pp}. *)

val compare : Image.t -> Image.t -> (t, [> `Msg of string ]) result
(** [compare a b] is the difference figures of [a] and [b], or [Error] if
    their sizes differ. *)

val share_within : t -> float
(** [share_within d] is the share of pixels, in [\[0, 1\]], whose channels
    all differ by at most 1: [1 - differing_gt1 / pixels]. *)

val pp_summary : Format.formatter -> t -> unit
(** [pp_summary ppf d] prints [d] on one line as
    [pixels=N differing=K differing_gt1=K1 max_abs=M mean_abs=X psnr=Y]. *)
