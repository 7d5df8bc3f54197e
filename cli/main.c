/* acd: command-line entry point; dispatches to one file per subcommand. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#if defined(_OPENMP) && defined(__linux__)
#include <unistd.h>
#endif

#include "cli.h"

#if defined(_OPENMP) && defined(__linux__)
/* OpenMP's idle threads wait for the next parallel region by spinning (libgomp, OMP_WAIT_POLICY
 * unset: some 300,000 spins before they sleep). The 3D pipelines open hundreds of short regions, and
 * on cores that other processes use a spinning thread takes turns from the working ones: measured
 * 2026-11-26 on 2 cores (docs/results/3d-speed.md, "Threads on a busy machine"), fandisk --budget 40
 * --trim-coverage 0.0008 took 1.72 s wall with both cores busy, 1.05 s with passive waiting, the
 * armadillo's 5.42 s against 3.67 s; on idle cores the two are within the noise. libgomp reads the
 * policy once, when it is loaded, so the CLI sets it and runs itself again; the user's own
 * OMP_WAIT_POLICY or GOMP_SPINCOUNT wins. Without /proc the default policy stays. */
static void passive_omp_wait(char **argv) {
    if (getenv("OMP_WAIT_POLICY") || getenv("GOMP_SPINCOUNT")) return;
    if (setenv("OMP_WAIT_POLICY", "passive", 1) != 0) return;
    execv("/proc/self/exe", argv);
}
#endif

typedef struct command {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
} command;

static const command commands[] = {
    {"2d", acd_cmd_2d, "approximate convex decomposition of polygons with holes"},
    {"3d", acd_cmd_3d, "approximate convex decomposition of polyhedra"},
    {"segment", acd_cmd_segment, "CoRiSe nearly convex segmentation of a mesh"},
    {"info", acd_cmd_info, "mesh report: topology, genus, volume, defects"},
    {"hull", acd_cmd_hull, "convex hull of a mesh or point set"},
    {"eval", acd_cmd_eval, "score a decomposition (IoU, coverage, surface distance)"},
    {"segeval", acd_cmd_segeval, "segmentation benchmark metrics between two .seg files"},
};

static void usage(FILE *f) {
    fprintf(f, "acd %s: approximate convex decomposition\n\nusage: acd COMMAND [options]\n\ncommands:\n",
            ACD_VERSION_STRING);
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        fprintf(f, "  %-9s %s\n", commands[i].name, commands[i].summary);
    fprintf(f, "\n'acd COMMAND --help' describes a command's options.\n");
}

int main(int argc, char **argv) {
#if defined(_OPENMP) && defined(__linux__)
    passive_omp_wait(argv);
#endif
    if (argc < 2) {
        usage(stderr);
        return ACD_EXIT_USAGE;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return ACD_EXIT_OK;
    }
    if (!strcmp(argv[1], "--version")) {
        printf("acd %s\n", ACD_VERSION_STRING);
#ifdef _OPENMP
        const char *wp = getenv("OMP_WAIT_POLICY"), *sc = getenv("GOMP_SPINCOUNT");
        printf("threads: OpenMP, OMP_WAIT_POLICY=%s", wp ? wp : "(unset)");
        if (sc) printf(", GOMP_SPINCOUNT=%s", sc);
        printf("\n");
#else
        printf("threads: none (built without OpenMP)\n");
#endif
        return ACD_EXIT_OK;
    }
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (!strcmp(argv[1], commands[i].name)) return commands[i].run(argc - 1, argv + 1);
    fprintf(stderr, "acd: unknown command '%s'\n\n", argv[1]);
    usage(stderr);
    return ACD_EXIT_USAGE;
}
