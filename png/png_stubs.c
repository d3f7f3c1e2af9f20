/* A PNG file's pixels decoded by libpng straight into a bigarray of 8-bit
   RGB: no buffer of the whole image but the bigarray (camlimages' reader
   decodes into one of its own, then copies it into OCaml strings). The
   transforms are those camlimages' readers ask of libpng, in their order,
   so that every layout reads as the same bytes as through them
   (png_file.ml, [decode]). Called in the decoding child process only:
   libpng's messages go to its silenced stderr. */

#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <png.h>
#include <caml/mlvalues.h>
#include <caml/bigarray.h>
#include <caml/fail.h>
#include <caml/memory.h>

/* The failure of the first reader's transforms where they give no 8-bit
   RGB: the second reader's are tried. */
static const char again[] = "again";

/* What a decoding needs to let go of on any way out. */
struct decoding {
  FILE *file;
  png_structp png;
  png_infop info;
  png_bytep *rows;
};

static void finish(struct decoding *d)
{
  if (d->png != NULL) png_destroy_read_struct(&d->png, d->info != NULL ? &d->info : NULL, NULL);
  if (d->file != NULL) fclose(d->file);
  free(d->rows);
  d->png = NULL;
  d->info = NULL;
  d->file = NULL;
  d->rows = NULL;
}

/* Opens [path] and reads its header; NULL on success, else the failure. */
static const char *start(struct decoding *d, const char *path)
{
  d->file = fopen(path, "rb");
  if (d->file == NULL) return "png file open failed";
  d->png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
  if (d->png == NULL) return "it is not a png file.";
  d->info = png_create_info_struct(d->png);
  if (d->info == NULL) return "not enough memory";
  return NULL;
}

/* The decoding of [path] into [out] ([3 width height] bytes). [rgb24]: the
   transforms of camlimages' [Png.load_as_rgb24] (gray to RGB, colour and
   palette expanded, which makes a transparent colour an alpha channel, 16
   bits stripped, alpha stripped); else those of its [Png.load] (gray to
   RGB, 16 bits stripped). Returns NULL, or the failure: [again]
   where [rgb24]'s result is not 8-bit RGB (camlimages' first reader
   fails there and its second is tried). */
static const char *decode(struct decoding *d, const char *path, unsigned char *out, png_uint_32 width,
                          png_uint_32 height, int rgb24)
{
  png_uint_32 w, h, y;
  int depth, colour, interlace;
  /* Where libpng fails: reading the header ([png read error] in
     camlimages), or the pixels, where camlimages crashes (the caller's
     message for a crash). */
  volatile int in_pixels = 0;
  const char *failure = start(d, path);
  if (failure != NULL) return failure;
  if (setjmp(png_jmpbuf(d->png))) return in_pixels ? "corrupt or truncated data" : "png read error";
  png_init_io(d->png, d->file);
  png_read_info(d->png, d->info);
  png_get_IHDR(d->png, d->info, &w, &h, &depth, &colour, &interlace, NULL, NULL);
  if (colour == PNG_COLOR_TYPE_GRAY || colour == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(d->png);
  if (rgb24 && (colour & PNG_COLOR_TYPE_PALETTE)) png_set_expand(d->png);
  if (depth == 16) png_set_strip_16(d->png);
  if (rgb24 && (colour & PNG_COLOR_MASK_ALPHA)) png_set_strip_alpha(d->png);
  png_read_update_info(d->png, d->info);
  png_get_IHDR(d->png, d->info, &w, &h, &depth, &colour, &interlace, NULL, NULL);
  if (rgb24 && (colour != PNG_COLOR_TYPE_RGB || depth != 8)) return again;
  /* Png.load's palette images are refused by png_file.ml, as are the
     layouts it leaves other than RGB: what is left here is an RGB file
     with a transparent colour, which Png.load reads as RGB. */
  if (colour != PNG_COLOR_TYPE_RGB || depth != 8) return "unsupported PNG layout";
  if (w != width || h != height) return "size differs from the header";
  d->rows = malloc(sizeof(png_bytep) * h);
  if (d->rows == NULL) return "not enough memory";
  for (y = 0; y < h; y++) d->rows[y] = out + (size_t)3 * w * y;
  in_pixels = 1;
  png_read_image(d->png, d->rows);
  png_read_end(d->png, d->info);
  return NULL;
}

value raytrace_png_decode(value path, value buffer, value width, value height)
{
  CAMLparam4(path, buffer, width, height);
  struct decoding d = { NULL, NULL, NULL, NULL };
  unsigned char *out = Caml_ba_data_val(buffer);
  png_uint_32 w = Long_val(width), h = Long_val(height);
  const char *failure;
  if (Caml_ba_array_val(buffer)->dim[0] != (intnat)3 * Long_val(width) * Long_val(height))
    caml_invalid_argument("Png_file.decode: the buffer does not fit the image");
  failure = decode(&d, String_val(path), out, w, h, 1);
  finish(&d);
  if (failure == again) {
    failure = decode(&d, String_val(path), out, w, h, 0);
    finish(&d);
  }
  if (failure != NULL) caml_failwith(failure);
  CAMLreturn(Val_unit);
}
