// A main-thread responsiveness probe: a requestAnimationFrame loop recording the longest gap
// between frames since the last reset. The page resets it when a remesh starts and reads it when
// the result is in (the gap still open then counts, up to the read). The end-to-end test measures
// with its own probe, through the result's application too.

export class FrameProbe {
  maxGap = 0;
  /** performance.now() at the end of the longest gap. */
  maxGapAt = 0;
  frames = 0;
  private last = 0;

  constructor() {
    const tick = () => {
      // performance.now(), not the rAF timestamp: the frame time of a late frame can predate the block
      const t = performance.now();
      if (this.last > 0 && t - this.last > this.maxGap) {
        this.maxGap = t - this.last;
        this.maxGapAt = t;
      }
      this.last = t;
      this.frames++;
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  }

  reset(): void {
    this.maxGap = 0;
    this.maxGapAt = 0;
    this.frames = 0;
    this.last = performance.now();
  }

  /** The longest gap so far, the one still open included. */
  read(): { maxGap: number; maxGapAt: number; frames: number } {
    const now = performance.now();
    if (this.last > 0 && now - this.last > this.maxGap) return { maxGap: now - this.last, maxGapAt: now, frames: this.frames };
    return { maxGap: this.maxGap, maxGapAt: this.maxGapAt, frames: this.frames };
  }
}
