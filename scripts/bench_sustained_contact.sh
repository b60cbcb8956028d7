#!/usr/bin/env bash
# Sustained contact measured (bench/sustained_contact.c; docs/reference_case.md, "Sustained
# contact"): grains placed on or settling on the chute, with the rigid and the compliant
# stick, each to the exit. With --before REV the same benchmark is also compiled against
# revision REV's core (built in a temporary folder) and run first, so that one run of this
# command gives the before and the after on the same machine.
# Usage: scripts/bench_sustained_contact.sh [--before REV] [rounds=3]
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=bench_before.sh
. "$ROOT/scripts/bench_before.sh"
"$ROOT/scripts/setup.sh" >/dev/null
if [ -n "$before" ]; then
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  before_program "$ROOT/bench/sustained_contact.c" "$tmp/before"
  echo "== before: $before ($(git -C "$ROOT" rev-parse --short "$before"))"
  "$tmp/before" "$@"
  echo
fi
echo "== this tree ($(tree_label))"
"$ROOT/build/tribo_sustained_contact" "$@"
