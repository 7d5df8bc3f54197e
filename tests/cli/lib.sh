# tests/cli/lib.sh: the prologue the CLI tests share. Each test sources it first:
#   . "$(dirname "$0")/lib.sh"
# with its own arguments (ctest runs `bash TEST.sh ACD_BINARY SOURCE_DIR SHARED_DATA_DIR`). It
# sets -u, and
#   ACD   the acd binary ($1, required)
#   SRC   the source directory ($2; empty when not given)
#   DATA  the shared data directory ($3; empty when not given)
#   T     a fresh temporary directory, removed when the test exits
#   fail MESSAGE...       prints "FAIL: MESSAGE" and exits 1 (in the test's own shell: not from
#                         inside $(...) or a pipeline, as before)
#   get KEY FILE          the first number after "KEY": in FILE (flat JSON)
#   near A B TOL          succeeds when |A - B| <= TOL
# Not a test itself (tests/CMakeLists.txt leaves it out of the glob).
set -u
ACD=$1
SRC=${2:-}
DATA=${3:-}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
get() { sed -n "s/.*\"$1\":[[:space:]]*\([-0-9.eE+]*\).*/\1/p" "$2" | head -1; }
near() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= t) }'; }
