/* acd segment: not built yet in this version of acd; says so and fails. */
#include <stdio.h>

#include "cli.h"

int acd_cmd_segment(int argc, char **argv) {
    (void)argc;
    (void)argv;
    fprintf(stderr, "acd segment: this command is not available in this build of acd yet\n");
    return ACD_EXIT_INTERNAL;
}
