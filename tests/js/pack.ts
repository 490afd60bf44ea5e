// Ship what you test: `npm pack` the project (dist/ must be built) and install the tarball into
// an empty temporary folder, offline (the package has no dependencies; three is an optional peer).
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readdirSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { root } from './helpers.js';

/** Pack and install; returns the folder whose node_modules holds conformesh. */
export function packAndInstall(prefix: string): string {
  const dir = mkdtempSync(join(tmpdir(), `conformesh-${prefix}-`));
  const out = execFileSync('npm', ['pack', '--pack-destination', dir, '--silent'], { cwd: root, encoding: 'utf8' });
  const tarball = out.trim().split('\n').at(-1)!;
  if (!readdirSync(dir).includes(tarball)) throw new Error(`npm pack did not produce ${tarball}: ${out}`);
  writeFileSync(join(dir, 'package.json'), JSON.stringify({ name: 'consumer', private: true, type: 'module' }));
  execFileSync('npm', ['install', '--offline', '--no-audit', '--no-fund', '--silent', `./${tarball}`], { cwd: dir, stdio: 'pipe' });
  return dir;
}
