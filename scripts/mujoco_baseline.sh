#!/usr/bin/env bash
# Issue 16's yardstick, in one sitting: the bare-physics real-time factor of a MuJoCo biped
# built like steplearn's humanoid (scripts/mujoco_baseline.py), then steplearn's Capture Step
# walker stepping in place (the probe `walk`), both on one core for SECONDS simulated seconds.
#
#   bash scripts/mujoco_baseline.sh [SECONDS]
#
# MuJoCo comes from PyPI into a virtual environment (MUJOCO_VENV, default target/mujoco-venv).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-120}"
venv="${MUJOCO_VENV:-target/mujoco-venv}"
if ! "$venv/bin/python" -c "import mujoco" 2>/dev/null; then
    echo "installing mujoco 4.0.0 into $venv" >&2
    python3 -m venv "$venv"
    "$venv/bin/pip" install --quiet "mujoco==4.0.0"
fi
cargo build --release --quiet -p steplearn-probes --bin walk
mujoco_line=$("$venv/bin/python" scripts/mujoco_baseline.py --seconds "$seconds" | tee /dev/stderr | tail -1)
walk_line=$(./target/release/walk --seconds "$seconds" | grep "real time" | head -1)
echo "steplearn walker: $walk_line" >&2
mujoco_x=$(sed -E 's/.*: ([0-9.]+)x real time/\1/' <<<"$mujoco_line")
walk_x=$(sed -E 's/.*, ([0-9.]+)x real time/\1/' <<<"$walk_line")
python3 -c "m, w = $mujoco_x, $walk_x; print(f'walker {w:.1f}x, MuJoCo bare physics {m:.0f}x: walker / MuJoCo = {w / m:.2f} (goal 0.50)')"
