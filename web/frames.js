// The frame loop: long-polls the server for each newer frame and draws it on the canvas
// (low-resolution frames are stretched), counting frames per second.
export class FrameLoop {
  constructor(canvas, onFrame) {
    this.canvas = canvas;
    this.context = canvas.getContext('2d', { willReadFrequently: true });
    this.onFrame = onFrame;
    this.format = 'jpeg';
    this.frameId = 0;
    this.samples = 0;
    this.times = [];
  }

  async run() {
    for (;;) {
      try {
        const response = await fetch(`/api/frame?after=${this.frameId}&format=${this.format}`, { cache: 'no-store' });
        if (!response.ok) { await sleep(300); continue; }
        const id = Number(response.headers.get('X-Glint-Frame'));
        if (id === this.frameId) continue;  // the wait timed out with nothing new
        const bitmap = await createImageBitmap(await response.blob());
        this.context.imageSmoothingEnabled = bitmap.width < this.canvas.width;
        this.context.drawImage(bitmap, 0, 0, this.canvas.width, this.canvas.height);
        this.frameId = id;
        this.frameType = response.headers.get('Content-Type');  // image/png or image/jpeg
        this.samples = Number(response.headers.get('X-Glint-Samples'));
        const now = performance.now();
        this.times.push(now);
        while (this.times.length && this.times[0] < now - 1000) this.times.shift();
        this.onFrame(this);
      } catch (error) {
        await sleep(500);  // the server restarted or went away; keep trying
      }
    }
  }

  fps() { return this.times.length; }
}

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
