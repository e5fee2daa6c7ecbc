/**
 * What was dropped on the page (or chosen in the Import panel), as one .zip to send: a single
 * .zip as it is; a folder, several files or a lone .urdf packed into one (`packZip`), each file
 * under its path inside the drop. Folders are walked with the browser's entry API.
 */
import { packZip, type ZipEntry } from './packZip.ts';

const isZip = (f: File) => /\.zip$/i.test(f.name);

async function bytes(f: File): Promise<Uint8Array> {
  return new Uint8Array(await f.arrayBuffer());
}

/** Files chosen in an input (a folder input fills `webkitRelativePath`) → one zip. */
export async function zipOfFiles(files: readonly File[]): Promise<Uint8Array> {
  if (files.length === 1 && isZip(files[0]!)) return bytes(files[0]!);
  const entries: ZipEntry[] = [];
  for (const f of files)
    entries.push({ path: f.webkitRelativePath || f.name, data: await bytes(f) });
  return packZip(entries);
}

function readAll(reader: FileSystemDirectoryReader): Promise<FileSystemEntry[]> {
  return new Promise((resolve, reject) => {
    const out: FileSystemEntry[] = [];
    const next = () =>
      reader.readEntries((batch) => {
        if (batch.length === 0) return resolve(out);
        out.push(...batch);
        next();
      }, reject);
    next();
  });
}

async function walk(entry: FileSystemEntry, out: ZipEntry[]): Promise<void> {
  if (entry.isFile) {
    const file = await new Promise<File>((resolve, reject) =>
      (entry as FileSystemFileEntry).file(resolve, reject),
    );
    out.push({ path: entry.fullPath.replace(/^\//, ''), data: await bytes(file) });
  } else if (entry.isDirectory) {
    for (const e of await readAll((entry as FileSystemDirectoryEntry).createReader()))
      await walk(e, out);
  }
}

/** A drop → one zip; null when nothing usable was dropped. */
export async function zipOfDrop(dt: DataTransfer): Promise<Uint8Array | null> {
  const entries = [...dt.items]
    .map((i) => (i.kind === 'file' ? i.webkitGetAsEntry() : null))
    .filter((e): e is FileSystemEntry => e !== null);
  if (entries.length === 0) return dt.files.length ? zipOfFiles([...dt.files]) : null;
  if (entries.length === 1 && entries[0]!.isFile && /\.zip$/i.test(entries[0]!.name))
    return zipOfFiles([...dt.files]);
  const out: ZipEntry[] = [];
  for (const e of entries) await walk(e, out);
  return out.length ? packZip(out) : null;
}
