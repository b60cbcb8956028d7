#!/usr/bin/env bash
# What the two normal dashpots cost on the paper's high-friction runs (docs/model.md §3, §7;
# mu = nu = 1, tau to 5000, CVODE at the study's rtol 1e-8, atol 1e-10, both charge models),
# one run at a time through the C API (build/tribo_paper_run): the integrator's steps and
# events do not depend on the machine's load, the CPU time does. Writes docs/dashpot_cost.md.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$ROOT/scripts/setup.sh" >/dev/null
OUT="$ROOT/docs/dashpot_cost.md"
rows=$(mktemp)
trap 'rm -f "$rows"' EXIT
for eps in 0.1 0.2 0.3 0.4 0.5 0.6 0.7 0.8 0.9 1.0; do
  for dp in 0 1; do
    # the last line: "<steps> steps, <sub> sub-steps, <rhs> right-hand sides, <events> events, <cpu> s CPU"
    set -- $("$ROOT/build/tribo_paper_run" epsilon=$eps mu=1 nu=1 rtol=1e-8 atol=1e-10 \
               damping_point=$dp t_end=5000 | tail -1 | tr -d ,)
    echo "$eps $dp $1 $5 $8 ${10}" >> "$rows"
  done
done
{
  cat <<HEAD
# What the two dashpots cost: the paper's high-friction runs

Produced by \`scripts/dashpot_cost.sh\`: mu = nu = 1, the paper's drop (docs/model.md §7),
tau from 0 to 5000, CVODE (Adams) at rtol 1e-8, atol 1e-10, both charge models, one run at a
time through the C API. Steps, right-hand sides and events (switches of the force law,
docs/model.md §3) do not depend on the machine's load; the CPU time was measured in this
run, on a 2-core machine shared with other work.

| epsilon | dashpot | steps | right-hand sides | events | CPU s |
|---|---|---|---|---|---|
HEAD
  awk '{ printf "| %s | %s | %d | %d | %d | %s |\n", $1, ($2 == 0 ? "contact point" : "centre"), $3, $4, $5, $6 }' "$rows"
  awk '{ s[$2] += $3; r[$2] += $4; e[$2] += $5; c[$2] += $6 }
       END { for (d = 0; d <= 1; d++)
               printf "| all | %s | %d | %d | %d | %.2f |\n", (d == 0 ? "contact point" : "centre"), s[d], r[d], e[d], c[d] }' "$rows"
} > "$OUT"
echo "wrote $OUT"
