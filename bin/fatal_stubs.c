/* The runtime's fatal errors, said in one line.

   When the OCaml runtime cannot grow its heap in the middle of a
   collection it cannot raise Out_of_memory: it prints "Fatal error: out of
   memory" and aborts (SIGABRT, status 134). This hook says it is memory,
   in the program's own words, and exits with status 1 instead. */

#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>
#include <caml/mlvalues.h>
#include <caml/misc.h>

static void say(const char *s) { ssize_t r = write(2, s, strlen(s)); (void) r; }

static void fatal_error(char *msg, va_list args)
{
  /* No allocation: the heap may be exhausted. */
  char line[256];
  if (strncmp(msg, "out of memory", 13) == 0) {
    say("raytrace: out of memory: the OCaml runtime could not grow its heap "
        "(see the limits in raytrace render --help, ENVIRONMENT)\n");
    _exit(1);
  }
  vsnprintf(line, sizeof line, msg, args);
  say("raytrace: fatal error in the OCaml runtime: ");
  say(line);
  say("\n");
  /* Returning aborts, as without the hook. */
}

value raytrace_install_fatal_hook(value unit)
{
  (void) unit;
  caml_fatal_error_hook = fatal_error;
  return Val_unit;
}
