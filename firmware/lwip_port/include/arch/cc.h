/*
 * arch/cc.h — lwIP compiler/platform abstraction for the IPE002Z firmware.
 *
 * One header for both builds: host-native Linux (GCC or Clang, x86-64) and the future Cortex-M
 * target (arm-none-eabi GCC, newlib). It is included by lwip/arch.h, in C (lwIP itself) and in
 * C++ (the firmware), so everything here is plain C with extern "C" guards.
 *
 * What the firmware must define (see firmware/lwip_port/ and docs/lwip.md):
 *   u32_t sys_now(void);                       declared by lwip/sys.h: milliseconds, wrapping
 *   u32_t ipe_lwip_rand(void);                 LWIP_RAND(): DHCP xid, IGMP delays, local ports
 *   void  ipe_lwip_diag(const char* fmt, ...); LWIP_PLATFORM_DIAG(): printf-like diagnostics
 *   void  ipe_lwip_assert(const char* message, const char* file, int line);   must not return
 */
#ifndef IPE_LWIP_ARCH_CC_H
#define IPE_LWIP_ARCH_CC_H

/* lwIP's arch.h includes <stdint.h>, <inttypes.h>, <limits.h>, <ctype.h> and <stddef.h> itself
 * (LWIP_NO_*_H left at 0: both toolchains have a hosted-enough C library). */
#include <stddef.h>
#include <stdint.h>

/* Byte order, from the compiler. If the C library already defined BYTE_ORDER (glibc's <endian.h>,
 * newlib's <machine/endian.h>), include it first so its definition is the only one and a later
 * inclusion cannot redefine ours with different tokens. */
#if defined(__has_include)
#if __has_include(<endian.h>)
#include <endian.h>
#endif
#endif
#ifndef BYTE_ORDER
#if defined(__BYTE_ORDER__) && (__BYTE_ORDER__ == __ORDER_BIG_ENDIAN__)
#define BYTE_ORDER BIG_ENDIAN
#else
#define BYTE_ORDER LITTLE_ENDIAN
#endif
#endif

/* Keep the standard headers lwIP includes by default. */
#define LWIP_NO_STDDEF_H 0
#define LWIP_NO_STDINT_H 0
#define LWIP_NO_INTTYPES_H 0
#define LWIP_NO_LIMITS_H 0
#define LWIP_NO_CTYPE_H 0

/* Structure packing: lwIP's arch.h already uses __attribute__((packed)) for GCC and Clang. */

#if defined(__GNUC__) || defined(__clang__)
#define IPE_LWIP_NORETURN __attribute__((__noreturn__))
#define IPE_LWIP_PRINTF_LIKE(fmt_index, first_arg) __attribute__((__format__(__printf__, fmt_index, first_arg)))
#else
#define IPE_LWIP_NORETURN
#define IPE_LWIP_PRINTF_LIKE(fmt_index, first_arg)
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Random numbers for LWIP_RAND() (uint32_t is lwIP's u32_t). */
uint32_t ipe_lwip_rand(void);

/* Diagnostic output, printf-like. */
void ipe_lwip_diag(const char* fmt, ...) IPE_LWIP_PRINTF_LIKE(1, 2);

/* Failed LWIP_ASSERT: report and stop; never returns. */
void ipe_lwip_assert(const char* message, const char* file, int line) IPE_LWIP_NORETURN;

#ifdef __cplusplus
}
#endif

/* x is a parenthesised printf argument list: LWIP_PLATFORM_DIAG(("%d\n", n)). */
#define LWIP_PLATFORM_DIAG(x) \
  do {                        \
    ipe_lwip_diag x;          \
  } while (0)

#define LWIP_PLATFORM_ASSERT(x)                  \
  do {                                           \
    ipe_lwip_assert((x), __FILE__, __LINE__);    \
  } while (0)

#define LWIP_RAND() ((uint32_t)ipe_lwip_rand())

#endif /* IPE_LWIP_ARCH_CC_H */
