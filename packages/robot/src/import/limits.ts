/** The largest robot a page may send `armtwin up` to import, bytes (the .zip as sent). */
export const MAX_IMPORT_BYTES = 100 * 1024 * 1024;
