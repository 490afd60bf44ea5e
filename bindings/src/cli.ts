#!/usr/bin/env node
// The package CLI (`npx conformesh COMMAND ...`): the native CLI's commands, flags and JSON
// output (src/cli/), running the WebAssembly module in Node. One entry in `commands` per command;
// docs/BINDINGS.md shows how to add one.
import { readFile } from 'node:fs/promises';
import type { Conformesh } from './api.js';
import { init } from './index.js';
import { ConformeshError, StatusCode } from './status.js';
import type { MeshFormat } from './types.js';

interface Args {
  positional: string[];
  flags: Map<string, string>;
}

interface Command {
  usage: string;
  summary: string;
  valueFlags: string[];
  switches: string[];
  run(args: Args, api: Conformesh): Promise<number>;
}

/** Same rules as the native parseArgs (src/cli/cli_util.cpp): unknown options are errors. */
function parseArgs(argv: string[], valueFlags: string[], switches: string[]): Args {
  const out: Args = { positional: [], flags: new Map() };
  for (let i = 0; i < argv.length; ++i) {
    const a = argv[i]!;
    if (a.length > 1 && a[0] === '-' && !/^-[0-9.]/.test(a)) {
      if (valueFlags.includes(a)) {
        if (i + 1 >= argv.length) throw new ConformeshError('InvalidArgument', 'api', `option ${a} needs a value`);
        out.flags.set(a, argv[++i]!);
      } else if (switches.includes(a)) {
        out.flags.set(a, '');
      } else {
        throw new ConformeshError('InvalidArgument', 'api', `unknown option ${a}`);
      }
    } else {
      out.positional.push(a);
    }
  }
  return out;
}

/** C's printf("%.{precision}g", v) for finite v. */
function formatG(v: number, precision: number): string {
  const [mantissa, expText] = v.toExponential(precision - 1).split('e') as [string, string];
  const exp = Number(expText);
  const strip = (t: string) => (t.includes('.') ? t.replace(/0+$/, '').replace(/\.$/, '') : t);
  if (exp < -4 || exp >= precision) {
    const e = Math.abs(exp);
    return `${strip(mantissa)}e${exp < 0 ? '-' : '+'}${e < 10 ? '0' : ''}${e}`;
  }
  return strip(v.toFixed(precision - 1 - exp));
}

/** A number as the native CLI prints it (jsonNumber in src/cli/cli_util.cpp): integers as integers, others %.*g with the fewest digits that round-trip; null if not finite. */
export function jsonNumber(v: number): string {
  if (!Number.isFinite(v)) return 'null';
  if (Number.isInteger(v) && Math.abs(v) < 2 ** 53) return (v === 0 ? 0 : v).toFixed(0);
  let s = formatG(v, 17);
  for (let p = 1; p <= 17; ++p) {
    s = formatG(v, p);
    if (Number(s) === v) break;
  }
  return s;
}

/** A JSON string literal escaped as the native CLI does (jsonString in src/cli/cli_util.cpp). */
export function jsonString(text: string): string {
  let out = '"';
  for (const ch of text) {
    const c = ch.codePointAt(0)!;
    if (ch === '"') out += '\\"';
    else if (ch === '\\') out += '\\\\';
    else if (ch === '\n') out += '\\n';
    else if (ch === '\r') out += '\\r';
    else if (ch === '\t') out += '\\t';
    else if (c < 0x20) out += `\\u${c.toString(16).padStart(4, '0')}`;
    else out += ch;
  }
  return out + '"';
}

function errorJson(e: ConformeshError): string {
  return `{"error":{"code":${StatusCode[e.code]},"name":${jsonString(e.code)},"stage":${jsonString(e.stage)},"message":${jsonString(e.message)}}}`;
}

const strerror: Record<string, string> = {
  ENOENT: 'No such file or directory',
  EACCES: 'Permission denied',
  EISDIR: 'Is a directory',
  ENOTDIR: 'Not a directory',
};

/** readFileBytes of the native CLI: same IoError message. */
async function readFileBytes(path: string): Promise<Uint8Array> {
  try {
    return await readFile(path);
  } catch (e) {
    const err = e as NodeJS.ErrnoException;
    throw new ConformeshError('IoError', 'read', `cannot open '${path}': ${strerror[err.code ?? ''] ?? err.message}`);
  }
}

/** Args.number of the native CLI. */
function numberFlag(args: Args, name: string, fallback: number): number {
  const v = args.flags.get(name);
  if (v === undefined) return fallback;
  const d = v.trim() === v && v !== '' ? Number(v) : Number.NaN;
  if (!Number.isFinite(d)) throw new ConformeshError('InvalidArgument', 'api', `option ${name} needs a number, got '${v}'`);
  return d;
}

const formatNames = ['obj', 'off', 'stl', 'stl-ascii', 'ply', 'ply-ascii', 'ply-be'];

