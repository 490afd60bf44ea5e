// A main-thread responsiveness probe: a requestAnimationFrame loop recording the longest gap
// between frames since the last reset. The page resets it when a remesh starts and reads it when
// the result is in; the end-to-end test reads it too (window.conformeshPage.probe).

export class FrameProbe {
  maxGap = 0;
  frames = 0;
  private last = 0;

  constructor() {
    const tick = () => {
      // performance.now(), not the rAF timestamp: the frame time of a late frame can predate the block
      const t = performance.now();
      if (this.last > 0) this.maxGap = Math.max(this.maxGap, t - this.last);
      this.last = t;
      this.frames++;
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  }

  reset(): void {
    this.maxGap = 0;
    this.frames = 0;
    this.last = performance.now();
  }

  read(): { maxGap: number; frames: number } {
    return { maxGap: this.maxGap, frames: this.frames };
  }
}
