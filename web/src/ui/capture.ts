// Capture for slides: the current 3D view as a PNG (with a caption line naming model, clip and
// seed), and the playing futures as a WebM video (MediaRecorder on the canvas's captureStream).
// The stage draws only when something changed and keeps no drawing buffer, so a PNG is taken in
// an animation frame right after asking for a render: frame callbacks run in the order they were
// requested, so the stage's render lands first and the canvas still holds it.
import { el, type StatusSink } from './dom';
import type { Player } from './player';

export interface CaptureInfo {
  model?: string;
  clip?: string;
  /** The history's first frame and length. */
  start?: number;
  historyFrames?: number;
  k?: number;
  seed?: number;
  selected?: number | null;
}

const safe = (s: string) => s.replace(/[^A-Za-z0-9_.-]+/g, '-').replace(/^-+|-+$/g, '');

/** "motion-futures.walk.keyposes.seed-3.png" */
export function captureFileName(info: CaptureInfo, ext: 'png' | 'webm'): string {
  const parts = ['motion-futures', info.clip, info.model, info.seed !== undefined ? `seed-${info.seed}` : undefined,
    info.selected !== null && info.selected !== undefined ? `sample-${info.selected + 1}` : undefined];
  return `${parts.filter((p): p is string => Boolean(p)).map(safe).join('.')}.${ext}`;
}

/** One caption line for a slide: what is shown and how to get it again. */
export function captionText(info: CaptureInfo): string {
  const bits = [
    info.model,
    info.clip && (info.start !== undefined && info.historyFrames ? `${info.clip}, history frames ${info.start}–${info.start + info.historyFrames - 1}` : info.clip),
    info.k !== undefined ? `K = ${info.k}` : undefined,
    info.seed !== undefined ? `seed ${info.seed}` : undefined,
    info.selected !== null && info.selected !== undefined ? `sample #${info.selected + 1} selected` : undefined,
  ];
  return ['motion futures', ...bits.filter(Boolean)].join(' · ');
}

/** The first WebM type this browser can record, or null. */
export function pickWebmType(isTypeSupported: (type: string) => boolean): string | null {
  for (const t of ['video/webm;codecs=vp9', 'video/webm;codecs=vp8', 'video/webm']) if (isTypeSupported(t)) return t;
  return null;
}

function nextFrame(): Promise<void> {
  return new Promise((r) => requestAnimationFrame(() => r()));
}

/** The canvas as drawn now, with a caption strip below, as a PNG. */
export async function snapshotPng(canvas: HTMLCanvasElement, caption: string, render: () => void): Promise<Blob> {
  render();
  await nextFrame();
  const strip = Math.round(Math.max(24, canvas.height * 0.045));
  const out = document.createElement('canvas');
  out.width = canvas.width;
  out.height = canvas.height + strip;
  const ctx = out.getContext('2d');
  if (!ctx) throw new Error('this browser cannot draw a 2D canvas to save the picture');
  ctx.drawImage(canvas, 0, 0);
  ctx.fillStyle = '#ffffff';
  ctx.fillRect(0, canvas.height, out.width, strip);
  ctx.fillStyle = '#1d232a';
  ctx.font = `${Math.round(strip * 0.55)}px system-ui, sans-serif`;
  ctx.textBaseline = 'middle';
  ctx.fillText(caption, Math.round(strip * 0.4), canvas.height + strip / 2, out.width - strip);
  return new Promise((resolve, reject) => out.toBlob((b) => (b ? resolve(b) : reject(new Error('the picture could not be encoded'))), 'image/png'));
}

