#!/usr/bin/env bash
# Random physical set-ups (tests/stability/random_setups.h): the named set-ups that once ended
# in an event cascade, then 1000 random SI set-ups with external normal forces of -1e4 to
# 1e4 N/m, each under both stick models, to the chute's exit, to rest or to 0.5 s, each with
# at most 5e5 units of work (about half a second of CPU; a run still going then is counted
# apart). Prints every run that failed and a summary; exits 1 if one did.
# Arguments go to the program: count=, seed=, horizon_s=, work=, verbose=1.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$ROOT/scripts/setup.sh" >/dev/null
exec "$ROOT/build/tests/stability/tribo_random_setups" "$@"
