#!/usr/bin/env bash
# Sourced by the benchmarks that set a package command beside its core in one run
# (bench_population_package.sh, bench_runs_package.sh), after bench_before.sh; they set ROOT,
# PYTHON, tmp and before (bench_before.sh). Gives
#   cpu_of COMMAND...       the CPU of a command and of every process it waited for (its Dask
#                           workers' too), and the system's part of it, in seconds
#   modes_run RESULTS ARGS...  `tribo ARGS` serially, on 2 threads and on 2 worker processes,
#                           each with revision $before's package first where given, its CPU
#                           appended to RESULTS ("<mode>-<before|after> <cpu> <system's>")
#   modes_report RESULTS TITLE ROUNDS  the table of the medians, each against RESULTS' "core"
#                           line's CPU, the parallel modes' also against its "core-2" line's
#                           (the same runs through the core on 2 processes at once), if any

cpu_of() {
  "$PYTHON" - "$@" <<'PY'
import resource
import subprocess
import sys

subprocess.run(sys.argv[1:], check=True, stdout=subprocess.DEVNULL)
used = resource.getrusage(resource.RUSAGE_CHILDREN)
print(f"{used.ru_utime + used.ru_stime:.3f} {used.ru_stime:.3f}")
PY
}

modes_run() {
  local results=$1 mode label out
  shift
  local -A options=([serial]="--serial" [threads]="--workers 2"
                    [processes]="--workers 2 --processes")
  for mode in serial threads processes; do
    for label in ${before:+before} after; do
      # a new folder for each, the earlier ones kept until the end: ext4 looks past the inodes
      # of files deleted in the last minutes for each file made (a line makes one per grain),
      # which cost the next command more system CPU than its own files
      out=$(mktemp -d "$tmp/out.XXXXXX")
      if [ "$label" = before ]; then
        command=(env PYTHONPATH="$tmp/before/python" "$PYTHON" -m tribo)
      else
        command=(env PYTHONPATH="$ROOT/python" "$PYTHON" -m tribo)
      fi
      # shellcheck disable=SC2086
      echo "$mode-$label $(cpu_of "${command[@]}" "$@" ${options[$mode]} --out "$out/out" \
        --no-progress --no-plot)" >> "$results"
    done
  done
}

modes_report() {
  "$PYTHON" - "$1" "$2" "$3" "${before:+$(git -C "$ROOT" rev-parse --short "$before")}" \
    "$(tree_label python src)" <<'PY'
import statistics
import sys

path, title, rounds, before, after = sys.argv[1:]
got, system = {}, {}
for line in open(path):
    name, value, *sys_part = line.split()
    got.setdefault(name, []).append(float(value))
    system.setdefault(name, []).append(float(sys_part[0]) if sys_part else 0.0)
median = {name: statistics.median(values) for name, values in got.items()}
median_system = {name: statistics.median(values) for name, values in system.items()}
core = median["core"]
print(f"{title}; the median of {rounds} round(s); the core alone: {core:.2f} s of CPU")
core2 = median.get("core-2")
if core2:  # the parallel modes against the same runs through the core on 2 processes at once
    print(f"the core split over 2 processes at once: {core2:.2f} s of CPU, {core2 / core:.2f}x "
          f"the core alone (in brackets: the parallel modes' CPU / this)")
print()
labels = (["before"] if before else []) + ["after"]
names = {"before": f"before ({before})", "after": f"this tree ({after})"}
print("| executor | " + " | ".join(f"{names[l]}: CPU [s] (the system's), / core" for l in labels)
      + " |")
print("|---|" + "---|" * len(labels))
for mode, text in (("serial", "in this process (--serial)"), ("threads", "2 threads (--workers 2)"),
                   ("processes", "2 worker processes (--workers 2 --processes)")):
    cells = [f"{median[f'{mode}-{l}']:.2f} ({median_system[f'{mode}-{l}']:.2f}), "
             f"{median[f'{mode}-{l}'] / core:.2f}x"
             + (f" [{median[f'{mode}-{l}'] / core2:.2f}x]" if core2 and mode != "serial" else "")
             for l in labels]
    print(f"| {text} | " + " | ".join(cells) + " |")
PY
}
