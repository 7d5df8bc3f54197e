/* cli: the acd command-line tool, a thin layer over the public API. One file per subcommand. */
#ifndef ACD_CLI_H
#define ACD_CLI_H

#include "acd/base.h"

/* Exit codes, the same for every subcommand (docs/cli.md). */
enum {
    ACD_EXIT_OK = 0,
    ACD_EXIT_USAGE = 1,       /* bad command line */
    ACD_EXIT_BAD_INPUT = 2,   /* malformed or invalid input data */
    ACD_EXIT_VERIFY = 3,      /* --verify found a violated property */
    ACD_EXIT_IO = 4,          /* a file could not be read or written */
    ACD_EXIT_INTERNAL = 5,    /* internal failure (a bug) or out of memory */
    ACD_EXIT_CANCELLED = 6
};

/* Maps a status to the exit code above. */
int acd_cli_exit_code(acd_status s);

/* Prints "acd <cmd>: <status text>: <message>" to stderr and returns the exit code. */
int acd_cli_report(const char *cmd, const acd_error *err);

/* Parses a finite double / a non-negative integer option value; prints a usage error and
 * returns 0 on failure. */
int acd_cli_parse_double(const char *cmd, const char *opt, const char *s, double *out);
int acd_cli_parse_size(const char *cmd, const char *opt, const char *s, size_t *out);

struct acd_mesh;
/* Refuses a mesh whose bounding box's largest extent is positive and below ACD_EXTENT_MIN
 * (core/tolerance.h, acd_check_extent: the library refuses the same): prints "acd <cmd>: invalid
 * input geometry: ..." and returns ACD_EXIT_BAD_INPUT; else 0. Called before repair, so that the
 * refusal names the size rather than what repair makes of such a model. */
int acd_cli_check_extent(const char *cmd, const struct acd_mesh *m);

struct acd_mesh_parts;
/* acd_mesh_read / acd_mesh_read_parts printing the reader's warnings (what it skipped that may be
 * geometry: OBJ points, lines, free-form elements) as "acd <cmd>: warning: FILE:LINE: ..." on
 * stderr; the exit code is not affected. */
acd_status acd_cli_read_mesh(const char *cmd, const char *path, struct acd_mesh *out, acd_error *err);
acd_status acd_cli_read_parts(const char *cmd, const char *path, struct acd_mesh_parts *out, acd_error *err);

/* Subcommands: argc/argv start at the subcommand's name. */
int acd_cmd_2d(int argc, char **argv);
int acd_cmd_info(int argc, char **argv);
int acd_cmd_hull(int argc, char **argv);
int acd_cmd_eval(int argc, char **argv);
int acd_cmd_3d(int argc, char **argv);
int acd_cmd_segment(int argc, char **argv);
int acd_cmd_segeval(int argc, char **argv);

#endif
