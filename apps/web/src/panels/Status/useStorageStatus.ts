/**
 * Whether the middleware stores history: GET api/healthz (relative to the page, so it works
 * behind `npm start`) and read `storage`. Unreachable, not JSON, or false → "off".
 */
import { useEffect, useState } from 'react';

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
    const check = () => {
      fetchStorageStatus()
        .then((s) => alive && setStatus(s))
        .catch(() => alive && setStatus('off'));
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
