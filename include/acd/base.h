/* acd/base.h: version, result codes and messages, progress and cancellation, warnings.
 *
 * Every public function that can fail returns an acd_status and, when given a non-NULL
 * acd_error*, fills it with a message naming the problem and where it is (file, line,
 * chain and vertex, ...). The library keeps no global state. */
#ifndef ACD_BASE_H
#define ACD_BASE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define ACD_VERSION_MAJOR 0
#define ACD_VERSION_MINOR 1
#define ACD_VERSION_PATCH 0
#define ACD_VERSION_STRING "0.1.0"

/* Result codes. Data errors (bad files, degenerate input) are distinct from internal failures. */
typedef enum acd_status {
    ACD_OK = 0,
    ACD_ERR_INVALID_ARGUMENT, /* a caller passed a bad parameter (programmer error) */
    ACD_ERR_PARSE,            /* malformed input file or string */
    ACD_ERR_INVALID_INPUT,    /* well-formed but geometrically invalid input (self-intersection, NaN, ...) */
    ACD_ERR_DEGENERATE,       /* input too degenerate for the operation (zero area/volume, < 3 points) */
    ACD_ERR_NON_MANIFOLD,     /* mesh topology the operation cannot take */
    ACD_ERR_IO,               /* file could not be read or written */
    ACD_ERR_NOMEM,            /* out of memory */
    ACD_ERR_CANCELLED,        /* the progress callback asked to stop */
    ACD_ERR_UNSUPPORTED,      /* format or option not supported */
    ACD_ERR_VERIFY,           /* a --verify check failed */
    ACD_ERR_INTERNAL          /* a bug: an invariant did not hold */
} acd_status;

/* Static English text for a status code. Never NULL. */
const char *acd_status_string(acd_status s);

#define ACD_ERROR_MESSAGE_SIZE 512

/* Detailed error report, filled by the function that failed. Caller-owned, may be on the stack. */
typedef struct acd_error {
    acd_status status;
    char message[ACD_ERROR_MESSAGE_SIZE];
} acd_error;

/* Progress report: fraction in [0,1] (or negative when unknown), stage a short static text.
 * Return non-zero to cancel: the running function then returns ACD_ERR_CANCELLED. */
typedef int (*acd_progress_fn)(void *user, double fraction, const char *stage);

/* Warning report: input that was accepted but not all used (e.g. OBJ statements a reader skipped,
 * so that the result may lack geometry). message names the input and where ("FILE:LINE: ..."),
 * is valid during the call only, and never ends with a newline. Called on the calling thread, in
 * input order; not called for an input that is refused (the error says why). */
typedef void (*acd_warning_fn)(void *user, const char *message);

#ifdef __cplusplus
}
#endif
#endif
