// The counting check of the CTest scripts in this folder: check(ok, what) records a result and
// prints what failed; finish() prints the tally and exits 1 when anything failed.
let failures = 0;
let checks = 0;

export function check(ok, what) {
  checks++;
  if (!ok) {
    failures++;
    console.error(`FAIL: ${what}`);
  }
}

export function finish() {
  console.log(`${checks - failures}/${checks} checks passed`);
  process.exit(failures ? 1 : 0);
}
