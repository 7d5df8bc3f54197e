/* acd3/budget: splitting under a part budget by hull excess; see budget.h. */
#include "acd3/budget.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef __SSE2__
#include <emmintrin.h>
#endif
#ifdef _OPENMP
#include <omp.h>
#endif

#include "acd/hull.h"
#include "acd3/budget_sort.h"
#include "acd3/leaf_test.h"
#include "acd3/merge.h"
#include "acd3/resolve.h"
#include "core/error.h"
#include "geom3/hull_volume.h"
#include "geom3/pca.h"
#include "geom3/plane_cut.h"
#include "geom3/volume.h"

/* A cut leaving a piece below this fraction of the part's volume is refused (a sliver), as in the
 * decomposition's own splits. */
#define BUDGET_MIN_PIECE_FRACTION 1e-6
/* Safety net on the number of atoms (parts and pieces). */
#define BUDGET_MAX_ATOMS 20000
/* Phase 1, the cuts after the budget (a part above the limit is cut whatever its cut saves), must
 * end. A phase-1 cut is made only when it makes progress: each piece's bounding box (in the input's
 * frame) has a diagonal at most BUDGET_P1_SHRINK times the part's. The part's best cut that does not
 * is replaced by the best one that does among its candidates and the midplanes of its bounding box
 * (a phase-1 evaluation); the midplane across the box's longest side always does (each piece lies
 * in half the box: a diagonal of at most sqrt(3/4) = 0.866 of the part's) unless it leaves a sliver
 * or an open piece, and then the part stays as it is: a stuck part (`over`). Termination: a piece of
 * diagonal below the limit is within it (its surface and its hull's boundary are no farther apart
 * than its diameter, and acd3/leaf_test's bounds are no larger: each corner's depth below a hull
 * facet and each hull facet point's distance to the surface are at most the diameter), so a chain
 * of phase-1 cuts below a part of diagonal D is at most log(D / limit) / log(1 / BUDGET_P1_SHRINK)
 * deep (77 at the default merge tolerance, 0.0195 of the input's diagonal). Measured (budget 16,
 * main's scores): 0.9 cut more (ChineseDragon-10kv 71 parts in 11 s instead of 43 in 6.9 s: a cut
 * taking off a chunk within the limit leaves the rest's box as it was); a volume rule instead (no
 * piece above 0.9 of the part's volume) does not end (a thin part's pieces halve for ever without
 * meeting the limit: anchor_dense, with up to 16 such cuts per chain, 493 parts and a stuck part).
 * Without a rule the section-hull scores cut anchor.off for minutes, 1% slivers shaved off thin
 * parts whose pieces' vertices doubled. */
#define BUDGET_P1_SHRINK 0.95
/* Hard caps on phase 1 besides (rounding, and the count of pieces, which the depth bound leaves
 * exponential), each ending it with the parts above the limit left stuck, the reason in
 * acd3_budget_result.phase1_stop: a part BUDGET_P1_MAX_GEN phase-1 cuts below the last part the
 * budget phase made is not cut again, and phase 1 makes at most BUDGET_P1_CUTS_PER_PART x (budget +
 * input parts) cuts. */
#define BUDGET_P1_MAX_GEN 96
#define BUDGET_P1_CUTS_PER_PART 32
/* Candidate planes a phase-1 evaluation adds: the midplanes of the part's bounding box. */
#define BUDGET_P1_MIDPLANES 3
/* A part whose phase-1 evaluation found no cut with progress is evaluated once more with planes
 * across its box's longest side at these fractions instead of the midplanes: the midplane can
 * graze a feature and leave a speck the sliver rule refuses (cheese.off as an OBJ soup: a third
 * piece of 6.4e-16 where it touched a hole's rim, the part left above the limit). Each leaves
 * pieces in at most 0.6 of that side, a box diagonal of at most sqrt((0.36 + 2) / 3) = 0.887 of the
 * part's, below BUDGET_P1_SHRINK. */
static const double BUDGET_P1_OFFSETS[BUDGET_P1_MIDPLANES] = {0.45, 0.55, 0.4};

typedef struct atom {
    acd_mesh mesh;   /* owned for pieces, a shallow copy for input parts */
    double vol, hvol, bound;
    int ok;          /* bound <= limit (or not checked) */
    int alive;       /* a part of the current decomposition (not cut) */
    double gain;     /* hull volume its best split saves; -INFINITY: no split */
    acd_cut_result cut; /* that split's pieces (npieces >= 2), or none */
    acd_hull *cut_hulls; /* the pieces' hulls (cut.npieces, owned), or NULL */
    acd_hull hull;   /* pieces: the hull (acd_hull_compute of mesh's vertices) while have_hull */
    int have_hull;
    acd_bvh bvh;     /* pieces: the tree and the hull's facet table its leaf test built (empty when */
    acd3_facet_table table; /* it did not get to them), handed out with the hull for the merge */
    const acd_hull *kept; /* input parts: the caller's hull of the part (read only), or NULL */
    double plane[4];
    acd_status st;
    size_t parent;   /* pieces: the atom cut */
    int evaluated;   /* gain and cut computed (lazily: only when the atom may be the next cut) */
    int p1;          /* evaluated for phase 1: its cut makes progress (BUDGET_P1_SHRINK) or it has none */
    int progress;    /* its cut's pieces' box diagonals are each at most BUDGET_P1_SHRINK of its own */
    int p1off;       /* evaluated for phase 1 again, with BUDGET_P1_OFFSETS (the first found none) */
    int p1gen;       /* phase-1 cuts between it and the last atom a budget-phase cut made */
    int tested;      /* leaf_test done: ok and bound hold */
    int use_kept;    /* its hull is `kept` */
} atom;

typedef struct budget_state {
    atom *a;
    size_t n, cap, nparts;
    double limit, extent;
    int ndir, nexact;
    double screen_rel;      /* BUDGET_SCREEN_REL, or the caller's (acd3_budget_split_screen) */
    size_t *fallbacks;      /* the result's screen_fallbacks */
    double bound_rel;       /* BUDGET_BOUND_REL, or the caller's (acd3_budget_split_tuned; <= -1 or NaN: no
                             * bound; in (-1, 0): a bound raised above the bound, for the tests) */
    size_t *dirs_bounded, *dirs_scored; /* the result's */
    acd_hull_volume_ws *ws; /* per thread of the parallel loops (nws): the sweeps' workspaces, kept
                             * between sweeps (the facets' room is not allocated and touched again) */
    int nws;
} budget_state;

/* The calling thread's sweep workspace. */
static acd_hull_volume_ws *thread_ws(const budget_state *S) {
    int t = 0;
#ifdef _OPENMP
    t = omp_get_thread_num();
#endif
    return &S->ws[t < S->nws ? t : 0];
}

/* A hull's volume as acd_hull_volume gives it for the same points (0 unless dim 3: the same bits,
 * geom3/hull's hull_from_qhull). */
static double hull_vol(const acd_hull *h) { return h->dim == 3 ? h->volume : 0; }

/* A cut's pieces and their hulls (*hulls: cr->npieces of them, or NULL) freed. */
static void cut_with_hulls_free(acd_cut_result *cr, acd_hull **hulls) {
    if (*hulls)
        for (size_t p = 0; p < cr->npieces; p++) acd_hull_free(&(*hulls)[p]);
    free(*hulls);
    *hulls = NULL;
    acd_cut_result_free(cr);
}

/* The atom's best split dropped. */
static void atom_cut_free(atom *A) { cut_with_hulls_free(&A->cut, &A->cut_hulls); }

#define BUDGET_MAX_DIRS 80
#define BUDGET_DIRS 40
#define BUDGET_EXACT 3
#define BUDGET_REFINE_DIRS 3
#define BUDGET_BATCH 4
/* The plane search scores each side of a plane by the hull volume of a sample that depends on the
 * surface, not on its triangulation (docs/acd3d.md "Triangulation density"): at most this many
 * vertices (every k-th of the hull candidates: acd3_budget_hull_candidates), and the plane's section
 * by the extreme points of every edge crossing in BUDGET_SECTION_DIRS directions. */
#define BUDGET_MAX_SCORED 1000
/* A vertex is a hull candidate when a plane through it has the other corners of its triangles
 * below by more than this fraction of their distance to it (rounding far below, a midpoint's
 * neighbours on its edge never). */
#define BUDGET_EXTREME_REL 1e-9
#define BUDGET_OFFSETS 9
/* A section's hull is represented by its extreme vertices in this many directions of its plane
 * (every hull vertex: bunny00 1.2x slower at 40 parts, IoU 0.9804 instead of 0.9802). */
#define BUDGET_SECTION_DIRS 32
/* An exact candidate cut whose pieces' hull volumes, as estimated (geom3/hull_volume), sum to more
 * than this fraction above the atom's best estimated sum is not given qhull hulls: it cannot be the
 * best by qhull's volumes unless an estimate is off by about as much (measured: within 1e-9
 * relative on knot1's sets, 2e-5 on fandisk's, 3e-15 on the armadillo's candidates: the margin is 5
 * times the largest, as decompose's ACD3_VOLUME_SCREEN_REL). The atom's chosen cut is still the best
 * of its candidates by qhull's volumes among those the screen leaves; when none of those is good,
 * the rest get their hulls too. On the armadillo's trimmed run every candidate not chosen now falls
 * out (by qhull's volumes their sums were 1.3e-4 to 1e-1 above the best; 1e-3 before 2026-11-27
 * left 38 of them, a quarter of the candidates' qhull work: 2.5% of the run's instructions; the
 * 21 settings of /work/ident.sh and the bench's budget column gave the same bytes). */
#define BUDGET_SCREEN_REL 1e-4
/* The directions' bound (direction_bound): a direction is scored only when a lower bound of its score,
 * the same sweeps over the sample's hull vertices alone, less BUDGET_BOUND_REL of it, is not above
 * the BUDGET_REFINE_DIRS-th lowest score of the directions scored before it (those the refinement
 * takes); the directions go in increasing order of their bounds. BUDGET_BOUND_REL covers the
 * estimates' error (within about 1e-9 relative of qhull's volumes on knot1's sets, 2e-5 on
 * fandisk's), so the directions refined and their scores are those of scoring every direction.
 * The bound's sweeps cost about half of the sample's (a third of its points, all of them on the
 * hull); on the armadillo's budget run about 1 direction in 5 is then scored. A sample whose hull
 * has more than BUDGET_BOUND_MAX_FRACTION of its points gets no bound (every direction scored). */
#define BUDGET_BOUND_REL 1e-3
#define BUDGET_BOUND_MAX_FRACTION 0.6
/* The bound's sweeps take each section by its extreme points in BUDGET_BOUND_SECTION_DIRS directions
 * of its plane (a subset of the section's points, so still a lower bound): 12 directions cost the
 * armadillo's trimmed run 3.1% fewer instructions than the 32 of the scoring (the bound looser: 839
 * directions scored instead of 612; 16: 2.7%, 20: 1.8%; docs/results/3d-speed.md). */
#define BUDGET_BOUND_SECTION_DIRS 12
_Static_assert(BUDGET_BOUND_SECTION_DIRS <= BUDGET_SECTION_DIRS, "the bound's section directions are at most the scoring's");
/* Offsets one sweep scores at most. */
#define BUDGET_MAX_QUERIES 32
#define BUDGET_REFINE 3

/* Every vertex's projection on a direction (n.p; less the offset per plane: the same bits as n.p - c). */
static void vertex_dots(const acd_mesh *m, const double nrm[3], double *dall) {
    for (size_t v = 0; v < m->nvertices; v++) {
        const double *p = m->vertices + 3 * v;
        dall[v] = nrm[0] * p[0] + nrm[1] * p[1] + nrm[2] * p[2];
    }
}

/* The plane search of one atom: its directions (the part's principal axes, the diagonals between
 * them and a Fibonacci half-sphere in the principal frame), the vertex sample, the edges and, per
 * direction, the projection's range and the best offset found. Filled by plan_init, then each
 * direction is scored on its own (score_dir, refine_dir: parallel tasks over the batch's atoms and
 * directions, each computing exactly what the sequential search did). */
