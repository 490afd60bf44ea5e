// CTest: `conformesh COMMAND --help` on every command of src/cli/. The flags are taken from each
// command's source (every "-x" / "--name" string literal of cmd_NAME.cpp: its flag table and the
// flags its code reads; for remesh also include/conformesh/remesh_schema.h, the option table its flags come
// from), never from a list kept here. Checks: --help and -h exit 0 and print the
// same text; every such flag the parser accepts has a line in the help, and every flag the help
// lists is accepted; unknown options still fail; --version prints package.json's version.
// usage: node cli_help.mjs CONFORMESH_EXE SOURCE_DIR
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readdirSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { check, finish } from './check.mjs';

const [exe, sourceDir] = process.argv.slice(2);

const run = (args) => spawnSync(exe, args, { encoding: 'utf8' });
const unknown = (r, flag) => r.stderr.includes(`unknown option ${flag}`) || r.stdout.includes(`unknown option ${flag}`);

const cliDir = join(sourceDir, 'src', 'cli');
const commands = [];
for (const file of readdirSync(cliDir).filter((f) => /^cmd_.*\.cpp$/.test(f)).sort()) {
  const text = readFileSync(join(cliDir, file), 'utf8');
  const name = text.match(/CommandRegistrar\s+\w+\(\{\s*"([a-z0-9]+)"/)?.[1];
  check(name !== undefined, `${file}: registers a command`);
  if (!name) continue;
  const tables = name === 'remesh' ? readFileSync(join(sourceDir, 'include', 'conformesh', 'remesh_schema.h'), 'utf8') : '';
  const flags = [...new Set([...(text + tables).matchAll(/"(--?[a-z](?:[a-z0-9-]*[a-z0-9])?)"/g)].map((m) => m[1]))];
  commands.push({ name, file, flags });
}
check(commands.some((c) => c.name === 'remesh'), 'remesh is among the commands found');

for (const { name, file, flags } of commands) {
  const help = run([name, '--help']);
  check(help.status === 0, `${name} --help: exit 0 (got ${help.status}: ${help.stderr})`);
  check(help.stdout.startsWith(`usage: conformesh ${name}`), `${name} --help: starts with its usage line`);
  check(help.stderr === '', `${name} --help: nothing on stderr`);
  const short = run([name, '-h']);
  check(short.status === 0 && short.stdout === help.stdout, `${name} -h: exit 0, the same text as --help`);
  // after other flags and positionals too
  const late = run([name, 'some-file', '--json', '--help']);
  check(late.status === 0 && late.stdout === help.stdout, `${name} FILE --json --help: the help`);

  // the flags the help lists: the first word of each option line
  const listed = [...help.stdout.matchAll(/^ {2}(--?[a-z][a-z0-9-]*)/gm)].map((m) => m[1]).filter((f) => f !== '-h');
  check(listed.length > 0, `${name} --help lists options`);
  for (const flag of flags) {
    if (flag === '--help' || flag === '-h') continue;
    const accepted = !unknown(run([name, flag]), flag);
    check(accepted, `${name}: ${flag} (read in ${file}) is accepted by the parser`);
    if (accepted) check(listed.includes(flag), `${name} --help lists ${flag}, which the parser accepts`);
  }
  for (const flag of listed) {
    check(!unknown(run([name, flag]), flag), `${name}: ${flag}, listed by --help, is accepted by the parser`);
    check(flags.includes(flag), `${name}: ${flag}, listed by --help, is in ${file}`);
  }
  // every option with a value says its value and a default or that it is required
  for (const line of help.stdout.split(/\n(?=  -)/).filter((l) => /^ {2}--?[a-z]/.test(l))) {
    const text = line.replace(/\s+/g, ' ');
    if (/^ {2}--?[a-z][a-z0-9-]* \S/.test(line) && !/^ -o /.test(text))
      check(/\(default [^)]+\)|required/.test(text), `${name} --help: '${text.slice(0, 40)}…' gives its default`);
  }

  const bad = run([name, '--frobnicate']);
  check(bad.status !== 0 && unknown(bad, '--frobnicate'), `${name} --frobnicate: fails with "unknown option --frobnicate"`);
}

// remesh: the defaults the help prints are the ones a run uses: every value flag given its
// printed default gives the same bytes as no flag at all (--edge-length and --max-error aside:
// they exclude --edge-length-rel and --max-error-rel).
{
  const dir = mkdtempSync(join(tmpdir(), 'conformesh-help-'));
  try {
    const help = run(['remesh', '--help']).stdout.replace(/\s+/g, ' ');
    // a flag's default within its own text: a switch without one (--no-inner-creases) gives none
    const given = [...help.matchAll(/ (--[a-z][a-z0-9-]*) \S+ (?:(?! --)[^(])*?\(default ([^)]+)\)/g)]
      .filter(([, flag]) => flag !== '--edge-length' && flag !== '--max-error')
      .flatMap(([, flag, value]) => [flag, value]);
    check(given.includes('--min-angle') && given.includes('--boundary'), `remesh --help: defaults found (${given.join(' ')})`);
    const cube = join(dir, 'cube.off');
    check(run(['generate', 'cube', '--level', '3', '-o', cube]).status === 0, 'generate cube');
    const plain = run(['remesh', cube, '-o', join(dir, 'plain.obj'), '--no-hausdorff']);
    const explicit = run(['remesh', cube, '-o', join(dir, 'explicit.obj'), '--no-hausdorff', ...given]);
    check(plain.status === 0 && explicit.status === 0, `remesh with the printed defaults: exit 0 (${explicit.stderr})`);
    check(plain.status === 0 && readFileSync(join(dir, 'plain.obj')).equals(readFileSync(join(dir, 'explicit.obj'))),
      'remesh with every printed default writes the same bytes as remesh without flags');
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

const version = JSON.parse(readFileSync(join(sourceDir, 'package.json'), 'utf8')).version;
const v = run(['--version']);
check(v.status === 0 && v.stdout === `conformesh ${version}\n`, `--version prints "conformesh ${version}" (got ${v.stdout})`);
const top = run(['--help']);
check(top.status === 0, '--help: exit 0');
for (const { name } of commands) check(top.stdout.includes(`conformesh ${name} `), `--help lists ${name}`);
check(/COMMAND --help/.test(top.stdout) && /--version/.test(top.stdout), '--help mentions COMMAND --help and --version');

finish();
