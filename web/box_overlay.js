// The selection box drawn over the frame: an SVG wireframe projected with the server's
// camera, a handle at each face centre that drags that face along its axis, and a translate
// gizmo (three axis arrows at the box centre) that drags the translate offset. Drags write
// the numeric fields, which stay the one source of the box and the offset.
import { Projection, add, scale, sub } from './camera.js';
import { vec } from './edits.js';

const $ = (id) => document.getElementById(id);
const SVG = 'http://www.w3.org/2000/svg';
const AXES = ['x', 'y', 'z'];
const AXIS_COLOURS = ['#f66', '#6d6', '#69f'];
const HANDLE_RADIUS = 5;  // screen pixels, whatever the frame's displayed size
const MIN_EXTENT = 1e-3;  // a dragged face stops this short of the opposite one

const unit = (i) => AXES.map((_, j) => (j === i ? 1 : 0));

// The box of the numeric fields, ordered as the selection sent to the server orders it.
function fieldBox() {
  const a = vec('box-min'), b = vec('box-max');
  return { lo: a.map((v, i) => Math.min(v, b[i])), hi: b.map((v, i) => Math.max(v, a[i])) };
}

function translating() {
  return ['translate', 'duplicate'].includes($('op-kind').value);
}

function element(name, attributes) {
  const e = document.createElementNS(SVG, name);
  for (const [k, v] of Object.entries(attributes)) e.setAttribute(k, v);
  return e;
}

export class BoxOverlay {
  // camera(): the camera the server renders with (CameraController.current()).
  constructor(svg, canvas, camera) {
    this.svg = svg;
    this.canvas = canvas;
    this.camera = camera;
    this.visible = true;
    const fields = ['box-min', 'box-max', 'op-offset'].flatMap((p) => AXES.map((a) => $(`${p}-${a}`)));
    for (const field of [...fields, $('op-kind')]) field.addEventListener('input', () => this.draw());
    $('op-kind').addEventListener('change', () => this.draw());
    window.addEventListener('resize', () => this.draw());
  }

  setVisible(visible) {
    this.visible = visible;
    this.draw();
  }

  projection() {
    return new Projection(this.camera(), this.canvas.width, this.canvas.height);
  }

  // Canvas pixels per screen pixel (the frame may be shown smaller than its resolution).
  pixelScale() {
    return this.canvas.width / Math.max(1, this.canvas.getBoundingClientRect().width);
  }

  draw() {
    this.svg.replaceChildren();
    this.svg.setAttribute('viewBox', `0 0 ${this.canvas.width} ${this.canvas.height}`);
    if (!this.visible) return;
    const projection = this.projection();
    const px = this.pixelScale();
    const { lo, hi } = fieldBox();
    const offset = translating() ? vec('op-offset') : [0, 0, 0];
    const moved = offset.some((v) => v !== 0);
    if (moved) this.drawBox(projection, add(lo, offset), add(hi, offset), { class: 'moved-box', 'stroke-width': px });
    this.drawBox(projection, lo, hi, { class: 'box', 'stroke-width': 1.5 * px });

    // Face handles: the field each one drags is its identity (data-field).
    const centre = scale(add(lo, hi), 0.5);
    for (const [i, axis] of AXES.entries()) {
      for (const [side, value] of [['min', lo[i]], ['max', hi[i]]]) {
        const at = centre.slice();
        at[i] = value;
        this.drawHandle(projection, at, i, `box-${side}-${axis}`, 'face', px);
      }
    }
    // The gizmo sits at the centre the translate would move the box to.
    const origin = add(centre, offset);
    const length = 0.35 * Math.max(...sub(hi, lo), MIN_EXTENT);
    for (const [i, axis] of AXES.entries()) {
      const tip = add(origin, scale(unit(i), length));
      const segment = projection.projectSegment(origin, tip);
      if (!segment) continue;
      this.svg.append(element('line', { class: 'gizmo-axis', stroke: AXIS_COLOURS[i], 'stroke-width': 2 * px,
        x1: segment[0][0], y1: segment[0][1], x2: segment[1][0], y2: segment[1][1] }));
      this.drawHandle(projection, tip, i, `op-offset-${axis}`, 'gizmo', px);
    }
  }

  drawBox(projection, lo, hi, attributes) {
    const corner = (k) => [k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]];
    for (let k = 0; k < 8; ++k) {
      for (const bit of [1, 2, 4]) {
        if (k & bit) continue;  // each edge once, from its lower corner
        const segment = projection.projectSegment(corner(k), corner(k | bit));
        if (!segment) continue;
        this.svg.append(element('line', { ...attributes,
          x1: segment[0][0], y1: segment[0][1], x2: segment[1][0], y2: segment[1][1] }));
      }
    }
  }

  // A draggable dot at a world point that moves `field` along axis i. Its data-dx/dy give
  // the screen direction of the axis there (tests drag along it).
  drawHandle(projection, at, i, field, kind, px) {
    const screen = projection.project(at);
    const axis = this.screenAxis(projection, at, i);
    if (!screen || !axis) return;
    const length = Math.hypot(...axis);
    const handle = element('circle', { class: `handle ${kind}`, cx: screen[0], cy: screen[1],
      r: (kind === 'gizmo' ? 1.3 : 1) * HANDLE_RADIUS * px, fill: AXIS_COLOURS[i],
      'data-field': field, 'data-dx': axis[0] / length, 'data-dy': axis[1] / length });
    handle.addEventListener('pointerdown', (e) => this.startDrag(e, field, axis));
    this.svg.append(handle);
  }

  // Canvas pixels moved per world unit along axis i at point `at`; null when the axis points
  // (almost) straight at the camera, where a drag cannot tell how far to go.
  screenAxis(projection, at, i) {
    // A step small next to the distance, so the perspective is linear over it.
    const step = 1e-3 * Math.max(1e-3, Math.hypot(...sub(at, projection.eye)));
    const a = projection.project(at), b = projection.project(add(at, scale(unit(i), step)));
    if (!a || !b) return null;
    const v = scale(sub(b, a), 1 / step);
    return Math.hypot(...v) > 1e-3 ? v : null;
  }

  // Dragging moves the field by the mouse displacement projected onto the axis on screen.
  startDrag(event, field, axis) {
    event.preventDefault();
    event.stopPropagation();
    if (field.startsWith('op-offset') && !translating()) {
      $('op-kind').value = 'translate';
      $('op-kind').dispatchEvent(new Event('change'));
    }
    const input = $(field);
    const start = Number(input.value);
    const from = [event.clientX, event.clientY];
    const px = this.pixelScale();
    const move = (e) => {
      const d = [(e.clientX - from[0]) * px, (e.clientY - from[1]) * px];
      let value = start + (d[0] * axis[0] + d[1] * axis[1]) / (axis[0] * axis[0] + axis[1] * axis[1]);
      if (field.startsWith('box-')) {  // a face stays on its side of the opposite one
        const [, side, name] = field.split('-');
        const other = Number($(`box-${side === 'min' ? 'max' : 'min'}-${name}`).value);
        value = side === 'min' ? Math.min(value, other - MIN_EXTENT) : Math.max(value, other + MIN_EXTENT);
      }
      input.value = value.toFixed(3);
      input.dispatchEvent(new Event('input', { bubbles: true }));  // the preview and this drawing follow
    };
    const stop = () => {
      window.removeEventListener('pointermove', move);
      window.removeEventListener('pointerup', stop);
    };
    window.addEventListener('pointermove', move);
    window.addEventListener('pointerup', stop);
  }
}
