/** Episodes: marked time ranges of an arm's history with a task (./marks.ts), kept in InfluxDB (./store.ts). */
export * from './marks.ts';
export { episodeStore, readMarks } from './store.ts';
