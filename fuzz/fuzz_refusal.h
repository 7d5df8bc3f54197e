/* The reader fuzz targets' check of a refusal's message: it must begin with the input's name, and a
 * line it names ("NAME:L:") or a byte offset ("NAME: byte offset N") must lie within the input. With
 * need_line, every refusal must name a line. Any violation aborts (a crash for libFuzzer). */
#ifndef ACD_FUZZ_REFUSAL_H
#define ACD_FUZZ_REFUSAL_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static void fuzz_check_refusal(const char *msg, const char *name, const uint8_t *data, size_t size, int need_line) {
    size_t k = strlen(name);
    if (strncmp(msg, name, k) != 0) abort(); /* every failure must say why, and in which input */
    const char *p = msg + k;
    if (p[0] == ':' && p[1] >= '0' && p[1] <= '9') {
        size_t line = strtoull(p + 1, NULL, 10), lines = 1;
        for (size_t i = 0; i < size; i++) lines += data[i] == '\n';
        if (line < 1 || line > lines) abort();
    } else if (need_line) {
        abort();
    }
    if (!strncmp(p, ": byte offset ", 14) && strtoull(p + 14, NULL, 10) > size) abort();
}

#endif
