#!/usr/bin/env bash
# Makes .tools/bin/nats-server (NATS 2.14.9) available for the cluster tests
# (tests/integration/cluster-*.test.ts, docs/cluster.md): built once per machine with
# `go install` into a cache outside the clone (ARMTWIN_CACHE, default ~/.cache/armtwin), then
# linked into the git-ignored .tools/bin. Debian's nats-server (2.9.10) is too old: MQTT over
# WebSockets, which the page needs, came in NATS 2.10, and so did many fixes to MQTT's
# JetStream-replicated sessions and retained messages in a cluster.
# Used by scripts/install-deps.sh. Exits 3 when Go is missing (the caller decides what to do).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="$PATH:/usr/local/go/bin"
VERSION=v2.14.9
NATS="$ROOT/.tools/bin/nats-server"
CACHE_DIR="${ARMTWIN_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/armtwin}/nats-server-$VERSION"

say() { printf 'build-nats: %s\n' "$*"; }

if [ -x "$NATS" ] && [ "$(readlink -f "$NATS")" = "$(readlink -f "$CACHE_DIR/nats-server")" ]; then
  say "present ($NATS)"
  exit 0
fi
if [ ! -x "$CACHE_DIR/nats-server" ]; then
  if ! command -v go >/dev/null; then
    say "Go is not on PATH, so nats-server cannot be built"
    exit 3
  fi
  say "building $VERSION with $(go version | cut -d' ' -f3) into $CACHE_DIR (minutes, once)"
  mkdir -p "$CACHE_DIR"
  tmp="$(mktemp -d)"
  trap 'rm -rf "$tmp"' EXIT
  # Build outside the repo so go never reads or writes our files.
  (cd "$tmp" && GOBIN="$CACHE_DIR" GOFLAGS="-mod=mod -buildvcs=false" GO111MODULE=on \
    go install "github.com/nats-io/nats-server/v2@$VERSION")
fi
mkdir -p "$ROOT/.tools/bin"
ln -sf "$CACHE_DIR/nats-server" "$NATS"
say "$NATS -> $CACHE_DIR/nats-server ($("$NATS" --version))"
