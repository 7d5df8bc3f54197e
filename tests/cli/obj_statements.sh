#!/usr/bin/env bash
# OBJ statements the reader skips with a warning (points, lines, free-form geometry) reach the
# CLI's stderr as "acd CMD: warning: FILE:LINE: ...", exit 0 and the faces read as without them;
# an unknown statement is an error naming its line, exit 2 (docs/mesh.md, "OBJ statements").
. "$(dirname "$0")/lib.sh"
faces='v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4'
printf '%s\n' "$faces" > "$T/plain.obj"
printf '%s\nvt 0 0\ns 1\nusemtl m\nl 1 2\nl 2 3\ncstype bspline\ndeg 1 1\nsurf 0 1 0 1 1 2 \\\n 3 4\nparm u 0 1\nend\n' \
  "$faces" > "$T/extra.obj"
"$ACD" info "$T/plain.obj" > "$T/plain.txt" 2> "$T/plain.err" || fail "plain: exit $?"
[ -s "$T/plain.err" ] && fail "plain: stderr $(cat "$T/plain.err")"
"$ACD" info "$T/extra.obj" > "$T/extra.txt" 2> "$T/extra.err" || fail "extra: exit $? $(cat "$T/extra.err")"
grep -q "^acd info: warning: $T/extra.obj:12: 2 'l' statements skipped (line elements" "$T/extra.err" ||
  fail "l warning: $(cat "$T/extra.err")"
grep -q "^acd info: warning: $T/extra.obj:16: 1 'surf' statement skipped (free-form surfaces" "$T/extra.err" ||
  fail "surf warning: $(cat "$T/extra.err")"
[ "$(wc -l < "$T/extra.err")" = 2 ] || fail "extra: $(wc -l < "$T/extra.err") lines on stderr, 2 expected"
# the same mesh as without the skipped statements (the report names the file: compare the rest)
diff <(sed 1d "$T/plain.txt") <(sed 1d "$T/extra.txt") > /dev/null || fail "extra read another mesh"
# the other commands print it too (segment: its own prefix; hull reads the groups)
"$ACD" segment "$T/extra.obj" > /dev/null 2> "$T/seg.err" || fail "segment: exit $?"
grep -q "^acd segment: warning: .*'l' statements skipped" "$T/seg.err" || fail "segment warning: $(cat "$T/seg.err")"
"$ACD" hull "$T/extra.obj" -o "$T/h.obj" > /dev/null 2> "$T/hull.err" || fail "hull: exit $?"
grep -q "^acd hull: warning: .*'surf' statement skipped" "$T/hull.err" || fail "hull warning: $(cat "$T/hull.err")"
# an unknown statement: exit 2, its line named
printf '%s\nvx 1 2 3\n' "$faces" > "$T/bad.obj"
"$ACD" info "$T/bad.obj" > /dev/null 2> "$T/bad.err"
rc=$?
[ $rc = 2 ] || fail "unknown statement: exit $rc"
grep -q "bad.obj:9: unknown statement 'vx'" "$T/bad.err" || fail "unknown statement message: $(cat "$T/bad.err")"
echo ok
