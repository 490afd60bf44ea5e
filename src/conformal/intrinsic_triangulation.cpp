#include "conformal/intrinsic_triangulation.h"

#include "core/bucket_sort.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "conformal/triangle_geometry.h"
#include "core/detmath.h"

namespace conformesh::conformal {

namespace {

[[noreturn]] void reject(Code code, const std::string& msg) { fail(code, Stage::Flatten, msg); }

double cornerHoro(const IntrinsicTriangulation& T, int g) { return T.cornerSize(g); }

}  // namespace

bool IntrinsicTriangulation::canFlip(int e) const {
  const int h = edgeHalf[e];
  const int t = twin[h];
  return t >= 0 && t / 3 != h / 3 && (locked.empty() || !locked[size_t(e)]);
}

double IntrinsicTriangulation::cornerSize(int g) const {
  if (positionKind == PositionKind::Horocyclic)
    return dmath::exp(0.5 * (lambda[edge[next(g)]] - lambda[edge[g]] - lambda[edge[prev(g)]]));
  const int f = g / 3;
  double lam[3] = {lambda[edge[3 * f]], lambda[edge[3 * f + 1]], lambda[edge[3 * f + 2]]};
  double ang[3];
  anglesFromLogLengths(lam, ang);
  return ang[next(g) % 3];  // the corner at g's origin is opposite next(g)
}

void IntrinsicTriangulation::resetOrigins() {
  for (int e = 0; e < nE; ++e) origin[e] = e;
}

void IntrinsicTriangulation::resetPositions(PositionKind kind) {
  positionKind = kind;
  const int nH = 3 * nF;
  std::vector<int> start(nV, -1);
  for (int h = 0; h < nH; ++h)
    if (start[vert[h]] < 0 || twin[h] < 0) start[vert[h]] = h;
  for (int v = 0; v < nV; ++v) {
    int g = start[v], count = 0;
    double acc = 0.0;
    do {
      horoPos[g] = acc;
      acc += cornerSize(g);
      const int p = twin[prev(g)];
      if (p < 0) break;
      g = p;
    } while (g != start[v] && ++count <= nH);
    horoTotal[v] = acc;
  }
}

void IntrinsicTriangulation::flipEuclidean(int e) {
  // Quad (a,b,c) + (b,a,d); lay it out with a = 0, b on the x axis, c above, d below.
  const int h0 = edgeHalf[e], h1 = next(h0), h2 = next(h1);
  const int t0 = twin[h0], t1 = next(t0), t2 = next(t1);
  double angF[3], angG[3];
  double lamF[3] = {lambda[edge[3 * (h0 / 3)]], lambda[edge[3 * (h0 / 3) + 1]], lambda[edge[3 * (h0 / 3) + 2]]};
  double lamG[3] = {lambda[edge[3 * (t0 / 3)]], lambda[edge[3 * (t0 / 3) + 1]], lambda[edge[3 * (t0 / 3) + 2]]};
  anglesFromLogLengths(lamF, angF);
  anglesFromLogLengths(lamG, angG);
  const double thA1 = angF[h1 % 3];  // at a in F, opposite b->c
  const double thA2 = angG[t2 % 3];  // at a in G, opposite d->b
  const double lac = dmath::exp(0.5 * lambda[edge[h2]]), lad = dmath::exp(0.5 * lambda[edge[t1]]);
  const double cx = lac * dmath::cos(thA1), cy = lac * dmath::sin(thA1);
  const double dx = lad * dmath::cos(thA2), dy = -lad * dmath::sin(thA2);
  const double l2 = (cx - dx) * (cx - dx) + (cy - dy) * (cy - dy);
  flipWithLambda(e, dmath::log(l2));
}

void IntrinsicTriangulation::flip(int e) {
  const int h0 = edgeHalf[e];
  const int h1 = next(h0), h2 = next(h1);
  const int t0 = twin[h0];
  const int t1 = next(t0), t2 = next(t1);
  const double lac = lambda[edge[h2]], lbc = lambda[edge[h1]];
  const double lad = lambda[edge[t1]], lbd = lambda[edge[t2]];
  const double lab = lambda[e];
  // Ptolemy in log form: lam_cd = 2 log(l_ac l_bd + l_ad l_bc) - lam_ab.
  const double x = 0.5 * (lac + lbd), y = 0.5 * (lad + lbc);
  const double mx = std::max(x, y);
  flipWithLambda(e, 2.0 * (mx + dmath::log1p(dmath::exp(-std::fabs(x - y)))) - lab);
}

void IntrinsicTriangulation::flipWithLambda(int e, double lcd) {
  // Quad: face F0 = (a,b,c) with h0 = a->b, h1 = b->c, h2 = c->a; face F1 = (b,a,d) with
  // t0 = b->a, t1 = a->d, t2 = d->b. After the flip F0 = (d,c,a), F1 = (c,d,b).
  const int h0 = edgeHalf[e];
  const int h1 = next(h0), h2 = next(h1);
  const int t0 = twin[h0];
  const int t1 = next(t0), t2 = next(t1);
  const int c = vert[h2], d = vert[t2];

  struct Half {
    int vert, twin, edge;
    double pos;
  };
  auto load = [&](int h) { return Half{vert[h], twin[h], edge[h], horoPos[h]}; };
  const Half A1 = load(h1), A2 = load(h2), B1 = load(t1), B2 = load(t2);
  // New slots: h1 <- c->a (A2), h2 <- a->d (B1), t1 <- d->b (B2), t2 <- b->c (A1).
  const int oldSlot[4] = {h2, t1, t2, h1};
  const int newSlot[4] = {h1, h2, t1, t2};
  const Half* data[4] = {&A2, &B1, &B2, &A1};
  auto remap = [&](int tw) {
    for (int k = 0; k < 4; ++k)
      if (tw == oldSlot[k]) return newSlot[k];
    return tw;
  };
  for (int k = 0; k < 4; ++k) {
    const int s = newSlot[k];
    vert[s] = data[k]->vert;
    twin[s] = data[k]->twin < 0 ? -1 : remap(data[k]->twin);
    edge[s] = data[k]->edge;
    horoPos[s] = data[k]->pos;
  }
  for (int k = 0; k < 4; ++k) {
    const int s = newSlot[k];
    if (twin[s] >= 0) twin[twin[s]] = s;
    edgeHalf[edge[s]] = s;
  }
  vert[h0] = d;
  vert[t0] = c;
  twin[h0] = t0;
  twin[t0] = h0;
  lambda[e] = lcd;
  origin[e] = -1;
  edgeHalf[e] = h0;

  // Positions of the new halfedges: d->c follows d->b counter-clockwise at d inside
  // face (c,d,b); c->d follows c->a at c inside face (d,c,a).
  auto wrap = [&](int v, double p) {
    if (boundaryVertex[v]) return p;
    const double H = horoTotal[v];
    p = std::fmod(p, H);
    return p < 0 ? p + H : p;
  };
  horoPos[h0] = wrap(d, horoPos[t1] + cornerHoro(*this, t1));  // t1 = d->b in face F1
  horoPos[t0] = wrap(c, horoPos[h1] + cornerHoro(*this, h1));  // h1 = c->a in face F0
  ++flips;
}

IntrinsicTriangulation buildIntrinsicTriangulation(const MeshBuffers& mesh) {
  if (mesh.positions.size() % 3 != 0 || mesh.triangles.size() % 3 != 0)
    reject(Code::InvalidArgument, "positions and triangles must have a multiple of 3 entries");
  const size_t nV = mesh.vertexCount(), nF = mesh.triangleCount();
  if (nV == 0 || nF == 0) reject(Code::EmptyMesh, "flatten: the patch has no vertices or no faces");
  if (nV > 50'000'000 || nF > 100'000'000) reject(Code::TooLarge, "flatten: patch too large");
  for (double p : mesh.positions)
    if (!std::isfinite(p)) reject(Code::NonFiniteCoordinate, "flatten: a coordinate is not finite");

  IntrinsicTriangulation T;
  T.nV = int(nV);
  T.nF = int(nF);
  const int nH = 3 * T.nF;
  T.vert.resize(nH);
  for (int h = 0; h < nH; ++h) {
    const uint32_t v = mesh.triangles[h];
    if (v >= nV) reject(Code::IndexOutOfRange, "flatten: face " + std::to_string(h / 3) + " refers to vertex " + std::to_string(v));
    T.vert[h] = int(v);
  }
  for (int f = 0; f < T.nF; ++f) {
    const int a = T.vert[3 * f], b = T.vert[3 * f + 1], c = T.vert[3 * f + 2];
    if (a == b || b == c || c == a) reject(Code::DegenerateFace, "flatten: face " + std::to_string(f) + " repeats a vertex");
  }

  // Twins by sorting undirected keys.
  struct Key {
    int lo, hi, h;
  };
  std::vector<Key> keys(nH);
  for (int h = 0; h < nH; ++h) {
    const int a = T.vert[h], b = T.tip(h);
    keys[h] = {std::min(a, b), std::max(a, b), h};
  }
  int maxLo = 0;
  for (const Key& k : keys) maxLo = std::max(maxLo, k.lo);
  bucketSort(keys, size_t(maxLo) + 1, [](const Key& k) { return k.lo; }, [](const Key& x, const Key& y) {
    return x.lo != y.lo ? x.lo < y.lo : (x.hi != y.hi ? x.hi < y.hi : x.h < y.h);
  });
  T.twin.assign(nH, -1);
  T.edge.assign(nH, -1);
  for (size_t i = 0; i < keys.size();) {
    size_t j = i + 1;
    while (j < keys.size() && keys[j].lo == keys[i].lo && keys[j].hi == keys[i].hi) ++j;
    const int e = T.nE++;
    if (j - i > 2)
      reject(Code::NonManifoldEdge, "flatten: edge " + std::to_string(keys[i].lo) + "-" + std::to_string(keys[i].hi) + " has more than two faces");
    const int h = keys[i].h;
    T.edge[h] = e;
    T.edgeHalf.push_back(h);
    if (j - i == 2) {
      const int g = keys[i + 1].h;
      if (T.vert[h] == T.vert[g])
        reject(Code::InconsistentOrientation, "flatten: faces " + std::to_string(h / 3) + " and " + std::to_string(g / 3) + " disagree on orientation");
      T.twin[h] = g;
      T.twin[g] = h;
      T.edge[g] = e;
    }
    i = j;
  }
  T.origin.resize(T.nE);
  for (int e = 0; e < T.nE; ++e) T.origin[e] = e;

  // Log lengths, degenerate faces.
  T.lambda.resize(T.nE);
  const double* P = mesh.positions.data();
  for (int e = 0; e < T.nE; ++e) {
    const int h = T.edgeHalf[e];
    const int a = T.vert[h], b = T.tip(h);
    const double dx = P[3 * a] - P[3 * b], dy = P[3 * a + 1] - P[3 * b + 1], dz = P[3 * a + 2] - P[3 * b + 2];
    const double l2 = dx * dx + dy * dy + dz * dz;
    if (!(l2 > 0.0)) reject(Code::DegenerateFace, "flatten: zero-length edge between vertices " + std::to_string(a) + " and " + std::to_string(b));
    T.lambda[e] = dmath::log(l2);
  }
  for (int f = 0; f < T.nF; ++f) {
    double lam[3] = {T.lambda[T.edge[3 * f]], T.lambda[T.edge[3 * f + 1]], T.lambda[T.edge[3 * f + 2]]};
    double ang[3];
    if (!anglesFromLogLengths(lam, ang) || !(ang[0] > 0 && ang[1] > 0 && ang[2] > 0))
      reject(Code::DegenerateFace, "flatten: face " + std::to_string(f) + " has zero area");
  }

  // Vertex fans: manifold vertices; boundary vertices start at their boundary halfedge.
  std::vector<int> degree(nV, 0), boundaryOut(nV, -1);
  for (int h = 0; h < nH; ++h) {
    ++degree[T.vert[h]];
    if (T.twin[h] < 0) {
      if (boundaryOut[T.vert[h]] >= 0)
        reject(Code::NonManifoldVertex, "flatten: vertex " + std::to_string(T.vert[h]) + " has more than one boundary fan");
      boundaryOut[T.vert[h]] = h;
    }
  }
  std::vector<int> anyOut(nV, -1);
  for (int h = 0; h < nH; ++h)
    if (anyOut[T.vert[h]] < 0) anyOut[T.vert[h]] = h;
  T.boundaryVertex.assign(nV, 0);
  T.horoPos.assign(nH, 0.0);
  T.horoTotal.assign(nV, 0.0);
  for (size_t v = 0; v < nV; ++v) {
    if (degree[v] == 0) reject(Code::InvalidTopology, "flatten: vertex " + std::to_string(v) + " is not used by any face");
    T.boundaryVertex[v] = boundaryOut[v] >= 0;
    const int start = boundaryOut[v] >= 0 ? boundaryOut[v] : anyOut[v];
    int g = start, count = 0;
    double acc = 0.0;
    do {
      T.horoPos[g] = acc;
      acc += cornerHoro(T, g);
      ++count;
      const int p = T.twin[IntrinsicTriangulation::prev(g)];
      if (p < 0) break;
      g = p;
    } while (g != start && count <= degree[v]);
    if (count != degree[v])
      reject(Code::NonManifoldVertex, "flatten: the faces around vertex " + std::to_string(v) + " do not form one fan");
    T.horoTotal[v] = acc;
  }

  // One connected component.
  {
    std::vector<char> seen(nF, 0);
    std::vector<int> stack = {0};
    seen[0] = 1;
    size_t reached = 1;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int t = T.twin[3 * f + k];
        if (t >= 0 && !seen[t / 3]) {
          seen[t / 3] = 1;
          ++reached;
          stack.push_back(t / 3);
        }
      }
    }
    if (reached != nF) reject(Code::InvalidTopology, "flatten: the patch has more than one connected component");
  }

  // Boundary loops.
  std::vector<char> used(nH, 0);
  for (int h = 0; h < nH; ++h) {
    if (T.twin[h] >= 0 || used[h]) continue;
    std::vector<int> loop, loopE;
    int g = h;
    while (!used[g]) {
      used[g] = 1;
      loop.push_back(T.vert[g]);
      loopE.push_back(T.edge[g]);
      g = boundaryOut[T.tip(g)];
      if (g < 0) reject(Code::InternalError, "flatten: broken boundary loop");
    }
    T.loops.push_back(std::move(loop));
    T.loopEdges.push_back(std::move(loopE));
  }
  const long long chi = (long long)nV - T.nE + (long long)nF;
  const long long b = (long long)T.loops.size();
  if (b == 0) reject(Code::InvalidTopology, "flatten: the patch is closed; cut it into disks first");
  if (2 - chi - b != 0)
    reject(Code::InvalidTopology, "flatten: the patch has genus " + std::to_string((2 - chi - b) / 2) +
                                      "; only planar domains (disks, disks with holes) can be flattened");
  return T;
}

}  // namespace conformesh::conformal
