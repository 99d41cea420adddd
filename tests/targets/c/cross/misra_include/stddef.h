/* cppcheck's view of <stddef.h> for the MISRA run (see stdint.h here). offsetof stays
 * undefined: cppcheck's std library configuration knows it. */
#ifndef MISRA_STUB_STDDEF_H
#define MISRA_STUB_STDDEF_H
typedef unsigned int size_t;
typedef int ptrdiff_t;
#define NULL ((void *)0)
#endif
