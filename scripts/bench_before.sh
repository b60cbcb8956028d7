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
