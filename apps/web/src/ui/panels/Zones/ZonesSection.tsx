/**
 * Keep-out zones of the active robot, a folded section of the Ghost panel (the ghost is where a
 * refused target shows its offending link red): the zones its profile declares, each with a
 * Remove button, and a form to add a box, a vertical cylinder or a plane (mm, the arm's base
 * frame). Saving writes the robot's profile.json through `armtwin up` (saveKeepOut.ts); the
 * arm's controller takes the zones from there and announces them, and this page draws and
 * checks them from that announcement: one source of truth (docs/protocol.md, "Keep-out zones").
 */
import { useState } from 'react';
import { ZONE_SHAPES, type Zone, type ZoneShape } from '@armtwin/robot';
import { useRobots, useSettings, useLink } from '../../hud/HudParts.ts';
import { saveKeepOut } from '../../../core/zones/saveKeepOut.ts';
import { describeZone, SHAPE_FIELDS, zoneFromFields } from '../../../core/zones/zoneFields.ts';
import './zones.css';

export function ZonesSection() {
  const robots = useRobots();
  const settings = useSettings();
  const link = useLink();
  const profile = robots.active.spec.profile;
  const keepOut = profile.keepOut;
  const zones = keepOut?.zones ?? [];
  const [name, setName] = useState('');
  const [shape, setShape] = useState<ZoneShape>('box');
  const [values, setValues] = useState<Record<string, string>>({});
  const [note, setNote] = useState<{ ok: boolean; text: string } | null>(null);
  const [busy, setBusy] = useState(false);
  const allowed = link.permissions.command;

  const save = async (next: readonly Zone[], what: string) => {
    setBusy(true);
    const r = await saveKeepOut(settings, profile.name, { ...keepOut, zones: next });
    setBusy(false);
    setNote(
      r.ok
        ? { ok: true, text: `${what}: saved; the arm checks it from now on.` }
        : { ok: false, text: `${what}: not saved (${r.error}).` },
    );
    return r.ok;
  };
  const add = async (e: React.FormEvent) => {
    e.preventDefault();
    const z = zoneFromFields(name, shape, values);
    if (!z.ok) return setNote({ ok: false, text: z.error });
    if (await save([...zones, z.zone], `Zone "${z.zone.name}"`)) {
      setName('');
      setValues({});
    }
  };

  return (
    <details className="zones" data-testid="zones-section">
      <summary>
        Keep-out zones <span className="dim">({zones.length})</span>
      </summary>
      {zones.length === 0 ? (
        <p className="dim">None: only the floor and the arm itself are kept out.</p>
      ) : (
        <ul className="zone-list">
          {zones.map((z) => (
            <li key={z.name} data-testid="zone-item">
              <strong>{z.name}</strong> <span className="dim">{describeZone(z)}</span>{' '}
              <button
                type="button"
                disabled={!allowed || busy}
                aria-label={`Remove zone ${z.name}`}
                onClick={() =>
                  void save(
                    zones.filter((y) => y !== z),
                    `Zone "${z.name}" removed`,
                  )
                }
              >
                Remove
              </button>
            </li>
          ))}
        </ul>
      )}
      <form onSubmit={(e) => void add(e)} aria-label="Add a keep-out zone">
        <label>
          Name <input value={name} onChange={(e) => setName(e.currentTarget.value)} />
        </label>
        <label>
          Shape{' '}
          <select value={shape} onChange={(e) => setShape(e.currentTarget.value as ZoneShape)}>
            {ZONE_SHAPES.map((s) => (
              <option key={s}>{s}</option>
            ))}
          </select>
        </label>
        <div className="zone-fields">
          {SHAPE_FIELDS[shape].map((f) => (
            <label key={f}>
              {f}
              <input
                inputMode="decimal"
                size={5}
                value={values[f] ?? ''}
                onChange={(e) => setValues({ ...values, [f]: e.currentTarget.value })}
              />
            </label>
          ))}
        </div>
        <button type="submit" disabled={!allowed || busy}>
          Add zone
        </button>
      </form>
      {note && (
        <p className={`note ${note.ok ? 'ok' : 'bad'}`} role="status" data-testid="zones-note">
          {note.text}
        </p>
      )}
    </details>
  );
}
