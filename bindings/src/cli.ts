#!/usr/bin/env node
// The package CLI (`npx conformesh COMMAND ...`): the native CLI's commands, flags and JSON
// output (src/cli/), running the WebAssembly module in Node. One entry in `commands` per command;
// docs/BINDINGS.md shows how to add one.
import { readFile } from 'node:fs/promises';
import type { Conformesh } from './api.js';
import { init } from './index.js';
import { ConformeshError, StatusCode } from './status.js';
import type { MeshInfo } from './types.js';

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

function errorJson(e: ConformeshError): string {
  return JSON.stringify({ error: { code: StatusCode[e.code], name: e.code, stage: e.stage, message: e.message } });
}

async function readInput(path: string, api: Conformesh) {
  let bytes: Uint8Array;
  try {
    bytes = await readFile(path);
  } catch (e) {
    throw new ConformeshError('IoError', 'read', `cannot open '${path}': ${(e as Error).message}`);
  }
  return api.readMesh(bytes, { fileName: path });
}

const infoKeys: (keyof MeshInfo)[] = [
  'vertices',
  'faces',
  'components',
  'boundaryLoops',
  'euler',
  'genus',
  'nonManifoldEdges',
  'degenerateFaces',
];

const commands: Record<string, Command> = {
  info: {
    usage: 'info FILE [--json]',
    summary: 'read a mesh and print its validation and topology report',
    valueFlags: [],
    switches: ['--json'],
    async run(args, api) {
      if (args.positional.length !== 1) throw new ConformeshError('InvalidArgument', 'api', 'info needs exactly one FILE');
      const mesh = await readInput(args.positional[0]!, api);
      const info = api.meshInfo(mesh);
      const warnings = [...mesh.warnings, ...info.warnings.map((w) => w.message)];
      if (args.flags.has('--json')) {
        const fields = infoKeys.map((k) => `${JSON.stringify(k)}:${jsonNumber(info[k] as number)}`);
        fields.push(`"warnings":[${warnings.map((w) => JSON.stringify(w)).join(',')}]`);
        process.stdout.write(`{${fields.join(',')}}\n`);
      } else {
        for (const k of infoKeys) process.stdout.write(`${k}: ${info[k]}\n`);
        for (const w of warnings) process.stdout.write(`warning: ${w}\n`);
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