function download(fileName: string, data: Blob): void {
  const url = URL.createObjectURL(data);
  const a = el('a', { href: url, download: fileName, hidden: true });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

export interface CapturePanelOptions {
  /** The 3D view's canvas, or null without WebGL. */
  canvas(): HTMLCanvasElement | null;
  info(): CaptureInfo;
  player: Player;
  /** Ask the viewer to draw the current frame. */
  render(): void;
  /** Reports captureStatus (busy, recording, done, error) and captureFile. */
  status: StatusSink;
  save?(fileName: string, data: Blob): void;
}

export interface CapturePanel {
  root: HTMLElement;
  /** Save the view as a PNG; resolves to the file name, or null when it failed. */
  png(): Promise<string | null>;
  /** Start recording from the first frame to the end of the futures, or stop a recording. */
  toggleRecording(): void;
  readonly recording: boolean;
}

export function mountCapturePanel(container: HTMLElement, o: CapturePanelOptions): CapturePanel {
  const save = o.save ?? download;
  const pngButton = el('button', { type: 'button', class: 'text-button', id: 'capture-png', 'aria-keyshortcuts': 'S' }, 'Save view as PNG');
  const recButton = el('button', { type: 'button', class: 'text-button', id: 'capture-webm', 'aria-keyshortcuts': 'R', 'aria-pressed': 'false' }, 'Record futures (WebM)');
  const note = el('p', { class: 'muted capture-status', role: 'status' }, 'S saves a picture, R records the futures from the first frame to the last.');
  container.replaceChildren(el('div', { class: 'share-row' }, pngButton, recButton), note);
  let recorder: MediaRecorder | null = null;

  const say = (text: string, state?: string) => { note.textContent = text; if (state) o.status('captureStatus', state); };

  async function png(): Promise<string | null> {
    const canvas = o.canvas();
    if (!canvas) { say('There is no 3D view to save (WebGL is not available).', 'error'); return null; }
    o.status('captureStatus', 'busy');
    try {
      const info = o.info();
      const blob = await snapshotPng(canvas, captionText(info), o.render);
      const name = captureFileName(info, 'png');
      save(name, blob);
      o.status('captureFile', name);
      say(`Saved ${name} (${Math.round(blob.size / 1024)} kB).`, 'done');
      return name;
    } catch (err) {
      say(`The picture could not be saved: ${(err as Error).message}`, 'error');
      return null;
    }
  }

  function startRecording(): void {
    const canvas = o.canvas();
    if (!canvas) { say('There is no 3D view to record (WebGL is not available).', 'error'); return; }
    const type = typeof MediaRecorder === 'undefined' ? null : pickWebmType((t) => MediaRecorder.isTypeSupported(t));
    if (!type || typeof canvas.captureStream !== 'function') {
      say('This browser cannot record video from the page (no WebM MediaRecorder); save pictures instead.', 'error');
      return;
    }
    const info = o.info();
    const fps = o.player.state.fps || 30;
    const stream = canvas.captureStream(fps);
    const chunks: Blob[] = [];
    const rec = new MediaRecorder(stream, { mimeType: type, videoBitsPerSecond: 4_000_000 });
    recorder = rec;
    const { player } = o;
    const loop = player.state.loop;
    let unsubscribe: () => void = () => {};
    rec.ondataavailable = (e) => { if (e.data.size) chunks.push(e.data); };
    rec.onstop = () => {
      unsubscribe();
      player.setLoop(loop);
      stream.getTracks().forEach((t) => t.stop());
      recorder = null;
      recButton.textContent = 'Record futures (WebM)';
      recButton.setAttribute('aria-pressed', 'false');
      const blob = new Blob(chunks, { type: 'video/webm' });
      if (!blob.size) { say('The recording is empty: nothing was drawn while it ran.', 'error'); return; }
      const name = captureFileName(info, 'webm');
      save(name, blob);
      o.status('captureFile', name);
      say(`Saved ${name} (${Math.round(blob.size / 1024)} kB).`, 'done');
    };
    // From the first frame to the end of the longest future, once: no loop while recording.
    player.pause();
    player.setLoop(false);
    player.seek(0);
    rec.start(250);
    recButton.textContent = 'Stop recording';
    recButton.setAttribute('aria-pressed', 'true');
    say('Recording… (R or the button stops it early)', 'recording');
    player.play();
    let started = false;
    unsubscribe = player.subscribe((s) => {
      if (s.playing) started = true;
      else if (started && rec.state === 'recording') rec.stop();
    });
  }

  function toggleRecording(): void {
    if (recorder) { if (recorder.state === 'recording') recorder.stop(); return; }
    startRecording();
  }

  pngButton.addEventListener('click', () => { void png(); });
  recButton.addEventListener('click', () => toggleRecording());
  return { root: container, png, toggleRecording, get recording() { return recorder !== null; } };
}
