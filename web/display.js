// The display controls: the render mode (the buffers, then "bounce k" for each traced
// bounce), bounces, exposure and denoise, sent to the server's settings.
import { postJson } from './api.js';

const $ = (id) => document.getElementById(id);

export class DisplayPanel {
  constructor(settings, report) {
    this.report = report;  // (message, isError)
    this.show(settings);
    $('exposure').value = settings.exposure;
    $('exposure-value').textContent = settings.exposure;
    $('denoise').checked = settings.denoise;
    $('mode').addEventListener('change', (e) => this.send({ mode: e.target.value }));
    $('bounces').addEventListener('change', (e) => {
      const bounces = Number(e.target.value);
      const request = { bounces };
      // The server refuses a bounce mode beyond the bounce count: move to the last bounce left.
      const shown = /^bounce(\d+)$/.exec($('mode').value);
      if (shown && Number(shown[1]) > bounces) request.mode = bounces > 0 ? `bounce${bounces}` : 'final';
      this.send(request);
    });
    $('exposure').addEventListener('input', (e) => {
      $('exposure-value').textContent = e.target.value;
      this.send({ exposure: Number(e.target.value) });
    });
    $('denoise').addEventListener('change', (e) => this.send({ denoise: e.target.checked }));
  }

  // Shows the server's mode and bounces, with one bounce mode per bounce.
  show(settings) {
    const select = $('mode');
    for (const option of [...select.options]) if (option.value.startsWith('bounce')) option.remove();
    for (let k = 1; k <= settings.bounces; ++k) select.add(new Option(`bounce ${k}`, `bounce${k}`));
    select.value = settings.mode;
    $('bounces').value = settings.bounces;
  }

  async send(request) {
    try {
      this.show(await postJson('/api/settings', request));
    } catch (error) {
      this.report(error.message, true);
    }
  }
}
