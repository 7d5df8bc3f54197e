#!/usr/bin/env bash
# acd 2d --verify: passes (exit 0) on real models for every measure; a stricter --verify-tau
# makes it fail with exit 3 and a message naming the component, its concavity and vertex.
. "$(dirname "$0")/lib.sh"
printf '1\n6 out\n0 0\n2 0\n2 1\n1 1\n1 2\n0 2\n1 2 3 4 5 6\n' > "$T/L.poly"

"$ACD" 2d "$T/L.poly" --verify > "$T/out" || fail "L --verify exit $?"
grep -q "verify: passed" "$T/out" || fail "no pass line: $(cat "$T/out")"
# tau 1 leaves the L whole (concavity 1/sqrt 2); checking it against 0.5 must fail
"$ACD" 2d "$T/L.poly" -t 1 --verify-tau 0.5 --json "$T/r.json" > "$T/out" 2> "$T/err"; rc=$?
[ $rc = 3 ] || fail "--verify-tau 0.5 exit $rc"
grep -q "verify failed: polygon 0: component 0 has concavity 0.7071" "$T/err" || fail "message: $(cat "$T/err")"
grep -q "vertex 3 (1, 1)" "$T/err" || fail "message lacks the vertex: $(cat "$T/err")"
grep -q '"passed":false' "$T/r.json" || fail "JSON lacks the failed verification"

M="$DATA/polygons-lien"
if [ -d "$M" ]; then
  for f in texas bird hole1 hole3 wierd1 nazca_nazca_heron; do
    for m in sl sp h1 h2; do
      for t in 0 0.5 10; do
        "$ACD" 2d "$M/$f.poly" -m $m -t $t --verify > "$T/out" 2> "$T/err"; rc=$?
        if [ $rc != 0 ] && grep -q "unsupported" "$T/err"; then continue; fi
        [ $rc = 0 ] || fail "$f $m tau $t: exit $rc: $(cat "$T/err")"
      done
    done
  done
  # a real component against a stricter bound
  "$ACD" 2d "$M/texas.poly" -t 1 --verify-tau 0.1 > /dev/null 2> "$T/err"; rc=$?
  [ $rc = 3 ] || fail "texas --verify-tau 0.1 exit $rc"
  grep -q "component [0-9]* has concavity" "$T/err" || fail "texas message: $(cat "$T/err")"
else
  echo "note: $M missing, real models skipped"
fi
echo "ok"
