#!/usr/bin/env bash
# Timings of the Python package quoted in docs/python.md and the README.
set -euo pipefail
cd "$(dirname "$0")/../.."
export CARGO_TARGET_DIR="$PWD/target"
echo "commit: $(git rev-parse --short HEAD)  date: $(date -u +%FT%TZ)  machine: $(nproc) cores (kind rust), shared with another build"
v=$(mktemp -d)/venv
python3 -m venv "$v"; "$v/bin/pip" install --quiet --upgrade pip
t0=$(date +%s.%N); "$v/bin/pip" install --quiet ./python; t1=$(date +%s.%N)
echo "pip install ./python, fresh venv, the crate changed since the last build (steplearn and the bindings rebuilt, dependencies built): $(python3 -c "print(round($t1-$t0,1))") s"
"$v/bin/pip" install --quiet pytest numpy river gymnasium
t0=$(date +%s.%N); "$v/bin/python" -m pytest -q python/tests 2>&1 | tail -1; t1=$(date +%s.%N)
echo "pytest python/tests: $(python3 -c "print(round($t1-$t0,1))") s"
t0=$(date +%s.%N); "$v/bin/python" -m pytest -q python/tests/test_gym.py 2>&1 | tail -1; t1=$(date +%s.%N)
echo "pytest python/tests/test_gym.py: $(python3 -c "print(round($t1-$t0,1))") s"
t0=$(date +%s.%N); bash python/ci.sh 2>&1 | tail -1; t1=$(date +%s.%N)
echo "bash python/ci.sh (its own fresh venv, nothing changed in the crate): $(python3 -c "print(round($t1-$t0,1))") s"
ls -l "$v"/lib/python3*/site-packages/steplearn/_steplearn*.so | awk '{print "installed module bytes:", $5}'
