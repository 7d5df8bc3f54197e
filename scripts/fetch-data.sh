#!/usr/bin/env bash
# Fetches real test meshes into data/meshes/ (git-ignored), idempotently:
#  - Debian's libcgal-demo (CGAL's data/meshes: armadillo, bunny00, elephant, eight, cheese, turbine,
#    camel, homer, mushroom, ...; CC0 1.0 per Debian's copyright file of cgal), with `apt-get download`;
#  - npm's `bunny` (the Stanford bunny, public domain), with `npm pack`, converted to OBJ;
#  - Debian's assimp-testmodels (BSD-3-clause): its OBJ, OFF, PLY, STL and invalid/ models, into
#    data/meshes/assimp/, as real-world and malformed-file cases for the readers.
# Source and licence of every mesh: docs/data.md (and data/meshes/SOURCES.txt, written here).
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
