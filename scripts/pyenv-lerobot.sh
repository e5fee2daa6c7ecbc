#!/usr/bin/env bash
# The Python 3.12 venv of the SO-101/LeRobot tests, cached outside the clone beside the servo-SDK
# venv (install-deps.sh calls this; idempotent: a stamp file holds the pinned requirements):
#   - lerobot[feetech] 0.6.1 (needs Python >= 3.12; its real torch): its FeetechMotorsBus and its
#     calibration files (MotorCalibration) are what tests/integration/lerobot-*.test.ts run
#   - example-robot-data 6.0.0: the SO-100/SO-101 descriptions public/models/so100, so101 come from
#   - yourdfpy 0.0.60: an FK that is not armtwin's, to check the shipped SO-101 against
#   - lerobot's dataset extra: lerobot-record's LeRobotDataset (tests/integration/lerobot-plugin.test.ts)
#   - paho-mqtt 2.1.0 and armtwin's own LeRobot robot plugin, packages/lerobot/python
#     (lerobot_robot_armtwin), installed as a copy (not editable: the venv is shared by every
#     clone); the stamp holds a hash of its sources, so a changed plugin is reinstalled
set -euo pipefail
say() { printf 'install-deps: %s\n' "$*"; }
CACHE="${ARMTWIN_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/armtwin}"
VENV="$CACHE/pyenv-lerobot"
REQS="lerobot[feetech,dataset]==0.6.1 example-robot-data==6.0.0 yourdfpy==0.0.60 paho-mqtt==2.1.0"
PLUGIN="$(cd "$(dirname "$0")/../packages/lerobot/python" && pwd)"
PLUGIN_HASH="$(cd "$PLUGIN" && find pyproject.toml lerobot_robot_armtwin -name '*.py' -o -name '*.toml' | LC_ALL=C sort | xargs sha256sum | sha256sum | cut -c1-16)"
STAMP="$VENV/.armtwin-requirements"
# example-robot-data has no Python module: its robots are files under site-packages/cmeel.prefix.
ROBOTS='cmeel.prefix/share/example-robot-data/robots'
CHECK="import os, sysconfig, lerobot, scservo_sdk, yourdfpy, datasets, paho.mqtt, lerobot_robot_armtwin; assert os.path.isdir(os.path.join(sysconfig.get_paths()['purelib'], '$ROBOTS', 'so_arm_description'))"
if [ -x "$VENV/bin/python" ] && [ "$(cat "$STAMP" 2>/dev/null)" = "$REQS plugin:$PLUGIN_HASH" ] \
  && "$VENV/bin/python" -c "$CHECK" 2>/dev/null; then
  say "lerobot venv: present ($VENV: $REQS)"
  exit 0
fi
PY=""
for c in python3.12 python3.13 "$HOME/.pyenv/versions/3.12.1/bin/python3.12"; do
  if command -v "$c" >/dev/null 2>&1 && "$c" -c 'import sys, venv; assert sys.version_info >= (3, 12)' 2>/dev/null; then
    PY="$c"; break
  fi
done
if [ -z "$PY" ]; then
  for d in "$HOME"/.pyenv/versions/3.1[2-9]*/bin; do
    if [ -x "$d/python3" ]; then PY="$d/python3"; break; fi
  done
fi
if [ -z "$PY" ]; then
  say "lerobot venv: no Python >= 3.12 (lerobot needs it): install one (pyenv install 3.12) and rerun"
  exit 1
fi
if [ -x "$VENV/bin/python" ] && "$VENV/bin/python" -c 'import sys; assert sys.version_info >= (3, 12)' 2>/dev/null; then
  say "lerobot venv: updating $VENV to $REQS"
else
  say "lerobot venv: creating $VENV with $PY: $REQS (torch included: a few minutes)"
  rm -rf "$VENV"
  mkdir -p "$CACHE"
  "$PY" -m venv "$VENV"
fi
"$VENV/bin/python" -m pip install --quiet --disable-pip-version-check --no-input $REQS
# A copy of the plugin, reinstalled over any older one; its build files stay out of the clone.
BUILD="$(mktemp -d)"
cp -r "$PLUGIN/pyproject.toml" "$PLUGIN/lerobot_robot_armtwin" "$BUILD/"
"$VENV/bin/python" -m pip install --quiet --disable-pip-version-check --no-input --force-reinstall --no-deps "$BUILD"
rm -rf "$BUILD"
"$VENV/bin/python" -c "$CHECK"
printf '%s\n' "$REQS plugin:$PLUGIN_HASH" >"$STAMP"
say "lerobot venv: ready ($VENV)"
