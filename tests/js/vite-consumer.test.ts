// The package in a web app: a tiny page that imports 'conformesh' (main-thread API and the worker
// pool) from the packed tarball installed into an empty folder, built with Vite's JS API exactly
// as an app would build it. The build must print no warning at all: in particular none of Vite's
// "Module "node:…" has been externalized for browser compatibility" (a browser entry that reaches
// Node builtins), and the bundle must not name a Node builtin.
import { readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { build, createLogger, type Logger } from 'vite';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { packAndInstall } from './pack.js';

const page = `<!doctype html>
<html><head><meta charset="utf-8"><title>conformesh in an app</title></head>
<body><script type="module" src="./main.js"></script></body></html>`;

// Uses the lazily loaded API, init(), and createRemesher (which bundles the module worker).
const main = `
import { createRemesher, init, readMesh, ConformeshError } from 'conformesh';
const remesher = createRemesher({ workers: 1 });
window.run = async (bytes) => {
  const cm = await init();
  const m = await readMesh(bytes);
  const w = await remesher.remesh(m, { targetEdgeLengthRel: 0.05 });
  return { version: cm.version, triangles: w.mesh.triangles.length, isError: w instanceof ConformeshError };
};
`;

/** A logger that records every warning and error Vite prints (and still prints them). */
function recordingLogger(): { logger: Logger; messages: string[] } {
  const base = createLogger('warn');
  const messages: string[] = [];
  const logger: Logger = {
    ...base,
    warn(msg, options) {
      messages.push(msg);
      base.warn(msg, options);
    },
    warnOnce(msg, options) {
      messages.push(msg);
      base.warnOnce(msg, options);
    },
    error(msg, options) {
      messages.push(msg);
      base.error(msg, options);
    },
  };
  return { logger, messages };
}

/** Every file under a folder, relative paths. */
function filesUnder(dir: string, prefix = ''): string[] {
  return readdirSync(join(dir, prefix), { withFileTypes: true }).flatMap((e) =>
    e.isDirectory() ? filesUnder(dir, join(prefix, e.name)) : [join(prefix, e.name)],
  );
}

describe('a Vite app importing the installed package', () => {
  let dir = '';
  const { logger, messages } = recordingLogger();
  const rolldownWarnings: string[] = [];

  beforeAll(async () => {
    dir = packAndInstall('vite-app');
    writeFileSync(join(dir, 'index.html'), page);
    writeFileSync(join(dir, 'main.js'), main);
    // `vite build` in an app runs with NODE_ENV unset (production); Vitest sets it to 'test', and
    // then Vite's resolver does not print the externalized-module warning this test looks for.
    const nodeEnv = process.env.NODE_ENV;
    process.env.NODE_ENV = 'production';
    try {
      await build({
        root: dir,
        configFile: false,
        customLogger: logger,
        logLevel: 'warn',
        base: './',
        build: {
          outDir: join(dir, 'out'),
          target: 'es2022',
          rollupOptions: {
            onwarn(warning, handle) {
              rolldownWarnings.push(typeof warning === 'string' ? warning : warning.message);
              handle(warning);
            },
          },
        },
      });
    } finally {
      if (nodeEnv === undefined) delete process.env.NODE_ENV;
      else process.env.NODE_ENV = nodeEnv;
    }
  });

  afterAll(() => {
    if (dir) rmSync(dir, { recursive: true, force: true });
  });

  it('builds without any warning (none about Node builtins externalized for browser compatibility)', () => {
    const all = [...messages, ...rolldownWarnings];
    const nodeRelated = all.filter((m) => /externali[sz]ed|browser compatibility|node:|worker_threads|fs\/promises/i.test(m));
    expect(nodeRelated, 'warnings about Node builtins').toEqual([]);
    expect(all, 'warnings of the build').toEqual([]);
  });

  it('bundles the module worker and the .wasm, and no Node builtin', () => {
    const out = join(dir, 'out');
    const files = filesUnder(out);
    const js = files.filter((f) => f.endsWith('.js'));
    expect(files.some((f) => f.endsWith('.wasm')), `a .wasm asset among ${files.join(', ')}`).toBe(true);
    // the page's script and the worker pool's worker script
    expect(js.length, `JS files: ${js.join(', ')}`).toBeGreaterThanOrEqual(2);
    for (const f of js) {
      const text = readFileSync(join(out, f), 'utf8');
      expect(text, `${f} names a Node builtin`).not.toMatch(/["'`]node:[a-z_/]+["'`]|["'`](fs|fs\/promises|worker_threads|child_process|path|url)["'`]/);
      expect(text, `${f} uses the __vite-browser-external stub`).not.toMatch(/__vite-browser-external/);
    }
  });
});
