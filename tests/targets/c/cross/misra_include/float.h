/* cppcheck's view of <float.h> for the MISRA run (see stdint.h here): IEEE 754 binary32 / binary64. */
#ifndef MISRA_STUB_FLOAT_H
#define MISRA_STUB_FLOAT_H
#define FLT_MANT_DIG 24
#define FLT_MAX_EXP 128
#define DBL_MANT_DIG 53
#define DBL_MAX_EXP 1024
#endif