typedef struct plan {
    int nd, ok, nomem; /* nomem: the sample could not be allocated */
    double dirs[BUDGET_MAX_DIRS][3];
    double centroid[3];
    size_t *sv;   /* the sampled vertices (nsv; owned: plan_free) */
    size_t nsv; /* sampled vertices */
    uint32_t *edges; /* the mesh's edges (ne pairs, each once: from its lower index, in triangle order; owned) */
    size_t ne;
    double lo[BUDGET_MAX_DIRS], st[BUDGET_MAX_DIRS], bs[BUDGET_MAX_DIRS], bc[BUDGET_MAX_DIRS];
    int ord[BUDGET_MAX_DIRS];
    uint32_t *sord; /* per direction, the sample's order along it (nsv; score_dir's, for the
                     * refinement; owned), or NULL */
    unsigned char *hv; /* per sampled vertex: a vertex of the sample's hull (the bound's subset:
                        * direction_bound; owned), or NULL: no bound, every direction scored */
    size_t nhv;
    double lb[BUDGET_MAX_DIRS]; /* per direction: a lower bound of bs (direction_bound), -INFINITY
                                 * when none */
    double lbo[BUDGET_MAX_DIRS][BUDGET_OFFSETS]; /* per direction and fixed offset: a lower bound of
                                                  * its score (direction_bound), -INFINITY when none */
    double top[BUDGET_REFINE_DIRS];   /* the lowest bs of the directions scored so far, increasing */
    unsigned char scored[BUDGET_MAX_DIRS]; /* the direction's full score computed (score_dir) */
} plan;

size_t acd3_budget_hull_candidates(const acd_mesh *m, unsigned char *flag) {
    size_t nv = m->nvertices, nt = m->ntriangles;
    /* per vertex: its normal (the sum of its triangles' area vectors) and its neighbours' sum less
     * its own position times their count (-(count) times its offset from their mean) */
    double *acc = calloc(8 * (nv ? nv : 1), sizeof *acc); /* then the two lengths (8 per vertex) */
    if (!acc) return SIZE_MAX;
    for (size_t v = 0; v < nv; v++) flag[v] = 0;
    for (size_t t = 0; t < nt; t++) {
        const uint32_t *T = m->triangles + 3 * t;
        const double *a = m->vertices + 3 * (size_t)T[0], *b = m->vertices + 3 * (size_t)T[1], *c = m->vertices + 3 * (size_t)T[2];
        double u[3], w[3];
        for (int k = 0; k < 3; k++) u[k] = b[k] - a[k], w[k] = c[k] - a[k];
        double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
        for (int i = 0; i < 3; i++) {
            double *A = acc + 8 * (size_t)T[i];
            const double *p = m->vertices + 3 * (size_t)T[i], *q = m->vertices + 3 * (size_t)T[(i + 1) % 3],
                         *r = m->vertices + 3 * (size_t)T[(i + 2) % 3];
            for (int k = 0; k < 3; k++) A[k] += n[k], A[3 + k] += (q[k] - p[k]) + (r[k] - p[k]);
            flag[T[i]] = 3; /* bit 0: the normal separates so far, bit 1: the offset from the mean */
        }
    }
    for (size_t v = 0; v < nv; v++) { /* the two vectors' lengths, once per vertex */
        double *A = acc + 8 * v;
        A[6] = sqrt(A[0] * A[0] + A[1] * A[1] + A[2] * A[2]), A[7] = sqrt(A[3] * A[3] + A[4] * A[4] + A[5] * A[5]);
    }
    for (size_t t = 0; t < nt; t++) {
        const uint32_t *T = m->triangles + 3 * t;
        for (int i = 0; i < 3; i++) {
            size_t v = T[i];
            if (!flag[v]) continue;
            const double *A = acc + 8 * v, *p = m->vertices + 3 * v;
            double ln = A[6], lm = A[7];
            for (int j = 1; j < 3; j++) {
                const double *q = m->vertices + 3 * (size_t)T[(i + j) % 3];
                double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
                double ld = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                /* below the plane of normal A (the normal), of normal -A[3..5] (away from the mean) */
                if (!(A[0] * d[0] + A[1] * d[1] + A[2] * d[2] < -BUDGET_EXTREME_REL * ln * ld)) flag[v] &= (unsigned char)~1u;
                if (!(A[3] * d[0] + A[4] * d[1] + A[5] * d[2] > BUDGET_EXTREME_REL * lm * ld)) flag[v] &= (unsigned char)~2u;
            }
        }
    }
    free(acc);
    size_t n = 0;
    for (size_t v = 0; v < nv; v++) n += flag[v] = flag[v] != 0;
    return n;
}

static void plan_free(plan *P) {
    free(P->sv);
    free(P->edges);
    free(P->sord);
    free(P->hv);
    P->sv = NULL;
    P->edges = NULL;
    P->sord = NULL;
    P->hv = NULL;
}

/* The sampled vertices: every k-th of the hull candidates, at most BUDGET_MAX_SCORED (every k-th
 * vertex when fewer than 4 are candidates, and every vertex of a part of at most BUDGET_MAX_SCORED,
 * as before the candidates: a coarse part's concave vertices carry the planes that split it; on
 * the budget sweep, 3torus.off and P.off, scored on candidates only, stayed above the merge
 * tolerance and were cut on for minutes); 0 when out of memory. */
static int plan_sample(const acd_mesh *m, plan *P) {
    size_t nv = m->nvertices;
    unsigned char *flag = malloc(nv ? nv : 1);
    if (!flag) return 0;
    size_t nc = acd3_budget_hull_candidates(m, flag);
    if (nc == SIZE_MAX) {
        free(flag);
        return 0;
    }
    int all = nc < 4 || nv <= BUDGET_MAX_SCORED;
    size_t pool = all ? nv : nc, stride = (pool + BUDGET_MAX_SCORED - 1) / BUDGET_MAX_SCORED;
    P->nsv = (pool + stride - 1) / stride;
    P->sv = malloc((P->nsv ? P->nsv : 1) * sizeof *P->sv);
    if (!P->sv) {
        free(flag);
        return 0;
    }
    size_t k = 0, j = 0;
    for (size_t v = 0; v < nv; v++) {
        if (!all && !flag[v]) continue;
        if (j++ % stride == 0) P->sv[k++] = v;
    }
    P->nsv = k;
    free(flag);
    return 1;
}

/* The bound's subset (direction_bound): P->hv flags the sampled vertices that are vertices of the
 * sample's hull as the own Quickhull finds them (acd_hull_volume_vertices: any subset gives a lower
 * bound, so its rounding cannot change a result; it replaced qhull's vertices, 3% of the
 * armadillo's trimmed run), when they are at most BUDGET_BOUND_MAX_FRACTION of the sample (else, or
 * when it has no hull, P->hv stays NULL: no bound); 0 when out of memory. */
static int plan_hull_subset(const acd_mesh *m, plan *P) {
    size_t nsv = P->nsv;
    if (nsv < 4) return 1;
    double *pts = malloc(3 * nsv * sizeof *pts);
    unsigned char *hv = malloc(nsv);
    if (!pts || !hv) {
        free(pts), free(hv);
        return 0;
    }
    for (size_t k = 0; k < nsv; k++) memcpy(pts + 3 * k, m->vertices + 3 * P->sv[k], sizeof(double[3]));
    acd_hull_volume_ws w;
    memset(&w, 0, sizeof w);
    size_t nh = 0;
    int r = acd_hull_volume_vertices(pts, nsv, &w, hv, &nh);
    acd_hull_volume_ws_free(&w);
    free(pts);
    if (r < 0) {
        free(hv);
        return 0;
    }
    if (r == 0 || (double)nh > BUDGET_BOUND_MAX_FRACTION * (double)nsv) {
        free(hv);
        return 1;
    }
    P->hv = hv;
    P->nhv = nh;
    return 1;
}

static void plan_init(const acd_mesh *m, int ndir, int bound, plan *P) {
    P->ok = 0;
    P->nd = 0;
    P->sv = NULL;
    P->edges = NULL;
    P->sord = NULL;
    P->hv = NULL;
    P->nhv = 0;
    for (int q = 0; q < BUDGET_REFINE_DIRS; q++) P->top[q] = INFINITY;
    if (m->nvertices < 4) return;
    acd_pca pca;
    if (acd_pca_points(m->vertices, m->nvertices, NULL, &pca, NULL) != ACD_OK) return;
    double (*dirs)[3] = P->dirs;
    int nd = 0;
    for (int a = 0; a < 3; a++) memcpy(dirs[nd++], pca.axes[a], sizeof(double[3]));
    if (ndir > 3) {
        static const int pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
        for (int q = 0; q < 3; q++)
            for (int sg = -1; sg <= 1; sg += 2) {
                for (int k = 0; k < 3; k++)
                    dirs[nd][k] = (pca.axes[pairs[q][0]][k] + sg * pca.axes[pairs[q][1]][k]) / sqrt(2.0);
                nd++;
            }
        for (int s1 = -1; s1 <= 1; s1 += 2)
            for (int s2 = -1; s2 <= 1; s2 += 2) {
                for (int k = 0; k < 3; k++)
                    dirs[nd][k] = (pca.axes[0][k] + s1 * pca.axes[1][k] + s2 * pca.axes[2][k]) / sqrt(3.0);
                nd++;
            }
    }
    if (ndir > 13) { /* more: a Fibonacci half-sphere in the principal frame */
        int extra = ndir - 13;
        if (extra > BUDGET_MAX_DIRS - 13) extra = BUDGET_MAX_DIRS - 13;
        for (int i = 0; i < extra; i++) {
            double z = 1 - (i + 0.5) / extra, r = sqrt(fmax(0, 1 - z * z)), ph = 2.399963229728653 * i;
            double l[3] = {r * cos(ph), r * sin(ph), z};
            for (int k = 0; k < 3; k++)
                dirs[nd][k] = l[0] * pca.axes[0][k] + l[1] * pca.axes[1][k] + l[2] * pca.axes[2][k];
            nd++;
        }
    }
    P->nd = nd;
    memcpy(P->centroid, pca.centroid, sizeof P->centroid);
    P->edges = malloc((3 * m->ntriangles + 1) * 2 * sizeof *P->edges);
    if (!P->edges || !plan_sample(m, P)) {
        P->nomem = 1;
        return;
    }
    if (P->nsv <= UINT32_MAX) P->sord = malloc(((size_t)nd * P->nsv + 1) * sizeof *P->sord); /* NULL: sorted again */
    P->ne = 0;
    for (size_t t = 0; t < m->ntriangles; t++)
        for (int e = 0; e < 3; e++) {
            uint32_t a = m->triangles[3 * t + e], b = m->triangles[3 * t + (e == 2 ? 0 : e + 1)];
            if (a < b) P->edges[2 * P->ne] = a, P->edges[2 * P->ne + 1] = b, P->ne++;
        }
    double rlo[BUDGET_MAX_DIRS], rhi[BUDGET_MAX_DIRS];
    int d0 = 0;
#ifdef __SSE2__
    /* four directions per pass over the vertices, two to a register: the same products and sums,
     * the same selections (compare masks: s on a tie, a NaN s ignored) */
    for (; d0 + 3 < nd; d0 += 4) {
        const __m128d a0 = _mm_set_pd(dirs[d0 + 1][0], dirs[d0][0]), a1 = _mm_set_pd(dirs[d0 + 1][1], dirs[d0][1]),
                      a2 = _mm_set_pd(dirs[d0 + 1][2], dirs[d0][2]), b0 = _mm_set_pd(dirs[d0 + 3][0], dirs[d0 + 2][0]),
                      b1 = _mm_set_pd(dirs[d0 + 3][1], dirs[d0 + 2][1]), b2 = _mm_set_pd(dirs[d0 + 3][2], dirs[d0 + 2][2]);
        __m128d loa = _mm_set1_pd(INFINITY), hia = _mm_set1_pd(-INFINITY), lob = loa, hib = hia;
        for (size_t v = 0; v < m->nvertices; v++) {
            const double *p = m->vertices + 3 * v;
            const __m128d x = _mm_set1_pd(p[0]), y = _mm_set1_pd(p[1]), z = _mm_set1_pd(p[2]);
            __m128d sa = _mm_add_pd(_mm_add_pd(_mm_mul_pd(a0, x), _mm_mul_pd(a1, y)), _mm_mul_pd(a2, z));
            __m128d sb = _mm_add_pd(_mm_add_pd(_mm_mul_pd(b0, x), _mm_mul_pd(b1, y)), _mm_mul_pd(b2, z));
            __m128d k = _mm_cmple_pd(sa, loa);
            loa = _mm_or_pd(_mm_and_pd(k, sa), _mm_andnot_pd(k, loa));
            k = _mm_cmpge_pd(sa, hia);
            hia = _mm_or_pd(_mm_and_pd(k, sa), _mm_andnot_pd(k, hia));
            k = _mm_cmple_pd(sb, lob);
            lob = _mm_or_pd(_mm_and_pd(k, sb), _mm_andnot_pd(k, lob));
            k = _mm_cmpge_pd(sb, hib);
            hib = _mm_or_pd(_mm_and_pd(k, sb), _mm_andnot_pd(k, hib));
        }
        _mm_storeu_pd(rlo + d0, loa), _mm_storeu_pd(rhi + d0, hia);
        _mm_storeu_pd(rlo + d0 + 2, lob), _mm_storeu_pd(rhi + d0 + 2, hib);
    }
#endif
    for (int d = d0; d < nd; d++) {
        const double *ax = dirs[d];
        double lo = INFINITY, hi = -INFINITY;
        for (size_t v = 0; v < m->nvertices; v++) {
            const double *p = m->vertices + 3 * v;
            double s = ax[0] * p[0] + ax[1] * p[1] + ax[2] * p[2];
            /* fmin(lo, s), fmax(hi, s) as glibc computes them (minsd, maxsd: s on a tie; a NaN s
             * ignored; lo and hi are never NaN) without the library calls (1.6% of the armadillo's
             * budget run) */
            if (s <= lo) lo = s;
            if (s >= hi) hi = s;
        }
        rlo[d] = lo, rhi[d] = hi;
    }
    for (int d = 0; d < nd; d++) {
        double lo = rlo[d], hi = rhi[d];
        P->bs[d] = INFINITY, P->bc[d] = 0, P->st[d] = (hi - lo) / (BUDGET_OFFSETS + 1);
        P->lo[d] = hi > lo ? lo : NAN;
        P->ord[d] = d;
        P->lb[d] = -INFINITY;
        P->scored[d] = 0;
    }
    if (bound && !plan_hull_subset(m, P)) {
        P->nomem = 1;
        return;
    }
    P->ok = 1;
}



