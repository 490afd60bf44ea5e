#!/usr/bin/env bash
# Remesh every model of ../shared/data with the native CLI and score each output with the outside
# checker (../shared/tools/meshq.cpp, CGAL): one table row per model.
# usage: bash bench/models.sh BIN OUTDIR [remesh flags...]   (MODELS="a.off b.obj" for a subset)
# Installs CGAL's Debian packages when missing (as bench/run.sh does); meshq is built once into
# build/tools/meshq.
set -u
cd "$(dirname "$0")/.."
BIN=$1; OUT=$2; shift 2
DATA=${DATA:-../shared/data}
MESHQ=${MESHQ:-build/tools/meshq}
need=()
for pkg in libcgal-dev libgmp-dev libmpfr-dev; do dpkg -s "$pkg" >/dev/null 2>&1 || need+=("$pkg"); done
if [ ${#need[@]} -gt 0 ]; then
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -q && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${need[@]}" || exit 1
fi
if [ ! -x "$MESHQ" ]; then
  mkdir -p "$(dirname "$MESHQ")"
  g++ -O2 -std=c++17 -DNDEBUG ../shared/tools/meshq.cpp -o "$MESHQ" -lgmp -lmpfr || exit 1
fi
mkdir -p $OUT
MODELS=${MODELS:-"fandisk.off t13_data.stl blade.off mech-holes-shark.off holes.off camelhead.off ALSTOM_TEST4.off alligator.obj face.obj stanford-bunny.obj spot.obj 3holes.off fertility.off armadillo.off camel.off man.off elk.off ChineseDragon-10kv.off lion-head.off"}
printf "%-22s %7s %7s %5s %5s %6s %6s %4s %6s %7s %6s %8s %5s %6s\n" model tris est ratio patch curves rawmin exmp minout meanmin s60kept haus topo sec
for m in $MODELS; do
  b=${m%.*}
  s=$(date +%s%N)
  timeout ${TIMEOUT:-300} $BIN remesh "$DATA"/$m -o $OUT/$b.obj --json "$@" > $OUT/$b.json 2> $OUT/$b.err
  rc=$?
  e=$(date +%s%N)
  if [ $rc -ne 0 ] && [ ! -s $OUT/$b.json ]; then echo "$b FAILED rc=$rc $(head -c 200 $OUT/$b.err)"; continue; fi
  "$MESHQ" "$DATA"/$m $OUT/$b.obj 60 > $OUT/$b.meshq 2>/dev/null
  node -e '
const r=JSON.parse(require("fs").readFileSync(process.argv[1]));const q=JSON.parse(require("fs").readFileSync(process.argv[2]));
const f=(x,d)=>x.toFixed(d);
console.log([process.argv[3].padEnd(22),String(r.triangles).padStart(7),String(Math.round(r.estimatedTriangles)).padStart(7),f(r.triangles/r.estimatedTriangles,2).padStart(5),String(r.patches).padStart(5),String(r.featureCurves).padStart(6),f(q.cand.min_angle,2).padStart(6),String(r.exemptCorners.length).padStart(4),f(r.minAngleOutsideExempt,2).padStart(6),f(q.cand.mean_min_angle,2).padStart(7),f(q.features.kept_pct,1).padStart(6),Math.max(q.hausdorff_rel.cand_to_ref,q.hausdorff_rel.ref_to_cand).toExponential(2).padStart(8),(q.topology_same&&r.topologyPreserved?"ok":"BAD").padStart(5),f(+process.argv[4] / 1000,1).padStart(6)].join(" "))' $OUT/$b.json $OUT/$b.meshq $b $(( (e - s) / 1000000 ))
done
