/* The checks of the package's unit tests (the programs in tests/unit, compiled and run by
   tests/lmprun.py's run_unit): a failed check prints a FAIL line and counts; report() ends
   main with "ok" and 0, or 1 after any failure. */

#ifndef SALTDEM_UNIT_CHECK_H
#define SALTDEM_UNIT_CHECK_H

#include <cstdio>

static int failures = 0;

static void check(bool ok, const char *what, double got, double want)
{
  if (!ok) {
    std::printf("FAIL %s: got %.17g, want %.17g\n", what, got, want);
    failures++;
  }
}

static int report()
{
  if (failures) return 1;
  std::printf("ok\n");
  return 0;
}

#endif
