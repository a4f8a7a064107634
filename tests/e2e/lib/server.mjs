// Serves the built site (and optional extra folders) over real HTTP on 127.0.0.1 for a test file.
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { startServer } from '../../../web/serve.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
export const REPO = path.resolve(here, '../../..');
export const SITE = process.env.QUAKEVIEW_SITE || path.join(REPO, 'build/wasm-release/site');
export const ARTIFACTS = path.join(REPO, 'tests/e2e/artifacts');

/// Starts a server on a free port; resolves to {url, close}.
export async function serveSite(mounts = {}) {
  const server = await startServer({ root: SITE, port: 0, host: '127.0.0.1', mounts });
  const { port } = server.address();
  return {
    url: `http://127.0.0.1:${port}`,
    close: () => new Promise((resolve) => server.close(resolve)),
  };
}
