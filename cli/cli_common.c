/* cli_common: exit codes, error reports and option parsing shared by the subcommands. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli.h"
#include "acd/mesh.h"
#include "core/tolerance.h"

int acd_cli_exit_code(acd_status s) {
    switch (s) {
    case ACD_OK: return ACD_EXIT_OK;
    case ACD_ERR_INVALID_ARGUMENT: return ACD_EXIT_USAGE;
    case ACD_ERR_PARSE:
    case ACD_ERR_INVALID_INPUT:
    case ACD_ERR_DEGENERATE:
    case ACD_ERR_NON_MANIFOLD:
    case ACD_ERR_UNSUPPORTED: return ACD_EXIT_BAD_INPUT;
    case ACD_ERR_VERIFY: return ACD_EXIT_VERIFY;
    case ACD_ERR_IO: return ACD_EXIT_IO;
    case ACD_ERR_CANCELLED: return ACD_EXIT_CANCELLED;
    case ACD_ERR_NOMEM:
    case ACD_ERR_INTERNAL: return ACD_EXIT_INTERNAL;
    }
    return ACD_EXIT_INTERNAL;
}

int acd_cli_report(const char *cmd, const acd_error *err) {
    fprintf(stderr, "acd %s: %s: %s\n", cmd, acd_status_string(err->status), err->message);
    return acd_cli_exit_code(err->status);
}

int acd_cli_parse_double(const char *cmd, const char *opt, const char *s, double *out) {
    char *end = NULL;
    errno = 0;
    double v = s ? strtod(s, &end) : 0.0;
    if (!s || end == s || *end != '\0' || errno == ERANGE || !isfinite(v)) {
        fprintf(stderr, "acd %s: option %s needs a finite number, got '%s'\n", cmd, opt, s ? s : "");
        return 0;
    }
    *out = v;
    return 1;
}

int acd_cli_parse_size(const char *cmd, const char *opt, const char *s, size_t *out) {
    char *end = NULL;
    errno = 0;
    long long v = s ? strtoll(s, &end, 10) : -1;
    if (!s || end == s || *end != '\0' || errno == ERANGE || v < 0) {
        fprintf(stderr, "acd %s: option %s needs a non-negative integer, got '%s'\n", cmd, opt, s ? s : "");
        return 0;
    }
    *out = (size_t)v;
    return 1;
}

int acd_cli_check_extent(const char *cmd, const acd_mesh *m) {
    if (!m || !m->nvertices) return 0;
    acd_error e;
    return acd_check_extent(m->vertices, m->nvertices, 3, &e) == ACD_OK ? 0 : acd_cli_report(cmd, &e);
}

static void print_warning(void *user, const char *message) {
    fprintf(stderr, "acd %s: warning: %s\n", (const char *)user, message);
}

static acd_mesh_read_options warning_options(const char *cmd) {
    acd_mesh_read_options o = acd_mesh_read_default_options();
    o.warning = print_warning;
    o.warning_user = (void *)(uintptr_t)cmd;
    return o;
}

acd_status acd_cli_read_mesh(const char *cmd, const char *path, acd_mesh *out, acd_error *err) {
    acd_mesh_read_options o = warning_options(cmd);
    return acd_mesh_read_ex(path, &o, out, err);
}

acd_status acd_cli_read_parts(const char *cmd, const char *path, acd_mesh_parts *out, acd_error *err) {
    acd_mesh_read_options o = warning_options(cmd);
    return acd_mesh_read_parts_ex(path, &o, out, err);
}
