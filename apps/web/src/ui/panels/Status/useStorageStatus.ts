/**
 * Whether the middleware stores history: GET api/healthz (relative to the page, so it works
 * behind `npm start`) and read `storage`. Unreachable, not JSON, or false → "off".
 */
import { useEffect, useState } from 'react';
import { changedOnly } from '../../hud/changedOnly.ts';

export type StorageStatus = 'checking' | 'on' | 'off';

const RECHECK_MS = 30_000;

export async function fetchStorageStatus(url = 'api/healthz'): Promise<StorageStatus> {
  try {
    const res = await fetch(url, { headers: { accept: 'application/json' } });
    if (!res.ok) return 'off';
    const body = (await res.json()) as { storage?: unknown };
    return body.storage === true ? 'on' : 'off';
  } catch {
    return 'off';
  }
}

export function useStorageStatus(): StorageStatus {
  const [status, setStatus] = useState<StorageStatus>('checking');
  useEffect(() => {
    let alive = true;
    // Only a change reaches React: an unchanged setState still queues an update on a component
    // that does not re-render (see src/ui/hud/changedOnly.ts), every 30 s for as long as the page is open.
    const offer = changedOnly<StorageStatus>('checking', setStatus, (a, b) => a === b);
    const check = () => {
      fetchStorageStatus()
        .then((s) => alive && offer(s))
        .catch(() => alive && offer('off'));
    };
    check();
    const id = setInterval(check, RECHECK_MS);
    return () => {
      alive = false;
      clearInterval(id);
    };
  }, []);
  return status;
}
