#!/usr/bin/env bash
# Installs what the tests need, only when it is missing; idempotent, never asks.
#   - Debian packages: mosquitto, mosquitto-clients, chromium, socat (and golang-go if no Go)
#   - influxd 1.8.10, built with `go install` into .tools/bin (git-ignored)
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
if [ "${#missing[@]}" -eq 0 ]; then
  say "apt packages: present (mosquitto, mosquitto-clients, chromium, socat)"
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
INFLUXD="$ROOT/.tools/bin/influxd"
if [ -x "$INFLUXD" ]; then
  say "influxd: present ($INFLUXD)"
else
  if ! command -v go >/dev/null; then
    say "influxd: installing golang-go"
    apt_install golang-go ca-certificates
  fi
  say "influxd: building v1.8.10 with $(go version | cut -d' ' -f3) (several minutes)"
  mkdir -p "$ROOT/.tools/bin"
  tmp="$(mktemp -d)"
  # Build outside the repo so go never reads or writes our files.
  (cd "$tmp" && GOBIN="$ROOT/.tools/bin" GOFLAGS="-mod=mod -buildvcs=false" GO111MODULE=on \
    go install github.com/influxdata/influxdb/cmd/influxd@v1.8.10)
  rm -rf "$tmp"
  say "influxd: built $INFLUXD"
fi

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
