#!/usr/bin/env bash
# Makes .tools/bin/influxd2 (InfluxDB 2.7.11, no UI assets) available: built once per machine into
# a cache outside the clone (ARMTWIN_CACHE, default ~/.cache/armtwin), then linked into the
# git-ignored .tools/bin. The recipe is the one ../shared/influxdb2.md found by trying:
#  1. `go install` refuses the module (its go.mod has a `replace`), so the module is downloaded,
#     copied out of the module cache and built with `go build ./cmd/influxd` inside it;
#  2. its Flux engine links libflux through pkg-config: influxdata's pkg-config wrapper, first on
#     PATH, builds it with cargo from the crates registry;
#  3. the flux sources pin Rust 1.68, which cannot be fetched here: RUSTUP_TOOLCHAIN=stable;
#  4. newer rustc lints break flux-core (`deny(warnings)`), and RUSTFLAGS does not reach its host
#     build, so a RUSTC_WRAPPER appends `--cap-lints warn` to every rustc call.
# Exits 3 when Go or cargo is missing (the caller decides what to do).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="$PATH:/usr/local/go/bin:$HOME/.cargo/bin"
VERSION=2.7.11
PKG_CONFIG_VERSION=0.2.7
CACHE_DIR="${ARMTWIN_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/armtwin}/influxd-$VERSION"
INFLUXD2="$ROOT/.tools/bin/influxd2"

say() { printf 'build-influxd2: %s\n' "$*"; }

# A build without the release's version would answer `X-Influxdb-Version: dev`: rebuild it.
if [ -x "$CACHE_DIR/influxd" ] && ! "$CACHE_DIR/influxd" version 2>/dev/null | grep -q "v$VERSION"; then
  rm -f "$CACHE_DIR/influxd"
fi
if [ -x "$INFLUXD2" ] && [ -x "$CACHE_DIR/influxd" ]; then
  say "present ($INFLUXD2)"
  exit 0
fi
if [ ! -x "$CACHE_DIR/influxd" ]; then
  for tool in go cargo; do
    if ! command -v "$tool" >/dev/null; then
      say "$tool is not on PATH, so InfluxDB $VERSION cannot be built"
      exit 3
    fi
  done
  say "building v$VERSION into $CACHE_DIR (Go $(go version | cut -d' ' -f3), $(cargo --version | cut -d' ' -f2); long the first time, once)"
  mkdir -p "$CACHE_DIR"
  tmp="$(mktemp -d)"
  trap 'chmod -R u+w "$tmp" 2>/dev/null; rm -rf "$tmp"' EXIT
  GOBIN="$tmp/bin" go install "github.com/influxdata/pkg-config@v$PKG_CONFIG_VERSION"
  dir="$(cd "$tmp" && go mod download -json "github.com/influxdata/influxdb/v2@v$VERSION" |
    sed -n 's/^[[:space:]]*"Dir": "\(.*\)",$/\1/p')"
  [ -d "$dir" ] || { say "go mod download gave no module directory"; exit 1; }
  cp -r "$dir" "$tmp/src"
  chmod -R u+w "$tmp/src"
  cat >"$tmp/bin/rustc-cap-lints" <<'WRAP'
#!/usr/bin/env bash
# RUSTC_WRAPPER: $1 is rustc; every call gets --cap-lints warn unless it has its own.
rustc="$1"; shift
for a in "$@"; do case "$a" in --cap-lints*) exec "$rustc" "$@";; esac; done
exec "$rustc" "$@" --cap-lints warn
WRAP
  chmod +x "$tmp/bin/rustc-cap-lints"
  (cd "$tmp/src" && PATH="$tmp/bin:$PATH" RUSTUP_TOOLCHAIN=stable \
    RUSTC_WRAPPER="$tmp/bin/rustc-cap-lints" GOFLAGS="-buildvcs=false" \
    go build -ldflags "-X main.version=v$VERSION -X main.commit=armtwin-build" \
      -o "$CACHE_DIR/influxd.partial" ./cmd/influxd)
  mv "$CACHE_DIR/influxd.partial" "$CACHE_DIR/influxd"
fi
mkdir -p "$ROOT/.tools/bin"
ln -sf "$CACHE_DIR/influxd" "$INFLUXD2"
say "$INFLUXD2 -> $CACHE_DIR/influxd ($("$CACHE_DIR/influxd" version 2>/dev/null | head -1))"
