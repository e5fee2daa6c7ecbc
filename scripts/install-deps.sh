#!/usr/bin/env bash
# Installs what the tests need, only when it is missing; idempotent, never asks.
#   - Debian packages: mosquitto, mosquitto-clients, chromium, socat, ffmpeg (and golang-go if no Go)
#   - influxd 1.8.10 (scripts/build-influxd.sh: built once per machine, linked into .tools/bin)
#   - influxd 2.7.11 (scripts/build-influxd2.sh: Go + Rust's cargo, built once, .tools/bin/influxd2)
#   - nats-server 2.14.9 (scripts/build-nats.sh: built once per machine, linked into .tools/bin)
#   - a Python venv with the servo vendors' SDKs (dynamixel-sdk, feetech-servo-sdk), cached outside the clone
#   - a Python 3.11 venv with ROS 2 Kilted's rclpy and FastDDS (scripts/install-ros2.sh), cached likewise
#   - node_modules (`npm ci`) when missing or older than package-lock.json
# Tests never use port 1883; the system Mosquitto service that the Debian package starts is
# stopped and disabled right after installing it anyway.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
export PATH="$PATH:/usr/sbin:/sbin:/usr/local/go/bin"
export DEBIAN_FRONTEND=noninteractive

say() { printf 'install-deps: %s\n' "$*"; }

SUDO=()
if [ "$(id -u)" -ne 0 ]; then SUDO=(sudo -n); fi

APT_UPDATED=0
apt_install() {
  if [ "$APT_UPDATED" -eq 0 ]; then
    "${SUDO[@]}" apt-get update -qq
    APT_UPDATED=1
  fi
  "${SUDO[@]}" apt-get install -y -qq "$@" >/dev/null
}

# --- Debian packages -------------------------------------------------------------------
missing=()
command -v mosquitto >/dev/null || missing+=(mosquitto)
command -v mosquitto_pub >/dev/null || missing+=(mosquitto-clients)
[ -x /usr/bin/chromium ] || missing+=(chromium)
command -v socat >/dev/null || missing+=(socat)
command -v ffmpeg >/dev/null || missing+=(ffmpeg)
if [ "${#missing[@]}" -eq 0 ]; then
  say "apt packages: present (mosquitto, mosquitto-clients, chromium, socat, ffmpeg)"
else
  say "apt packages: installing ${missing[*]}"
  apt_install "${missing[@]}"
  if [[ " ${missing[*]} " == *" mosquitto "* ]]; then
    # The package may start a system broker on 1883; our tests do not want it.
    if command -v systemctl >/dev/null && [ -d /run/systemd/system ]; then
      "${SUDO[@]}" systemctl disable --now mosquitto >/dev/null 2>&1 || true
    elif command -v service >/dev/null; then
      "${SUDO[@]}" service mosquitto stop >/dev/null 2>&1 || true
    fi
    say "apt packages: system mosquitto service stopped (tests use their own brokers)"
  fi
fi

# --- influxd 1.8.10 --------------------------------------------------------------------
# Built once per machine into a cache outside the clone, linked into .tools/bin.
if ! bash "$ROOT/scripts/build-influxd.sh"; then
  say "influxd: installing golang-go"
  apt_install golang-go ca-certificates
  bash "$ROOT/scripts/build-influxd.sh"
fi

# --- influxd 2.7.11 --------------------------------------------------------------------
# The storage tests run against 1.8 and 2.7. 2.7's Flux engine is Rust, so cargo is needed too.
# Built and tested here with rustup's stable 1.95; Debian's cargo, installed when there is no
# cargo at all, is the fall-back (not tried on this machine, which has rustup).
if ! bash "$ROOT/scripts/build-influxd2.sh"; then
  say "influxd 2.7: installing cargo (Rust) for its Flux engine"
  apt_install cargo
  bash "$ROOT/scripts/build-influxd2.sh"
fi

# --- nats-server 2.14.9 ------------------------------------------------------------------
# The cluster tests (tests/integration/cluster-*.test.ts, docs/cluster.md) run a 3-node NATS
# cluster. Debian's nats-server (2.9.10) lacks MQTT over WebSockets (NATS 2.10), so it is built
# with Go (installed above when missing), once per machine, like influxd.
bash "$ROOT/scripts/build-nats.sh"

