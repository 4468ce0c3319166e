#!/usr/bin/env bash
# Builds the PLCopen peer driver against pyplcopen's C++ core and writes the
# traces ecam's facade is compared with. See README.md next to this script.
#
#   scripts/plcopen-peer/build.sh            build, write the fixtures
#   scripts/plcopen-peer/build.sh --check    build, diff against the fixtures
#   scripts/plcopen-peer/build.sh --bench [N]  build, print ns per FB cycle
#
# The peer's source: PLCOPEN_PEER_SRC (an unpacked pyplcopen-0.21.0 sdist),
# else /work/peer/pyplcopen-0.21.0 if present, else the sdist is downloaded
# with pip into target/plcopen-peer/ (a venv there holds the build backends
# pip needs to produce an sdist).
set -euo pipefail

VERSION=0.21.0
SHA256=$(cat "$(dirname "$0")/SDIST_SHA256")
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
WORK="$ROOT/target/plcopen-peer"
FIXTURES="$ROOT/crates/ecam-engine/tests/it/fixtures/plcopen-peer"
mkdir -p "$WORK"

src="${PLCOPEN_PEER_SRC:-}"
tarball=""
if [[ -z "$src" && -d /work/peer/pyplcopen-$VERSION/core ]]; then
    src=/work/peer/pyplcopen-$VERSION
    tarball=/work/peer/pyplcopen-$VERSION.tar.gz
fi
if [[ -z "$src" ]]; then
    tarball="$WORK/pyplcopen-$VERSION.tar.gz"
    if [[ ! -f "$tarball" ]]; then
        python3 -m venv "$WORK/venv"
        "$WORK/venv/bin/pip" install --quiet scikit-build-core pybind11 cmake
        "$WORK/venv/bin/pip" download --quiet --no-binary :all: --no-deps \
            --no-build-isolation -d "$WORK" "pyplcopen==$VERSION"
    fi
    tar -xzf "$tarball" -C "$WORK"
    src="$WORK/pyplcopen-$VERSION"
fi
if [[ -n "$tarball" && -f "$tarball" ]]; then
    got=$(sha256sum "$tarball" | cut -d' ' -f1)
    if [[ "$got" != "$SHA256" ]]; then
        echo "sdist sha256 $got, expected $SHA256" >&2
        exit 1
    fi
fi

g++ -std=c++17 -O2 -fno-exceptions -fno-rtti -Wall -I "$src/core" \
    "$HERE/driver.cpp" -o "$WORK/driver"
g++ -std=c++17 -O2 -fno-exceptions -fno-rtti -Wall -I "$src/core" \
    "$HERE/couplings.cpp" -o "$WORK/couplings"

case "${1:-}" in
--bench)
    exec "$WORK/driver" --bench "${2:-1000000}"
    ;;
--check)
    out="$WORK/traces"
    ;;
"")
    out="$FIXTURES"
    ;;
*)
    echo "usage: build.sh [--check | --bench [N]]" >&2
    exit 2
    ;;
esac

mkdir -p "$out"
for program in driver couplings; do
    commit=$(git -C "$ROOT" log -1 --format=%h -- "scripts/plcopen-peer/$program.cpp" 2>/dev/null || true)
    for c in $("$WORK/$program" --list); do
        {
            echo "# pyplcopen $VERSION (lusipad/plcopen, Apache-2.0) sdist sha256 $SHA256"
            echo "# driver scripts/plcopen-peer/$program.cpp at commit ${commit:-uncommitted}"
            echo "# command: scripts/plcopen-peer/build.sh   ($program $c); g++ $(g++ -dumpfullversion); date $(date -u +%Y-%m-%d)"
            "$WORK/$program" "$c"
        } >"$out/$c.csv"
    done
done
"$WORK/driver" --tables >"$out/tables.csv"
if [[ "$out" != "$FIXTURES" ]]; then
    # The header names the commit and compiler; compare the data only.
    status=0
    for f in "$FIXTURES"/*.csv; do
        if ! diff -q <(grep -Ev '^# (pyplcopen|driver|command)' "$f") <(grep -Ev '^# (pyplcopen|driver|command)' "$out/$(basename "$f")") >/dev/null; then
            echo "differs: $(basename "$f")" >&2
            status=1
        fi
    done
    [[ $status == 0 ]] && echo "peer traces match the fixtures"
    exit $status
fi
echo "wrote $(ls "$out" | wc -l) traces to ${out#$ROOT/}"
