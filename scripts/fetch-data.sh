#!/usr/bin/env bash
# Fetches real test meshes into data/meshes/ (git-ignored), idempotently:
#  - Debian's libcgal-demo (CGAL's data/meshes: armadillo, bunny00, elephant, eight, cheese, turbine,
#    camel, homer, mushroom, ...; CC0 1.0 per Debian's copyright file of cgal), with `apt-get download`;
#  - npm's `bunny` (the Stanford bunny, public domain), with `npm pack`, converted to OBJ;
#  - Debian's assimp-testmodels (BSD-3-clause): its OBJ, OFF, PLY, STL and invalid/ models, into
#    data/meshes/assimp/, as real-world and malformed-file cases for the readers.
# and real 2D polygons into data/2d/ (git-ignored):
#  - npm's `world-atlas` (Natural Earth countries and land as TopoJSON; ISC, data public domain),
#    with `npm pack`, into data/2d/world-atlas/;
#  - CGAL's Straight_skeleton_2 example polygons sample_1..4.dat (20, 11, 0 and 2 holes; CC0 1.0)
#    from libcgal-demo's examples.tar.gz, converted to .poly by scripts/cgal_pwh_to_poly.py, into
#    data/2d/cgal/;
#  - glyphs with holes (B, 8, @, g) of DejaVu Sans from Debian's fonts-dejavu-core (Bitstream Vera
#    derived licence, free), flattened by scripts/ttf_glyph_to_poly.py, into data/2d/glyphs/.
# Source and licence of every file: docs/data.md (and data/meshes/SOURCES.txt,
# data/2d/SOURCES.txt, written here).
# Usage: scripts/fetch-data.sh [--force]
set -euo pipefail
cd "$(dirname "$0")/.."
DEST=data/meshes
FORCE=0
[ "${1:-}" = "--force" ] && FORCE=1
mkdir -p "$DEST"
TMP=$(mktemp -d)
chmod 755 "$TMP" # apt-get download runs as _apt and must write here
trap 'rm -rf "$TMP"' EXIT

# The CGAL meshes the tests rely on (all of data/meshes is extracted).
NEEDED=(armadillo.off bunny00.off elephant.off eight.off cheese.off turbine.off camel.off homer.off mushroom.off)

have_cgal=1
for f in "${NEEDED[@]}"; do [ -s "$DEST/$f" ] || have_cgal=0; done
if [ $have_cgal = 1 ] && [ -f "$DEST/.cgal-version" ] && [ $FORCE = 0 ]; then
  echo "fetch-data: CGAL meshes already present ($(cat "$DEST/.cgal-version"), $(ls "$DEST"/*.off | wc -l) OFF files)"
