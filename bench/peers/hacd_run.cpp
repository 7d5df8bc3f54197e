// hacd_run: bench-only peer harness for bench/bench_corise_hacd.sh (docs/results/corise.md).
// Not part of the CMake build or CI, never linked into libacd; built by the script with g++
// against Debian's libbullet-extras-dev (HACD by K. Mamou, zlib licence; libHACD.so).
//
// usage: hacd_run MESH.off HULLS.obj TAU
//   MESH.off: triangles (polygons are fanned); HULLS.obj: written here, one "o hull_K" group per
//   HACD cluster (its convex hull, HACD's GetCH with full hulls).
//   TAU: concavity tolerance relative to HACD's normalisation (HACD scales the mesh so that half
//   its bounding-box diagonal is the scale factor, 1000 here), so concavity = TAU * 1000, which is
//   Bullet's demo setting (100) for TAU = 0.1.
// Other parameters: Bullet's ConvexDecompositionDemo defaults (at least 2 clusters, compacity
// weight 0.1, volume weight 0, extra and neighbour distance points on, face points off).
// Prints "parts,cpu_s" (process CPU time of Compute() only, std::clock).
#include <hacdHACD.h>

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

static bool next_line(std::istream &in, std::string &line) {
    while (std::getline(in, line)) {
        size_t h = line.find('#');
        if (h != std::string::npos) line.resize(h);
        if (line.find_first_not_of(" \t\r") != std::string::npos) return true;
    }
    return false;
}

int main(int argc, char **argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: hacd_run MESH.off HULLS.obj TAU\n");
        return 2;
    }
    std::ifstream in(argv[1]);
    std::string line;
    if (!in || !next_line(in, line)) {
        std::fprintf(stderr, "hacd_run: cannot read %s\n", argv[1]);
        return 1;
    }
    std::istringstream head(line);
    std::string magic;
    head >> magic;
    if (magic.find("OFF") == std::string::npos) { // OFF, COFF, NOFF, ...
        std::fprintf(stderr, "hacd_run: %s is not an OFF file\n", argv[1]);
        return 1;
    }
    long nv = -1, nf = -1;
    if (!(head >> nv >> nf)) {
        if (!next_line(in, line)) return 1;
        std::istringstream c(line);
        c >> nv >> nf;
    }
    if (nv <= 0 || nf <= 0) {
        std::fprintf(stderr, "hacd_run: bad counts in %s\n", argv[1]);
        return 1;
    }
    std::vector<HACD::Vec3<HACD::Real> > pts(nv);
    for (long i = 0; i < nv; i++) {
        if (!next_line(in, line)) return 1;
        std::istringstream c(line);
        double x, y, z;
        c >> x >> y >> z;
        pts[i] = HACD::Vec3<HACD::Real>(x, y, z);
    }
    std::vector<HACD::Vec3<long> > tris;
    for (long f = 0; f < nf; f++) {
        if (!next_line(in, line)) return 1;
        std::istringstream c(line);
        long k;
        c >> k;
        std::vector<long> idx(k);
        for (long j = 0; j < k; j++) c >> idx[j];
        for (long j = 1; j + 1 < k; j++) tris.push_back(HACD::Vec3<long>(idx[0], idx[j], idx[j + 1]));
    }
    double tau = std::atof(argv[3]);
    HACD::HACD h;
    h.SetPoints(&pts[0]);
    h.SetNPoints(pts.size());
    h.SetTriangles(&tris[0]);
    h.SetNTriangles(tris.size());
    h.SetCompacityWeight(0.1);
    h.SetVolumeWeight(0.0);
    h.SetNClusters(2);
    h.SetNVerticesPerCH(100);
    h.SetScaleFactor(1000.0);
    h.SetConcavity(tau * 1000.0);
    h.SetAddExtraDistPoints(true);
    h.SetAddNeighboursDistPoints(true);
    h.SetAddFacesPoints(false);
    std::clock_t t0 = std::clock();
    if (!h.Compute(true)) {
        std::fprintf(stderr, "hacd_run: Compute failed\n");
        return 1;
    }
    double cpu = double(std::clock() - t0) / CLOCKS_PER_SEC;
    size_t nc = h.GetNClusters();
    std::ofstream out(argv[2]);
    size_t base = 1;
    for (size_t c = 0; c < nc; c++) {
        size_t np = h.GetNPointsCH(c), nt = h.GetNTrianglesCH(c);
        std::vector<HACD::Vec3<HACD::Real> > p(np);
        std::vector<HACD::Vec3<long> > t(nt);
        h.GetCH(c, &p[0], &t[0]);
        out << "o hull_" << c << "\n";
        for (size_t i = 0; i < np; i++) out << "v " << p[i].X() << " " << p[i].Y() << " " << p[i].Z() << "\n";
        for (size_t i = 0; i < nt; i++)
            out << "f " << base + t[i].X() << " " << base + t[i].Y() << " " << base + t[i].Z() << "\n";
        base += np;
    }
    std::printf("%zu,%.3f\n", nc, cpu);
    return 0;
}