/* The first l of the m points (u[l], v[l]) maximising cu u[l] + sn v[l] (0 when none is above
 * -INFINITY: NaN or -INFINITY everywhere), each value computed as cu * u + sn * v (a product, a
 * product, their sum: the same bits two at a time where SSE2 is there; each lane keeps its first
 * maximum, the lanes' are then joined by value, then the lower index). */
static size_t argmax_first(const double *u, const double *v, size_t m, double cu, double sn) {
    size_t l = 0, arg = 0;
    double best = -INFINITY;
#ifdef __SSE2__
    if (m >= 2) {
        const __m128d c = _mm_set1_pd(cu), s = _mm_set1_pd(sn), two = _mm_set1_pd(2);
        __m128d b = _mm_set1_pd(-INFINITY), at = _mm_set_pd(1, 0), ix = at; /* (index as a double: exact) */
        for (; l + 1 < m; l += 2) {
            __m128d y = _mm_add_pd(_mm_mul_pd(c, _mm_loadu_pd(u + l)), _mm_mul_pd(s, _mm_loadu_pd(v + l)));
            __m128d gt = _mm_cmpgt_pd(y, b);
            b = _mm_or_pd(_mm_and_pd(gt, y), _mm_andnot_pd(gt, b));
            at = _mm_or_pd(_mm_and_pd(gt, ix), _mm_andnot_pd(gt, at));
            ix = _mm_add_pd(ix, two);
        }
        double bb[2], aa[2];
        _mm_storeu_pd(bb, b), _mm_storeu_pd(aa, at);
        int one = bb[1] > bb[0] || (bb[1] == bb[0] && aa[1] < aa[0]);
        best = bb[one], arg = (size_t)aa[one];
    }
#endif
    for (; l < m; l++) {
        double y = cu * u[l] + sn * v[l];
        if (y > best) best = y, arg = l;
    }
    return arg;
}

/* The cosines and sines of K directions of a section's plane evenly spread (section_hull's:
 * BUDGET_SECTION_DIRS), into cssn (2 each). */
static void section_dirs(double *cssn, int K) {
    for (int j = 0; j < K; j++) {
        double an = 6.283185307179586 * j / K;
        cssn[2 * j] = cos(an), cssn[2 * j + 1] = sin(an);
    }
}

/* Two axes e1, e2 of the plane of normal nrm (section_hull's frame). */
static void section_frame(const double nrm[3], double e1[3], double e2[3]) {
    int k0 = fabs(nrm[0]) <= fabs(nrm[1]) && fabs(nrm[0]) <= fabs(nrm[2]) ? 0 : fabs(nrm[1]) <= fabs(nrm[2]) ? 1 : 2;
    double a[3] = {0, 0, 0};
    a[k0] = 1;
    e1[0] = nrm[1] * a[2] - nrm[2] * a[1], e1[1] = nrm[2] * a[0] - nrm[0] * a[2], e1[2] = nrm[0] * a[1] - nrm[1] * a[0];
    e2[0] = nrm[1] * e1[2] - nrm[2] * e1[1], e2[1] = nrm[2] * e1[0] - nrm[0] * e1[2], e2[2] = nrm[0] * e1[1] - nrm[1] * e1[0];
}

/* The n points x (3 each, on a plane of normal nrm: a section as section_hull left it) that are
 * extreme (the first on ties) in the BUDGET_BOUND_SECTION_DIRS directions cssn (2 each) of the
 * plane, copied to out in their order (all n when there are not more than those directions, or more
 * than section_hull keeps: a collinear section); how many. */
static size_t section_extremes(const double *x, size_t n, const double nrm[3], const double *cssn, double *out) {
    const int K = BUDGET_BOUND_SECTION_DIRS;
    if (n <= (size_t)K || n > BUDGET_SECTION_DIRS) {
        memcpy(out, x, 3 * n * sizeof *out);
        return n;
    }
    double e1[3], e2[3], uu[BUDGET_SECTION_DIRS], vv[BUDGET_SECTION_DIRS];
    unsigned char mark[BUDGET_SECTION_DIRS] = {0};
    section_frame(nrm, e1, e2);
    for (size_t l = 0; l < n; l++) {
        const double *q = x + 3 * l;
        uu[l] = e1[0] * q[0] + e1[1] * q[1] + e1[2] * q[2];
        vv[l] = e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2];
    }
    for (int j = 0; j < K; j++) mark[argmax_first(uu, vv, n, cssn[2 * j], cssn[2 * j + 1])] = 1;
    size_t m = 0;
    for (size_t l = 0; l < n; l++)
        if (mark[l]) memcpy(out + 3 * m++, x + 3 * l, sizeof(double[3]));
    return m;
}

/* The n points pts (3 each, on a plane of normal nrm) reduced in place to the vertices of their
 * convex hull in that plane (monotone chain, collinear points dropped; in floating point: the points
 * only feed a score), then, beyond BUDGET_SECTION_DIRS of them, to the extreme ones in those
 * directions (cssn: section_dirs), kept in their input order; tmp: room for 3 * n + 1 (the points sorted, then the
 * chains: 2 * n + 1); how many. Only the hull's vertices
 * can be vertices of a 3D hull holding the section, so a side's hull is the same from them as from
 * every crossing (less what the directions leave). */
static size_t section_hull(double *pts, size_t n, const double nrm[3], const double *cssn, xpt *tmp, size_t *cnt) {
    if (n < 4) return n;
    double e1[3], e2[3];
    section_frame(nrm, e1, e2);
    xpt *p = tmp, *h = tmp + n;
    for (size_t k = 0; k < n; k++) {
        const double *x = pts + 3 * k;
        p[k].u = e1[0] * x[0] + e1[1] * x[1] + e1[2] * x[2];
        p[k].v = e2[0] * x[0] + e2[1] * x[1] + e2[2] * x[2];
        p[k].i = k;
    }
    xpt_bucket_sort(p, n, h, cnt); /* h: free until the chains */
    size_t m = 0;
    for (int pass = 0; pass < 2; pass++) { /* lower chain, then upper */
        size_t base = m;
        for (size_t j = 0; j < n; j++) {
            const xpt *q = &p[pass ? n - 1 - j : j];
            while (m >= base + 2) {
                const xpt *o = &h[m - 2], *r = &h[m - 1];
                if ((r->u - o->u) * (q->v - o->v) - (r->v - o->v) * (q->u - o->u) > 0) break;
                m--;
            }
            h[m++] = *q;
        }
        m--; /* the last is the next chain's first */
    }
    if (m < 3) return n; /* degenerate (collinear): all kept */
    const int K = BUDGET_SECTION_DIRS;
    if (m > (size_t)K) { /* the extreme vertex in each of K directions of the plane (the first on ties) */
        /* p (free now): the chain's coordinates apart (m of each, m <= n) and its marks */
        double *hu = (double *)p, *hv = hu + m;
        unsigned char *mk = (unsigned char *)(hv + m);
        _Static_assert(sizeof(xpt) >= 2 * sizeof(double) + 1, "a section point's room holds its two coordinates and a mark");
        for (size_t l = 0; l < m; l++) hu[l] = h[l].u, hv[l] = h[l].v, mk[l] = 0;
        for (int j = 0; j < K; j++) mk[argmax_first(hu, hv, m, cssn[2 * j], cssn[2 * j + 1])] = 1;
        size_t keep = 0;
        for (size_t l = 0; l < m; l++)
            if (mk[l]) h[keep++] = h[l];
        m = keep;
    }
    /* in increasing index order, in place */
    for (size_t j = 1; j < m; j++)
        for (size_t l = j; l > 0 && h[l].i < h[l - 1].i; l--) {
            xpt t = h[l];
            h[l] = h[l - 1];
            h[l - 1] = t;
        }
    for (size_t j = 0; j < m; j++) memmove(pts + 3 * j, pts + 3 * h[j].i, sizeof(double[3]));
    return m;
}

/* The crossings of the planes n.x = cs[i] (nq increasing offsets) with the ne edges (pairs of vertex
 * indices), dall the vertices' projections (vertex_dots), each plane's reduced to its section's hull
 * (section_hull): *xs (allocated) holds plane i's at [xb[i], xe[i]) (points). 0 when out of memory. */
