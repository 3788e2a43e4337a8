import { describe, expect, it } from 'vitest';
import { Scheduler, type Job } from '../../web/src/predictor/scheduler';

const job = (id: number, view?: string): Job => ({ id, view, cancelled: false });

describe('worker scheduler', () => {
  it('a new request from a view supersedes its queued one and cancels its running one; other views queue', async () => {
    const s = new Scheduler<Job>();
    const ran: number[] = [];
    const gates: (() => void)[] = [];
    const run = (j: Job) => new Promise<void>((resolve) => { ran.push(j.id); gates.push(resolve); });
    const a1 = job(1, 'a');
    s.push(a1);
    const draining = s.drain(run);
    expect(s.running?.id).toBe(1);
    expect(s.push(job(2, 'b'))).toEqual([]);
    expect(s.push(job(3, 'a'))).toEqual([]);       // nothing of a's was queued yet...
    expect(a1.cancelled).toBe(true);               // ...but its running job is told to stop
    const dropped = s.push(job(4, 'a'));           // a's queued job 3 is superseded by 4
    expect(dropped.map((j) => j.id)).toEqual([3]);
    expect(s.push(job(5))).toEqual([]);            // a model load is never superseded
    while (gates.length) { gates.shift()!(); await new Promise((r) => setTimeout(r, 0)); }
    await draining;
    expect(ran).toEqual([1, 2, 4, 5]);
    expect(s.running).toBeNull();
  });

  it('a second drain while running returns at once and the first drains everything', async () => {
    const s = new Scheduler<Job>();
    const ran: number[] = [];
    s.push(job(1, 'a'));
    s.push(job(2, 'b'));
    const first = s.drain(async (j) => { ran.push(j.id); await new Promise((r) => setTimeout(r, 1)); });
    await s.drain(async () => { throw new Error('must not run'); });
    await first;
    expect(ran).toEqual([1, 2]);
  });
});
