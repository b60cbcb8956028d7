#!/usr/bin/env bash
# Sourced (without arguments) by the benchmarks whose first option may be --before REV: sets
# `before` to REV (empty without the option) and shifts the option off the caller's own
# arguments, which a sourced file shares; before_package puts that revision's package where
# the benchmark runs it from.
before=""
if [ "${1:-}" = --before ]; then
  before=${2:?"--before needs a revision"}
  shift 2
fi

# before_package DIR: revision $before's package (python/tribo) under DIR/before/python, for
# PYTHONPATH; nothing without --before
before_package() {
  if [ -n "$before" ]; then
    mkdir -p "$1/before"
    git -C "$ROOT" archive "$before" python/tribo | tar -x -C "$1/before"
  fi
}

# before_program SOURCE OUT: the C benchmark SOURCE compiled against revision $before's core
# into OUT (bench_at_revision.sh); nothing without --before
before_program() {
  if [ -n "$before" ]; then
    # shellcheck source=bench_at_revision.sh
    . "$ROOT/scripts/bench_at_revision.sh"
    bench_at_revision "$before" "$1" "$2"
  fi
}

# tree_label [PATH...]: this checkout's revision, and ", modified" where PATH (default src)
# differs from it, as the benchmarks name the tree they measured
tree_label() {
  [ $# -gt 0 ] || set -- src
  echo "$(git -C "$ROOT" rev-parse --short HEAD)$(git -C "$ROOT" diff --quiet HEAD -- "$@" || echo ', modified')"
}
