#!/usr/bin/env bash
# Makes .tools/bin/influxd (InfluxDB 1.8.10) available: built once per machine with
# `go install` into a cache outside the clone (ARMTWIN_CACHE, default ~/.cache/armtwin), since
# the build takes minutes on two cores, then linked into the git-ignored .tools/bin.
# Used by scripts/install-deps.sh (npm test) and by `npm start` (apps/middleware/src/local-influx.ts).
# Exits 3 when Go is missing (the caller decides whether to install it).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="$PATH:/usr/local/go/bin"
INFLUXD="$ROOT/.tools/bin/influxd"
CACHE_DIR="${ARMTWIN_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/armtwin}/influxd-1.8.10"

say() { printf 'build-influxd: %s\n' "$*"; }

if [ -x "$INFLUXD" ]; then
  say "present ($INFLUXD)"
  exit 0
fi
if [ ! -x "$CACHE_DIR/influxd" ]; then
  if ! command -v go >/dev/null; then
    say "Go is not on PATH, so influxd cannot be built"
    exit 3
  fi
  say "building v1.8.10 with $(go version | cut -d' ' -f3) into $CACHE_DIR (several minutes, once)"
  mkdir -p "$CACHE_DIR"
  tmp="$(mktemp -d)"
  trap 'rm -rf "$tmp"' EXIT
  # Build outside the repo so go never reads or writes our files.
  (cd "$tmp" && GOBIN="$CACHE_DIR" GOFLAGS="-mod=mod -buildvcs=false" GO111MODULE=on \
    go install github.com/influxdata/influxdb/cmd/influxd@v1.8.10)
fi
mkdir -p "$ROOT/.tools/bin"
ln -sf "$CACHE_DIR/influxd" "$INFLUXD"
say "$INFLUXD -> $CACHE_DIR/influxd"
