#!/usr/bin/env bash
# acd 2d far from the origin: BarbedThing translated by 1e9 (doubles 1.2e-7 apart for a polygon
# of extent 14) decomposes and verifies under every measure (it exited 3 with two overlapping
# components before cut ends were shared); translated by 1e14 its coordinates cannot resolve
# its edges and it is refused with exit 2, naming the edge and the ratio.
. "$(dirname "$0")/lib.sh"
B="$DATA/polygons-lien/BarbedThing.poly"
[ -f "$B" ] || { echo "note: $B missing, skipped"; exit 77; }
# .poly: chain count, then per chain "N out|in", N lines "x y", one order line
shift_poly() {
  awk -v d="$1" 'BEGIN { st = 0 }
    { for (i = 1; i <= NF; i++) tok[n++] = $i }
    END {
      k = 0; c = tok[k++]; print c
      for (ch = 0; ch < c; ch++) {
        m = tok[k++]; t = tok[k++]; print m " " t
        for (j = 0; j < m; j++) { x = tok[k++] + d; y = tok[k++] + d; printf "%.17g %.17g\n", x, y }
        o = ""; for (j = 0; j < m; j++) o = o (j ? " " : "") tok[k++]; print o
      }
    }' "$B"
}
shift_poly 1e9 > "$T/far.poly"
for m in sl sp h1 h2; do
  for t in 0 0.05; do
    "$ACD" 2d "$T/far.poly" -m $m -t $t --verify > "$T/out" 2> "$T/err" || fail "$m tau $t: exit $?: $(cat "$T/err")"
    grep -q "verify: passed" "$T/out" || fail "$m tau $t: no pass line"
  done
done
"$ACD" 2d "$T/far.poly" --exact hm --verify > /dev/null 2> "$T/err" || fail "exact hm: $(cat "$T/err")"
shift_poly 1e14 > "$T/farther.poly"
"$ACD" 2d "$T/farther.poly" -t 0.05 --verify > /dev/null 2> "$T/err"; rc=$?
[ $rc = 2 ] || fail "1e14: exit $rc: $(cat "$T/err")"
grep -q "polygon 0: acd2d: the coordinates cannot resolve a feature" "$T/err" || fail "1e14 message: $(cat "$T/err")"
grep -q "times the polygon's extent" "$T/err" || fail "1e14 message lacks the ratio: $(cat "$T/err")"
echo "ok"
