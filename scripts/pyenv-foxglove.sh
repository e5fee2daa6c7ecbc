#!/usr/bin/env bash
# The Python venv of the Foxglove tests (tests/integration/foxglove-*.test.ts), cached outside the
# clone beside the others (install-deps.sh calls this; idempotent: a stamp file holds the pins):
#   - foxglove-sdk 0.30.3: Foxglove's own Python SDK, whose server speaks foxglove.sdk.v1. It has
#     no WebSocket client (its `foxglove.websocket.Client` is a server's view of a connected
#     client), so the tests' sdk.v1 client is written on:
#   - websockets 17.4: the WebSocket library, speaking foxglove.sdk.v1 from Python
#     (tests/helpers/foxglove/sdk_client.py)
set -euo pipefail
say() { printf 'install-deps: %s\n' "$*"; }
CACHE="${ARMTWIN_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/armtwin}"
VENV="$CACHE/pyenv-foxglove"
REQS="foxglove-sdk==0.30.3 websockets==17.4"
STAMP="$VENV/.armtwin-requirements"
CHECK="import foxglove, websockets"
if [ -x "$VENV/bin/python" ] && [ "$(cat "$STAMP" 2>/dev/null)" = "$REQS" ] \
  && "$VENV/bin/python" -c "$CHECK" 2>/dev/null; then
  say "foxglove venv: present ($VENV: $REQS)"
  exit 0
fi
PY=""
for c in python3.12 python3.13 python3.11 python3.10 python3; do
  if command -v "$c" >/dev/null 2>&1 && "$c" -c 'import sys, venv; assert sys.version_info >= (3, 10)' 2>/dev/null; then
    PY="$c"; break
  fi
done
if [ -z "$PY" ]; then
  say "foxglove venv: no Python >= 3.10 with venv: install one and rerun"
  exit 1
fi
say "foxglove venv: creating $VENV with $PY: $REQS"
rm -rf "$VENV"
mkdir -p "$CACHE"
"$PY" -m venv "$VENV"
"$VENV/bin/python" -m pip install --quiet --disable-pip-version-check --no-input $REQS
"$VENV/bin/python" -c "$CHECK"
printf '%s\n' "$REQS" >"$STAMP"
say "foxglove venv: ready ($VENV)"
