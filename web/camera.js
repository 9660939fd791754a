// The page's camera: orbit (drag turns around a target, wheel zooms) or fly (drag looks
// around, WASD/QE move), expressed as yaw and pitch about the scene's up axis and sent to
// the server as eye, forward, up and horizontal field of view.
export const add = (a, b) => a.map((v, i) => v + b[i]);
export const sub = (a, b) => a.map((v, i) => v - b[i]);
export const scale = (a, s) => a.map((v) => v * s);
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const normalize = (a) => scale(a, 1 / Math.hypot(...a));

// Distance in front of the eye below which points are not drawn.
const kNear = 1e-3;

// The server's pinhole camera for a camera the page sends (ViewerCamera::camera, which
// builds Mat4::lookAt, and Camera::project in src/), so drawings over the frame land on
// the rendered pixels of a width x height frame.
export class Projection {
  constructor(camera, width, height) {
    this.eye = camera.eye;
    // lookAt: camera +z points back from the view direction, x = up x back, y = back x x.
    this.back = normalize(scale(camera.forward, -1));
    let right = cross(camera.up, this.back);
    if (Math.hypot(...right) === 0) right = cross([0, 0, 1], this.back);
    this.right = normalize(right);
    this.up = cross(this.back, this.right);
    this.width = width;
    this.height = height;
    this.focal = 0.5 * width / Math.tan(0.5 * camera.fov_x);  // Camera::focal
  }

  // Camera-space coordinates of a world point (the camera looks down -z).
  toCamera(p) {
    const d = sub(p, this.eye);
    return [dot(d, this.right), dot(d, this.up), dot(d, this.back)];
  }

  // Pixel position (x right, y down, pixel centres at +0.5) of a camera-space point ahead.
  toPixel(c) {
    const ahead = -c[2];
    return [0.5 * this.width + this.focal * c[0] / ahead, 0.5 * this.height - this.focal * c[1] / ahead];
  }

  // The pixel position of a world point, or null when it is not in front of the camera.
  project(p) {
    const c = this.toCamera(p);
    return -c[2] > kNear ? this.toPixel(c) : null;
  }

  // The part of the segment a-b in front of the camera, as two pixel positions, or null.
  projectSegment(a, b) {
    let ca = this.toCamera(a), cb = this.toCamera(b);
    const da = -ca[2] - kNear, db = -cb[2] - kNear;
    if (da <= 0 && db <= 0) return null;
    // Cut at the near plane: drawing through the eye would flip the far end across the frame.
    const cut = (inside, outside, di, dout) => add(inside, scale(sub(outside, inside), di / (di - dout)));
    if (da <= 0) ca = cut(cb, ca, db, da);
    if (db <= 0) cb = cut(ca, cb, da, db);
    return [this.toPixel(ca), this.toPixel(cb)];
  }
}

export class CameraController {
  constructor(onChange) {
    this.onChange = onChange;
    this.mode = 'orbit';
    this.fovX = 0.8;
    this.setFrom({ eye: [0, 0, 3], forward: [0, 0, -1], up: [0, 1, 0], fov_x: 0.8 });
  }

  // Adopts a camera exactly (a training camera): its own up vector is kept until the user moves.
  setFrom(camera, distance) {
    this.exact = camera;
    this.eye = camera.eye.slice();
    this.fovX = camera.fov_x;
    // The scene's up axis is the world axis closest to the camera's up (datasets are y- or z-up).
    const axes = [[0, 1, 0], [0, 0, 1], [1, 0, 0]];
    let best = axes[0];
    for (const a of axes) if (Math.abs(dot(a, camera.up)) > Math.abs(dot(best, camera.up))) best = a;
    this.worldUp = dot(best, camera.up) < 0 ? scale(best, -1) : best;
    this.side = Math.abs(this.worldUp[0]) > 0.5 ? [0, 1, 0] : [1, 0, 0];
    this.front = cross(this.worldUp, this.side);
    const f = normalize(camera.forward);
    this.pitch = Math.asin(Math.max(-1, Math.min(1, dot(f, this.worldUp))));
    this.yaw = Math.atan2(dot(f, this.front), dot(f, this.side));
    this.distance = distance || Math.max(0.1, Math.hypot(...this.eye));
  }

  forward() {
    const c = Math.cos(this.pitch);
    return normalize(add(add(scale(this.side, c * Math.cos(this.yaw)), scale(this.front, c * Math.sin(this.yaw))),
      scale(this.worldUp, Math.sin(this.pitch))));
  }

  target() { return add(this.eye, scale(this.forward(), this.distance)); }

  current() {
    if (this.exact) return this.exact;
    return { eye: this.eye, forward: this.forward(), up: this.worldUp, fov_x: this.fovX };
  }

  turn(dx, dy) {
    const target = this.target();
    this.yaw -= dx * 0.008;
    this.pitch = Math.max(-1.55, Math.min(1.55, this.pitch - dy * 0.008));
    if (this.mode === 'orbit') this.eye = add(target, scale(this.forward(), -this.distance));
    this.changed();
  }

  zoom(steps) {
    if (this.mode === 'orbit') {
      const target = this.target();
      this.distance = Math.max(0.02, this.distance * Math.pow(1.1, steps));
      this.eye = add(target, scale(this.forward(), -this.distance));
    } else {
      this.eye = add(this.eye, scale(this.forward(), -steps * 0.1 * this.distance));
    }
    this.changed();
  }

  // Moves along the view (forward/right/up in units of a tenth of the orbit distance).
  move(forwardAmount, rightAmount, upAmount) {
    const f = this.forward();
    const right = normalize(cross(f, this.worldUp));
    const step = 0.05 * this.distance;
    this.eye = add(this.eye, add(add(scale(f, forwardAmount * step), scale(right, rightAmount * step)),
      scale(this.worldUp, upAmount * step)));
    this.changed();
  }

  setFov(fovX) { this.fovX = fovX; if (this.exact) this.exact = { ...this.exact, fov_x: fovX }; this.onChange(this.current()); }

  changed() { this.exact = null; this.onChange(this.current()); }

  // Mouse drag, wheel and WASD/QE on the canvas.
  attach(canvas) {
    let last = null;
    canvas.addEventListener('pointerdown', (e) => { last = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); canvas.focus(); });
    canvas.addEventListener('pointermove', (e) => {
      if (!last) return;
      this.turn(e.clientX - last[0], e.clientY - last[1]);
      last = [e.clientX, e.clientY];
    });
    canvas.addEventListener('pointerup', () => { last = null; });
    canvas.addEventListener('wheel', (e) => { e.preventDefault(); this.zoom(Math.sign(e.deltaY)); }, { passive: false });
    const keys = { w: [1, 0, 0], s: [-1, 0, 0], a: [0, -1, 0], d: [0, 1, 0], e: [0, 0, 1], q: [0, 0, -1] };
    canvas.addEventListener('keydown', (e) => {
      const k = keys[e.key.toLowerCase()];
      if (k) { e.preventDefault(); this.move(...k); }
    });
  }
}
