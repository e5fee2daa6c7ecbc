#!/usr/bin/env node
// The final summary of scripts/test.sh, computed from the steps it ran and their JSON reports.
//
//   node scripts/test-summary.mjs <steps.tsv> [elapsedSeconds]
//
// steps.tsv has one line per event: `name<TAB>status<TAB>report`, where status is `started`,
// `skipped:<reason>` or the step's exit code, and report is a Vitest JSON report, a
// Playwright JSON report or empty. The last line for a step wins. A step that failed without
// a failing test in its report (typecheck, build, a crash, an interrupt) counts as 1 failed.
// The very last line printed is exactly `N passed, N failed, N skipped` (CI reads it); the
// exit code is 1 if anything failed.
import fs from 'node:fs';

const [stepsFile = 'test-results/steps.tsv', elapsedArg] = process.argv.slice(2);

function readSteps(file) {
  const steps = new Map();
  if (!fs.existsSync(file)) return steps;
  for (const line of fs.readFileSync(file, 'utf8').split('\n')) {
    if (!line.trim()) continue;
    const [name, status = '', report = ''] = line.split('\t');
    steps.set(name, { name, status, report });
  }
  return steps;
}

/** Counts from a Vitest JSON report (Jest-compatible shape). */
function vitestCounts(r) {
  const failures = [];
  let brokenFiles = 0;
  for (const file of r.testResults ?? []) {
    const failed = (file.assertionResults ?? []).filter((a) => a.status === 'failed');
    for (const a of failed) failures.push(a.fullName);
    if (file.status === 'failed' && failed.length === 0) {
      brokenFiles++;
      failures.push(`${file.name}: ${String(file.message ?? '').split('\n')[0]}`);
    }
  }
  return {
    passed: r.numPassedTests ?? 0,
    failed: (r.numFailedTests ?? 0) + brokenFiles,
    skipped: (r.numPendingTests ?? 0) + (r.numTodoTests ?? 0),
    failures,
  };
}

/** Counts from a Playwright JSON report. */
function playwrightCounts(r) {
  const failures = [];
  const walk = (suite, path) => {
    for (const spec of suite.specs ?? []) {
      if (spec.ok === false) failures.push([...path, spec.title].join(' › '));
    }
    for (const child of suite.suites ?? []) walk(child, [...path, child.title]);
  };
  for (const suite of r.suites ?? []) walk(suite, [suite.title]);
  for (const error of r.errors ?? []) failures.push(String(error.message ?? error).split('\n')[0]);
  const s = r.stats ?? {};
  return {
    passed: (s.expected ?? 0) + (s.flaky ?? 0),
    failed: (s.unexpected ?? 0) + (r.errors ?? []).length,
    skipped: s.skipped ?? 0,
    failures,
  };
}

function countsOf(report) {
  if (!report || !fs.existsSync(report)) return undefined;
  try {
    const r = JSON.parse(fs.readFileSync(report, 'utf8'));
    return 'numTotalTests' in r ? vitestCounts(r) : playwrightCounts(r);
  } catch (err) {
    return {
      passed: 0,
      failed: 1,
      skipped: 0,
      failures: [`${report}: unreadable (${err.message})`],
    };
  }
}

const total = { passed: 0, failed: 0, skipped: 0 };
const failures = [];
const steps = readSteps(stepsFile);
console.log('\n──────── test summary ────────');
if (steps.size === 0) {
  total.failed = 1;
  failures.push(`no step ran (${stepsFile} is missing or empty)`);
}
for (const step of steps.values()) {
  const counts = countsOf(step.report);
  let line;
  if (step.status.startsWith('skipped')) {
    line = `skipped (${step.status.slice('skipped:'.length) || 'not applicable'})`;
  } else {
    const c = counts ?? { passed: 0, failed: 0, skipped: 0, failures: [] };
    const ok = step.status === '0';
    if (!ok && c.failed === 0) {
      c.failed = 1;
      const why = step.status === 'started' ? 'interrupted' : `exit code ${step.status}`;
      c.failures.push(`${why}${counts ? '' : ', no test report'}`);
    }
    total.passed += c.passed;
    total.failed += c.failed;
    total.skipped += c.skipped;
    failures.push(...c.failures.map((f) => `${step.name} › ${f}`));
    const tests = counts ? `: ${c.passed} passed, ${c.failed} failed, ${c.skipped} skipped` : '';
    line = `${ok ? 'ok' : 'FAILED'}${tests}`;
  }
  console.log(`${step.name.padEnd(14)} ${line}`);
}
if (failures.length) {
  console.log('\nfailed:');
  for (const f of failures.slice(0, 50)) console.log(`  ✗ ${f}`);
  if (failures.length > 50) console.log(`  … and ${failures.length - 50} more`);
}
if (elapsedArg !== undefined) {
  const s = Number(elapsedArg);
  console.log(`\nelapsed: ${Math.floor(s / 60)}m ${String(s % 60).padStart(2, '0')}s`);
}
console.log(`${total.passed} passed, ${total.failed} failed, ${total.skipped} skipped`);
process.exitCode = total.failed > 0 ? 1 : 0;
