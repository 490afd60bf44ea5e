#!/usr/bin/env node
// The package CLI (`npx conformesh COMMAND ...`): the native CLI's commands, flags and JSON
// output (src/cli/), running the WebAssembly module in Node. One entry in `commands` per command;
// docs/BINDINGS.md shows how to add one.
import { readFile, writeFile } from 'node:fs/promises';
import { setFlagsFromString } from 'node:v8';
import type { Conformesh } from './api.js';
import { init } from './index.js';
import { REMESH_STAGES } from './stages.js';
import { ConformeshError, StatusCode } from './status.js';
import type { OptionRow } from './schema.js';
import type { MeshFormat, Refine2dResult, RemeshResult } from './types.js';

/** One flag of a command (the native Flag of src/cli/cli_util.h): what parsing and --help read. */
interface Flag {
  name: string;
  /** What its value is, as --help shows it ('DEG'); '' for a switch. */
  value: string;
  /** What it sets, with its units. */
  help: string;
  /** Its default: what a run uses when the flag is absent, and what --help prints. */
  default?: number | string;
}

interface Args {
  positional: string[];
  flags: Map<string, string>;
  table: Flag[];
}

interface Command {
  usage: string;
  summary: string;
  /** The flags, or how to make them from the module (remesh: from its option table). */
  flags: Flag[] | ((api: Conformesh) => Flag[]);
  run(args: Args, api: Conformesh): Promise<number>;
}

