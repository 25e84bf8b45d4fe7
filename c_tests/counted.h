/* Counted checks: what every C test program shares, with no library header needed. */
#ifndef COUNTED_H
#define COUNTED_H

extern long checks_passed;
extern long checks_failed;

/* Counts one check; prints "FAIL: <message>" when ok is zero. Returns ok. */
int check(int ok, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

#endif
