/* Transparent huge pages for the large blocks of the heap (huge_pages.mli).

   A program linked with -Wl,--wrap=malloc calls __wrap_malloc for every
   malloc of its statically linked code, the OCaml runtime's included:
   its heap's chunks and its bigarrays. A block of HUGE_MIN bytes or more
   is then marked MADV_HUGEPAGE, where its 2 MiB-aligned interior, not yet
   touched (fresh from mmap or from the top of the heap), is then backed
   by huge pages as it is first written. Smaller blocks, and programs
   linked without the flag, are left as they are. */

#define _GNU_SOURCE
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <caml/mlvalues.h>

static int wrapped = 0;   /* Has __wrap_malloc been called? */
static int enabled = -1;  /* RAYTRACE_HUGE_PAGES is not 0: read once. */
static long asked = 0;    /* Blocks marked. */

static int read_enabled(void)
{
  const char *v = getenv("RAYTRACE_HUGE_PAGES");
  return !(v != NULL && (strcmp(v, "0") == 0 || strcmp(v, "off") == 0
                         || strcmp(v, "no") == 0 || strcmp(v, "false") == 0));
}

/* Linux only: elsewhere no huge pages are asked for, and the programs
   are linked without the flag (see bin/dune). */
#if defined(__linux__) && defined(MADV_HUGEPAGE)

#define HUGE_PAGE ((uintptr_t) 2 << 20)
#define HUGE_MIN ((size_t) 4 << 20)

/* Weak: a program linked without the flag never calls __wrap_malloc,
   and needs no __real_malloc. */
extern void *__real_malloc(size_t size) __attribute__((weak));

void *__wrap_malloc(size_t size)
{
  void *p = __real_malloc(size);
  wrapped = 1;
  if (p != NULL && size >= HUGE_MIN) {
    if (enabled < 0) enabled = read_enabled();
    if (enabled) {
      uintptr_t a = ((uintptr_t) p + HUGE_PAGE - 1) & ~(HUGE_PAGE - 1);
      uintptr_t b = ((uintptr_t) p + size) & ~(HUGE_PAGE - 1);
      /* Refused (a kernel without huge pages): the block is as before. */
      if (b > a && madvise((void *) a, b - a, MADV_HUGEPAGE) == 0) asked++;
    }
  }
  return p;
}

#endif

value raytrace_huge_pages_wrapped(value unit)
{
  (void) unit;
  return Val_bool(wrapped);
}

value raytrace_huge_pages_enabled(value unit)
{
  (void) unit;
  if (enabled < 0) enabled = read_enabled();
  return Val_bool(enabled);
}

value raytrace_huge_pages_asked(value unit)
{
  (void) unit;
  return Val_long(asked);
}