/** Same rules as the native parseArgs (src/cli/cli_util.cpp): unknown options are errors. */
function parseArgs(argv: string[], table: Flag[]): Args {
  const out: Args = { positional: [], flags: new Map(), table };
  const flag = (name: string) => table.find((f) => f.name === name);
  for (let i = 0; i < argv.length; ++i) {
    const a = argv[i]!;
    if (a.length > 1 && a[0] === '-' && !/^-[0-9.]/.test(a)) {
      if (flag(a)?.value) {
        if (i + 1 >= argv.length) throw new ConformeshError('InvalidArgument', 'api', `option ${a} needs a value`);
        out.flags.set(a, argv[++i]!);
      } else if (flag(a)) {
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

/** True when argv holds --help or -h where a flag may stand (asksForHelp in src/cli/cli_util.cpp). */
function asksForHelp(argv: string[], table: Flag[]): boolean {
  for (let i = 0; i < argv.length; ++i) {
    if (argv[i] === '--help' || argv[i] === '-h') return true;
    if (table.find((f) => f.name === argv[i])?.value) ++i;
  }
  return false;
}

/** A command's --help, laid out as helpText in src/cli/cli_util.cpp: flags in a column of 30, text wrapped at 100. */
function helpText(command: Command, flags: Flag[]): string {
  const indent = 30, width = 100;
  let s = `usage: conformesh ${command.usage}\n\n${command.summary}\n\noptions:\n`;
  const line = (left: string, text: string) => {
    let l = `  ${left}`;
    l += l.length < indent ? ' '.repeat(indent - l.length) : `\n${' '.repeat(indent)}`;
    let column = indent;
    for (const word of text.split(' ')) {
      if (column > indent && column + 1 + word.length > width) {
        l += `\n${' '.repeat(indent)}`;
        column = indent;
      }
      if (column > indent) (l += ' '), ++column;
      l += word;
      column += word.length;
    }
    s += `${l}\n`;
  };
  for (const f of flags) {
    const fallback = f.default === undefined ? '' : ` (default ${typeof f.default === 'number' ? jsonNumber(f.default) : f.default})`;
    line(f.value ? `${f.name} ${f.value}` : f.name, f.help + fallback);
  }
  line('-h, --help', 'print this help and exit');
  return s;
}

/** The package's version, from its package.json (one level above dist/). */
async function packageVersion(): Promise<string> {
  const json = JSON.parse(await readFile(new URL('../package.json', import.meta.url), 'utf8')) as { version: string };
  return json.version;
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

/** --boundary circle|free|corners (InvalidArgument otherwise), as the native CLI; the table's default when absent. */
function boundaryFlag(args: Args): 'circle' | 'free' | 'corners' {
  const b = args.flags.get('--boundary') ?? defaultOf(args, '--boundary');
  if (b !== 'circle' && b !== 'free' && b !== 'corners') throw new ConformeshError('InvalidArgument', 'api', '--boundary must be circle, free or corners');
  return b;
}

/** A flag's default from its command's table. */
function defaultOf(args: Args, name: string): number | string {
  const d = args.table.find((f) => f.name === name)?.default;
  if (d === undefined) throw new ConformeshError('InternalError', 'api', `no default for ${name}`);
  return d;
}

/** Args.number of the native CLI; the table's default when the flag is absent. */
function numberFlag(args: Args, name: string): number {
  const v = args.flags.get(name);
  if (v === undefined) return defaultOf(args, name) as number;
  const d = v.trim() === v && v !== '' ? Number(v) : Number.NaN;
  if (!Number.isFinite(d)) throw new ConformeshError('InvalidArgument', 'api', `option ${name} needs a number, got '${v}'`);
  return d;
}

/** numberFlag for a count: the native CLI's error for a fractional value. */
function integerFlag(args: Args, name: string): number {
  const d = numberFlag(args, name);
  if (!Number.isInteger(d)) throw new ConformeshError('InvalidArgument', 'api', `option ${name} needs an integer`);
  return d;
}

/** The value of an option's flag, by its kind, as the native CLI reads it (readFlag in src/cli/cmd_remesh.cpp). */
function optionFlag(args: Args, o: OptionRow): unknown {
  switch (o.kind) {
    case 'boolean':
      return args.flags.has(o.flag) ? !o.flag.startsWith('--no-') : o.default;
    case 'integer':
      return integerFlag(args, o.flag);
    case 'count': {
      // values below 1 are passed as 0 (InvalidArgument, never "unlimited")
      const v = numberFlag(args, o.flag);
      return v >= 1 ? Math.floor(Math.min(v, 1e18)) : 0;
    }
    case 'boundary':
      return boundaryFlag(args);
    default:
      return numberFlag(args, o.flag);
  }
}

/** A value as JSON the way the native CLI writes it: numbers by jsonNumber, objects in their key order. */
function jsonValue(v: unknown): string {
  if (typeof v === 'number') return jsonNumber(v);
  if (typeof v === 'boolean') return v ? 'true' : 'false';
  if (typeof v === 'string') return jsonString(v);
  if (Array.isArray(v) || ArrayBuffer.isView(v)) return `[${Array.from(v as ArrayLike<unknown>, jsonValue).join(',')}]`;
  if (typeof v === 'object' && v !== null) {
    return `{${Object.entries(v).map(([k, x]) => `${jsonString(k)}:${jsonValue(x)}`).join(',')}}`;
  }
  return 'null';
}

/** writeFileBytes of the native CLI: same IoError message. */
async function writeFileBytes(path: string, bytes: Uint8Array | string): Promise<void> {
  try {
    await writeFile(path, bytes);
  } catch (e) {
    const err = e as NodeJS.ErrnoException;
    throw new ConformeshError('IoError', 'write', `cannot create '${path}': ${strerror[err.code ?? ''] ?? err.message}`);
  }
}

/** printf("%.17g") of the native CLI for finite numbers. */
function g17(v: number): string {
  return Number.isFinite(v) ? formatG(v, 17) : String(v);
}

/** The refined planar mesh as OBJ or OFF text, as cmd_refine2d.cpp writes it (z = 0). */
function planarMeshText(vertices: Float64Array, triangles: Uint32Array, off: boolean): string {
  const parts: string[] = [];
  const nV = vertices.length / 2, nT = triangles.length / 3;
  if (off) parts.push(`OFF\n${nV} ${nT} 0\n`);
  for (let i = 0; i < nV; ++i) parts.push(`${off ? '' : 'v '}${g17(vertices[2 * i]!)} ${g17(vertices[2 * i + 1]!)} 0\n`);
  for (let t = 0; t < nT; ++t) {
    const a = triangles[3 * t]!, b = triangles[3 * t + 1]!, c = triangles[3 * t + 2]!;
    parts.push(off ? `3 ${a} ${b} ${c}\n` : `f ${a + 1} ${b + 1} ${c + 1}\n`);
  }
  return parts.join('');
}

/** printf("%.{digits}f") / ("%.{digits}g") helpers for the text reports. */
const fixed = (v: number, digits: number) => v.toFixed(digits);

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

const refine2dUsage =
  'refine2d IN.poly [-o OUT.obj|OUT.off] [--min-angle D] [--max-area A | --max-edge L] [--convex-hull] [--holes-by-orientation] [--circumcenters] [--max-insertions N] [--json]';
const flattenUsage =
  'flatten IN -o OUT.obj [--boundary circle|free|corners] [--corner-angle DEG] [--no-flips] [--json]';
const remeshUsage = 'remesh IN [-o OUT] [options]';

const infoUsage = 'info FILE [--json] [--weld TOL] [--format NAME]';

// The flag tables below say what the native ones say (src/cli/cmd_*.cpp, defaults from the C++
// options structs); tests/js/cli.test.ts compares the two --help texts.
const jsonFlag: Flag = { name: '--json', value: '', help: 'print the report, or the error, as one JSON object on stdout' };

const commands: Record<string, Command> = {
  // src/cli/cmd_refine2d.cpp
  refine2d: {
    usage: refine2dUsage,
    summary: 'quality triangulation of a planar straight-line graph (Delaunay refinement)',
    flags: [
      { name: '-o', value: 'OUT.obj|OUT.off', help: 'write the planar mesh (z = 0); without it no file is written' },
      { name: '--min-angle', value: 'DEG', help: 'angle bound of every triangle that is not exempt, degrees in [0, 34]', default: 30 },
      { name: '--max-area', value: 'A', help: "largest triangle area, in the input's units squared; 0: none; not with --max-edge", default: 0 },
      { name: '--max-edge', value: 'L', help: "largest edge length, in the input's units; 0: none; not with --max-area", default: 0 },
      { name: '--max-insertions', value: 'N', help: 'Steiner points at most (then IterationLimit, exit 3)', default: 1e8 },
      { name: '--convex-hull', value: '', help: "the domain is the convex hull minus the holes (Triangle's -c)" },
      { name: '--holes-by-orientation', value: '', help: 'counterclockwise loops bound the domain, clockwise loops in them are holes' },
      { name: '--circumcenters', value: '', help: 'insert circumcenters instead of off-centers' },
      jsonFlag,
    ],
    async run(args, api) {
      if (args.positional.length !== 1) throw new ConformeshError('InvalidArgument', 'api', 'refine2d needs exactly one input .poly file');
      if (args.flags.has('--max-area') && args.flags.has('--max-edge'))
        throw new ConformeshError('InvalidArgument', 'api', 'give --max-area or --max-edge, not both');
      const minAngle = numberFlag(args, '--min-angle');
      const maxArea = numberFlag(args, '--max-area');
      const maxEdge = numberFlag(args, '--max-edge');
      const cap = numberFlag(args, '--max-insertions');
      if (!(cap >= 0)) throw new ConformeshError('InvalidArgument', 'api', '--max-insertions must be >= 0');
      const out = args.flags.get('-o') ?? '';
      let off = false;
      if (out !== '') {
        if (out.endsWith('.off')) off = true;
        else if (!out.endsWith('.obj')) throw new ConformeshError('InvalidArgument', 'api', '-o must name a .obj or .off file');
      }
      const pslg = api.readPoly(await readFileBytes(args.positional[0]!));
      const refine = () => api.refine2d(pslg, {
        minAngle,
        maxArea,
        maxEdge,
        maxInsertions: Math.floor(cap),
        convexHull: args.flags.has('--convex-hull'),
        holesByOrientation: args.flags.has('--holes-by-orientation'),
        offcenters: !args.flags.has('--circumcenters'),
      });
      let r: Refine2dResult;
      try {
        r = refine();
      } catch (e) {
        // stopped at --max-insertions: the mesh made so far is written and reported (exit 3)
        if (!(e instanceof ConformeshError && e.code === 'IterationLimit' && e.result)) throw e;
        r = e.result as Refine2dResult;
      }
      if (out !== '') await writeFileBytes(out, planarMeshText(r.vertices, r.triangles, off));
      const nT = r.triangles.length / 3, nV = r.vertices.length / 2;
      if (args.flags.has('--json')) {
        process.stdout.write(
          `{"triangles":${nT},"vertices":${nV},"minAngle":${jsonNumber(r.minAngle)},"exemptTriangles":${r.exemptTriangles},` +
            `"insertions":${r.insertions},"segmentSplits":${r.segmentSplits},"rejected":${r.rejected},` +
            `"seconds":${jsonNumber(r.seconds)},"status":${jsonString(r.status)}}\n`,
        );
      } else {
        process.stdout.write(
          `${nT} triangles, ${nV} vertices, min angle ${fixed(r.minAngle, 3)} deg (${r.exemptTriangles} exempt), ${fixed(r.seconds, 3)} s\n`,
        );
        if (r.status !== 'Ok') process.stderr.write(`conformesh: ${r.message}\n`);
      }
      return r.status === 'Ok' ? 0 : 3;
    },
  },
  // src/cli/cmd_flatten.cpp
  flatten: {
    usage: flattenUsage,
    summary: 'conformal flattening (Ricci flow with intrinsic Delaunay flips); writes uv as vt',
    flags: [
      { name: '-o', value: 'OUT.obj', help: 'the input mesh with the planar coordinates as vt (required)' },
      {
        name: '--boundary',
        value: 'circle|free|corners',
        help: 'circle: a round disk; free: u = 0 on the boundary; corners: corners keep their 3D angle',
        default: 'circle',
      },
      {
        name: '--corner-angle',
        value: 'DEG',
        help: 'with --boundary corners: boundary vertices whose 3D angle differs from 180 degrees by more are corners',
        default: 30,
      },
      { name: '--tolerance', value: 'T', help: 'stop at a curvature error max |K - Kbar| below this, radians', default: 1e-9 },
      { name: '--max-iterations', value: 'N', help: 'Newton iterations at most (then IterationLimit)', default: 100 },
      { name: '--no-flips', value: '', help: 'no intrinsic Delaunay flips during the flow (to study the flow without them)' },
      jsonFlag,
    ],
    async run(args, api) {
      const out = args.flags.get('-o');
      if (args.positional.length !== 1 || out === undefined)
        throw new ConformeshError(
          'InvalidArgument',
          'api',
          'usage: conformesh flatten IN -o OUT.obj [--boundary circle|free|corners] [--corner-angle DEG] [--json]',
        );
      const path = args.positional[0]!;
      const boundary = boundaryFlag(args);
      const tolerance = numberFlag(args, '--tolerance');
      const maxIterations = Math.trunc(numberFlag(args, '--max-iterations'));
      const mesh = api.readMesh(await readFileBytes(path), { fileName: path });
      const cornerAngle = boundary === 'corners' ? numberFlag(args, '--corner-angle') : (defaultOf(args, '--corner-angle') as number);
      if (!(cornerAngle > 0 && cornerAngle < 180))
        throw new ConformeshError('InvalidArgument', 'api', '--corner-angle must be in (0, 180) degrees');
      const r = api.flatten(mesh, { boundary, cornerAngle, tolerance, maxIterations, flips: !args.flags.has('--no-flips') });
      await writeFileBytes(out, api.writeMesh({ positions: mesh.positions, triangles: mesh.triangles, uvs: r.uv }, 'obj'));
      const R = r.report;
      if (args.flags.has('--json')) {
        const fields: [string, string][] = [
          ['iterations', jsonNumber(R.iterations)],
          ['maxCurvatureError', jsonNumber(R.maxCurvatureError)],
          ['flips', jsonNumber(R.flips)],
          ['euclideanFlips', jsonNumber(R.euclideanFlips)],
          ['seconds', jsonNumber(R.seconds)],
          ['invertedTriangles', jsonNumber(R.invertedTriangles)],
          ['inputTrianglesInvertedInUv', jsonNumber(R.inputTrianglesInvertedInUv)],
          ['boundaryCrossings', jsonNumber(R.boundaryCrossings)],
          ['angleDistortionMax', jsonNumber(R.angleDistortionMax)],
          ['angleDistortionMean', jsonNumber(R.angleDistortionMean)],
          ['areaDistortionRange', jsonNumber(R.areaDistortionRange)],
          ['gaussBonnetError', jsonNumber(R.gaussBonnetError)],
          ['boundaryLoops', jsonNumber(R.boundaryLoops)],
          ['corners', jsonNumber(R.corners)],
          ['residuals', `[${Array.from(R.residuals, jsonNumber).join(',')}]`],
        ];
        process.stdout.write(`{${fields.map(([k, v]) => `${jsonString(k)}:${v}`).join(',')}}\n`);
      } else {
        process.stdout.write(
          `flattened ${mesh.positions.length / 3} vertices, ${mesh.triangles.length / 3} triangles: ${R.iterations} Newton iterations, ` +
            `error ${formatG(R.maxCurvatureError, 3)}, ${R.flips} flips, ${fixed(R.seconds, 3)} s -> ${out}\n`,
        );
      }
      if (R.inputTrianglesInvertedInUv > 0 && !args.flags.has('--json'))
        process.stderr.write(
          `conformesh: warning: ${R.inputTrianglesInvertedInUv} triangles of ${out} are inverted in uv (vertex uv of input triangles; the layout has ${R.invertedTriangles})\n`,
        );
      return 0;
    },
  },
  // src/cli/cmd_remesh.cpp
  remesh: {
    usage: remeshUsage,
    summary: 'remesh a surface: conformal flattening per patch, planar Delaunay refinement, lift',
    flags: (api) => [
      { name: '-o', value: 'OUT', help: 'write the output mesh; .obj, .off, .stl or .ply picks the format; without it no file is written' },
      ...api
        .remeshSchema()
        .options.filter((o) => o.flag !== '')
        .map((o): Flag => ({ name: o.flag, value: o.value, help: o.help, ...(o.kind === 'boolean' ? {} : { default: o.default as number | string }) })),
      jsonFlag,
    ],
    async run(args, api) {
      if (args.positional.length !== 1) throw new ConformeshError('InvalidArgument', 'api', 'remesh needs exactly one input file');
      if (args.flags.has('--edge-length') && args.flags.has('--edge-length-rel'))
        throw new ConformeshError('InvalidArgument', 'api', 'give --edge-length or --edge-length-rel, not both');
      if (args.flags.has('--max-error') && args.flags.has('--max-error-rel'))
        throw new ConformeshError('InvalidArgument', 'api', 'give --max-error or --max-error-rel, not both');
      const schema = api.remeshSchema();
      const options: Record<string, unknown> = {};
      for (const o of schema.options) if (o.flag !== '') options[o.name] = optionFlag(args, o);
      const path = args.positional[0]!;
      const mesh = api.readMesh(await readFileBytes(path), { fileName: path });
      let r: RemeshResult, failure: ConformeshError | undefined;
      try {
        r = api.remesh(mesh, options);
      } catch (e) {
        // a failed result has a mesh only with --keep-defective: it is written, and still an error
        if (!(e instanceof ConformeshError && e.result)) throw e;
        [r, failure] = [e.result as RemeshResult, e];
      }
      const out = args.flags.get('-o') ?? '';
      if (out !== '') {
        const slash = Math.max(out.lastIndexOf('/'), out.lastIndexOf('\\'));
        const dot = out.lastIndexOf('.');
        const ext = dot > slash ? out.slice(dot + 1).toLowerCase() : '';
        const format = ({ obj: 'obj', off: 'off', stl: 'stl', ply: 'ply' } as const)[ext as 'obj'];
        if (!format) throw new ConformeshError('InvalidArgument', 'write', '-o: unknown extension (obj, off, stl, ply)');
        await writeFileBytes(out, api.writeMesh(r.mesh, format));
      }
      if (failure) throw failure;
      const R = r.report;
      if (args.flags.has('--json')) {
        const fields = schema.report.map((k) => `${jsonString(k)}:${jsonValue(R[k as keyof typeof R])}`);
        process.stdout.write(`{${fields.join(',')}}\n`);
      } else {
        const t = R.seconds;
        const row = (k: string, v: string) => process.stdout.write(`${k.padEnd(28)} ${v}\n`);
        row('triangles (in -> out)', `${R.inputTriangles} -> ${R.triangles}`);
        row('vertices', `${R.vertices}`);
        row('angle min / mean-min / max', `${fixed(R.minAngle, 2)} / ${fixed(R.meanMinAngle, 2)} / ${fixed(R.maxAngle, 2)} deg`);
        row('min angle outside exempt', `${fixed(R.minAngleOutsideExempt, 2)} deg (${R.trianglesBelowBoundOutsideExempt} triangles below the bound)`);
        row('below 20 / 26 / 30 deg', `${fixed(R.pctBelow20, 3)} / ${fixed(R.pctBelow26, 3)} / ${fixed(R.pctBelow30, 3)} %`);
        row('min angle >= 40 / 50 deg', `${fixed(R.pctMinAtLeast40, 2)} / ${fixed(R.pctMinAtLeast50, 2)} %`);
        row('exempt corners', `${R.exemptCorners.length}`);
        row('Hausdorff / bbox diagonal', `${formatG(R.hausdorffRel, 3)} (max vertex distance ${formatG(R.maxDistanceToInputRel, 2)})`);
        row('mean edge length', `${formatG(R.meanEdgeLength, 4)} (target ${formatG(R.targetEdgeLength, 4)})`);
        row('feature curves kept', `${R.featureCurvesKept} / ${R.featureCurves}`);
        if (R.seamEdges > 0) row('attribute seam edges kept', `${R.seamEdges}`);
        row('patches', `${R.patches} (${R.curves} curves, ${R.curveSamples} samples)`);
        row('topology preserved', R.topologyPreserved ? 'yes' : 'NO');
        for (const w of R.warnings) row('warning', w);
        row('seconds', `${REMESH_STAGES.map((s) => `${s.label} ${fixed(t[s.key], 3)}, `).join('')}total ${fixed(t.total, 3)}`);
      }
      return 0;
    },
  },
  // src/cli/cmd_info.cpp
  info: {
    usage: infoUsage,
    summary:
      'validation and topology report: vertices, faces, components, boundary loops, Euler characteristic, genus, non-manifold edges, degenerate faces, warnings',
    flags: [
      {
        name: '--weld',
        value: 'TOL',
        help: "also weld vertices closer than this, in the input's units; 0: exact duplicates in STL only",
        default: 0,
      },
      {
        name: '--format',
        value: 'NAME',
        help: 'read as obj, off, stl, stl-ascii, ply, ply-ascii or ply-be; auto: from the content',
        default: 'auto',
      },
      jsonFlag,
    ],
    async run(args, api) {
      if (args.positional.length !== 1) throw new ConformeshError('InvalidArgument', 'api', `usage: conformesh ${infoUsage}`);
      const path = args.positional[0]!;
      const weldTolerance = numberFlag(args, '--weld');
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
  lines.push('', '  conformesh COMMAND --help   flags, defaults and units of a command', '  conformesh --version        print the version');
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
  if (name === '--version') {
    process.stdout.write(`conformesh ${await packageVersion()}\n`);
    return 0;
  }
  const command = Object.prototype.hasOwnProperty.call(commands, name) ? commands[name] : undefined;
  if (!command) {
    process.stderr.write(`conformesh: unknown command '${name}'\n\n${usage()}`);
    return 2;
  }
  const json = argv.includes('--json');
  try {
    // the module is loaded before parsing only for a command whose flags come from it
    let api: Conformesh | undefined;
    const flags = typeof command.flags === 'function' ? command.flags((api = await init())) : command.flags;
    if (asksForHelp(argv.slice(1), flags)) {
      process.stdout.write(helpText(command, flags));
      return 0;
    }
    const args = parseArgs(argv.slice(1), flags);
    return await command.run(args, api ?? (await init()));
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
  // V8 runs new WebAssembly code in its baseline tier and optimizes a function only once it has
  // run a while; it cannot switch a call that is already running (no on-stack replacement for
  // wasm). A remesh spends seconds inside a few long calls, so the first one ran almost all of
  // it in baseline code. This process is ours and runs one command: have V8 optimize the whole
  // module from the start (before main() compiles it), all of it at once on its background
  // threads, not each function on the main thread at its first call (docs/decisions/0014).
  // Not done when the file is imported.
  setFlagsFromString('--no-wasm-dynamic-tiering');
  setFlagsFromString('--no-wasm-lazy-compilation');
  process.exitCode = await main(process.argv.slice(2));
}
