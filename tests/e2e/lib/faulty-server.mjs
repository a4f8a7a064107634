// A fault-injecting HTTP server for the failing-network test, on 127.0.0.1 only. It serves the
// site and a city like serve.mjs, but while `faulty` is on, each city data file (tiles, response
// summaries and histories; never the manifest) gets a fault chosen from its name: an HTTP 500,
// a slow answer, a truncated body, wrong content, or a dropped connection. `faults` counts what
// was injected. Turning `faulty` off makes it a healthy server, so the viewer can recover.
import crypto from 'node:crypto';
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { handleStatic } from '../../../web/serve.mjs';
import { SITE } from './server.mjs';

export const FAULTS = ['http-500', 'slow', 'truncated', 'wrong-content', 'dropped', 'none'];

/// Serves SITE at / and `cityDir` at /city. Resolves to {url, setFaulty(on), faults, close}.
export async function serveFaulty(cityDir, { slowMs = 3000 } = {}) {
  let faulty = true;
  const faults = Object.fromEntries(FAULTS.map((f) => [f, 0]));
  const timers = new Set();
  const faultFor = (name) => FAULTS[crypto.createHash('sha1').update(name).digest()[0] % FAULTS.length];

  const server = http.createServer((req, res) => {
    const url = new URL(req.url, 'http://127.0.0.1');
    const isData = url.pathname.startsWith('/city/') && /\.(qvt|qvs|qvh)$/.test(url.pathname);
    if (!faulty || !isData) {
      handleStatic(req, res, SITE, { '/city': cityDir });
      return;
    }
    const fault = faultFor(url.pathname);
    faults[fault] += 1;
    const file = path.join(cityDir, url.pathname.slice('/city/'.length));
    const headers = { 'Content-Type': 'application/octet-stream', 'Access-Control-Allow-Origin': '*', 'Cache-Control': 'no-cache' };
    switch (fault) {
      case 'http-500':
        res.writeHead(500, headers);
        res.end('injected server error');
        return;
      case 'dropped':
        req.socket.destroy();
        return;
      case 'slow': {
        const t = setTimeout(() => { timers.delete(t); handleStatic(req, res, SITE, { '/city': cityDir }); }, slowMs);
        timers.add(t);
        return;
      }
      case 'truncated': {
        const bytes = fs.readFileSync(file);
        res.writeHead(200, { ...headers, 'Content-Length': bytes.length });
        res.write(bytes.subarray(0, Math.floor(bytes.length / 2)));
        // Announced length not delivered: the connection ends early.
        setImmediate(() => req.socket.destroy());
        return;
      }
      case 'wrong-content': {
        const bytes = Buffer.from(fs.readFileSync(file));
        for (let i = 16; i < bytes.length; i += 97) bytes[i] ^= 0x5a;
        res.writeHead(200, { ...headers, 'Content-Length': bytes.length });
        res.end(bytes);
        return;
      }
      default:
        handleStatic(req, res, SITE, { '/city': cityDir });
    }
  });
  await new Promise((resolve, reject) => {
    server.once('error', reject);
    server.listen(0, '127.0.0.1', resolve);
  });
  return {
    url: `http://127.0.0.1:${server.address().port}`,
    faults,
    faultFor,
    setFaulty(on) { faulty = on; },
    close: () => new Promise((resolve) => {
      for (const t of timers) clearTimeout(t);
      server.closeAllConnections?.();
      server.close(resolve);
    }),
  };
}