static int section_crossings(const acd_mesh *m, const uint32_t *edges, size_t ne, const double nrm[3], const double *dall,
                             const double *cs, int nq, double **xs, size_t *xb, size_t *xe) {
    size_t cnt[BUDGET_MAX_QUERIES] = {0}, nh = 0, hcap = 1024;
    uint32_t *hit = malloc(hcap * sizeof *hit); /* (edge, offset) pairs */
    uint8_t *le = malloc(m->nvertices + 1); /* per vertex: how many offsets lie at or below it */
    *xs = NULL;
    if (!hit || !le) {
        free(hit), free(le);
        return 0;
    }
    _Static_assert(BUDGET_MAX_QUERIES < 256, "a vertex's offset count must fit a byte");
    /* le[v]: the count of cs[i] <= dall[v] (cs increasing): guessed from where dall[v] falls between
     * the first and the last offset (exact for evenly spread ones up to rounding), then moved up while
     * the next offset is at or below it and down while the previous one is above it, the only count
     * that satisfies both (the same counts as comparing every offset, which took 19% of this
     * function on the armadillo; a binary search of fixed steps mispredicted its branches) */
    const double c0 = nq > 0 ? cs[0] : 0, span = nq > 1 ? cs[nq - 1] - cs[0] : 0;
    double sc = nq > 1 && span > 0 ? (nq - 1) / span : 0;
    if (!(sc < INFINITY)) sc = 0;
    for (size_t v = 0; v < m->nvertices; v++) {
        const double x = dall[v], t = (x - c0) * sc;
        int c = t >= 0 ? (t < nq ? (int)t + 1 : nq) : 0; /* (NaN: 0, as no offset is at or below it) */
        while (c < nq && cs[c] <= x) c++;
        while (c > 0 && cs[c - 1] > x) c--;
        le[v] = (uint8_t)c;
    }
    for (size_t k = 0; k < ne; k++) {
        /* the planes it crosses: (da - c >= 0) != (db - c >= 0), i.e. lo < c <= hi for its ends' lower
         * and higher projections: the offsets (increasing) from le[lo] (the first above lo) to before
         * le[hi] (the first above hi) */
        int la = le[edges[2 * k]], lb = le[edges[2 * k + 1]];
        if (la == lb) continue;
        int i0 = la < lb ? la : lb, i1 = la < lb ? lb : la;
        for (int i = i0; i < i1; i++) {
            if (nh + 2 > hcap) {
                uint32_t *nhit = realloc(hit, 2 * hcap * sizeof *hit);
                if (!nhit) {
                    free(hit), free(le);
                    return 0;
                }
                hit = nhit, hcap *= 2;
            }
            hit[nh++] = (uint32_t)k, hit[nh++] = (uint32_t)i;
            cnt[i]++;
        }
    }
    free(le);
    size_t tot = 0, mx = 0;
    for (int i = 0; i < nq; i++) xb[i] = xe[i] = tot, tot += cnt[i], mx = cnt[i] > mx ? cnt[i] : mx;
    *xs = malloc((3 * tot + 3) * sizeof **xs);
    xpt *tmp = malloc((3 * mx + 1) * sizeof *tmp);
    size_t *bcnt = malloc((mx + 1) * sizeof *bcnt);
    if (!*xs || !tmp || !bcnt) {
        free(hit), free(*xs), free(tmp), free(bcnt);
        *xs = NULL;
        return 0;
    }
    for (size_t h = 0; h < nh; h += 2) {
        uint32_t a = edges[2 * (size_t)hit[h]], b = edges[2 * (size_t)hit[h] + 1];
        int i = (int)hit[h + 1];
        const double *p = m->vertices + 3 * (size_t)a, *q = m->vertices + 3 * (size_t)b;
        double sp = dall[a] - cs[i], sq = dall[b] - cs[i], w = sp / (sp - sq), *o = *xs + 3 * xe[i]++;
        for (int d = 0; d < 3; d++) o[d] = p[d] + w * (q[d] - p[d]);
    }
    free(hit);
    double cssn[2 * BUDGET_SECTION_DIRS];
    section_dirs(cssn, BUDGET_SECTION_DIRS);
    for (int i = 0; i < nq; i++) xe[i] = xb[i] + section_hull(*xs + 3 * xb[i], xe[i] - xb[i], nrm, cssn, tmp, bcnt);
    free(tmp), free(bcnt);
    return 1;
}

/* One side's sampled hull volume of the plane n.x = c (above: s >= 0, else below): its sampled
 * vertices (dv: their projections), then the nx crossings x; buf: room for them. */
static double side_volume(const acd_mesh *m, const size_t *sv, size_t nsv, const double *dv, double c, int above,
                          const double *x, size_t nx, double *buf, acd_hull_volume_ws *w) {
    size_t n = 0, k = 0;
    for (; k < nsv; k++)
        if ((dv[k] - c >= 0) == above) memcpy(buf + 3 * n++, m->vertices + 3 * sv[k], sizeof(double[3]));
    memcpy(buf + 3 * n, x, 3 * nx * sizeof *x);
    return acd_hull_volume_fast(buf, n + nx, w, NULL);
}

/* A direction's offsets prepared for its sweeps (dir_prep): the sample's projections, the
 * sections' hull points and the sample sorted along the direction. Read only by the sweeps (the two
 * sides of a refined direction are parallel tasks over one of these). */
typedef struct dir_data {
    int d, nq;
    const double *cs;  /* the nq increasing offsets */
    const size_t *sv;  /* the sampled vertices (nsv: P's, or the bound's subset) */
    size_t nsv;
    double *dv;        /* their projections (nsv) */
    double *xs;        /* the sections' points (section_crossings) */
    size_t xb[BUDGET_MAX_QUERIES], xe[BUDGET_MAX_QUERIES], mx; /* mx: the most points of a section */
    double *srt;       /* the sample sorted along d (3 each) */
    size_t cntb[BUDGET_MAX_QUERIES]; /* the sampled vertices below offset i: a prefix of srt */
} dir_data;

static void dir_free(dir_data *D) {
    free(D->dv), free(D->xs), free(D->srt);
    D->dv = D->xs = D->srt = NULL;
}

/* Direction d at the nq increasing offsets cs prepared (touches only D, and P->sord's row d when
 * sorted is 0: the sample's order along d kept for the refinement, which reads it when sorted is 1);
 * 0 when out of memory (D freed). */
static int dir_prep(const acd_mesh *m, const plan *P, int d, const double *cs, int nq, int sorted, dir_data *D) {
    size_t nsv = P->nsv;
    D->d = d, D->nq = nq, D->cs = cs, D->sv = P->sv, D->nsv = nsv;
    D->xs = D->srt = NULL;
    D->dv = malloc((nsv + 1) * sizeof *D->dv);
    double *dall = malloc((m->nvertices + 1) * sizeof *dall);
    keyed *ord = malloc(2 * (nsv + 1) * sizeof *ord + (nsv + 1) * sizeof(size_t)); /* then keyed_bucket_sort's counts */
    D->srt = malloc(3 * (nsv + 1) * sizeof *D->srt);
    if (!D->dv || !dall || !ord || !D->srt) {
        free(dall), free(ord), dir_free(D);
        return 0;
    }
    double *dv = D->dv;
    vertex_dots(m, P->dirs[d], dall);
    for (size_t k = 0; k < nsv; k++) dv[k] = dall[P->sv[k]];
    if (!section_crossings(m, P->edges, P->ne, P->dirs[d], dall, cs, nq, &D->xs, D->xb, D->xe)) {
        free(dall), free(ord), dir_free(D);
        return 0;
    }
    free(dall);
    D->mx = 0;
    for (int i = 0; i < nq; i++) D->mx = D->xe[i] - D->xb[i] > D->mx ? D->xe[i] - D->xb[i] : D->mx;
    /* the sample sorted along d (by projection, then index): side below (n.p - c < 0) a prefix,
     * side above a suffix */
    uint32_t *so = P->sord ? P->sord + (size_t)d * nsv : NULL;
    if (so && sorted)
        for (size_t k = 0; k < nsv; k++) ord[k].key = dv[so[k]], ord[k].i = so[k];
    else {
        for (size_t k = 0; k < nsv; k++) ord[k].key = dv[k], ord[k].i = k;
        keyed_bucket_sort(ord, nsv, ord + nsv, (size_t *)(ord + 2 * (nsv + 1)));
        if (so)
            for (size_t k = 0; k < nsv; k++) so[k] = (uint32_t)ord[k].i;
    }
    for (size_t k = 0; k < nsv; k++) memcpy(D->srt + 3 * k, m->vertices + 3 * P->sv[ord[k].i], sizeof(double[3]));
    size_t c = 0;
    for (int i = 0; i < nq; i++) {
        while (c < nsv && ord[c].key < cs[i]) c++;
        D->cntb[i] = c;
    }
    free(ord);
    return 1;
}

/* A prepared direction's sampled side hull volumes at its offsets (which: 1 the side below, 2
 * above, 3 both) by one sweep per side (acd_hull_volume_sweep: the sampled vertices sorted along
 * d, the hull grown offset by offset, each plane's section hull added and undone); an offset a sweep
 * leaves computed on its own (side_volume). Touches only vb, va; 0 when out of memory. */
static int dir_sweep(const acd_mesh *m, const plan *P, const dir_data *D, int which, const unsigned char *need,
                     double *vb, double *va, acd_hull_volume_ws *hw) {
    size_t nsv = D->nsv;
    int nq = D->nq, d = D->d;
    const double *cs = D->cs, *xs = D->xs;
    const size_t *xb = D->xb, *xe = D->xe;
    double *buf = malloc(3 * (nsv + D->mx + 1) * sizeof *buf), *rev = NULL;
    if (!buf) return 0;
    size_t cnta[BUDGET_MAX_QUERIES], xba[BUDGET_MAX_QUERIES], xea[BUDGET_MAX_QUERIES];
    unsigned char needa[BUDGET_MAX_QUERIES];
    for (int i = 0; i < nq; i++) {
        cnta[nq - 1 - i] = nsv - D->cntb[i], xba[nq - 1 - i] = xb[i], xea[nq - 1 - i] = xe[i];
        needa[nq - 1 - i] = need ? need[i] : 1;
    }
    double vr[BUDGET_MAX_QUERIES];
    int ok = 1;
    if (which & 1) ok = acd_hull_volume_sweep_some(D->srt, nsv, P->dirs[d], D->cntb, xs, xb, xe, nq, need, vb, hw) == 0;
    if (ok && (which & 2)) {
        rev = malloc(3 * (nsv + 1) * sizeof *rev); /* reversed: the side above as a prefix */
        if (!rev) ok = 0;
        for (size_t k = 0; rev && k < nsv; k++) memcpy(rev + 3 * k, D->srt + 3 * (nsv - 1 - k), sizeof(double[3]));
        if (ok) ok = acd_hull_volume_sweep_some(rev, nsv, P->dirs[d], cnta, xs, xba, xea, nq, need ? needa : NULL, vr, hw) == 0;
        for (int i = 0; ok && i < nq; i++) va[i] = vr[nq - 1 - i];
    }
    for (int i = 0; ok && i < nq; i++) { /* the offsets a sweep left (of those asked for) */
        if (need && !need[i]) continue;
        const double *x = xs + 3 * xb[i];
        size_t nx = xe[i] - xb[i];
        if ((which & 1) && vb[i] == -3) vb[i] = side_volume(m, D->sv, nsv, D->dv, cs[i], 0, x, nx, buf, hw);
        if ((which & 2) && va[i] == -3) va[i] = side_volume(m, D->sv, nsv, D->dv, cs[i], 1, x, nx, buf, hw);
        if (((which & 1) && vb[i] == -1) || ((which & 2) && va[i] == -1)) ok = 0;
    }
    free(buf), free(rev);
    return ok;
}

/* Direction d's bound (touches only D and P->lb[d], P->sord's row d): its fixed offsets prepared
 * (dir_prep, into D: cs, room for BUDGET_OFFSETS, is D's offsets) and, when the plan has the bound's
 * subset (P->hv: the sample's hull vertices), the same sweeps over that subset alone. A subset's hull
 * lies in the set's, so each side's volume, and the best sum over the offsets, is at most the
 * sample's (as estimated: within about 1e-9 relative of qhull's volumes on knot1's sets, 2e-5 on
 * fandisk's); P->lb[d] is that best sum less BUDGET_BOUND_REL of it, a lower bound of the bs[d]
 * that score_dir computes. 0 when out of memory (D freed). */
