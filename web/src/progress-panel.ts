// The demo page's progress panel: a bar per stage the library reports (its progress events, then
// its per-stage seconds) and the status line of the running remesh.
import type { RemeshReport } from 'conformesh';
import { reportedStages, stageKey, stageLabel } from './quality.ts';
import { StageProgress, type BarUpdate } from './stages.ts';

interface Bar {
  li: HTMLLIElement;
  bar: HTMLDivElement;
  time: HTMLDivElement;
  label: HTMLSpanElement;
}

export class ProgressPanel {
  /** The progress events of the last remesh as received, and the bar values shown (for the tests). */
  readonly log: { events: { stage: string; fraction: number }[]; bars: BarUpdate[] } = { events: [], bars: [] };
  private readonly stages = new StageProgress();
  private readonly bars = new Map<string, Bar>();
  /** The running remesh, for the status line: its start, the last stage and overall fraction reported. */
  private readonly run = { startAt: NaN, stage: '', fraction: 0, timer: 0 as ReturnType<typeof setInterval> | 0 };

  /** list: the <ol> of bars; status: the status line; running: whether a remesh runs now. */
  constructor(
    private readonly list: HTMLElement,
    private readonly status: HTMLElement,
    private readonly running: () => boolean,
  ) {}

  /** Bars for these library stages (new ones only), in the order the stages keep. */
  addBars(stages: readonly string[]): void {
    if (this.stages.adopt(stages).length === 0) return;
    this.syncBars();
  }

  reset(): void {
    this.stages.reset();
    this.log.events = [];
    this.log.bars = [];
    for (const { li, bar, time, label } of this.bars.values()) {
      li.className = '';
      bar.style.width = '0';
      time.style.width = '0';
      label.textContent = '';
    }
  }

  /** The result is in: every stage has ended; each bar gets its stage's time from the report. */
  finish(report: RemeshReport): void {
    this.addBars(reportedStages(report));
    for (const u of this.stages.finish()) this.showBar(u);
    const total = report.seconds.total;
    for (const stage of reportedStages(report)) {
      const b = this.bars.get(stageKey(stage))!;
      const s = (report.seconds as unknown as Record<string, number>)[stage]!;
      b.label.textContent = `${s.toFixed(2)} s`;
      b.time.style.width = `${(100 * Math.min(1, total > 0 ? s / total : 0)).toFixed(1)}%`;
      b.li.title = `${stageLabel(stage)}: ${s.toFixed(3)} s of ${total.toFixed(3)} s`;
    }
  }

  /** A library progress event (fraction: of the whole call) shown as the stage's own progress. */
  setProgress(stage: string, fraction: number): void {
    this.log.events.push({ stage, fraction });
    const known = this.stages.values.has(stageKey(stage));
    const updates = this.stages.update(stage, fraction);
    if (!known) this.syncBars();
    for (const u of updates) this.showBar(u);
    this.run.stage = stage;
    this.run.fraction = Math.max(this.run.fraction, fraction);
    this.showRunStatus();
  }

  /** The call failed or was cancelled: the bars still running show it. */
  fail(): void {
    for (const b of this.bars.values()) if (b.li.className === 'running') b.li.className = 'failed';
  }

  /** The status line while a remesh runs (ticks every 100 ms) and after it ends. */
  startRunStatus(): void {
    Object.assign(this.run, { startAt: performance.now(), stage: '', fraction: 0 });
    this.showRunStatus();
    this.run.timer = setInterval(() => this.showRunStatus(), 100);
  }

  endRunStatus(text: string): void {
    if (this.run.timer) clearInterval(this.run.timer);
    this.run.timer = 0;
    this.status.textContent = text;
  }

  /** One <li> per stage, in the stages' order. */
  private syncBars(): void {
    for (const key of this.stages.order) {
      if (this.bars.has(key)) continue;
      const li = document.createElement('li');
      const name = document.createElement('span');
      name.textContent = stageLabel(this.stages.names.get(key)!);
      li.title = name.textContent;
      const outer = document.createElement('div');
      outer.className = 'bar';
      const bar = document.createElement('div');
      const time = document.createElement('div');
      time.className = 'time';
      outer.append(bar, time);
      const label = document.createElement('span');
      li.append(name, outer, label);
      li.dataset.stage = key;
      this.bars.set(key, { li, bar, time, label });
    }
    this.list.replaceChildren(...this.stages.order.map((k) => this.bars.get(k)!.li));
  }

  private showBar(u: BarUpdate): void {
    this.log.bars.push(u);
    const b = this.bars.get(u.stage)!;
    b.bar.style.width = `${(100 * u.value).toFixed(1)}%`;
    b.label.textContent = `${Math.floor(100 * u.value)}%`;
    b.li.className = u.value >= 1 ? 'done' : 'running';
  }

  private showRunStatus(): void {
    if (!this.running()) return;
    const elapsed = (performance.now() - this.run.startAt) / 1000;
    const stage = this.run.stage ? `${stageLabel(this.run.stage)} · ` : 'starting · ';
    this.status.textContent = `${stage}${Math.floor(100 * this.run.fraction)}% · ${elapsed.toFixed(1)} s`;
  }
}
