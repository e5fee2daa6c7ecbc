#!/usr/bin/env bash
# Makes .tools/bin/telegraf (Telegraf 1.37.2 with only the plugins the benchmark uses) available:
# built once per machine from its Go module into ARMTWIN_CACHE (default ~/.cache/armtwin), then
# linked into the git-ignored .tools/bin. For `npm run bench -- --only telegraf`; not for tests.
# A full build fails here: the checksum database has no entry for some plugins' modules
# (404 for github.com/tdrn-org/go-tr064, github.com/SAP/go-hdb); the custom build needs none of them.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="$PATH:/usr/local/go/bin"
VERSION=1.37.2
# grok parses single frames; value + starlark split a 6-servo group into one metric per servo.
TAGS="custom,inputs.mqtt_consumer,outputs.influxdb,outputs.influxdb_v2,parsers.grok,parsers.value,processors.starlark"
# The plugin set is part of the cache key: another set is another build.
CACHE_DIR="${ARMTWIN_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/armtwin}/telegraf-$VERSION-$(printf '%s' "$TAGS" | sha256sum | cut -c1-8)"
TELEGRAF="$ROOT/.tools/bin/telegraf"

say() { printf 'build-telegraf: %s\n' "$*"; }

if [ ! -x "$CACHE_DIR/telegraf" ]; then
  command -v go >/dev/null || { say "Go is not on PATH"; exit 3; }
  say "building v$VERSION ($TAGS) into $CACHE_DIR"
  tmp="$(mktemp -d)"
  trap 'rm -rf "$tmp"' EXIT
  (cd "$tmp" && GOBIN="$CACHE_DIR" go install -tags "$TAGS" \
    "github.com/influxdata/telegraf/cmd/telegraf@v$VERSION")
fi
mkdir -p "$ROOT/.tools/bin"
ln -sf "$CACHE_DIR/telegraf" "$TELEGRAF"
say "$TELEGRAF -> $CACHE_DIR/telegraf"