static int direction_bound(const acd_mesh *m, plan *P, int d, double *cs, dir_data *D, double bound_rel,
                           acd_hull_volume_ws *hw) {
    P->lb[d] = -INFINITY;
    for (int i = 0; i < BUDGET_OFFSETS; i++) P->lbo[d][i] = -INFINITY;
    for (int i = 1; i <= BUDGET_OFFSETS; i++) cs[i - 1] = P->lo[d] + P->st[d] * i;
    if (!dir_prep(m, P, d, cs, BUDGET_OFFSETS, 0, D)) return 0;
    if (!P->hv || !P->sord || !(bound_rel > -1)) return 1;
    size_t nsv = P->nsv, nc = 0;
    const uint32_t *so = P->sord + (size_t)d * nsv;
    dir_data C = *D;
    size_t *svc = malloc((P->nhv + 1) * sizeof *svc);
    C.dv = malloc((P->nhv + 1) * sizeof *C.dv);
    C.srt = malloc(3 * (P->nhv + 1) * sizeof *C.srt);
    int ok = svc && C.dv && C.srt;
    int q = 0;
    for (size_t k = 0; ok && k < nsv; k++) { /* the subset in the sample's order along d */
        while (q < BUDGET_OFFSETS && D->cntb[q] == k) C.cntb[q++] = nc;
        if (!P->hv[so[k]]) continue;
        svc[nc] = P->sv[so[k]], C.dv[nc] = D->dv[so[k]];
        memcpy(C.srt + 3 * nc, D->srt + 3 * k, sizeof(double[3]));
        nc++;
    }
    while (q < BUDGET_OFFSETS) C.cntb[q++] = nc;
    C.sv = svc, C.nsv = nc;
    /* the sections by their extremes in fewer directions (BUDGET_BOUND_SECTION_DIRS) */
    C.xs = ok ? malloc((3 * D->xe[BUDGET_OFFSETS - 1] + 3) * sizeof *C.xs) : NULL;
    ok = ok && C.xs;
    if (ok) {
        double cssn[2 * BUDGET_BOUND_SECTION_DIRS];
        section_dirs(cssn, BUDGET_BOUND_SECTION_DIRS);
        size_t o = 0;
        C.mx = 0;
        for (int i = 0; i < BUDGET_OFFSETS; i++) {
            C.xb[i] = o;
            o += section_extremes(D->xs + 3 * D->xb[i], D->xe[i] - D->xb[i], P->dirs[d], cssn, C.xs + 3 * o);
            C.xe[i] = o;
            C.mx = o - C.xb[i] > C.mx ? o - C.xb[i] : C.mx;
        }
    }
    double va[BUDGET_OFFSETS], vb[BUDGET_OFFSETS];
    if (ok) ok = dir_sweep(m, P, &C, 3, NULL, vb, va, hw);
    free(svc), free(C.dv), free(C.srt), free(C.xs);
    if (!ok) {
        dir_free(D);
        return 0;
    }
    double best = INFINITY;
    for (int i = 0; i < BUDGET_OFFSETS; i++) {
        double sc = va[i] < 0 || vb[i] < 0 ? -1 : va[i] + vb[i];
        P->lbo[d][i] = sc >= 0 ? sc - bound_rel * sc : -INFINITY;
        if (sc >= 0 && sc < best) best = sc;
    }
    P->lb[d] = best < INFINITY ? best - bound_rel * best : -INFINITY;
    return 1;
}

/* Direction d's best of the fixed offsets (D: direction_bound's; touches only P->bs[d], P->bc[d]),
 * scored only at the offsets whose bound (P->lbo) is not above top, the BUDGET_REFINE_DIRS-th lowest
 * score of the directions scored so far: an offset above it scores above top, so it is not the
 * direction's best when the direction is among those refined (its best is then at most top), and
 * when it is not, bs[d] is only compared with top (top_add), either way at or above it. bs[d] and
 * bc[d] are then those of scoring every offset whenever bs[d] is below top (the same bits: each
 * offset's sweep value is the same, acd_hull_volume_sweep_some). 0 when out of memory. */
static int score_dir(const acd_mesh *m, plan *P, int d, const dir_data *D, double top, acd_hull_volume_ws *hw) {
    double va[BUDGET_OFFSETS], vb[BUDGET_OFFSETS];
    unsigned char need[BUDGET_OFFSETS];
    for (int i = 0; i < BUDGET_OFFSETS; i++) need[i] = !(P->lbo[d][i] > top);
    if (!dir_sweep(m, P, D, 3, need, vb, va, hw)) return 0;
    for (int i = 0; i < BUDGET_OFFSETS; i++) {
        double sc = va[i] < 0 || vb[i] < 0 ? -1 : va[i] + vb[i];
        if (sc >= 0 && sc < P->bs[d]) P->bs[d] = sc, P->bc[d] = D->cs[i];
    }
    return 1;
}

/* P->top updated with direction d's score (the BUDGET_REFINE_DIRS lowest bs so far, increasing). */
static void top_add(plan *P, double sc) {
    int q = BUDGET_REFINE_DIRS;
    if (!(sc < P->top[q - 1])) return;
    while (q > 0 && sc < P->top[q - 1]) {
        if (q < BUDGET_REFINE_DIRS) P->top[q] = P->top[q - 1];
        q--;
    }
    P->top[q] = sc;
}

/* The offsets a refinement from c0 can score (its BUDGET_REFINE rounds of half the step from st,
 * each from the best offset so far: c0 or one scored before), computed as the rounds compute them,
 * increasing and each once, into out (room for BUDGET_MAX_QUERIES); how many. All of them fit
 * (3^BUDGET_REFINE - 1), so every offset the refinement tries is among them. */
_Static_assert(BUDGET_REFINE <= 3 && BUDGET_MAX_QUERIES >= 26, "a refinement's offsets must fit BUDGET_MAX_QUERIES");
static int refine_offsets(double c0, double st, double *out) {
    double reach[BUDGET_MAX_QUERIES + 1];
    int nr = 1, n = 0;
    reach[0] = c0;
    double step = st;
    for (int r = 0; r < BUDGET_REFINE; r++) {
        step *= 0.5;
        int nr0 = nr;
        for (int i = 0; i < nr0; i++)
            for (int sg = -1; sg <= 1; sg += 2)
                if (nr <= BUDGET_MAX_QUERIES) reach[nr++] = reach[i] + sg * step;
    }
    for (int i = 1; i < nr; i++) { /* increasing, each once */
        double x = reach[i];
        int at = 0;
        while (at < n && out[at] < x) at++;
        if (at < n && out[at] == x) continue;
        memmove(out + at + 1, out + at, (size_t)(n - at) * sizeof *out);
        out[at] = x;
        n++;
    }
    return n;
}

static void sort_dirs(plan *P, int lim) {
    for (int i = 1; i < lim; i++)
        for (int j = i; j > 0 && P->bs[P->ord[j]] < P->bs[P->ord[j - 1]]; j--) {
            int x = P->ord[j];
            P->ord[j] = P->ord[j - 1];
            P->ord[j - 1] = x;
        }
}

/* Up to nmax planes, best first by their sampled score, one per direction (after the refinement of
 * the best nrefine_dirs directions). */
static int plan_planes(const plan *P, int nmax, int nrefine_dirs, acd3_plane_candidate *out) {
    int lim = P->nd < nrefine_dirs ? P->nd : nrefine_dirs;
    int n = 0;
    for (int q = 0; q < lim && n < nmax; q++) {
        int d = P->ord[q];
        if (!(P->bs[d] < INFINITY)) continue;
        const double *ax = P->dirs[d];
        double cc = ax[0] * P->centroid[0] + ax[1] * P->centroid[1] + ax[2] * P->centroid[2];
        for (int k = 0; k < 3; k++) {
            out[n].normal[k] = ax[k];
            out[n].point[k] = P->centroid[k] + (P->bc[d] - cc) * ax[k];
        }
        out[n].kind = "volume";
        n++;
    }
    return n;
}

/* The diagonal of m's bounding box (in the input's frame); its corners into lo, hi. */
static double box_diag(const acd_mesh *m, double lo[3], double hi[3]) {
    for (int k = 0; k < 3; k++) lo[k] = INFINITY, hi[k] = -INFINITY;
    for (size_t v = 0; v < m->nvertices; v++)
        for (int k = 0; k < 3; k++) { /* fmin, fmax (as in plan_init) */
            double x = m->vertices[3 * v + k];
            if (x <= lo[k]) lo[k] = x;
            if (x >= hi[k]) hi[k] = x;
        }
    double d2 = 0;
    for (int k = 0; k < 3; k++) d2 += hi[k] > lo[k] ? (hi[k] - lo[k]) * (hi[k] - lo[k]) : 0;
    return sqrt(d2);
}

/* The midplanes of m's bounding box, across its longest side first (a phase-1 evaluation's fallback
 * candidates: the first always makes progress), into out (room for BUDGET_P1_MIDPLANES); how many.
 * offsets: instead, the planes across the longest side at BUDGET_P1_OFFSETS. */
static int box_midplanes(const acd_mesh *m, int offsets, acd3_plane_candidate *out) {
    double lo[3], hi[3];
    box_diag(m, lo, hi);
    int ord[3] = {0, 1, 2}, n = 0;
    for (int i = 1; i < 3; i++)
        for (int j = i; j > 0 && hi[ord[j]] - lo[ord[j]] > hi[ord[j - 1]] - lo[ord[j - 1]]; j--) {
            int x = ord[j];
            ord[j] = ord[j - 1];
            ord[j - 1] = x;
        }
    if (offsets) {
        const int k = ord[0];
        if (!(hi[k] > lo[k])) return 0;
        for (int i = 0; i < BUDGET_P1_MIDPLANES; i++, n++) {
            for (int c = 0; c < 3; c++) out[n].normal[c] = c == k, out[n].point[c] = 0.5 * (lo[c] + hi[c]);
            out[n].point[k] = lo[k] + BUDGET_P1_OFFSETS[i] * (hi[k] - lo[k]);
            out[n].kind = "volume";
        }
        return n;
    }
    for (int i = 0; i < 3; i++) {
        int k = ord[i];
        if (!(hi[k] > lo[k])) continue;
        for (int c = 0; c < 3; c++) out[n].normal[c] = c == k, out[n].point[c] = 0.5 * (lo[c] + hi[c]);
        out[n].kind = "volume";
        n++;
    }
    return n;
}

/* The atom's hull volume (touches only the atom). Its hull: a piece's from its parent's exact cut
 * (computed once: its volume chose the cut), an input part's the caller's when it matches, else
 * computed (kept until the atom's leaf test). An input part's bound waits for leaf_test: it is used
 * only when the part is not cut before phase 1 or the end (the caller measures a part left above
 * the limit itself), so an input part the budget phase cuts is never tested (the armadillo's single
 * part: 52,000 triangles, alone on one thread); a piece's is its tree node's concavity, tested at
 * once (prepare_range). */
static void prepare(const budget_state *S, size_t i) {
    atom *A = &S->a[i];
    A->st = ACD_OK;
    A->gain = -INFINITY;
    A->tested = 0;
    A->use_kept = 0;
    A->ok = 1;
    A->bound = 0;
    const acd_hull *H;
    if (A->have_hull)
        H = &A->hull;
    else if (A->kept && acd3_kept_hull_matches(A->kept, A->mesh.vertices, A->mesh.nvertices)) {
        H = A->kept;
        A->use_kept = 1;
    } else if (acd_hull_compute(A->mesh.vertices, A->mesh.nvertices, &A->hull, NULL) != ACD_OK) {
        A->st = ACD_ERR_NOMEM;
        return;
    } else {
        A->have_hull = 1;
        H = &A->hull;
    }
    A->hvol = hull_vol(H);
}

/* The atom's bound (acd3/leaf_test; touches only the atom), once. A piece keeps the leaf test's tree
 * and facet table with its hull (for the merge); an input part's hull computed by prepare is dropped. */
