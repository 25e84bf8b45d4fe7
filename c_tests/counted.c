#include "counted.h"

#include <stdarg.h>
#include <stdio.h>

long checks_passed = 0;
long checks_failed = 0;

int check(int ok, const char *format, ...)
{
    if (ok) {
        checks_passed++;
    } else {
        va_list args;
        checks_failed++;
        fputs("FAIL: ", stdout);
        va_start(args, format);
        vprintf(format, args);
        va_end(args);
        fputc('\n', stdout);
        fflush(stdout);
    }
    return ok;
}
