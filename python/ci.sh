#!/usr/bin/env bash
# Python package check: a fresh venv, `pip install ./python` from the repository root, pytest.
# Called from .ci/run; run from anywhere. Uses $CARGO_TARGET_DIR, or the repository's target/,
# so the Rust build is shared with the other jobs.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-$root/target}
venv=$(mktemp -d)/venv
trap 'rm -rf "$(dirname "$venv")"' EXIT
python3 -m venv "$venv"
"$venv/bin/pip" install --quiet --upgrade pip
"$venv/bin/pip" install --quiet ./python
"$venv/bin/pip" install --quiet pytest numpy river gymnasium
"$venv/bin/python" -m pytest -q python/tests
