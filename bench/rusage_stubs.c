/* The resources used by the children this process has waited for
   (getrusage RUSAGE_CHILDREN), for bench/speed.ml: OCaml's Unix has
   Unix.times, which gives the children's user and system time but not
   their page faults, and has no wait4. A child that waits for its own
   children (the render's workers and helpers) counts theirs in its
   own. POSIX, so that the benchmark needs no /usr/bin/time. */

#include <sys/resource.h>
#include <caml/mlvalues.h>
#include <caml/alloc.h>
#include <caml/memory.h>

/* (user seconds, system seconds, minor faults, major faults), summed over
   every child waited for so far: the difference across one waitpid is
   that child's. */
value bench_children_usage(value unit)
{
  CAMLparam1(unit);
  CAMLlocal3(result, user, sys);
  struct rusage u;
  (void)unit;
  if (getrusage(RUSAGE_CHILDREN, &u) != 0) {
    u.ru_utime.tv_sec = u.ru_utime.tv_usec = 0;
    u.ru_stime.tv_sec = u.ru_stime.tv_usec = 0;
    u.ru_minflt = u.ru_majflt = -1;
  }
  user = caml_copy_double((double)u.ru_utime.tv_sec + 1e-6 * (double)u.ru_utime.tv_usec);
  sys = caml_copy_double((double)u.ru_stime.tv_sec + 1e-6 * (double)u.ru_stime.tv_usec);
  result = caml_alloc_tuple(4);
  Store_field(result, 0, user);
  Store_field(result, 1, sys);
  Store_field(result, 2, Val_long(u.ru_minflt));
  Store_field(result, 3, Val_long(u.ru_majflt));
  CAMLreturn(result);
}
