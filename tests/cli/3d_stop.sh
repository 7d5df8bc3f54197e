#!/usr/bin/env bash
# acd 3d --stop: the hull-distance stopping test keeps some torus parts whole (leaf reason
# "hull_distance", concavity within tau, --verify passes) and gives fewer leaves than the measure
# alone; a bad value is a usage error.
. "$(dirname "$0")/lib.sh"
IN=$SRC/tests/data/meshes/torus.off
"$ACD" 3d "$IN" -t 0.1 --no-merge --stop hull --verify --json "$T/h.json" -o "$T/h.obj" > "$T/h.txt" || fail "--stop hull failed"
"$ACD" 3d "$IN" -t 0.1 --no-merge --stop measure --json "$T/m.json" > "$T/m.txt" || fail "--stop measure failed"
grep -q '"hull_distance"' "$T/h.json" || fail "no hull_distance leaf on the torus at tau 0.1"
grep -q '"hull_distance"' "$T/m.json" && fail "hull_distance leaf with --stop measure"
ph=$(awk '{print $1; exit}' "$T/h.txt"); pm=$(awk '{print $1; exit}' "$T/m.txt")
[ "$ph" -lt "$pm" ] || fail "--stop hull gave $ph parts, --stop measure $pm"
"$ACD" 3d "$IN" --stop sometimes > /dev/null 2> "$T/err"; rc=$?
[ $rc -ne 0 ] || fail "--stop sometimes accepted"
grep -q -- "--stop takes measure or hull" "$T/err" || fail "no message for a bad --stop"
echo ok