static void leaf_test(const budget_state *S, size_t i) {
    atom *A = &S->a[i];
    if (A->tested || A->st != ACD_OK) return;
    A->tested = 1;
    const acd_hull *H = A->use_kept ? A->kept : &A->hull;
    if (H->dim == 3) {
        int acc = 0, own = i >= S->nparts; /* a piece: its tree and table kept with its hull */
        acd_error e;
        A->st = acd3_leaf_test_keep(&A->mesh, H, S->limit, UINT32_MAX, &acc, &A->bound, own ? &A->bvh : NULL,
                                    own ? &A->table : NULL, &e);
        A->ok = acc;
    }
    if (i < S->nparts && A->have_hull) {
        acd_hull_free(&A->hull);
        A->have_hull = 0;
    }
}

/* One exact cut of an atom by a candidate plane: its pieces and the sum of their hull volumes. */
typedef struct exact_cut {
    acd_status cs;
    int good;
    double sum, maxbox; /* maxbox: its pieces' largest box diagonal over the atom's (boxratio) when
                         * good, else infinite */
    double boxratio;    /* that ratio, computed with the cut (exact_cut_do: in its task) */
    acd_cut_plane cp;
    acd_cut_result cr;
    acd_hull *hulls; /* the pieces' hulls (cr.npieces), or NULL */
} exact_cut;

/* A candidate cut dropped. */
static void exact_cut_free(exact_cut *X) { cut_with_hulls_free(&X->cr, &X->hulls); }

/* The cut itself and its pieces' largest box diagonal over the atom's (the pieces' volumes and
 * hulls are tasks of their own, in evaluate_batch). em: the atom's edge map with its twins
 * (acd_edge_map_closed), shared by its candidates' cuts, or NULL (the cut builds and checks one). */
static void exact_cut_do(const budget_state *S, const atom *A, const acd_edge_map *em, const acd3_plane_candidate *cand,
                         exact_cut *X) {
    memset(X, 0, sizeof *X);
    X->cs = acd_cut_plane_from_normal(cand->point, cand->normal, S->extent, &X->cp, NULL);
    if (X->cs != ACD_OK) {
        X->cs = ACD_ERR_DEGENERATE; /* skipped, as a failed cut */
        return;
    }
    acd_error ce;
    X->cs = acd_plane_cut_map(&A->mesh, em, &X->cp, ACD_PLANE_CUT_DROP_SPECKS, &X->cr, &ce);
    /* every piece must be closed and consistently oriented, as decompose.c and merge.c ask of their
     * cuts: rounding can leave a piece with a triangle repeating a vertex (fuzz_acd3d_tight, budget 2
     * on a pinched sphere: a budget part not closed); such a cut is skipped */
    if (X->cs != ACD_OK) return;
    acd_status es = acd_cut_result_check_closed(&X->cr);
    if (es != ACD_OK) {
        acd_cut_result_free(&X->cr);
        X->cs = es == ACD_ERR_NOMEM ? ACD_ERR_NOMEM : ACD_ERR_DEGENERATE;
        return;
    }
    double mb = 0, lo[3], hi[3];
    for (size_t p = 0; p < X->cr.npieces; p++) mb = fmax(mb, box_diag(&X->cr.pieces[p].mesh, lo, hi));
    double d = box_diag(&A->mesh, lo, hi);
    X->boxratio = d > 0 ? mb / d : INFINITY;
}

/* A cut's verdict from its pieces' volumes pv and hull volumes hv (-1: no hull): good when at
 * least two pieces, none a sliver (under BUDGET_MIN_PIECE_FRACTION of the atom's volume) and every
 * hull computed, and for a phase-1 evaluation (A->p1) when it makes progress (no piece's box
 * diagonal above BUDGET_P1_SHRINK of the atom's); sum, the hull volumes' sum in the pieces' order. */
static void exact_cut_judge(const atom *A, exact_cut *X, const double *pv, const double *hv) {
    double sum = 0;
    int good = X->cr.npieces >= 2;
    for (size_t p = 0; p < X->cr.npieces && good; p++) {
        if (!(pv[p] > BUDGET_MIN_PIECE_FRACTION * A->vol) || hv[p] < 0) good = 0;
        sum += hv[p];
    }
    X->maxbox = good ? X->boxratio : INFINITY;
    if (A->p1 && !(X->maxbox <= BUDGET_P1_SHRINK)) good = 0;
    X->good = good;
    X->sum = sum;
}

/* The best splits of a batch of atoms (touches only those atoms): the directions of all of them
 * scored as parallel tasks, then the best directions refined, then the candidates cut exactly; every
 * choice is made in the order of the sequential search, so the result is the same for any thread
 * count. */
static void evaluate_batch(const budget_state *S, const size_t *idx, int nb, int threads) {
    (void)threads;
    plan *P = malloc((size_t)nb * sizeof *P);
    if (!P) {
        for (int j = 0; j < nb; j++) S->a[idx[j]].evaluated = 1, S->a[idx[j]].st = ACD_ERR_NOMEM;
        return;
    }
    int live = 0;
    for (int j = 0; j < nb; j++) {
        atom *A = &S->a[idx[j]];
        A->evaluated = 1;
        A->progress = 0;
        P[j].ok = 0, P[j].nd = 0, P[j].nomem = 0, P[j].sv = NULL, P[j].edges = NULL, P[j].sord = NULL;
        if (A->st == ACD_OK) live = 1;
    }
    if (!live) {
        free(P);
        return;
    }
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && nb > 1)
#endif
    for (int j = 0; j < nb; j++)
        if (S->a[idx[j]].st == ACD_OK) plan_init(&S->a[idx[j]].mesh, S->ndir, S->bound_rel > -1, &P[j]);
    /* tasks: (atom, direction) pairs; first every direction's offsets prepared and its bound */
    int ntask = 0, tj[BUDGET_BATCH * BUDGET_MAX_DIRS], td[BUDGET_BATCH * BUDGET_MAX_DIRS];
    for (int j = 0; j < nb; j++)
        for (int d = 0; d < (P[j].ok ? P[j].nd : 0); d++)
            if (P[j].lo[d] == P[j].lo[d]) tj[ntask] = j, td[ntask] = d, ntask++; /* else flat along d */
    int fail[BUDGET_BATCH] = {0};
    dir_data *DD = malloc(((size_t)ntask + 1) * sizeof *DD);
    double(*DC)[BUDGET_OFFSETS] = malloc(((size_t)ntask + 1) * sizeof *DC);
    int dk[BUDGET_BATCH * BUDGET_MAX_DIRS];
    unsigned char *dok = calloc((size_t)ntask + 1, 1);
    if (!DD || !DC || !dok) {
        for (int j = 0; j < nb; j++) fail[j] = 1;
        ntask = 0;
    }
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && ntask > 1)
#endif
    for (int t = 0; t < ntask; t++) {
        dok[t] = (unsigned char)direction_bound(&S->a[idx[tj[t]]].mesh, &P[tj[t]], td[t], DC[t], &DD[t], S->bound_rel,
                                                    thread_ws(S));
        if (!dok[t]) {
#ifdef _OPENMP
#pragma omp atomic write
#endif
            fail[tj[t]] = 1;
        }
    }
    /* then the directions scored in increasing order of their bounds (by rank, the batch's atoms in
     * turn: ties by direction), each only when its bound is not above the BUDGET_REFINE_DIRS-th
     * lowest score so far (P->top): the directions the refinement takes, and their scores, are those
     * of scoring every direction, for any thread count and any order the tasks end in */
    int byb[BUDGET_BATCH][BUDGET_MAX_DIRS], nbyb[BUDGET_BATCH] = {0}, ndk = 0;
    for (int t = 0; t < ntask; t++) { /* each atom's tasks by bound (stable: then direction) */
        int j = tj[t], k = nbyb[j]++;
        for (; k > 0 && P[j].lb[td[t]] < P[j].lb[td[byb[j][k - 1]]]; k--) byb[j][k] = byb[j][k - 1];
        byb[j][k] = t;
    }
    for (int r = 0; r < BUDGET_MAX_DIRS; r++)
        for (int j = 0; j < nb; j++)
            if (r < nbyb[j]) dk[ndk++] = byb[j][r];
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && ntask > 1)
#endif
    for (int k = 0; k < ntask; k++) {
        int t = dk[k], j = tj[t], d = td[t];
        if (!dok[t]) continue;
        plan *Q = &P[j];
        double top;
#ifdef _OPENMP
#pragma omp critical(budget_top)
#endif
        top = Q->top[BUDGET_REFINE_DIRS - 1];
        if (Q->lb[d] > top) continue;
        if (!score_dir(&S->a[idx[j]].mesh, Q, d, &DD[t], top, thread_ws(S))) {
#ifdef _OPENMP
#pragma omp atomic write
#endif
            fail[j] = 1;
            continue;
        }
        Q->scored[d] = 1;
#ifdef _OPENMP
#pragma omp critical(budget_top)
#endif
        top_add(Q, Q->bs[d]);
    }
    for (int t = 0; t < ntask; t++)
        if (dok[t]) dir_free(&DD[t]);
    for (int t = 0; t < ntask; t++) {
        *S->dirs_bounded += P[tj[t]].hv != NULL;
        *S->dirs_scored += P[tj[t]].scored[td[t]];
    }
    free(DD), free(DC), free(dok);
    /* the best directions refined around their best offsets: BUDGET_REFINE rounds of half the
     * step, the lower offset first, each taken when it lowers the score (as the sequential search);
     * the scores looked up among the offsets the rounds can reach (refine_offsets), whose sides are
     * swept once per refined direction and side, as parallel tasks */
    int nref = 0, rj[BUDGET_BATCH * BUDGET_REFINE_DIRS], rd[BUDGET_BATCH * BUDGET_REFINE_DIRS];
    for (int j = 0; j < nb; j++) {
        if (!P[j].ok) continue;
        sort_dirs(&P[j], P[j].nd);
        for (int q = 0; q < P[j].nd && q < BUDGET_REFINE_DIRS; q++) rj[nref] = j, rd[nref] = P[j].ord[q], nref++;
    }
    double roff[BUDGET_BATCH * BUDGET_REFINE_DIRS][BUDGET_MAX_QUERIES], rvb[BUDGET_BATCH * BUDGET_REFINE_DIRS][BUDGET_MAX_QUERIES],
        rva[BUDGET_BATCH * BUDGET_REFINE_DIRS][BUDGET_MAX_QUERIES];
    int nro[BUDGET_BATCH * BUDGET_REFINE_DIRS];
    for (int k = 0; k < nref; k++)
        nro[k] = P[rj[k]].bs[rd[k]] < INFINITY ? refine_offsets(P[rj[k]].bc[rd[k]], P[rj[k]].st[rd[k]], roff[k]) : 0;
    /* each refined direction prepared once (its sections and sorted sample: dir_prep), then its two
     * sides swept */
    dir_data RD[BUDGET_BATCH * BUDGET_REFINE_DIRS];
    int rok[BUDGET_BATCH * BUDGET_REFINE_DIRS];
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && nref > 1)
#endif
    for (int k = 0; k < nref; k++) {
        RD[k].dv = RD[k].xs = RD[k].srt = NULL;
        rok[k] = nro[k] > 0 && dir_prep(&S->a[idx[rj[k]]].mesh, &P[rj[k]], rd[k], roff[k], nro[k], 1, &RD[k]);
        if (nro[k] > 0 && !rok[k]) {
#ifdef _OPENMP
#pragma omp atomic write
#endif
            fail[rj[k]] = 1;
        }
    }
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && nref > 0)
#endif
    for (int t = 0; t < 2 * nref; t++) {
        int k = t / 2;
        if (rok[k] && !dir_sweep(&S->a[idx[rj[k]]].mesh, &P[rj[k]], &RD[k], t % 2 ? 2 : 1, NULL, rvb[k], rva[k], thread_ws(S))) {
#ifdef _OPENMP
#pragma omp atomic write
#endif
            fail[rj[k]] = 1;
        }
    }
    for (int k = 0; k < nref; k++) dir_free(&RD[k]);
    for (int k = 0; k < nref; k++) {
        plan *Q = &P[rj[k]];
        int d = rd[k];
        if (nro[k] == 0 || fail[rj[k]]) continue;
        double step = Q->st[d];
        for (int r = 0; r < BUDGET_REFINE && Q->bs[d] < INFINITY; r++) {
            step *= 0.5;
            double c0 = Q->bc[d];
            for (int sg = -1; sg <= 1; sg += 2) {
                double c = c0 + sg * step, sc = -1;
                int i = 0;
                while (i < nro[k] && roff[k][i] != c) i++; /* found: refine_offsets made every c */
                if (i < nro[k]) sc = rva[k][i] < 0 || rvb[k][i] < 0 ? -1 : rva[k][i] + rvb[k][i];
                if (sc >= 0 && sc < Q->bs[d]) Q->bs[d] = sc, Q->bc[d] = c;
            }
        }
    }
    acd3_plane_candidate cand[BUDGET_BATCH][BUDGET_EXACT + BUDGET_P1_MIDPLANES];
    int nc[BUDGET_BATCH] = {0};
    ntask = 0;
    for (int j = 0; j < nb; j++) {
        if (P[j].nomem) fail[j] = 1;
        if (!P[j].ok && !fail[j]) continue;
        if (fail[j]) {
            S->a[idx[j]].st = ACD_ERR_NOMEM;
            continue;
        }
        int lim = P[j].nd < BUDGET_REFINE_DIRS ? P[j].nd : BUDGET_REFINE_DIRS;
        sort_dirs(&P[j], lim);
        nc[j] = plan_planes(&P[j], S->nexact, BUDGET_REFINE_DIRS, cand[j]);
        if (S->a[idx[j]].p1) nc[j] += box_midplanes(&S->a[idx[j]].mesh, S->a[idx[j]].p1off, cand[j] + nc[j]);
        for (int k = 0; k < nc[j]; k++) tj[ntask] = j, td[ntask] = k, ntask++;
    }
    for (int j = 0; j < nb; j++) plan_free(&P[j]);
    free(P);
    exact_cut X[BUDGET_BATCH][BUDGET_EXACT + BUDGET_P1_MIDPLANES];
    /* each atom's edge map and twins, built and checked once for its candidates' cuts (an atom
     * whose map fails passes none: each cut builds its own and fails as before) */
    acd_edge_map em[BUDGET_BATCH];
    int hem[BUDGET_BATCH] = {0};
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && nb > 1)
#endif
    for (int j = 0; j < nb; j++)
        if (nc[j] > 0)
            hem[j] = acd_edge_map_closed(S->a[idx[j]].mesh.triangles, S->a[idx[j]].mesh.ntriangles, &em[j], NULL) == ACD_OK;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && ntask > 1)
