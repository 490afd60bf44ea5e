// A CAD-like sample part generated in code: a mounting plate (80 × 50 × 8 mm) with rounded
// corners, four bolt holes and a slot, a 2 mm fillet along every top edge (outline and holes)
// and sharp bottom edges. A closed, consistently oriented genus-5 triangle mesh.
//
// Every outline is an offset curve of the same arcs (corner arcs, circles, the slot's stadium),
// so the rings of the fillet are sampled with the same points per ring and joined by quads. The
// flat caps are triangulated by ear clipping (three.js ShapeUtils): long, thin triangles, like a
// typical CAD tessellation — exactly what the remesher is for.
import { ShapeUtils, Vector2 } from 'three';

export interface PlateOptions {
  width: number;
  height: number;
  thickness: number;
  cornerRadius: number;
  fillet: number;
  holeRadius: number;
}

const DEFAULTS: PlateOptions = { width: 80, height: 50, thickness: 8, cornerRadius: 10, fillet: 2, holeRadius: 4 };

/** A closed outline as a function of the offset d into the material: 2D points, the loop's order fixed. */
type Loop = (d: number) => [number, number][];

function roundedRect(hw: number, hh: number, r: number, perCorner: number): Loop {
  return (d) => {
    const pts: [number, number][] = [];
    const corners: [number, number, number][] = [
      [hw - r, hh - r, 0],
      [-(hw - r), hh - r, Math.PI / 2],
      [-(hw - r), -(hh - r), Math.PI],
      [hw - r, -(hh - r), (3 * Math.PI) / 2],
    ];
    for (const [cx, cy, a0] of corners) {
      for (let k = 0; k <= perCorner; ++k) {
        const a = a0 + (k / perCorner) * (Math.PI / 2);
        pts.push([cx + (r - d) * Math.cos(a), cy + (r - d) * Math.sin(a)]);
      }
    }
    return pts; // counter-clockwise seen from +z
  };
}

function circle(cx: number, cy: number, r: number, n: number): Loop {
  return (d) => {
    const pts: [number, number][] = [];
    for (let k = 0; k < n; ++k) {
      const a = (-2 * Math.PI * k) / n; // clockwise: a hole
      pts.push([cx + (r + d) * Math.cos(a), cy + (r + d) * Math.sin(a)]);
    }
    return pts;
  };
}

function slot(cx: number, cy: number, halfLength: number, r: number, perEnd: number): Loop {
  return (d) => {
    const pts: [number, number][] = [];
    // clockwise: right end from top (+90°) down to bottom (-90°), then the left end
    for (let k = 0; k <= perEnd; ++k) {
      const a = Math.PI / 2 - (k / perEnd) * Math.PI;
      pts.push([cx + halfLength + (r + d) * Math.cos(a), cy + (r + d) * Math.sin(a)]);
    }
    for (let k = 0; k <= perEnd; ++k) {
      const a = -Math.PI / 2 - (k / perEnd) * Math.PI;
      pts.push([cx - halfLength + (r + d) * Math.cos(a), cy + (r + d) * Math.sin(a)]);
    }
    return pts;
  };
}

export function mountingPlate(options: Partial<PlateOptions> = {}): { positions: Float64Array; triangles: Uint32Array } {
  const o = { ...DEFAULTS, ...options };
  const hw = o.width / 2, hh = o.height / 2, f = o.fillet, T = o.thickness;
  const loops: Loop[] = [
    roundedRect(hw, hh, o.cornerRadius, 8),
    circle(hw - 10, hh - 10, o.holeRadius, 24),
    circle(-(hw - 10), hh - 10, o.holeRadius, 24),
    circle(-(hw - 10), -(hh - 10), o.holeRadius, 24),
    circle(hw - 10, -(hh - 10), o.holeRadius, 24),
    slot(0, 0, 12, 5, 12),
  ];
  // the wall profile: (offset into the material, z) from the bottom edge up over the fillet
  const profile: [number, number][] = [[0, 0], [0, T - f]];
  const filletSteps = 5;
  for (let j = 1; j <= filletSteps; ++j) {
    const t = (j / filletSteps) * (Math.PI / 2);
    profile.push([f * (1 - Math.cos(t)), T - f + f * Math.sin(t)]);
  }

  const positions: number[] = [];
  const triangles: number[] = [];
  const bottomRings: number[][] = [];
  const topRings: number[][] = [];
  const topPoints: [number, number][][] = [];
  for (const loop of loops) {
    const rings: number[][] = [];
    for (const [d, z] of profile) {
      const pts = loop(d);
      const ring: number[] = [];
      for (const [x, y] of pts) {
        ring.push(positions.length / 3);
        positions.push(x, y, z);
      }
      rings.push(ring);
    }
    for (let r = 0; r + 1 < rings.length; ++r) {
      const lo = rings[r]!, hi = rings[r + 1]!, n = lo.length;
      for (let i = 0; i < n; ++i) {
        const j = (i + 1) % n;
        triangles.push(lo[i]!, lo[j]!, hi[j]!, lo[i]!, hi[j]!, hi[i]!);
      }
    }
    bottomRings.push(rings[0]!);
    topRings.push(rings[rings.length - 1]!);
    topPoints.push(loop(profile[profile.length - 1]![0]));
  }

  // caps: ear clipping of the outline with its holes, oriented +z on top and -z at the bottom
  const bottomPoints = loops.map((loop) => loop(0));
  const cap = (pts: [number, number][][], rings: number[][], up: boolean) => {
    const contour = pts[0]!.map(([x, y]) => new Vector2(x, y));
    const holes = pts.slice(1).map((h) => h.map(([x, y]) => new Vector2(x, y)));
    const ids = rings.flat();
    const flatPts = pts.flat();
    for (const tri of ShapeUtils.triangulateShape(contour, holes)) {
      const a = tri[0]!, b = tri[1]!, c = tri[2]!;
      const pa = flatPts[a]!, pb = flatPts[b]!, pc = flatPts[c]!;
      const area = (pb[0] - pa[0]) * (pc[1] - pa[1]) - (pb[1] - pa[1]) * (pc[0] - pa[0]);
      if (area > 0 === up) triangles.push(ids[a]!, ids[b]!, ids[c]!);
      else triangles.push(ids[a]!, ids[c]!, ids[b]!);
    }
  };
  cap(topPoints, topRings, true);
  cap(bottomPoints, bottomRings, false);
  return { positions: Float64Array.from(positions), triangles: Uint32Array.from(triangles) };
}

/** The plate as an OFF file (what the page reads, through the library's reader like any file). */
export function mountingPlateOff(options: Partial<PlateOptions> = {}): string {
  const { positions, triangles } = mountingPlate(options);
  const lines = ['OFF', `${positions.length / 3} ${triangles.length / 3} 0`];
  for (let i = 0; i < positions.length; i += 3) {
    lines.push(`${+positions[i]!.toFixed(6)} ${+positions[i + 1]!.toFixed(6)} ${+positions[i + 2]!.toFixed(6)}`);
  }
  for (let i = 0; i < triangles.length; i += 3) lines.push(`3 ${triangles[i]} ${triangles[i + 1]} ${triangles[i + 2]}`);
  return lines.join('\n') + '\n';
}
