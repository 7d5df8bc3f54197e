/* mesh/io_formats: the per-format readers and writers behind acd_mesh_read / acd_mesh_write.
 * Internal.
 *
 * Readers parse buf[0..len) (buf[len] must be '\0'), append to the builder, and fail with
 * ACD_ERR_PARSE naming `name` and the line (text) or byte offset (binary). Writers append to
 * an output buffer; the mesh has been checked (finite coordinates, indices in range). */
#ifndef ACD_MESH_IO_FORMATS_H
#define ACD_MESH_IO_FORMATS_H

#include "acd/mesh.h"
#include "mesh/io_util.h"

acd_status acd_obj_read(const char *buf, size_t len, const char *name, acd_mesh_builder *b, acd_error *err);
acd_status acd_off_read(const char *buf, size_t len, const char *name, acd_mesh_builder *b, acd_error *err);
acd_status acd_ply_read(const char *buf, size_t len, const char *name, acd_mesh_builder *b, acd_error *err);
/* ASCII or binary, decided by acd_stl_is_binary; the soup is welded on exact coordinates. */
acd_status acd_stl_read(const char *buf, size_t len, const char *name, acd_mesh_builder *b, acd_error *err);

/* Content sniffing: non-zero if the bytes look like the format. */
int acd_stl_is_binary(const unsigned char *buf, size_t len);
int acd_stl_is_ascii(const char *buf, size_t len);
int acd_off_sniff(const char *buf, size_t len);
int acd_ply_sniff(const char *buf, size_t len);
int acd_obj_sniff(const char *buf, size_t len);

void acd_obj_write(acd_obuf *o, const acd_mesh *m);
void acd_obj_write_parts(acd_obuf *o, const acd_mesh_parts *p);
void acd_off_write(acd_obuf *o, const acd_mesh *m);
void acd_ply_write(acd_obuf *o, const acd_mesh *m, int ascii);
void acd_stl_write(acd_obuf *o, const acd_mesh *m, int ascii);

#endif
