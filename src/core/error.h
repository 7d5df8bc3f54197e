/* core/error: filling acd_error with formatted messages. */
#ifndef ACD_CORE_ERROR_H
#define ACD_CORE_ERROR_H

#include "acd/base.h"

#if defined(__GNUC__)
#define ACD_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define ACD_PRINTF(a, b)
#endif

/* Sets err (if non-NULL) to status and the formatted message; returns status. */
acd_status acd_fail(acd_error *err, acd_status status, const char *fmt, ...) ACD_PRINTF(3, 4);

/* Clears err (if non-NULL) to ACD_OK with an empty message. */
void acd_error_clear(acd_error *err);

#endif
