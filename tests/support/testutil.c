#include "testutil.h"

#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

static const char *exists(char *buf, size_t size, const char *root, const char *rel) {
    snprintf(buf, size, "%s/%s", root, rel);
    return access(buf, R_OK) == 0 ? buf : NULL;
}

const char *tu_shared_data(char *buf, size_t size, const char *rel) { return exists(buf, size, ACD_SHARED_DATA, rel); }
const char *tu_mesh_data(char *buf, size_t size, const char *rel) { return exists(buf, size, ACD_MESH_DATA, rel); }

char *tu_read_file(const char *path, size_t *len) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *b = malloc((size_t)n + 1);
    if (b && fread(b, 1, (size_t)n, f) != (size_t)n) { free(b); b = NULL; }
    fclose(f);
    if (b) { b[n] = 0; if (len) *len = (size_t)n; }
    return b;
}

int tu_count_calls(void *user, double fraction, const char *stage) {
    (void)fraction, (void)stage;
    tu_counter *c = user;
    c->calls++;
    return c->stop_at && c->calls >= c->stop_at;
}