# --- Python venv for the servo-bus SDK tests -------------------------------------------
# tests/integration/servo-bus-sdk.test.ts drives the emulated servo buses with the vendors'
# own Python SDKs: ROBOTIS `dynamixel-sdk` and Feetech `feetech-servo-sdk` (both need only
# pyserial). They live in a venv cached outside the clone, like influxd; a stamp file holds
# the pinned requirements, so a changed pin rebuilds the venv and an unchanged one is kept.
# tests/helpers/servo-sdk-python.ts finds it at the same path. The same venv holds `rtb-data`
# (Robotics Toolbox's robot descriptions: URDFs with STL and DAE meshes), whose third-party
# robots tests/integration/robot-import.test.ts imports as a user would, `example-robot-data`
# (its xacro-generated ROS 2 descriptions keep their `<ros2_control>` and `<transmission>` blocks:
# tests/integration/robot-import-ros2.test.ts), and Foxglove's `mcap` reader, which checks the
# files `armtwin export` writes (tests/integration/export-mcap.test.ts).
PYENV_DIR="${ARMTWIN_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/armtwin}/pyenv"
PYENV_REQS="dynamixel-sdk==4.1.0 feetech-servo-sdk==1.0.0 pyserial==3.5 rtb-data==2.0.0 mcap==1.6.0 example-robot-data==6.0.0"
PYENV_STAMP="$PYENV_DIR/.armtwin-requirements"
# example-robot-data is a cmeel wheel: data under site-packages/cmeel.prefix, no module to import.
PYENV_CHECK='import dynamixel_sdk, scservo_sdk, serial, rtbdata, mcap.reader, os, sysconfig
assert os.path.isdir(os.path.join(sysconfig.get_paths()["purelib"], "cmeel.prefix/share/example-robot-data/robots"))'
if [ -x "$PYENV_DIR/bin/python" ] && [ "$(cat "$PYENV_STAMP" 2>/dev/null)" = "$PYENV_REQS" ] \
  && "$PYENV_DIR/bin/python" -c "$PYENV_CHECK" 2>/dev/null; then
  say "python venv: present ($PYENV_DIR: $PYENV_REQS)"
else
  if ! command -v python3 >/dev/null; then
    say "python venv: installing python3, python3-venv"
    apt_install python3 python3-venv
  elif ! python3 -c 'import ensurepip, venv' 2>/dev/null; then
    say "python venv: installing python3-venv"
    apt_install python3-venv
  fi
  say "python venv: creating $PYENV_DIR with $PYENV_REQS"
  rm -rf "$PYENV_DIR"
  mkdir -p "$(dirname "$PYENV_DIR")"
  python3 -m venv "$PYENV_DIR"
  "$PYENV_DIR/bin/python" -m pip install --quiet --disable-pip-version-check --no-input $PYENV_REQS
  "$PYENV_DIR/bin/python" -c "$PYENV_CHECK"
  printf '%s\n' "$PYENV_REQS" >"$PYENV_STAMP"
  say "python venv: ready ($PYENV_DIR)"
fi

# --- Python 3.12 venv for the SO-101 / LeRobot tests --------------------------------------
# lerobot 0.6.1 (with its torch), example-robot-data (the SO-100/SO-101 descriptions) and yourdfpy
# (an independent FK), cached beside the venv above: scripts/pyenv-lerobot.sh says what and why.
bash "$ROOT/scripts/pyenv-lerobot.sh"

# --- ROS 2 (rclpy + FastDDS wheels) ---------------------------------------------------
# `armtwin ros2` and tests/integration/ros2-*.test.ts run a Python rclpy process from this venv.
bash "$ROOT/scripts/install-ros2.sh"

# --- Python venv for the Foxglove tests ------------------------------------------------
# foxglove-sdk 0.30.3 and websockets: tests/integration/foxglove-*.test.ts's foxglove.sdk.v1
# client (scripts/pyenv-foxglove.sh says why a websockets client).
bash "$ROOT/scripts/pyenv-foxglove.sh"

# --- node_modules ----------------------------------------------------------------------
if [ ! -d node_modules ] || [ ! -f node_modules/.package-lock.json ] \
  || [ package-lock.json -nt node_modules/.package-lock.json ]; then
  say "node_modules: npm ci"
  if command -v flock >/dev/null; then
    flock /tmp/armtwin-npm.lock npm ci --no-audit --no-fund --loglevel=error
  else
    npm ci --no-audit --no-fund --loglevel=error
  fi
else
  say "node_modules: up to date"
fi
