#!/usr/bin/env bash
# acd 2d command line: help, usage errors (exit 1 with a message), every option accepted in
# both "--opt V" and "--opt=V" forms, and the summary line.
. "$(dirname "$0")/lib.sh"
# expect CODE WORD CMD...: exit code CODE and WORD in stderr
expect() {
  local code=$1 word=$2; shift 2
  "$@" > "$T/out" 2> "$T/err"
  local rc=$?
  [ "$rc" = "$code" ] || fail "'$*' exited $rc, expected $code; stderr: $(cat "$T/err")"
  grep -q -- "$word" "$T/err" || fail "'$*': stderr lacks '$word': $(cat "$T/err")"
}
printf '1\n6 out\n0 0\n2 0\n2 1\n1 1\n1 2\n0 2\n1 2 3 4 5 6\n' > "$T/L.poly"

"$ACD" 2d --help > "$T/help" || fail "--help exit $?"
for w in --tau --measure --sc --sd --cut --normalize --json --svg --verify -o -v; do
  grep -q -- "$w" "$T/help" || fail "help lacks $w"
done
expect 1 usage "$ACD" 2d
expect 1 "unknown option" "$ACD" 2d "$T/L.poly" --bogus
expect 1 "finite number" "$ACD" 2d "$T/L.poly" -t abc
expect 1 ">= 0" "$ACD" 2d "$T/L.poly" -t -1
expect 1 "needs a value" "$ACD" 2d "$T/L.poly" --tau
expect 1 "sl, sp, h1 or h2" "$ACD" 2d "$T/L.poly" -m xx
expect 1 "ray or diagonal" "$ACD" 2d "$T/L.poly" --cut zigzag
expect 1 "> 0" "$ACD" 2d "$T/L.poly" --sd 0
expect 1 ">= 0" "$ACD" 2d "$T/L.poly" --sc -0.5
expect 1 ".geojson, .json or .poly" "$ACD" 2d "$T/L.poly" -o "$T/x.txt"
expect 1 "one input file" "$ACD" 2d "$T/L.poly" "$T/L.poly"
expect 1 "auto, poly, geojson, topojson or wkt" "$ACD" 2d "$T/L.poly" --format xml

for m in sl sp h1 h2; do
  for form in "-m $m" "--measure=$m"; do
    "$ACD" 2d "$T/L.poly" $form -t 0.1 --sc 0 --sd 2 --cut=diagonal > "$T/out" 2>"$T/err" || { grep -q "unsupported\|not supported\|not implemented" "$T/err" && continue; fail "$form exit $?: $(cat "$T/err")"; }
    grep -q "measure $m: 2 components" "$T/out" || fail "$form: $(cat "$T/out")"
  done
done
"$ACD" 2d "$T/L.poly" --tau=1 > "$T/out" || fail "--tau=1"
grep -q "tau 1, measure sl: 1 components" "$T/out" || fail "tau 1 keeps the L whole (concavity 0.707): $(cat "$T/out")"
"$ACD" 2d "$T/L.poly" --tau 0.5 --normalize > "$T/out" || fail "--normalize"
grep -q "x R" "$T/out" || fail "--normalize summary: $(cat "$T/out")"
"$ACD" 2d "$T/L.poly" --notch-eps 0 --format poly > "$T/out" || fail "--notch-eps/--format"
grep -q "1 notches" "$T/out" || fail "notch count: $(cat "$T/out")"
echo "ok"
