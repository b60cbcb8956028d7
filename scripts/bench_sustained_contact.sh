#!/usr/bin/env bash
# Sustained contact measured (bench/sustained_contact.c; docs/reference_case.md, "Sustained
# contact"): grains placed on or settling on the chute, with the rigid and the compliant
# stick, each to the exit. With --before REV the same benchmark is also compiled against
# revision REV's core (built in a temporary folder) and run first, so that one run of this
# command gives the before and the after on the same machine.
# Usage: scripts/bench_sustained_contact.sh [--before REV] [rounds=3]
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
before=""
if [ "${1:-}" = --before ]; then
  before=${2:?"--before needs a revision"}
  shift 2
fi
"$ROOT/scripts/setup.sh" >/dev/null
if [ -n "$before" ]; then
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  mkdir "$tmp/src"
  git -C "$ROOT" archive "$before" | tar -x -C "$tmp/src"
  cmake -S "$tmp/src" -B "$tmp/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
        -DTRIBO_BUILD_FMU=OFF -DTRIBO_BUILD_TESTS=OFF >/dev/null
  cmake --build "$tmp/build" --target tribo_core >/dev/null
  # every folder of that revision's src/ on the include path (its files include by name)
  includes=()
  while IFS= read -r folder; do includes+=(-I"$folder"); done < <(find "$tmp/src/src" -type d)
  cc -O3 -DNDEBUG -std=c11 -D_DEFAULT_SOURCE "${includes[@]}" "$ROOT/bench/sustained_contact.c" \
     "$tmp/build/libtribo_core.a" -lsundials_cvode -lsundials_nvecserial -lm -o "$tmp/before"
  echo "== before: $before ($(git -C "$ROOT" rev-parse --short "$before"))"
  "$tmp/before" "$@"
  echo
fi
echo "== this tree ($(git -C "$ROOT" rev-parse --short HEAD)$(git -C "$ROOT" diff --quiet HEAD -- src || echo ', modified'))"
"$ROOT/build/tribo_sustained_contact" "$@"
