# Sourced by the benches that run HACD (bench/bench_corise_hacd.sh, bench/bench_3d_hacd.sh):
# Debian's libbullet-extras-dev (libHACD, zlib licence) through the bench-only harness
# bench/peers/hacd_run.cpp, built here with g++ (never part of libacd or CI).
HACD_HDR=/usr/include/bullet/HACD/hacdHACD.h

# hacd_available NAME: 0 when HACD is installed; otherwise says NAME is skipped and returns 1.
hacd_available() {
  if [ ! -f "$HACD_HDR" ] || ! ls /usr/lib/*/libHACD.so >/dev/null 2>&1; then
    echo "$1: HACD not found ($HACD_HDR, libHACD.so): apt-get install libbullet-extras-dev; skipped"
    return 1
  fi
}

# hacd_build NAME DEST: builds the harness as DEST; says so and returns 1 when it cannot.
hacd_build() {
  g++ -O2 -std=c++17 -I"$(dirname "$HACD_HDR")" -o "$2" bench/peers/hacd_run.cpp -lHACD ||
    { echo "$1: cannot build bench/peers/hacd_run.cpp"; return 1; }
}