#endif
    for (int t = 0; t < ntask; t++)
        exact_cut_do(S, &S->a[idx[tj[t]]], hem[tj[t]] ? &em[tj[t]] : NULL, &cand[tj[t]][td[t]], &X[tj[t]][td[t]]);
    for (int j = 0; j < nb; j++)
        if (hem[j]) acd_edge_map_free(&em[j]);
    /* then every piece's volume and its hull's volume estimate (geom3/hull_volume) as a task: the
     * cuts' pieces spread over the threads; the qhull hulls (kept for the cut chosen: its pieces'
     * hulls are computed once) only for the candidates the estimates leave (BUDGET_SCREEN_REL) */
    size_t npc = 0, at = 0;
    int hfail = 0;
    for (int t = 0; t < ntask; t++) {
        exact_cut *x = &X[tj[t]][td[t]];
        if (x->cs != ACD_OK) continue;
        npc += x->cr.npieces;
        x->hulls = calloc(x->cr.npieces ? x->cr.npieces : 1, sizeof *x->hulls);
        if (!x->hulls) hfail = 1;
        for (size_t p = 0; x->hulls && p < x->cr.npieces; p++) x->hulls[p].dim = -1;
    }
    double *pv = malloc((3 * npc + 1) * sizeof *pv), *hv = pv ? pv + npc : NULL, *fv = pv ? pv + 2 * npc : NULL;
    size_t *pt = malloc((2 * npc + 1) * sizeof *pt), *off = malloc(((size_t)ntask + 1) * sizeof *off);
    unsigned char *need = malloc((size_t)ntask + 1);
    if (!pv || !pt || !off || !need || hfail) {
        for (int j = 0; j < nb; j++) S->a[idx[j]].st = ACD_ERR_NOMEM;
        npc = 0;
    }
    for (int t = 0; t < ntask && off; t++) {
        off[t] = at;
        const exact_cut *x = &X[tj[t]][td[t]];
        for (size_t p = 0; x->cs == ACD_OK && p < x->cr.npieces && at < npc; p++) pt[2 * at] = (size_t)t, pt[2 * at + 1] = p, at++;
    }
#ifdef _OPENMP
#pragma omp parallel num_threads(threads) if (threads > 1 && npc > 1)
#endif
    {
        acd_hull_volume_ws hw;
        memset(&hw, 0, sizeof hw);
#ifdef _OPENMP
#pragma omp for schedule(dynamic, 1)
#endif
        for (long k = 0; k < (long)npc; k++) {
            int t = (int)pt[2 * k];
            const acd_mesh *pm = &X[tj[t]][td[t]].cr.pieces[pt[2 * k + 1]].mesh;
            pv[k] = acd_geom3_signed_volume(pm);
            fv[k] = acd_hull_volume_fast(pm->vertices, pm->nvertices, &hw, NULL);
            hv[k] = -1;
        }
        acd_hull_volume_ws_free(&hw);
    }
    /* the screen: an atom's candidates judged on the estimates; those whose estimated sum is within
     * BUDGET_SCREEN_REL of the best estimated sum (or not estimated) get their qhull hulls */
    for (int j = 0; j < nb && npc > 0; j++) {
        double fbest = INFINITY;
        for (int t = 0; t < ntask; t++) {
            exact_cut *x = &X[tj[t]][td[t]];
            if (tj[t] != j) continue;
            need[t] = 0;
            if (x->cs != ACD_OK) continue;
            int est = 1;
            for (size_t p = 0; p < x->cr.npieces; p++) est &= fv[off[t] + p] >= 0;
            exact_cut_judge(&S->a[idx[j]], x, pv + off[t], fv + off[t]);
            if (!est) need[t] = 1;
            else if (x->good && x->sum < fbest) fbest = x->sum;
        }
        for (int t = 0; t < ntask; t++) {
            const exact_cut *x = &X[tj[t]][td[t]];
            if (tj[t] == j && x->cs == ACD_OK && x->good && x->sum <= fbest * (1 + S->screen_rel)) need[t] = 1;
        }
    }
    for (int round = 0; round < 2 && npc > 0; round++) {
        /* round 1: the atoms none of whose screened candidates was good, their other candidates */
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && npc > 1)
#endif
        for (long k = 0; k < (long)npc; k++) {
            int t = (int)pt[2 * k];
            if (need[t] != 1) continue;
            exact_cut *x = &X[tj[t]][td[t]];
            const acd_mesh *pm = &x->cr.pieces[pt[2 * k + 1]].mesh;
            acd_hull *ph = &x->hulls[pt[2 * k + 1]];
            hv[k] = acd_hull_compute(pm->vertices, pm->nvertices, ph, NULL) == ACD_OK ? hull_vol(ph) : -1;
        }
        int again = 0;
        for (int t = 0; t < ntask; t++) {
            exact_cut *x = &X[tj[t]][td[t]];
            if (x->cs != ACD_OK) continue;
            if (need[t] == 1) exact_cut_judge(&S->a[idx[tj[t]]], x, pv + off[t], hv + off[t]), need[t] = 2;
            else if (!need[t]) x->good = 0; /* screened out (judged again if round 1 takes it) */
        }
        for (int j = 0; j < nb && round == 0; j++) {
            int good = 0, left = 0;
            for (int t = 0; t < ntask; t++) {
                if (tj[t] != j || X[tj[t]][td[t]].cs != ACD_OK) continue;
                good |= need[t] == 2 && X[tj[t]][td[t]].good;
                left |= !need[t];
            }
            if (!good && left) {
                (*S->fallbacks)++;
                for (int t = 0; t < ntask; t++)
                    if (tj[t] == j && X[tj[t]][td[t]].cs == ACD_OK && !need[t]) need[t] = 1, again = 1;
            }
        }
        if (!again) break;
    }
    free(need);
    free(pv), free(pt), free(off);
    for (int j = 0; j < nb; j++) {
        atom *A = &S->a[idx[j]];
        double best = INFINITY;
        for (int k = 0; k < nc[j]; k++) {
            exact_cut *x = &X[j][k];
            if (x->cs != ACD_OK) {
                if (x->cs == ACD_ERR_NOMEM) A->st = x->cs;
                continue;
            }
            if (x->good && x->sum < best) {
                best = x->sum;
                A->progress = x->maxbox <= BUDGET_P1_SHRINK;
                atom_cut_free(A);
                A->cut = x->cr;
                A->cut_hulls = x->hulls;
                memcpy(A->plane, x->cp.normal, sizeof(double[3]));
                A->plane[3] = -(x->cp.normal[0] * x->cp.a[0] + x->cp.normal[1] * x->cp.a[1] + x->cp.normal[2] * x->cp.a[2]);
            } else
                exact_cut_free(x);
        }
        if (isfinite(best) && A->st == ACD_OK) A->gain = A->hvol - best;
    }
}

static void prepare_range(const budget_state *S, size_t b0, size_t b1, int threads) {
    (void)threads;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && b1 - b0 > 1)
#endif
    for (long j = (long)b0; j < (long)b1; j++) {
        prepare(S, (size_t)j);
        if ((size_t)j >= S->nparts) leaf_test(S, (size_t)j); /* a piece's bound is its tree node's concavity */
    }
}

/* The leaf tests of the atoms alive and not tested yet. */
static void test_alive(const budget_state *S, int threads) {
    (void)threads;
    size_t n = 0;
    for (size_t i = 0; i < S->n; i++) n += S->a[i].alive && !S->a[i].tested && S->a[i].st == ACD_OK;
    if (n == 0) return;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && n > 1)
#endif
    for (long j = 0; j < (long)S->n; j++)
        if (S->a[j].alive) leaf_test(S, (size_t)j);
}

void acd3_budget_result_free(acd3_budget_result *r) {
    if (!r) return;
    for (size_t k = 0; k < r->nnew; k++) acd_mesh_free(&r->new_parts[k]);
    free(r->new_parts);
    free(r->new_parent);
    free(r->new_plane);
    free(r->new_volume);
    free(r->new_bound);
    if (r->new_hull)
        for (size_t k = 0; k < r->nnew; k++) acd_hull_free(&r->new_hull[k]);
    free(r->new_hull);
    if (r->new_bvh)
        for (size_t k = 0; k < r->nnew; k++) acd_bvh_free(&r->new_bvh[k]);
    free(r->new_bvh);
    if (r->new_table)
        for (size_t k = 0; k < r->nnew; k++) acd3_facet_table_free(&r->new_table[k]);
    free(r->new_table);
    memset(r, 0, sizeof *r);
}

acd_status acd3_budget_split(const acd_mesh *parts, size_t nparts, size_t budget, double limit,
                             double min_gain, double extent, int threads, acd3_budget_result *out, acd_error *err) {
    return acd3_budget_split_hulls(parts, NULL, nparts, budget, limit, min_gain, extent, threads, NULL, NULL, out, err);
}

static acd_status budget_split(const acd_mesh *parts, const acd_hull *const *hulls, size_t nparts, size_t budget,
                               double limit, double min_gain, double extent, int threads, double screen_rel,
                               double bound_rel, acd_progress_fn progress, void *progress_user,
                               acd3_budget_result *out, acd_error *err);

acd_status acd3_budget_split_hulls(const acd_mesh *parts, const acd_hull *const *hulls, size_t nparts, size_t budget,
                                   double limit, double min_gain, double extent, int threads, acd_progress_fn progress,
                                   void *progress_user, acd3_budget_result *out, acd_error *err) {
    return budget_split(parts, hulls, nparts, budget, limit, min_gain, extent, threads, BUDGET_SCREEN_REL,
                        BUDGET_BOUND_REL, progress, progress_user, out, err);
}

