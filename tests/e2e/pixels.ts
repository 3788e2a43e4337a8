// Colour statistics of a PNG, decoded by the browser itself (no image library needed in node).
import type { BrowserContext } from 'playwright-core';

export interface PixelStats {
  width: number;
  height: number;
  /** Distinct colours at 4 bits per channel. */
  distinct: number;
  /** Saturated warm (orange) and cool (blue) pixels: the left and right limbs of a clip figure. */
  warm: number;
  cool: number;
  /** Pixels that differ clearly from the most common colour (the background). */
  foreground: number;
}

export async function pixelStats(context: BrowserContext, png: Buffer): Promise<PixelStats> {
  const page = await context.newPage();
  try {
    return await page.evaluate(async (b64) => {
      const blob = await (await fetch(`data:image/png;base64,${b64}`)).blob();
      const bitmap = await createImageBitmap(blob);
      const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
      const ctx = canvas.getContext('2d')!;
      ctx.drawImage(bitmap, 0, 0);
      const { data } = ctx.getImageData(0, 0, bitmap.width, bitmap.height);
      const counts = new Map<number, number>();
      let warm = 0;
      let cool = 0;
      for (let i = 0; i < data.length; i += 4) {
        const r = data[i], g = data[i + 1], b = data[i + 2];
        const key = ((r >> 4) << 8) | ((g >> 4) << 4) | (b >> 4);
        counts.set(key, (counts.get(key) ?? 0) + 1);
        const max = Math.max(r, g, b), min = Math.min(r, g, b);
        if (max < 90 || max - min < 0.45 * max) continue;
        let h = 0;
        if (max === r) h = (60 * (g - b)) / (max - min);
        else if (max === g) h = 120 + (60 * (b - r)) / (max - min);
        else h = 240 + (60 * (r - g)) / (max - min);
        h = (h + 360) % 360;
        if (h >= 15 && h <= 55) warm++;
        else if (h >= 195 && h <= 235) cool++;
      }
      let bgKey = 0, bgCount = -1;
      for (const [k, n] of counts) if (n > bgCount) { bgKey = k; bgCount = n; }
      const br = (bgKey >> 8) * 16, bg = ((bgKey >> 4) & 15) * 16, bb = (bgKey & 15) * 16;
      let foreground = 0;
      for (let i = 0; i < data.length; i += 4) {
        if (Math.abs(data[i] - br) + Math.abs(data[i + 1] - bg) + Math.abs(data[i + 2] - bb) > 90) foreground++;
      }
      return { width: bitmap.width, height: bitmap.height, distinct: counts.size, warm, cool, foreground };
    }, png.toString('base64'));
  } finally {
    await page.close();
  }
}
