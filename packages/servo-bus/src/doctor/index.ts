/** The servo doctor: scan a bus (scan.ts), say what is wrong and how to fix it (findings.ts). */
export * from './scan.ts';
export * from './findings.ts';
export * from './emulated-link.ts';
