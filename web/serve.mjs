#!/usr/bin/env node
// A small static file server for the QuakeView site: correct MIME types (application/wasm lets the
// browser compile while downloading), no caching surprises, 127.0.0.1 by default, and the security
// headers a deployment should send (README, "Deploying"): a Content-Security-Policy the page works
// under, X-Content-Type-Options: nosniff, no framing, no referrer.
//
//   node web/serve.mjs --root DIR [--port 8080] [--host 127.0.0.1] [--mount /data=DIR ...]
//
// Also importable: `startServer({root, port, host, mounts})` resolves to the http.Server.
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

export const MIME_TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json',
  '.geojson': 'application/geo+json',
  '.wasm': 'application/wasm',
  '.png': 'image/png',
  '.svg': 'image/svg+xml',
  '.ico': 'image/x-icon',
  '.csv': 'text/csv; charset=utf-8',
  '.txt': 'text/plain; charset=utf-8',
  '.md': 'text/markdown; charset=utf-8',
  // A city's binary files: tiles, response summaries and histories, the search index.
  '.qvt': 'application/octet-stream',
  '.qvs': 'application/octet-stream',
  '.qvh': 'application/octet-stream',
  '.qvi': 'application/octet-stream',
};

/// The origins a site's config.json (beside index.html) allows cities to be loaded from:
/// {"dataOrigins": ["https://data.example.org"]}. Entries that are not origins are left out (the
/// page reports them); a missing or unreadable file allows none.
export function allowedDataOrigins(root) {
  let json;
  try {
    json = JSON.parse(fs.readFileSync(path.join(root, 'config.json'), 'utf8'));
  } catch {
    return [];
  }
  const list = json && Array.isArray(json.dataOrigins) ? json.dataOrigins : [];
  return list.filter((entry) => {
    try {
      const url = new URL(String(entry));
      return (url.protocol === 'https:' || url.protocol === 'http:') && url.origin === String(entry);
    } catch {
      return false;
    }
  });
}

/// The Content-Security-Policy the site works under: its own scripts only (no inline script, no
/// eval; 'wasm-unsafe-eval' lets it compile its WebAssembly), its own styles, data only from
/// itself and the allowed origins, and no plugins, frames, forms or base-URL tricks.
export function contentSecurityPolicy(dataOrigins = []) {
  const connect = ["'self'", ...dataOrigins].join(' ');
  return [
    "default-src 'none'",
    "script-src 'self' 'wasm-unsafe-eval'",
    "style-src 'self'",
    "img-src 'self' data: blob:",
    `connect-src ${connect}`,
    "object-src 'none'",
    "base-uri 'none'",
    "form-action 'none'",
    "frame-ancestors 'none'",
  ].join('; ');
}

/// Headers every response of the site carries.
export function securityHeaders(root) {
  return {
    'Content-Security-Policy': contentSecurityPolicy(allowedDataOrigins(root)),
    'X-Content-Type-Options': 'nosniff',
    'Referrer-Policy': 'no-referrer',
    'X-Frame-Options': 'DENY',
  };
}

/// Maps a URL path to a file under one of the roots; null when it escapes them.
export function resolvePath(urlPath, root, mounts = {}) {
  let decoded;
  try {
    decoded = decodeURIComponent(urlPath.split('?')[0].split('#')[0]);
  } catch {
    return null;
  }
  let base = root;
  let rest = decoded;
  for (const [prefix, dir] of Object.entries(mounts)) {
    if (decoded === prefix || decoded.startsWith(prefix + '/')) {
      base = dir;
      rest = decoded.slice(prefix.length);
      break;
    }
  }
  const full = path.resolve(base, '.' + path.posix.normalize('/' + rest));
  if (full !== path.resolve(base) && !full.startsWith(path.resolve(base) + path.sep)) return null;
  return full;
}

export function handleStatic(req, res, root, mounts = {}) {
  const security = securityHeaders(root);
  if (req.method !== 'GET' && req.method !== 'HEAD') {
    res.writeHead(405, { ...security, Allow: 'GET, HEAD' });
    res.end();
    return;
  }
  let file = resolvePath(req.url, root, mounts);
  if (file === null) {
    res.writeHead(400, { ...security, 'Content-Type': 'text/plain; charset=utf-8' });
    res.end('bad path');
    return;
  }
  fs.stat(file, (err, stat) => {
    if (!err && stat.isDirectory()) {
      file = path.join(file, 'index.html');
      try {
        stat = fs.statSync(file);
      } catch (e) {
        err = e;
      }
    }
    if (err || !stat.isFile()) {
      // With CORS too: a page on another origin then learns that an optional file (a city's
      // scenarios.json) is missing, where a bare 404 reads as a network error in the browser.
      res.writeHead(404, { ...security, 'Content-Type': 'text/plain; charset=utf-8', 'Access-Control-Allow-Origin': '*' });
      res.end('not found');
      return;
    }
    const type = MIME_TYPES[path.extname(file).toLowerCase()] || 'application/octet-stream';
    res.writeHead(200, {
      ...security,
      'Content-Type': type,
      'Content-Length': stat.size,
      'Cache-Control': 'no-cache',
      'Access-Control-Allow-Origin': '*',
    });
    if (req.method === 'HEAD') {
      res.end();
      return;
    }
    fs.createReadStream(file).pipe(res);
  });
}

export function startServer({ root, port = 8080, host = '127.0.0.1', mounts = {} }) {
  const server = http.createServer((req, res) => handleStatic(req, res, root, mounts));
  return new Promise((resolve, reject) => {
    server.once('error', reject);
    server.listen(port, host, () => resolve(server));
  });
}

function parseArgs(argv) {
  const options = { root: null, port: Number(process.env.PORT || 8080), host: '127.0.0.1', mounts: {} };
  for (let i = 0; i < argv.length; ++i) {
    const a = argv[i];
    const next = () => {
      if (i + 1 >= argv.length) throw new Error(`${a} needs a value`);
      return argv[++i];
    };
    if (a === '--root') options.root = next();
    else if (a === '--port') options.port = Number(next());
    else if (a === '--host') options.host = next();
    else if (a === '--mount') {
      const [prefix, dir] = next().split('=');
      if (!prefix.startsWith('/') || !dir) throw new Error('--mount takes /prefix=DIR');
      options.mounts[prefix.replace(/\/$/, '')] = path.resolve(dir);
    } else throw new Error(`unknown argument ${a}`);
  }
  if (!options.root) throw new Error('--root DIR is required');
  if (!Number.isInteger(options.port) || options.port < 0 || options.port > 65535) {
    throw new Error(`invalid port ${options.port}`);
  }
  return options;
}

if (process.argv[1] && path.resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  let options;
  try {
    options = parseArgs(process.argv.slice(2));
  } catch (e) {
    console.error(`serve.mjs: ${e.message}`);
    process.exit(2);
  }
  startServer(options).then(
    (server) => {
      const { port } = server.address();
      console.log(`QuakeView is served at http://${options.host}:${port}/  (Ctrl-C to stop)`);
    },
    (e) => {
      console.error(`serve.mjs: cannot listen on ${options.host}:${options.port}: ${e.message}`);
      process.exit(1);
    },
  );
}
