// Colour maps of the views.

export type RGB = [number, number, number];

/** A distinct colour per patch id (golden-ratio hue steps, two lightness levels). */
export function patchColor(id: number): RGB {
  const h = (id * 0.618033988749895) % 1;
  const l = id % 2 === 0 ? 0.62 : 0.5;
  return hsl(h, 0.55, l);
}

export function hsl(h: number, s: number, l: number): RGB {
  const f = (n: number) => {
    const k = (n + h * 12) % 12;
    const a = s * Math.min(l, 1 - l);
    return l - a * Math.max(-1, Math.min(k - 3, 9 - k, 1));
  };
  return [f(0), f(8), f(4)];
}

// A perceptually ordered ramp (dark blue -> teal -> yellow), sampled at 5 stops.
const RAMP: RGB[] = [
  [0.19, 0.11, 0.42],
  [0.16, 0.39, 0.56],
  [0.13, 0.6, 0.54],
  [0.47, 0.8, 0.33],
  [0.99, 0.9, 0.15],
];

/** Ramp colour for s in [0, 1] (clamped). */
export function ramp(s: number): RGB {
  const x = Math.min(1, Math.max(0, Number.isFinite(s) ? s : 0)) * (RAMP.length - 1);
  const i = Math.min(RAMP.length - 2, Math.floor(x));
  const u = x - i;
  const a = RAMP[i]!, b = RAMP[i + 1]!;
  return [a[0] + (b[0] - a[0]) * u, a[1] + (b[1] - a[1]) * u, a[2] + (b[2] - a[2]) * u];
}

/**
 * Colour of a triangle's minimum angle (degrees): red below 20°, orange to 30°, then green
 * shades brightening towards 60° (the equilateral triangle).
 */
export function minAngleColor(deg: number): RGB {
  if (deg < 20) return [0.9, 0.22, 0.18];
  if (deg < 30) return [0.95, 0.6, 0.15];
  const s = Math.min(1, (deg - 30) / 30);
  return [0.2 + 0.25 * s, 0.55 + 0.3 * s, 0.35 + 0.25 * s];
}

export function css(c: RGB): string {
  return `rgb(${Math.round(c[0] * 255)},${Math.round(c[1] * 255)},${Math.round(c[2] * 255)})`;
}
