#!/usr/bin/env bash
# Installs the third-party robot descriptions that the URDF loader's tests and
# examples may use, into <repo>/.robots/ (ignored by git), and prints the
# absolute path of Talos' talos_reduced_box.urdf.
#
#   example-robot-data 6.0.0 (PyPI wheel, Apache-2.0, by the Gepetto team,
#   https://github.com/Gepetto/example-robot-data) ships Talos (PAL Robotics).
#
# Idempotent: a second run downloads nothing. Runs from any directory.
# pip's own environment variables apply (e.g. PIP_FIND_LINKS, PIP_NO_INDEX
# for an offline copy of the wheel).
set -euo pipefail

VERSION="6.0.0"
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
TARGET="$REPO/.robots/pip"
SHARE="$TARGET/cmeel.prefix/share/example-robot-data"
TALOS="$SHARE/robots/talos_data/robots/talos_reduced_box.urdf"
STAMP="$TARGET/example_robot_data-$VERSION.dist-info"

if [[ -d "$STAMP" && -f "$TALOS" ]]; then
    echo "example-robot-data $VERSION already in $TARGET" >&2
else
    if [[ -e "$TARGET" ]]; then
        # Another version, or a broken install: start again.
        echo "removing incomplete or other-version install in $TARGET" >&2
        rm -rf "$TARGET"
    fi
    mkdir -p "$REPO/.robots"
    echo "installing example-robot-data==$VERSION into $TARGET (about 131 MB)" >&2
    python3 -m pip install --disable-pip-version-check --no-deps \
        --target "$TARGET" "example-robot-data==$VERSION" >&2
    if [[ ! -f "$TALOS" ]]; then
        echo "error: $TALOS not found after installing" >&2
        exit 1
    fi
fi

echo "$TALOS"
