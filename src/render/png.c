/* PNG output through libpng. */
#include "specseg/render.h"
#include "util/out_file.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

#ifdef SS_HAVE_PNG
#include <png.h>
#include <setjmp.h>

/* libpng reports through these instead of printing (the library never prints): the error message is
 * kept for ss_error, warnings are dropped */
static void png_error_fn(png_structp png, png_const_charp msg) {
  char *buf = png_get_error_ptr(png);
  if (buf) snprintf(buf, 128, "%s", msg ? msg : "libpng error");
  png_longjmp(png, 1);
}
static void png_warning_fn(png_structp png, png_const_charp msg) { (void)png, (void)msg; }

ss_status ss_write_png(const char *path, const unsigned char *rgb, int width, int height, ss_error *err) {
  if (width < 1 || height < 1) return ss_fail(err, SS_ERR_INVALID, "%s: empty image", path);
  ssi_out o; /* whole or not at all (util/out_file.h) */
  ss_status st = ssi_out_open(&o, path, err);
  if (st) return st;
  FILE *f = o.f;
  char pmsg[128] = "";
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, pmsg, png_error_fn, png_warning_fn);
  png_infop info = png ? png_create_info_struct(png) : NULL;
  if (!png || !info) {
    png_destroy_write_struct(&png, &info);
    ssi_out_abort(&o);
    return ss_fail(err, SS_ERR_NOMEM, "%s: cannot create the PNG writer", path);
  }
  errno = 0;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    int e = errno;
    ssi_out_abort(&o);
    return ss_fail(err, SS_ERR_IO, "%s: PNG write failed: %s", path, e ? strerror(e) : pmsg[0] ? pmsg : "libpng error");
  }
  png_init_io(png, f);
  png_set_IHDR(png, info, (png_uint_32)width, (png_uint_32)height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < height; y++) png_write_row(png, (png_const_bytep)(rgb + 3 * (size_t)y * width));
  png_write_end(png, NULL);
  png_destroy_write_struct(&png, &info);
  return ssi_out_commit(&o, path, err);
}
#else
/* libpng reports through these instead of printing (the library never prints): the error message is
 * kept for ss_error, warnings are dropped */
static void png_error_fn(png_structp png, png_const_charp msg) {
  char *buf = png_get_error_ptr(png);
  if (buf) snprintf(buf, 128, "%s", msg ? msg : "libpng error");
  png_longjmp(png, 1);
}
static void png_warning_fn(png_structp png, png_const_charp msg) { (void)png, (void)msg; }

ss_status ss_write_png(const char *path, const unsigned char *rgb, int width, int height, ss_error *err) {
  (void)rgb; (void)width; (void)height;
  return ss_fail(err, SS_ERR_UNSUPPORTED, "%s: built without libpng", path);
}
#endif
