#!/usr/bin/env bash
# acd eval --export: the hulls of a peer decomposition written as one OBJ (which acd eval reads back
# with the same score), per-hull files, summary.json, URDF and MJCF; --max-hull-vertices keeps the
# budget; bad options exit 1.
. "$(dirname "$0")/lib.sh"

# an octagonal prism (16 vertices) split in two groups
{
  for z in 0 1; do
    for i in 0 1 2 3 4 5 6 7; do
      awk -v i=$i -v z=$z 'BEGIN { a = i * 3.14159265358979 / 4; printf "v %.17g %.17g %s\n", cos(a), sin(a), z }'
    done
  done
  echo "f 1 8 7 6 5 4 3 2"
  echo "f 9 10 11 12 13 14 15 16"
  for i in 1 2 3 4 5 6 7 8; do j=$(( i % 8 + 1 )); echo "f $i $j $((j + 8)) $((i + 8))"; done
} > "$T/prism.obj"
{
  cat "$T/prism.obj" | grep '^v'
  echo "o a"; echo "f 1 2 3 4 5"; echo "f 9 10 11 12 13"
  echo "o b"; echo "f 5 6 7 8 1"; echo "f 13 14 15 16 9"
} > "$T/split.obj"

"$ACD" eval "$T/prism.obj" "$T/split.obj" --json --samples 20000 --surface-samples 5000 \
  --export "$T/out" --name prism > "$T/r1.json" || fail "export exit $?"
for f in decomposition.obj hulls/hull_000.obj hulls/hull_001.obj parts/part_000.obj parts/part_001.obj \
         summary.json prism.urdf prism.xml; do
  [ -s "$T/out/$f" ] || fail "missing $f"
done
[ "$(grep -c '^o hull_' "$T/out/decomposition.obj")" = 2 ] || fail "groups in decomposition.obj"
[ "$(grep -c '<collision' "$T/out/prism.urdf")" = 2 ] || fail "URDF collisions"
[ "$(grep -c '<geom ' "$T/out/prism.xml")" = 2 ] || fail "MJCF geoms"
grep -q '"eval"' "$T/out/summary.json" || fail "summary without the report"
# the exported hulls score the same as the groups they came from
"$ACD" eval "$T/prism.obj" "$T/out/decomposition.obj" --json --samples 20000 --surface-samples 5000 > "$T/r2.json" || fail "re-eval"
a=$(grep '"iou"' "$T/r1.json"); b=$(grep '"iou"' "$T/r2.json")
[ "$a" = "$b" ] || fail "iou changed after export: $a vs $b"

# a budget of 4 vertices per hull: every hull in the OBJ has at most 4 vertices and still covers
"$ACD" eval "$T/prism.obj" "$T/split.obj" --samples 20000 --surface-samples 5000 --export "$T/small" \
  --max-hull-vertices 4 > /dev/null || fail "simplified export"
awk '/^o /{ if (n > 4) bad = 1; n = 0 } /^v /{ n++ } END { if (n > 4) bad = 1; exit bad }' "$T/small/decomposition.obj" \
  || fail "more than 4 vertices in a simplified hull"
"$ACD" eval "$T/prism.obj" "$T/small/decomposition.obj" --json --samples 20000 --surface-samples 5000 > "$T/r3.json" || fail "re-eval small"
grep -Eq "\"coverage\":[[:space:]]*1(,|$)" "$T/r3.json" || fail "simplified hulls do not cover: $(grep coverage "$T/r3.json")"

"$ACD" eval "$T/prism.obj" "$T/split.obj" --export "$T/x" --max-hull-vertices 3 > /dev/null 2>&1; [ $? = 1 ] || fail "budget 3 exit"
"$ACD" eval "$T/prism.obj" "$T/split.obj" --export "$T/x" --name "bad name" --samples 1000 --surface-samples 100 > /dev/null 2>&1
[ $? = 1 ] || fail "bad name exit"
echo "eval_export: ok"
