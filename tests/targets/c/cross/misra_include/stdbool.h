/* cppcheck's view of <stdbool.h> for the MISRA run (see stdint.h here). */
#ifndef MISRA_STUB_STDBOOL_H
#define MISRA_STUB_STDBOOL_H
#define bool _Bool
#define true 1
#define false 0
#endif
