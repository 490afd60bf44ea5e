// The angle histogram: share of triangle angles per 2° bin, input (grey, filled) vs remesh
// (outline), with the minimum-angle target marked.

const BIN = 2;
const BINS = 180 / BIN;

export function binAngles(angles: Float64Array): Float64Array {
  const h = new Float64Array(BINS);
  for (let i = 0; i < angles.length; ++i) h[Math.min(BINS - 1, Math.max(0, Math.floor(angles[i]! / BIN)))]! += 1;
  const n = Math.max(1, angles.length);
  for (let i = 0; i < BINS; ++i) h[i]! /= n;
  return h;
}

export function drawHistogram(canvas: HTMLCanvasElement, input: Float64Array | undefined, output: Float64Array | undefined, target: number): void {
  const dpr = Math.min(2, window.devicePixelRatio || 1);
  const cssW = canvas.clientWidth || canvas.width;
  const cssH = canvas.clientHeight || canvas.height;
  canvas.width = Math.round(cssW * dpr);
  canvas.height = Math.round(cssH * dpr);
  const g = canvas.getContext('2d')!;
  g.setTransform(dpr, 0, 0, dpr, 0, 0);
  g.clearRect(0, 0, cssW, cssH);
  const L = 28, R = 14, T = 16, B = 18;
  const w = cssW - L - R, h = cssH - T - B;
  const hi = binAngles(input ?? new Float64Array());
  const ho = binAngles(output ?? new Float64Array());
  let top = 0;
  for (let i = 0; i < BINS; ++i) top = Math.max(top, input ? hi[i]! : 0, output ? ho[i]! : 0);
  top = top > 0 ? top * 1.08 : 1;
  const x = (deg: number) => L + (deg / 180) * w;
  const y = (share: number) => T + h - (share / top) * h;

  g.font = '10px system-ui, sans-serif';
  g.strokeStyle = '#30343d';
  g.fillStyle = '#8a91a0';
  g.lineWidth = 1;
  for (const deg of [0, 30, 60, 90, 120, 150, 180]) {
    g.beginPath();
    g.moveTo(x(deg) + 0.5, T);
    g.lineTo(x(deg) + 0.5, T + h);
    g.stroke();
    g.fillText(`${deg}°`, x(deg) - 8, cssH - 5);
  }
  g.fillText(`${(top * 100).toFixed(0)}%`, 2, T + 4);
  if (input) {
    g.fillStyle = 'rgba(160,168,184,0.45)';
    for (let i = 0; i < BINS; ++i) {
      if (hi[i]! > 0) g.fillRect(x(i * BIN), y(hi[i]!), Math.max(1, x(BIN) - x(0) - 0.5), T + h - y(hi[i]!));
    }
  }
  if (output) {
    g.strokeStyle = '#5aa9ff';
    g.lineWidth = 1.5;
    g.beginPath();
    g.moveTo(x(0), y(0));
    for (let i = 0; i < BINS; ++i) {
      g.lineTo(x(i * BIN), y(ho[i]!));
      g.lineTo(x((i + 1) * BIN), y(ho[i]!));
    }
    g.lineTo(x(180), y(0));
    g.stroke();
  }
  g.strokeStyle = '#ff6b5a';
  g.setLineDash([3, 3]);
  g.beginPath();
  g.moveTo(x(target) + 0.5, T);
  g.lineTo(x(target) + 0.5, T + h);
  g.stroke();
  g.setLineDash([]);
  g.fillStyle = '#dde1e8';
  g.fillText('input', L + w - 86, T + 2);
  g.fillStyle = '#5aa9ff';
  g.fillText('remesh', L + w - 44, T + 2);
}
