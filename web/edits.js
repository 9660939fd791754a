// The selection and operation controls: builds edit-file JSON (docs/edit-files.md) from the
// fields, previews the selection (count and histogram) and sends operations, undo and redo.
import { postJson } from './api.js';

const $ = (id) => document.getElementById(id);
const number = (id) => Number($(id).value);
// The three number fields PREFIX-x, -y, -z.
export const vec = (prefix) => ['x', 'y', 'z'].map((a) => number(`${prefix}-${a}`));

// sRGB colour picker value -> linear RGB, the space of the scene's colours.
function linearFromHex(hex) {
  return [1, 3, 5].map((i) => {
    const c = parseInt(hex.slice(i, i + 2), 16) / 255;
    return c <= 0.04045 ? c / 12.92 : Math.pow((c + 0.055) / 1.055, 2.4);
  });
}

export function selectionJson() {
  const lo = vec('box-min'), hi = vec('box-max');
  const selection = { box: { min: lo.map((v, i) => Math.min(v, hi[i])), max: hi.map((v, i) => Math.max(v, lo[i])) } };
  const attribute = $('filter-attribute').value;
  if (attribute) {
    const a = number('filter-lo'), b = number('filter-hi');
    selection.filters = [{ attribute, range: [Math.min(a, b), Math.max(a, b)] }];
  }
  return selection;
}

export function operationJson() {
  const op = $('op-kind').value;
  switch (op) {
    case 'translate': case 'duplicate': return { op, offset: vec('op-offset') };
    case 'rotate': return { op, axis: vec('op-axis'), angle_degrees: number('op-angle') };
    case 'scale': return { op, factor: number('op-factor') };
    case 'delete': return { op };
    case 'roughness': return { op, [$('op-roughness-mode').value]: number('op-roughness') };
    default: return { op, set: linearFromHex($('op-color').value), blend: number('op-blend') };
  }
}

export class EditPanel {
  constructor(report) {
    this.report = report;  // (message, isError)
    this.previewTimer = null;
    for (const el of document.querySelectorAll('#selection-panel input, #selection-panel select'))
      el.addEventListener('input', () => this.schedulePreview());
    $('op-kind').addEventListener('change', () => this.showFields());
    $('apply').addEventListener('click', () => this.send('/api/edits/apply', { selection: selectionJson(), operation: operationJson() }, 'applied'));
    $('undo').addEventListener('click', () => this.send('/api/edits/undo', {}, 'undone'));
    $('redo').addEventListener('click', () => this.send('/api/edits/redo', {}, 'redone'));
    $('save').addEventListener('click', () => this.save('/api/edits/save', $('save-name').value));
    $('export').addEventListener('click', () => this.save('/api/edits/export', $('export-name').value));
    this.showFields();
  }

  showFields() {
    const op = $('op-kind').value;
    for (const div of document.querySelectorAll('.op-fields')) div.hidden = !div.dataset.ops.split(' ').includes(op);
  }

  setStatus(status) {
    $('edit-count').textContent = `${status.operations} ops`;
    $('undo').disabled = status.operations === 0;
    $('redo').disabled = status.redoable === 0;
    $('gaussians').textContent = `${status.gaussians} Gaussians`;
  }

  // Shows the edit as soon as the server has applied it; when its relighting was deferred,
  // asks for it next, and the shadows follow when that answers.
  async send(path, body, verb) {
    try {
      const status = await postJson(path, body);
      this.setStatus(status);
      const done = `${verb}; ${status.operations} operations${describeTracerUpdate(status.tracer_update)}`;
      this.report(status.relight_pending ? `${done}\nrelighting...` : status.relight ? `${done}\n${status.relight}` : done,
        false);
      this.schedulePreview();
      if (status.relight_pending) {
        // A newer edit cancels a relighting under way (the answer still says pending, with
        // no preview shown): that edit then reports and relights itself.
        const preview = await postJson('/api/edits/relight', { preview: true });
        if (preview.relight_pending && !preview.relight_preview) return;
        this.setStatus(preview);
        if (preview.relight_pending) this.report(`${done}\n${preview.relight}\nrelighting...`, false);
        const relit = await postJson('/api/edits/relight', {});
        if (relit.relight_pending) return;
        this.setStatus(relit);
        this.report(`${done}\n${relit.relight}`, false);
      }
    } catch (error) {
      this.report(error.message, true);
    }
  }

  async save(path, name) {
    try {
      const result = await postJson(path, { name });
      this.report(`saved ${result.saved}`, false);
    } catch (error) {
      this.report(error.message, true);
    }
  }

  schedulePreview() {
    for (const id of ['filter-lo', 'filter-hi']) $(`${id}-value`).textContent = $(id).value;
    clearTimeout(this.previewTimer);
    this.previewTimer = setTimeout(() => this.preview(), 150);
  }

  async preview() {
    try {
      const result = await postJson('/api/edits/preview',
        { selection: selectionJson(), attribute: $('histogram-attribute').value, bins: 40 });
      $('selection-count').textContent = `${result.count} of ${result.total} Gaussians selected`;
      drawHistogram($('histogram'), result.histogram, result.range);
    } catch (error) {
      $('selection-count').textContent = error.message;
    }
  }
}

// The server's choice between refitting and rebuilding the tracer after the edit, and the
// measured costs it chose by (render/tracer_update.h).
function describeTracerUpdate(update) {
  if (!update) return '';
  const ms = (v) => `${v.toFixed(1)} ms`;
  const refit = update.refit_possible ? `refit ${ms(update.refit_ms)} (probe ${ms(update.refit_probe_ms)})`
    : `no refit (${update.no_refit})`;
  return `\ntracer: ${update.action}; ${refit}, rebuild ${ms(update.rebuild_ms)} (probe ${ms(update.rebuild_probe_ms)})`;
}

function drawHistogram(canvas, counts, range) {
  const g = canvas.getContext('2d');
  g.clearRect(0, 0, canvas.width, canvas.height);
  const top = Math.max(1, ...counts);
  const w = canvas.width / counts.length;
  g.fillStyle = '#7ab';
  counts.forEach((c, i) => {
    const h = (canvas.height - 12) * Math.sqrt(c / top);  // square root: small bins stay visible
    g.fillRect(i * w, canvas.height - 12 - h, Math.max(1, w - 1), h);
  });
  g.fillStyle = '#aaa';
  g.font = '10px sans-serif';
  g.fillText(range[0].toFixed(2), 0, canvas.height - 1);
  g.fillText(range[1].toFixed(2), canvas.width - 24, canvas.height - 1);
}
