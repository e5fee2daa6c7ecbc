/**
 * Import robot: a folded panel, and a drop target the size of the page. An operator drops a
 * robot folder or a .zip holding a URDF and its meshes anywhere on the page (or picks one here);
 * it is sent to `armtwin up`, imported as `armtwin robot import` does and written to the models
 * folder, served at once under /models/NAME/. The answer is shown: the robot's name and files,
 * warnings, or every reason it was refused (not a URDF, too big, a bad zip, a name taken).
 */
import { useEffect, useRef, useState, type InputHTMLAttributes } from 'react';
import { useLink, useSettings, useSession } from '../../hud/HudParts.ts';
import { useSampled } from '../../hud/useSampled.ts';
import { zipOfDrop, zipOfFiles } from './droppedFiles.ts';
import { sendImport, type ImportAnswer } from './sendImport.ts';
import './import.css';

/** A folder picker (`webkitdirectory` is not in React's input props). */
const FOLDER: InputHTMLAttributes<HTMLInputElement> = { webkitdirectory: '' } as never;

const hasFiles = (e: DragEvent) => e.dataTransfer?.types.includes('Files') ?? false;

export function ImportPanel() {
  const link = useLink();
  const settings = useSettings();
  const session = useSession();
  const allowed = useSampled(() => link.permissions.command);
  const details = useRef<HTMLDetailsElement>(null);
  const [name, setName] = useState('');
  const [urdf, setUrdf] = useState('');
  const [replace, setReplace] = useState(false);
  const [busy, setBusy] = useState(false);
  const [answer, setAnswer] = useState<ImportAnswer | null>(null);
  const options = useRef({ name, urdf, replace, settings });
  useEffect(() => {
    options.current = { name, urdf, replace, settings };
  });

  const send = async (zip: Promise<Uint8Array | null>) => {
    if (details.current) details.current.open = true;
    setBusy(true);
    setAnswer(null);
    try {
      const bytes = await zip;
      const o = options.current;
      setAnswer(
        bytes
          ? await sendImport(o.settings, bytes, {
              name: o.name.trim(),
              urdf: o.urdf.trim(),
              replace: o.replace,
            })
          : { ok: false, errors: ['nothing to import in what was dropped'] },
      );
    } catch (err) {
      setAnswer({ ok: false, errors: [`could not read the files: ${(err as Error).message}`] });
    } finally {
      setBusy(false);
    }
  };
  const sendRef = useRef(send);
  useEffect(() => {
    sendRef.current = send;
  });

  // The whole page is the drop target, for an operator.
  useEffect(() => {
    if (!allowed) return;
    const over = (e: DragEvent) => {
      if (!hasFiles(e)) return;
      e.preventDefault();
      if (e.dataTransfer) e.dataTransfer.dropEffect = 'copy';
    };
    const drop = (e: DragEvent) => {
      if (!hasFiles(e) || !e.dataTransfer) return;
      e.preventDefault();
      void sendRef.current(zipOfDrop(e.dataTransfer));
    };
    window.addEventListener('dragover', over);
    window.addEventListener('drop', drop);
    return () => {
      window.removeEventListener('dragover', over);
      window.removeEventListener('drop', drop);
    };
  }, [allowed]);

  const picked = (files: FileList | null) => {
    if (files?.length) void send(zipOfFiles([...files]));
  };

  return (
    <details className="panel import" ref={details} data-testid="import">
      <summary>
        <h2>Import robot</h2> <span className="dim">drop a robot folder or .zip on the page</span>
      </summary>
      {!allowed ? (
        <p className="note warn" role="status">
          {session.permissions?.reason || 'Importing a robot is for operators.'}
        </p>
      ) : (
        <div className="import-form">
          <label>
            .zip or files{' '}
            <input
              type="file"
              accept=".zip,.urdf,.stl,.obj,.dae"
              multiple
              disabled={busy}
              onChange={(e) => picked(e.currentTarget.files)}
            />
          </label>
          <label>
            a folder{' '}
            <input
              type="file"
              {...FOLDER}
              disabled={busy}
              onChange={(e) => picked(e.currentTarget.files)}
            />
          </label>
          <label>
            name{' '}
            <input
              type="text"
              value={name}
              placeholder="from the URDF"
              pattern="[a-z0-9_-]{1,32}"
              onChange={(e) => setName(e.currentTarget.value)}
            />
          </label>
          <label>
            which .urdf{' '}
            <input
              type="text"
              value={urdf}
              placeholder="the only one"
              onChange={(e) => setUrdf(e.currentTarget.value)}
            />
          </label>
          <label className="check">
            <input
              type="checkbox"
              checked={replace}
              onChange={(e) => setReplace(e.currentTarget.checked)}
            />
            replace a robot of that name
          </label>
        </div>
      )}
      {busy && <p role="status">Importing…</p>}
      {answer?.ok && (
        <div role="status" data-testid="import-result">
          <p>
            Imported <strong>{answer.name}</strong> ({answer.files} files): served at /models/
            {answer.name}/ now. Run an arm on it:{' '}
            <code>
              npx armtwin sim --profile {answer.name} --arm {answer.name.replace(/_/g, '-')}
            </code>
            , then pick it in the fleet list.
          </p>
          {answer.warnings.length + answer.notes.length > 0 && (
            <ul className="dim">
              {[...answer.warnings, ...answer.notes].map((w) => (
                <li key={w}>{w}</li>
              ))}
            </ul>
          )}
        </div>
      )}
      {answer && !answer.ok && (
        <div className="note error" role="alert" data-testid="import-error">
          Not imported:
          <ul>
            {answer.errors.map((e) => (
              <li key={e}>{e}</li>
            ))}
          </ul>
        </div>
      )}
    </details>
  );
}
