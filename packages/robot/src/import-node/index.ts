/** Robot import's edge on disk (Node only): sources (.urdf, folder, .zip) and writing the folder. */
export { importSource, zipSource } from './source.ts';
export { MAX_ZIP_BYTES, readZip } from './zip.ts';
export { RobotExistsError, writeRobotFolder } from './write-folder.ts';
