#!/usr/bin/env bash
# segment_ident.sh BASE_ACD NEW_ACD [OUTDIR]: runs `acd segment` with both binaries on the meshes of
# data/meshes listed below (labels --seg, parts --parts, hulls -o), and compares exit codes and the
# output files byte for byte (and the summary line on stdout less its seconds). Prints one line per run and "segment ident: K/N the same".
# A change meant to keep CoRiSe's output must give N/N.
set -u
BASE="$1"; NEW="$2"; OUT="${3:-/tmp/segment-ident}"
M="$(cd "$(dirname "$0")/.." && pwd)/data/meshes"
rm -rf "$OUT"; mkdir -p "$OUT"
runs=(
 "bunny|bunny.obj|" "camel|camel.off|" "armadillo|armadillo.off|" "knot1|knot1.off|" "fandisk|fandisk.off|"
 "elephant|elephant.off|" "cheese|cheese.off|" "bunny00|bunny00.off|" "anchor|anchor.off|" "star|star.off|"
 "cow|cow.off|" "dino|dino.off|" "hand|hand.off|" "homer|homer.off|" "horse_bull|bull.off|" "pig|pig.off|"
 "lion|lion.off|" "man|man.off|" "femur|femur.off|" "bones|bones.off|" "mushroom|mushroom.off|"
 "rotor|rotor.off|" "turbine|turbine.off|" "triceratops|triceratops.off|" "tripod|tripod.off|"
 "knot2|knot2.off|" "eight|eight.off|" "elk|elk.off|" "cactus|cactus.off|" "blade|blade.off|"
 "3torus|3torus.off|" "cross|cross.off|" "P|P.off|" "couplingdown|couplingdown.off|"
 "camel_t05|camel.off|-t 0.05" "armadillo_t05|armadillo.off|-t 0.05" "fandisk_t03|fandisk.off|-t 0.03"
 "elephant_t2|elephant.off|--threads 2" "armadillo_t2|armadillo.off|--threads 2 -t 0.05"
 "open_cube|open_cube.off|" "bad_missing|no-such-mesh.off|"
)
same=0
for r in "${runs[@]}"; do
  IFS='|' read -r name file args <<<"$r"
  for side in base new; do
    bin=$BASE; [ $side = new ] && bin=$NEW
    timeout 600 "$bin" segment "$M/$file" $args --seg "$OUT/$name.$side.seg" --parts "$OUT/$name.$side.parts.obj" \
      -o "$OUT/$name.$side.hulls.obj" >"$OUT/$name.$side.raw" 2>"$OUT/$name.$side.err"
    echo $? >"$OUT/$name.$side.rc"
    sed -E 's/, [0-9.e+-]+ s$//' "$OUT/$name.$side.raw" >"$OUT/$name.$side.out" # the summary line less its time
  done
  ok=1
  for ext in rc seg parts.obj hulls.obj out; do
    a="$OUT/$name.base.$ext"; b="$OUT/$name.new.$ext"
    if [ -e "$a" ] || [ -e "$b" ]; then cmp -s "$a" "$b" || ok=0; fi
  done
  if [ $ok = 1 ]; then
    echo "$name: same (exit $(cat "$OUT/$name.new.rc"), $(sort -u "$OUT/$name.new.seg" 2>/dev/null | wc -l) parts)"; same=$((same+1))
  else
    echo "$name: DIFFERENT (exit $(cat "$OUT/$name.base.rc")/$(cat "$OUT/$name.new.rc"))"
  fi
done
echo "segment ident: $same/${#runs[@]} the same"
