/* cppcheck's view of <stdint.h> for the MISRA run (tests/targets/c/cross/misra.py): the exact-width
 * types of a 32-bit ARM EABI target as real typedefs, so the misra addon knows the essential
 * types (without a definition it sees none and reports no essential-type findings). */
#ifndef MISRA_STUB_STDINT_H
#define MISRA_STUB_STDINT_H
typedef signed char int8_t;
typedef short int16_t;
typedef long int32_t;
typedef long long int64_t;
typedef unsigned char uint8_t;
typedef unsigned short uint16_t;
typedef unsigned long uint32_t;
typedef unsigned long long uint64_t;
typedef long intptr_t;
typedef unsigned long uintptr_t;
#define INT8_MIN (-128)
#define INT8_MAX 127
#define UINT8_MAX 255
#define INT16_MIN (-32767 - 1)
#define INT16_MAX 32767
#define UINT16_MAX 65535
#define INT32_MIN (-2147483647L - 1L)
#define INT32_MAX 2147483647L
#define UINT32_MAX 4294967295UL
#define INT64_MIN (-9223372036854775807LL - 1LL)
#define INT64_MAX 9223372036854775807LL
#define UINT64_MAX 18446744073709551615ULL
#define INT8_C(c) c
#define INT16_C(c) c
#define INT32_C(c) c##L
#define INT64_C(c) c##LL
#define UINT8_C(c) c##U
#define UINT16_C(c) c##U
#define UINT32_C(c) c##UL
#define UINT64_C(c) c##ULL
#endif
