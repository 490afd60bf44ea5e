// An e2e test's HTTP server on a free port of 127.0.0.1.
import type { Server } from 'node:http';

/** Start `server` on a free local port; its base URL (with the trailing slash). */
export function listenLocal(server: Server): Promise<{ server: Server; url: string }> {
  return new Promise((resolve) => {
    server.listen(0, '127.0.0.1', () => {
      const addr = server.address();
      resolve({ server, url: `http://127.0.0.1:${typeof addr === 'object' && addr ? addr.port : 0}/` });
    });
  });
}
