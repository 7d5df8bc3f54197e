#!/usr/bin/env bash
# Optional CAD corpus: OpenSCAD's example models (CC0 1.0 per Debian's copyright file of openscad,
# "Files: examples/*"), rendered to binary STL by OpenSCAD itself, into data/meshes/openscad/
# (git-ignored), idempotently. These are CAD solids as users export them: unions of separate
# bodies, extrusions, rotated and rounded coordinates, STL soups. OpenSCAD (GPL) is only run as a
# program to make the data; nothing of it is linked. It needs `apt-get install openscad` (about
# 100 MB with its libraries), so the main fetch (scripts/fetch-data.sh) does not do it.
# Rendering takes 5-10 minutes on 2 cores (CGAL's exact booleans). Examples that render nothing 3D
# (2D-only, echo/assert demos that fail by design) are listed as skipped.
# Usage: scripts/fetch-openscad.sh [--force]
set -euo pipefail
cd "$(dirname "$0")/.."
DEST=data/meshes/openscad
FORCE=0
[ "${1:-}" = "--force" ] && FORCE=1
if ! command -v openscad >/dev/null; then
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO=sudo
  echo "fetch-openscad: installing openscad with apt-get"
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends openscad >/dev/null ||
    { $SUDO apt-get update -qq && $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends openscad >/dev/null; }
fi
EX=/usr/share/openscad/examples
[ -d "$EX" ] || { echo "fetch-openscad: no $EX (openscad's examples are missing)" >&2; exit 1; }
version=$(dpkg-query -W -f '${Version}' openscad 2>/dev/null || echo unknown)
mkdir -p "$DEST"
if [ -f "$DEST/.version" ] && [ "$(cat "$DEST/.version")" = "$version" ] && [ $FORCE = 0 ]; then
  echo "fetch-openscad: already present (openscad $version, $(ls "$DEST"/*.stl | wc -l) STL files)"
  exit 0
fi
: > "$DEST/SOURCES.txt"
n=0
for f in $(find "$EX" -name '*.scad' | sort); do
  name=$(basename "$f" .scad)
  rel=${f#"$EX"/}
  if timeout 600 openscad -o "$DEST/$name.stl" "$f" >"$DEST/.log" 2>&1 && [ -s "$DEST/$name.stl" ]; then
    echo "$name.stl	Debian openscad $version (examples/$rel, rendered to STL by openscad)	CC0-1.0" >> "$DEST/SOURCES.txt"
    n=$((n + 1))
  else
    rm -f "$DEST/$name.stl"
    echo "fetch-openscad: skipped $rel (no 3D result: $(grep -m1 -i 'error\|warning\|not a 3D' "$DEST/.log" || echo 'see openscad'))"
  fi
done
rm -f "$DEST/.log"
echo "$version" > "$DEST/.version"
echo "fetch-openscad: $n STL files in $DEST; sources in $DEST/SOURCES.txt"