acd_status acd3_budget_split_screen(const acd_mesh *parts, size_t nparts, size_t budget, double limit, double min_gain,
                                    double extent, int threads, double screen_rel, acd3_budget_result *out,
                                    acd_error *err) {
    return budget_split(parts, NULL, nparts, budget, limit, min_gain, extent, threads, screen_rel, BUDGET_BOUND_REL,
                        NULL, NULL, out, err);
}

acd_status acd3_budget_split_tuned(const acd_mesh *parts, size_t nparts, size_t budget, double limit, double min_gain,
                                   double extent, int threads, double screen_rel, double bound_rel,
                                   acd3_budget_result *out, acd_error *err) {
    return budget_split(parts, NULL, nparts, budget, limit, min_gain, extent, threads, screen_rel, bound_rel, NULL,
                        NULL, out, err);
}

static acd_status budget_split(const acd_mesh *parts, const acd_hull *const *hulls, size_t nparts, size_t budget,
                               double limit, double min_gain, double extent, int threads, double screen_rel,
                               double bound_rel, acd_progress_fn progress, void *progress_user,
                               acd3_budget_result *out, acd_error *err) {
    memset(out, 0, sizeof *out);
    budget_state S = {0};
    S.screen_rel = screen_rel;
    S.fallbacks = &out->screen_fallbacks;
    S.bound_rel = bound_rel;
    S.dirs_bounded = &out->directions_bounded;
    S.dirs_scored = &out->directions_scored;
    S.nparts = nparts;
    S.limit = limit;
    S.extent = extent;
    S.ndir = BUDGET_DIRS;
    S.nexact = BUDGET_EXACT;
    S.cap = 2 * nparts + 16;
    S.nws = threads > 1 ? threads : 1;
    S.a = calloc(S.cap, sizeof *S.a);
    S.ws = calloc((size_t)S.nws, sizeof *S.ws);
    if (!S.a || !S.ws) {
        free(S.a), free(S.ws);
        return acd_fail(err, ACD_ERR_NOMEM, "budget: out of memory");
    }
    acd_status st = ACD_OK;
    for (size_t i = 0; i < nparts; i++) {
        S.a[i].mesh = parts[i];
        S.a[i].vol = acd_geom3_signed_volume(&parts[i]);
        S.a[i].alive = 1;
        S.a[i].kept = hulls ? hulls[i] : NULL;
    }
    S.n = nparts;
    const size_t p1cap = BUDGET_P1_CUTS_PER_PART * (budget + nparts);
    prepare_range(&S, 0, nparts, threads);
    size_t nalive = nparts;
    for (;;) {
        for (size_t i = 0; i < S.n && st == ACD_OK; i++)
            if (S.a[i].st != ACD_OK) st = acd_fail(err, S.a[i].st, "budget: out of memory");
        if (st == ACD_OK && progress &&
            progress(progress_user, budget ? fmin(1.0, (double)nalive / (double)budget) : -1.0, "budget: splitting"))
            st = acd_fail(err, ACD_ERR_CANCELLED, "cancelled in the budget pass after %zu cuts", out->cuts);
        if (st != ACD_OK) break;
        /* the next cut: while under the budget, the largest saving above min_gain; an atom not
         * evaluated yet may save at most its excess (hull volume less volume: each piece's hull
         * holds the piece), so those whose excess reaches the best saving found are evaluated
         * first (largest excess first, BUDGET_BATCH at a time in parallel; the choice is the same
         * as evaluating all). Then, the budget spent, a part above the limit (largest saving). */
        size_t pick = SIZE_MAX, batch[BUDGET_BATCH];
        int nb = 0, phase = 0;
        for (; phase < 2 && pick == SIZE_MAX && nb == 0; phase++) {
            if (phase == 0 && nalive >= budget) continue;
            if (phase == 1) {
                test_alive(&S, threads); /* the parts' bounds, for the parts above the limit */
                if (out->phase1_cuts >= p1cap) {
                    out->phase1_stop = "the phase-1 cut cap was reached";
                    break;
                }
                /* a part above the limit is cut in phase 1 only by a cut that makes progress: one
                 * evaluated for the budget phase whose cut does not is evaluated again for phase 1
                 * (that cut among its candidates and the midplanes; none: it stays as it is) */
                for (size_t i = 0; i < S.n; i++) {
                    atom *A = &S.a[i];
                    if (!A->alive || A->ok || A->p1gen >= BUDGET_P1_MAX_GEN) continue;
                    if (A->p1) { /* evaluated for phase 1 without progress: once more, off the middle */
                        if (A->evaluated && !A->progress && !A->p1off && A->st == ACD_OK) {
                            atom_cut_free(A);
                            A->evaluated = 0;
                            A->gain = -INFINITY;
                            A->p1off = 1;
                        }
                        continue;
                    }
                    A->p1 = 1;
                    if (A->evaluated && !A->progress) {
                        atom_cut_free(A);
                        A->evaluated = 0;
                        A->gain = -INFINITY;
                    }
                }
            }
            for (size_t i = 0; i < S.n; i++) {
                const atom *A = &S.a[i];
                if (!A->alive || !A->evaluated || A->cut.npieces < 2) continue;
                if (phase == 0 ? !(A->gain > min_gain) : A->ok || !A->progress || A->p1gen >= BUDGET_P1_MAX_GEN) continue;
                if (pick == SIZE_MAX || A->gain > S.a[pick].gain) pick = i;
            }
            double floor = pick == SIZE_MAX ? (phase == 0 ? min_gain : -INFINITY) : S.a[pick].gain;
            for (size_t i = 0; i < S.n; i++) { /* the unevaluated candidates of largest excess */
                const atom *A = &S.a[i];
                if (!A->alive || A->evaluated || (phase == 1 && (A->ok || A->p1gen >= BUDGET_P1_MAX_GEN))) continue;
                double ex = A->hvol - A->vol;
                if (phase == 0 && !(ex >= floor)) continue;
                int at = nb < BUDGET_BATCH ? nb++ : BUDGET_BATCH;
                while (at > 0) {
                    const atom *B = &S.a[batch[at - 1]];
                    if (B->hvol - B->vol >= ex) break;
                    if (at < BUDGET_BATCH) batch[at] = batch[at - 1];
                    at--;
                }
                if (at < BUDGET_BATCH) batch[at] = i;
            }
        }
        if (nb > 0) {
            pick = SIZE_MAX;
            evaluate_batch(&S, batch, nb, threads);
            continue;
        }
        if (pick == SIZE_MAX) break;
        phase--; /* the phase that picked */
        size_t np = S.a[pick].cut.npieces;
        if (S.n + np > BUDGET_MAX_ATOMS) {
            out->phase1_stop = "the atom cap was reached";
            break;
        }
        if (S.n + np > S.cap) {
            size_t nc = 2 * S.cap + np;
            atom *na = realloc(S.a, nc * sizeof *na);
            if (!na) {
                st = acd_fail(err, ACD_ERR_NOMEM, "budget: out of memory");
                break;
            }
            memset(na + S.cap, 0, (nc - S.cap) * sizeof *na);
            S.a = na;
            S.cap = nc;
        }
        atom *P = &S.a[pick];
        size_t b0 = S.n;
        for (size_t p = 0; p < np; p++) {
            atom *A = &S.a[S.n++];
            A->mesh = P->cut.pieces[p].mesh;
            memset(&P->cut.pieces[p].mesh, 0, sizeof A->mesh);
            A->vol = acd_geom3_signed_volume(&A->mesh);
            A->alive = 1;
            A->parent = pick;
            A->p1gen = phase == 1 ? P->p1gen + 1 : 0;
            A->hull = acd_hull_take(&P->cut_hulls[p]); /* the hull its volume was scored with */
            A->have_hull = 1;
        }
        atom_cut_free(P);
        acd_hull_free(&P->hull); /* cut: its hull is no part's */
        P->have_hull = 0;
        acd_bvh_free(&P->bvh);
        acd3_facet_table_free(&P->table);
        P->alive = 0;
        nalive += np - 1;
        out->cuts++;
        out->phase1_cuts += phase == 1;
        prepare_range(&S, b0, S.n, threads);
    }
    if (st == ACD_OK) { /* the bounds of the parts not tested yet (phase 1 did not run) */
        test_alive(&S, threads);
        for (size_t i = 0; i < S.n && st == ACD_OK; i++)
            if (S.a[i].st != ACD_OK) st = acd_fail(err, S.a[i].st, "budget: out of memory");
    }
    /* the pieces out; the atoms' cached splits freed */
    size_t nnew = S.n - nparts;
    if (st == ACD_OK && nnew) {
        out->new_parts = calloc(nnew, sizeof *out->new_parts);
        out->new_parent = malloc(nnew * sizeof *out->new_parent);
        out->new_plane = malloc(nnew * sizeof *out->new_plane);
        out->new_volume = malloc(nnew * sizeof *out->new_volume);
        out->new_bound = malloc(nnew * sizeof *out->new_bound);
        out->new_hull = calloc(nnew, sizeof *out->new_hull);
        out->new_bvh = calloc(nnew, sizeof *out->new_bvh);
        out->new_table = calloc(nnew, sizeof *out->new_table);
        if (!out->new_parts || !out->new_parent || !out->new_plane || !out->new_volume || !out->new_bound ||
            !out->new_hull || !out->new_bvh || !out->new_table)
            st = acd_fail(err, ACD_ERR_NOMEM, "budget: out of memory");
    }
    if (st == ACD_OK) {
        /* parents: recorded as the cut order made them (each cut's pieces consecutive) */
        size_t k = 0;
        out->nnew = nnew;
        out->nalive = nalive;
        for (size_t i = nparts; i < S.n; i++, k++) {
            out->new_parts[k] = S.a[i].mesh;
            memset(&S.a[i].mesh, 0, sizeof S.a[i].mesh);
            out->new_volume[k] = S.a[i].vol;
            out->new_bound[k] = S.a[i].bound;
            out->new_parent[k] = (uint32_t)S.a[i].parent;
            memcpy(out->new_plane[k], S.a[S.a[i].parent].plane, sizeof out->new_plane[k]);
            out->new_hull[k].dim = -1;
            if (S.a[i].alive && S.a[i].have_hull) { /* a part: its hull out (a piece cut again has none) */
                out->new_hull[k] = acd_hull_take(&S.a[i].hull);
                S.a[i].have_hull = 0;
                out->new_bvh[k] = S.a[i].bvh; /* with its tree and facet table (over the same arrays) */
                out->new_table[k] = S.a[i].table;
                memset(&S.a[i].bvh, 0, sizeof S.a[i].bvh);
                memset(&S.a[i].table, 0, sizeof S.a[i].table);
            }
        }
        int deep = 0;
        for (size_t i = 0; i < S.n; i++) {
            out->over += S.a[i].alive && !S.a[i].ok;
            deep |= S.a[i].alive && !S.a[i].ok && S.a[i].p1gen >= BUDGET_P1_MAX_GEN;
            out->hull_volume += S.a[i].alive ? S.a[i].hvol : 0;
        }
        if (out->over == 0) out->phase1_stop = NULL;
        else if (!out->phase1_stop)
            out->phase1_stop = deep ? "a part reached the phase-1 generation cap"
                                    : "no cut of a part above the limit splits it with progress";
    }
    for (size_t i = 0; i < S.n; i++) {
        atom_cut_free(&S.a[i]);
        if (S.a[i].have_hull) acd_hull_free(&S.a[i].hull);
        acd_bvh_free(&S.a[i].bvh);
        acd3_facet_table_free(&S.a[i].table);
        if (i >= nparts) acd_mesh_free(&S.a[i].mesh);
    }
    free(S.a);
    for (int t = 0; t < S.nws; t++) acd_hull_volume_ws_free(&S.ws[t]);
    free(S.ws);
    if (st != ACD_OK) acd3_budget_result_free(out);
    return st;
}
