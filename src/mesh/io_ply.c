/* mesh/io_ply: PLY reader and writer (placeholder until the full reader lands). */
#include "mesh/io_formats.h"

#include <string.h>

#include "core/error.h"

int acd_ply_sniff(const char *buf, size_t len) {
    return len >= 4 && !strncmp(buf, "ply", 3) && (buf[3] == '\n' || buf[3] == '\r');
}

acd_status acd_ply_read(const char *buf, size_t len, const char *name, acd_mesh_builder *b, acd_error *err) {
    (void)buf;
    (void)len;
    (void)b;
    return acd_fail(err, ACD_ERR_UNSUPPORTED, "%s: PLY reading is not available yet", name);
}

void acd_ply_write(acd_obuf *o, const acd_mesh *m, int ascii) {
    (void)m;
    (void)ascii;
    o->failed = 1;
}