/** --format NAME as the native CLI takes it (a format name or an extension, any case). */
function formatFlag(args: Args): MeshFormat | 'auto' | undefined {
  const v = args.flags.get('--format');
  if (v === undefined) return undefined;
  const name = v.toLowerCase().replace(/^\./, '');
  if (name === 'auto') return 'auto';
  if (!formatNames.includes(name)) throw new ConformeshError('InvalidArgument', 'api', `unknown format '${v}'`);
  return name as MeshFormat;
}

const infoUsage = 'info FILE [--json] [--weld TOL] [--format NAME]';

const commands: Record<string, Command> = {
  // src/cli/cmd_info.cpp
  info: {
    usage: infoUsage,
    summary:
      'validation and topology report: vertices, faces, components, boundary loops, Euler characteristic, genus, non-manifold edges, degenerate faces, warnings',
    valueFlags: ['--weld', '--format'],
    switches: ['--json'],
    async run(args, api) {
      if (args.positional.length !== 1) throw new ConformeshError('InvalidArgument', 'api', `usage: conformesh ${infoUsage}`);
      const path = args.positional[0]!;
      const weldTolerance = numberFlag(args, '--weld', 0);
      if (weldTolerance < 0) throw new ConformeshError('InvalidArgument', 'api', '--weld needs a tolerance >= 0');
      const format = formatFlag(args);
      const mesh = api.readMesh(await readFileBytes(path), { fileName: path, weldTolerance, ...(format ? { format } : {}) });
      const info = api.meshInfo(mesh);
      const warnings = [
        ...mesh.warnings.map((message) => ({ code: 'Ok', stage: 'read', message, count: 1 })),
        ...info.warnings.map((w) => ({ code: w.code, stage: 'validate', message: w.message, count: w.count })),
      ];
      const rows: [string, string][] = [
        ['vertices', jsonNumber(info.vertices)],
        ['faces', jsonNumber(info.faces)],
        ['components', jsonNumber(info.components)],
        ['boundaryLoops', jsonNumber(info.boundaryLoops)],
        ['euler', jsonNumber(info.euler)],
        ['genus', jsonNumber(info.genus)],
        ['nonManifoldEdges', jsonNumber(info.nonManifoldEdges)],
        ['degenerateFaces', jsonNumber(info.degenerateFaces)],
      ];
      if (args.flags.has('--json')) {
        const ws = warnings.map(
          (w) =>
            `{"code":${jsonString(w.code)},"stage":${jsonString(w.stage)},"count":${jsonNumber(w.count)},"message":${jsonString(w.message)}}`,
        );
        const fields = rows.map(([k, v]) => `${jsonString(k)}:${v}`);
        fields.push(`"warnings":[${ws.join(',')}]`);
        process.stdout.write(`{${fields.join(',')}}\n`);
      } else {
        const table: [string, string][] = [
          ['file', `${path} (${mesh.format})`],
          ...rows,
          ['warnings', String(warnings.length)],
        ];
        for (const [k, v] of table) process.stdout.write(`${k.padEnd(17)} ${v}\n`);
        for (const w of warnings) process.stdout.write(`  - ${w.code} [${w.stage}]: ${w.message}\n`);
      }
      return 0;
    },
  },
};

function usage(): string {
  const lines = ['usage: conformesh COMMAND [ARGS]', '', 'commands:'];
  for (const name of Object.keys(commands).sort()) {
    lines.push(`  conformesh ${commands[name]!.usage}`, `      ${commands[name]!.summary}`);
  }
  return lines.join('\n') + '\n';
}

export async function main(argv: string[]): Promise<number> {
  const name = argv[0];
  if (name === undefined) {
    process.stderr.write(usage());
    return 2;
  }
  if (name === '--help' || name === '-h' || name === 'help') {
    process.stdout.write(usage());
    return 0;
  }
  const command = Object.prototype.hasOwnProperty.call(commands, name) ? commands[name] : undefined;
  if (!command) {
    process.stderr.write(`conformesh: unknown command '${name}'\n\n${usage()}`);
    return 2;
  }
  const json = argv.includes('--json');
  try {
    const args = parseArgs(argv.slice(1), command.valueFlags, command.switches);
    return await command.run(args, await init());
  } catch (e) {
    const err =
      e instanceof ConformeshError ? e : new ConformeshError('InternalError', 'api', e instanceof Error ? e.message : String(e));
    if (json) process.stdout.write(errorJson(err) + '\n');
    else process.stderr.write(`conformesh: ${err.message} (${err.code}, stage ${err.stage})\n`);
    return 1;
  }
}

// Run when executed as the bin (not when imported by tests).
const self = process.argv[1] ? await import('node:fs').then((fs) => fs.realpathSync(process.argv[1]!)) : '';
if (self && import.meta.url === (await import('node:url')).pathToFileURL(self).href) {
  process.exitCode = await main(process.argv.slice(2));
}
