/**
 * Forwards a request to another HTTP server unchanged (method, path, headers, body) and
 * streams the answer back: how `npm start` puts the middleware's API on the HUD's own origin
 * at `/api`, so the HUD needs no CORS. An unreachable upstream answers 502 `{error}`.
 */
import http from 'node:http';

export function proxyRequest(
  req: http.IncomingMessage,
  res: http.ServerResponse,
  target: string,
): void {
  const url = new URL(req.url ?? '/', target);
  const upstream = http.request(
    url,
    { method: req.method, headers: { ...req.headers, host: url.host } },
    (answer) => {
      res.writeHead(answer.statusCode ?? 502, answer.headers);
      answer.pipe(res);
    },
  );
  upstream.on('error', (err) => {
    if (!res.headersSent) res.writeHead(502, { 'content-type': 'application/json' });
    res.end(JSON.stringify({ error: `proxy to ${target}: ${err.message}` }));
  });
  req.pipe(upstream);
}
