// cgal_partition: bench-only peer harness for bench_2d_experiments (docs/experiments-2d.md).
// Not part of the CMake build or CI; built by scripts/bench-2d-experiments.sh with g++ against
// Debian's libcgal-dev (header-only).
//
// usage: cgal_partition optimal|approx|greene POLY.txt PIECES.txt
//   POLY.txt: "n" then n lines "x y" (counterclockwise outer ring, written by bench_2d_experiments)
//   PIECES.txt: written here, "count" then one piece per line "n x1 y1 ... xn yn"
// Prints "method,pieces,cpu_s" (process CPU time of the partition call only, std::clock).
//   optimal: CGAL::optimal_convex_partition_2 (Greene's dynamic programme, no Steiner points)
//   approx:  CGAL::approx_convex_partition_2 (Hertel-Mehlhorn over a constrained triangulation)
//   greene:  CGAL::greene_approx_convex_partition_2 (sweep into y-monotone pieces, then Greene)
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Partition_traits_2.h>
#include <CGAL/partition_2.h>

#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <iterator>
#include <list>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Partition_traits_2<K> Traits;
typedef Traits::Point_2 Point_2;
typedef Traits::Polygon_2 Polygon_2;

int main(int argc, char **argv) {
    if (argc != 4) {
        std::cerr << "usage: cgal_partition optimal|approx|greene POLY.txt PIECES.txt\n";
        return 2;
    }
    std::string method = argv[1];
    std::ifstream in(argv[2]);
    size_t n = 0;
    if (!(in >> n) || n < 3) {
        std::cerr << "cgal_partition: cannot read " << argv[2] << "\n";
        return 1;
    }
    Polygon_2 poly;
    for (size_t i = 0; i < n; i++) {
        double x, y;
        if (!(in >> x >> y)) {
            std::cerr << "cgal_partition: " << argv[2] << ": short at point " << i << "\n";
            return 1;
        }
        poly.push_back(Point_2(x, y));
    }
    if (poly.orientation() != CGAL::COUNTERCLOCKWISE) poly.reverse_orientation();
    std::list<Polygon_2> parts;
    std::clock_t c0 = std::clock();
    if (method == "optimal")
        CGAL::optimal_convex_partition_2(poly.vertices_begin(), poly.vertices_end(), std::back_inserter(parts));
    else if (method == "approx")
        CGAL::approx_convex_partition_2(poly.vertices_begin(), poly.vertices_end(), std::back_inserter(parts));
    else if (method == "greene")
        CGAL::greene_approx_convex_partition_2(poly.vertices_begin(), poly.vertices_end(), std::back_inserter(parts));
    else {
        std::cerr << "cgal_partition: unknown method " << method << "\n";
        return 2;
    }
    double sec = double(std::clock() - c0) / CLOCKS_PER_SEC;
    FILE *f = std::fopen(argv[3], "w");
    if (!f) {
        std::cerr << "cgal_partition: cannot write " << argv[3] << "\n";
        return 1;
    }
    std::fprintf(f, "%zu\n", parts.size());
    for (const Polygon_2 &p : parts) {
        std::fprintf(f, "%zu", (size_t)p.size());
        for (auto v = p.vertices_begin(); v != p.vertices_end(); ++v)
            std::fprintf(f, " %.17g %.17g", CGAL::to_double(v->x()), CGAL::to_double(v->y()));
        std::fprintf(f, "\n");
    }
    if (std::fclose(f) != 0) return 1;
    std::printf("%s,%zu,%.6g\n", method.c_str(), parts.size(), sec);
    return 0;
}
