# Sourced by the benches that score peers and ours side by side (bench/bench_3d_hacd.sh,
# bench/bench_3d_vhacd.sh). Needs $ACD (the acd binary) and $T (a scratch directory).

# ev MESH HULLS: prints "concavity_max iou coverage" of acd eval (or "fail fail fail")
ev() {
  "$ACD" eval "$1" "$2" --json 2>/dev/null |
    python3 -c "import json,sys; d=json.load(sys.stdin); print('%.4f %.4f %.4f' % (d['concavity_max'], d['iou'], d['coverage']))" 2>/dev/null ||
    echo "fail fail fail"
}

# cputime COMMAND...: prints the user + system CPU seconds of the command (its output goes to
# $T/out, its errors to $T/err)
cputime() {
  local TIMEFORMAT=%U+%S t
  t=$( { time "$@" >"$T/out" 2>"$T/err"; } 2>&1 )
  python3 -c "print('%.2f' % ($t))"
}
