/* Test support shared by the cmocka suites: data paths, skipping, deterministic randomness. */
#ifndef ACD_TESTUTIL_H
#define ACD_TESTUTIL_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

/* Path of a file under ../shared/data (e.g. "polygons-lien/bird.poly") in buf; returns buf, or
 * NULL when the file does not exist (the caller then skips with a message). */
const char *tu_shared_data(char *buf, size_t size, const char *rel);
/* Same for the fetched meshes (data/meshes, see scripts/fetch-data.sh). */
const char *tu_mesh_data(char *buf, size_t size, const char *rel);

/* Skips the current cmocka test, printing why. */
#define TU_SKIP(...)                                  \
    do {                                              \
        print_message("[  SKIP    ] " __VA_ARGS__);   \
        print_message("\n");                          \
        skip();                                       \
    } while (0)

/* A progress callback (acd_progress_fn) for the cancellation tests: counts its calls in a tu_counter
 * (user) and asks to stop at call number stop_at (0: never). */
typedef struct tu_counter {
    int calls, stop_at;
} tu_counter;
int tu_count_calls(void *user, double fraction, const char *stage);

/* Reads a whole file into a NUL-terminated malloc'd buffer; NULL on failure. */
char *tu_read_file(const char *path, size_t *len);

#endif
