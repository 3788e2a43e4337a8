// The worker's job queue: one job runs at a time; a new prediction from a view supersedes that
// view's queued job and cancels its running one, while other views' jobs wait their turn.

export interface Job {
  id: number;
  /** The view (page instance) a prediction belongs to; loads have none and are never superseded. */
  view?: string;
  cancelled: boolean;
}

export class Scheduler<J extends Job> {
  private queue: J[] = [];
  running: J | null = null;

  /** Queue a job; returns the queued jobs it superseded (to be answered "superseded"). */
  push(job: J): J[] {
    const dropped: J[] = [];
    if (job.view !== undefined) {
      this.queue = this.queue.filter((q) => {
        if (q.view !== job.view) return true;
        dropped.push(q);
        return false;
      });
      if (this.running && this.running.view === job.view) this.running.cancelled = true;
    }
    this.queue.push(job);
    return dropped;
  }

  /** Run queued jobs one after another until the queue is empty; re-entrant calls return at once. */
  async drain(run: (job: J) => Promise<void>): Promise<void> {
    if (this.running) return;
    for (let job = this.queue.shift(); job; job = this.queue.shift()) {
      this.running = job;
      try {
        await run(job);
      } finally {
        this.running = null;
      }
    }
  }
}
