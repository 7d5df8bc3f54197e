/* core/error: status texts and formatted error reports. */
#include "core/error.h"

#include <stdarg.h>
#include <stdio.h>

const char *acd_status_string(acd_status s) {
    switch (s) {
    case ACD_OK: return "ok";
    case ACD_ERR_INVALID_ARGUMENT: return "invalid argument";
    case ACD_ERR_PARSE: return "malformed input";
    case ACD_ERR_INVALID_INPUT: return "invalid input geometry";
    case ACD_ERR_DEGENERATE: return "degenerate input";
    case ACD_ERR_NON_MANIFOLD: return "non-manifold input";
    case ACD_ERR_IO: return "input/output error";
    case ACD_ERR_NOMEM: return "out of memory";
    case ACD_ERR_CANCELLED: return "cancelled";
    case ACD_ERR_UNSUPPORTED: return "unsupported";
    case ACD_ERR_VERIFY: return "verification failed";
    case ACD_ERR_INTERNAL: return "internal error";
    }
    return "unknown status";
}

acd_status acd_fail(acd_error *err, acd_status status, const char *fmt, ...) {
    if (err) {
        err->status = status;
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
    }
    return status;
}

void acd_error_clear(acd_error *err) {
    if (err) {
        err->status = ACD_OK;
        err->message[0] = '\0';
    }
}
