#!/usr/bin/env bash
# Runs every test: `npm test`. Installs what is missing (scripts/install-deps.sh), typechecks, lints (ESLint),
# runs Vitest `unit` then `integration` (real Mosquitto and influxd), then, when the web app
# can be built and tests/e2e has specs, builds it and runs Playwright on the system Chromium.
# Always ends with a summary from the JSON reports in test-results/ (scripts/test-summary.mjs)
# whose last line is `N passed, N failed, N skipped`; exits non-zero if anything failed.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
RESULTS="$ROOT/test-results"
STEPS="$RESULTS/steps.tsv"
START=$(date +%s)
FAILED=0

mkdir -p "$RESULTS"
rm -f "$RESULTS"/vitest-*.json "$RESULTS"/e2e-*.json "$STEPS"

finish() {
  local rc=$?
  set +e
  trap - EXIT INT TERM
  # Stopped by something other than a recorded step: make the summary count it.
  if [ "$rc" -ne 0 ] && [ "$FAILED" -eq 0 ]; then printf 'test.sh\t%s\t\n' "$rc" >>"$STEPS"; fi
  node "$ROOT/scripts/test-summary.mjs" "$STEPS" "$(($(date +%s) - START))"
  local summary_rc=$?
  if [ "$rc" -eq 0 ] && { [ "$FAILED" -ne 0 ] || [ "$summary_rc" -ne 0 ]; }; then rc=1; fi
  exit "$rc"
}
trap finish EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# step <name> <json report or ''> <command…>: runs it, records its exit code, carries on.
step() {
  local name=$1 report=$2 rc=0
  shift 2
  printf '\n=== %s: %s\n' "$name" "$*"
  printf '%s\tstarted\t%s\n' "$name" "$report" >>"$STEPS"
  "$@" || rc=$?
  printf '%s\t%s\t%s\n' "$name" "$rc" "$report" >>"$STEPS"
  if [ "$rc" -ne 0 ]; then FAILED=1; fi
  return "$rc"
}
skip() { printf '%s\tskipped:%s\t\n' "$1" "$2" >>"$STEPS"; }

# vitest_project <project filter> [report name]
vitest_project() {
  npx vitest run --project "$1" --passWithNoTests \
    --reporter=default --reporter=json --outputFile.json="$RESULTS/vitest-${2:-$1}.json"
}

step install '' bash "$ROOT/scripts/install-deps.sh" || exit 1

step typecheck '' npx tsc -p tsconfig.json || true
if [ -f apps/web/tsconfig.json ]; then
  step typecheck-web '' npx tsc -p apps/web/tsconfig.json || true
fi
if [ -f bench/tsconfig.json ]; then
  step typecheck-bench '' npx tsc -p bench || true
fi
step lint '' npx eslint . || true

step unit "$RESULTS/vitest-unit.json" vitest_project unit || true
step integration "$RESULTS/vitest-integration.json" vitest_project 'integration*' integration || true

has_build=$(node -e "try{const p=require('./apps/web/package.json');process.stdout.write(p.scripts&&p.scripts.build?'yes':'no')}catch{process.stdout.write('no')}")
has_specs=''
if [ -d tests/e2e ]; then
  has_specs=$(find tests/e2e -type f \( -name '*.spec.*' -o -name '*.test.*' \) | head -n 1 || true)
fi
if [ "$has_build" != yes ]; then
  skip e2e 'apps/web has no build script'
elif [ -z "$has_specs" ]; then
  skip e2e 'no specs in tests/e2e'
elif step build-web '' npm run build -w @armtwin/web; then
  # Two at a time, then the specs that must run alone (playwright.config.ts says which).
  step e2e "$RESULTS/e2e-results.json" npx playwright test --project shared || true
  E2E_REPORT="$RESULTS/e2e-alone-results.json" \
    step e2e-alone "$RESULTS/e2e-alone-results.json" npx playwright test --project alone || true
else
  skip e2e 'web build failed'
fi
