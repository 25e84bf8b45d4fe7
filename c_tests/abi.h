/* The ABI a soname freezes: constants, struct layouts and function types against a table. */
#ifndef ABI_H
#define ABI_H

/* Every constant's value, every field's offset and size in the four structs callers allocate,
   and every function's type (checked as it compiles) against this soname's table. */
void test_abi(void);

#endif