else
  echo "fetch-data: downloading libcgal-demo with apt-get"
  if ! (cd "$TMP" && apt-get download libcgal-demo >/dev/null 2>&1); then
    echo "fetch-data: apt-get download failed; running apt-get update once"
    SUDO=""
    [ "$(id -u)" -eq 0 ] || SUDO=sudo
    $SUDO apt-get update -qq
    (cd "$TMP" && apt-get download libcgal-demo >/dev/null)
  fi
  deb=$(ls "$TMP"/libcgal-demo_*.deb)
  version=$(dpkg-deb -f "$deb" Version)
  dpkg-deb -x "$deb" "$TMP/x"
  tarball=$(find "$TMP/x" -name data.tar.gz | head -n 1)
  [ -n "$tarball" ] || { echo "fetch-data: no data.tar.gz in $deb" >&2; exit 1; }
  tar -xzf "$tarball" -C "$TMP" data/meshes
  n=0
  : > "$TMP/sources"
  for f in "$TMP"/data/meshes/*; do
    case "$f" in *.off|*.obj|*.ply|*.stl) ;; *) continue ;; esac
    base=$(basename "$f")
    cp "$f" "$DEST/$base"
    echo "$base	Debian libcgal-demo $version (CGAL data/meshes/$base)	CC0-1.0" >> "$TMP/sources"
    n=$((n + 1))
  done
  echo "libcgal-demo $version" > "$DEST/.cgal-version"
  grep -v "libcgal-demo" "$DEST/SOURCES.txt" 2>/dev/null > "$TMP/old" || true
  cat "$TMP/old" "$TMP/sources" > "$DEST/SOURCES.txt"
  echo "fetch-data: extracted $n meshes from libcgal-demo $version into $DEST"
fi

if [ -s "$DEST/bunny.obj" ] && [ $FORCE = 0 ]; then
  echo "fetch-data: npm bunny already present ($DEST/bunny.obj)"
elif ! command -v npm >/dev/null 2>&1; then
  echo "fetch-data: npm not found: skipping the npm 'bunny' package (tests that need it skip)"
else
  echo "fetch-data: downloading the npm package 'bunny'"
  (cd "$TMP" && npm pack bunny --silent >/dev/null 2>&1)
  tgz=$(ls "$TMP"/bunny-*.tgz)
  tar -xzf "$tgz" -C "$TMP"
  version=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["version"])' "$TMP/package/package.json")
  python3 scripts/npm-bunny-to-obj.py "$TMP/package/index.js" "$DEST/bunny.obj"
  grep -v "^bunny.obj" "$DEST/SOURCES.txt" 2>/dev/null > "$TMP/old" || true
  { cat "$TMP/old"; echo "bunny.obj	npm bunny $version (index.js converted by scripts/npm-bunny-to-obj.py)	public domain"; } > "$DEST/SOURCES.txt"
  echo "fetch-data: wrote $DEST/bunny.obj from npm bunny $version"
fi
AS="$DEST/assimp"
if [ -f "$AS/.version" ] && [ $FORCE = 0 ]; then
  echo "fetch-data: assimp test models already present ($(cat "$AS/.version"))"
else
  echo "fetch-data: downloading assimp-testmodels with apt-get"
  if (cd "$TMP" && apt-get download assimp-testmodels >/dev/null 2>&1); then
    deb=$(ls "$TMP"/assimp-testmodels_*.deb)
    version=$(dpkg-deb -f "$deb" Version)
    dpkg-deb -x "$deb" "$TMP/as"
    models="$TMP/as/usr/share/assimp/models"
    rm -rf "$AS"
    for sub in OBJ OFF PLY STL invalid; do
      mkdir -p "$AS/$sub"
      find "$models/$sub" -maxdepth 1 -type f \( -iname '*.obj' -o -iname '*.off' -o -iname '*.ply' -o -iname '*.stl' \) \
        -exec cp {} "$AS/$sub/" \;
    done
    echo "assimp-testmodels $version" > "$AS/.version"
    grep -v "^assimp/" "$DEST/SOURCES.txt" 2>/dev/null > "$TMP/old" || true
    { cat "$TMP/old"
      (cd "$DEST" && find assimp -type f ! -name .version | sort | while read -r f; do
        echo "$f	Debian assimp-testmodels $version (usr/share/assimp/models/${f#assimp/})	BSD-3-clause"; done); } > "$DEST/SOURCES.txt"
    echo "fetch-data: extracted $(find "$AS" -type f ! -name .version | wc -l) assimp test models ($version) into $AS"
  else
    echo "fetch-data: apt-get download assimp-testmodels failed: skipping them (tests that need them skip)"
  fi
fi
echo "fetch-data: $DEST holds $(ls "$DEST" | grep -cE '\.(off|obj|ply|stl)$') meshes; sources in $DEST/SOURCES.txt"

# --- real 2D polygons: data/2d ---
D2=data/2d
mkdir -p "$D2"
touch "$D2/SOURCES.txt"
set_source() { # file-prefix lines...: replaces the SOURCES.txt lines of files starting with the prefix
  local prefix=$1; shift
  grep -v "^$prefix" "$D2/SOURCES.txt" > "$TMP/old2d" || true
  { cat "$TMP/old2d"; printf '%s\n' "$@"; } > "$D2/SOURCES.txt"
}
if [ -s "$D2/world-atlas/countries-10m.json" ] && [ $FORCE = 0 ]; then
  echo "fetch-data: world-atlas already present ($(cat "$D2/world-atlas/.version" 2>/dev/null))"
elif ! command -v npm >/dev/null 2>&1; then
  echo "fetch-data: npm not found: skipping world-atlas (tests that need it skip)"
else
  echo "fetch-data: downloading the npm package 'world-atlas'"
  mkdir -p "$TMP/wa" "$D2/world-atlas"
  (cd "$TMP/wa" && npm pack world-atlas --silent >/dev/null 2>&1)
  tar -xzf "$TMP"/wa/world-atlas-*.tgz -C "$TMP/wa"
  version=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["version"])' "$TMP/wa/package/package.json")
  cp "$TMP"/wa/package/*.json "$D2/world-atlas/"
  rm -f "$D2/world-atlas/package.json"
  cp "$TMP/wa/package/LICENSE" "$D2/world-atlas/LICENSE"
  echo "world-atlas $version" > "$D2/world-atlas/.version"
  lines=()
  for f in "$D2"/world-atlas/*.json; do
    lines+=("world-atlas/$(basename "$f")	npm world-atlas $version (Natural Earth admin-0 countries / land, TopoJSON)	ISC (package); Natural Earth data public domain")
  done
  set_source "world-atlas/" "${lines[@]}"
  echo "fetch-data: wrote $(ls "$D2"/world-atlas/*.json | wc -l) TopoJSON files of world-atlas $version into $D2/world-atlas"
fi
if [ -s "$D2/cgal/straight_skeleton_sample_1.poly" ] && [ $FORCE = 0 ]; then
  echo "fetch-data: CGAL straight-skeleton samples already present"
else
  echo "fetch-data: extracting CGAL's Straight_skeleton_2 samples from libcgal-demo"
  mkdir -p "$TMP/cg" "$D2/cgal"
  chmod 755 "$TMP/cg"
  if (cd "$TMP/cg" && apt-get download libcgal-demo >/dev/null 2>&1); then
    deb=$(ls "$TMP"/cg/libcgal-demo_*.deb)
    version=$(dpkg-deb -f "$deb" Version)
    dpkg-deb -x "$deb" "$TMP/cg/x"
    ex=$(find "$TMP/cg/x" -name examples.tar.gz | head -n 1)
    tar -xzf "$ex" -C "$TMP/cg" examples/Straight_skeleton_2
    lines=()
    for i in 1 2 3 4; do
      python3 scripts/cgal_pwh_to_poly.py "$TMP/cg/examples/Straight_skeleton_2/sample_$i.dat" \
        "$D2/cgal/straight_skeleton_sample_$i.poly" "CGAL $version examples/Straight_skeleton_2/sample_$i.dat"
      lines+=("cgal/straight_skeleton_sample_$i.poly	Debian libcgal-demo $version (examples.tar.gz: examples/Straight_skeleton_2/sample_$i.dat, converted by scripts/cgal_pwh_to_poly.py)	CC0-1.0")
    done
    set_source "cgal/" "${lines[@]}"
  else
    echo "fetch-data: apt-get download libcgal-demo failed: skipping the CGAL 2D samples"
  fi
fi
if [ -s "$D2/glyphs/dejavu-sans-at.poly" ] && [ $FORCE = 0 ]; then
  echo "fetch-data: DejaVu glyphs already present"
else
  FONT=/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
  fversion=$(dpkg-query -W -f '${Version}' fonts-dejavu-core 2>/dev/null || true)
  if [ ! -s "$FONT" ]; then
    echo "fetch-data: DejaVuSans.ttf not installed: downloading fonts-dejavu-core"
    mkdir -p "$TMP/fd"
    chmod 755 "$TMP/fd"
    (cd "$TMP/fd" && apt-get download fonts-dejavu-core >/dev/null 2>&1) || true
    deb=$(ls "$TMP"/fd/fonts-dejavu-core_*.deb 2>/dev/null | head -n 1)
    if [ -n "$deb" ]; then
      fversion=$(dpkg-deb -f "$deb" Version)
      dpkg-deb -x "$deb" "$TMP/fd/x"
      FONT=$TMP/fd/x/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
    fi
  fi
  if [ -s "$FONT" ]; then
    mkdir -p "$D2/glyphs"
    lines=()
    for c in B 8 @ g; do
      n=$c; [ "$c" = "@" ] && n=at
      python3 scripts/ttf_glyph_to_poly.py "$FONT" "$c" "$D2/glyphs/dejavu-sans-$n.poly"
      lines+=("glyphs/dejavu-sans-$n.poly	Debian fonts-dejavu-core $fversion (DejaVuSans.ttf, glyph '$c', flattened within 0.001 em by scripts/ttf_glyph_to_poly.py)	Bitstream Vera / DejaVu font licence (free)")
    done
    set_source "glyphs/" "${lines[@]}"
  else
    echo "fetch-data: no DejaVuSans.ttf: skipping the glyphs"
  fi
fi
echo "fetch-data: $D2 holds $(find "$D2" -name '*.json' -o -name '*.poly' | wc -l) 2D files; sources in $D2/SOURCES.txt"
