// Wires the page: loads the server's state, connects the camera, display and edit
// controls, and runs the frame loop. window.glintViewer exposes the state to tests.
import { getJson, postJson } from './api.js';
import { BoxOverlay } from './box_overlay.js';
import { CameraController } from './camera.js';
import { DisplayPanel } from './display.js';
import { EditPanel } from './edits.js';
import { FrameLoop } from './frames.js';

const $ = (id) => document.getElementById(id);

function report(message, isError) {
  $('message').textContent = message;
  $('message').className = isError ? 'error' : '';
}

// Camera updates are sent at most one at a time; the newest pending one wins.
function cameraSender() {
  let pending = null, busy = false;
  const flush = async () => {
    if (busy || !pending) return;
    busy = true;
    const camera = pending;
    pending = null;
    try { await postJson('/api/camera', camera); } catch (error) { report(error.message, true); }
    busy = false;
    flush();
  };
  return (camera) => { pending = camera; flush(); };
}

async function start() {
  const state = await getJson('/api/state');
  const canvas = $('frame');
  canvas.width = state.width;
  canvas.height = state.height;

  const center = state.bounds ? state.bounds.min.map((v, i) => (v + state.bounds.max[i]) / 2) : [0, 0, 0];
  const distanceTo = (eye) => Math.max(0.05, Math.hypot(...eye.map((v, i) => v - center[i])));
  const sendCamera = cameraSender();
  let overlay = null;  // the selection box over the frame, redrawn with every camera change
  const camera = new CameraController((c) => { sendCamera(c); if (overlay) overlay.draw(); });
  camera.setFrom(state.camera, distanceTo(state.camera.eye));
  camera.attach(canvas);
  const showFov = () => { $('fov').value = Math.round(camera.fovX * 180 / Math.PI); $('fov-value').textContent = `${$('fov').value}°`; };
  showFov();
  $('camera-mode').addEventListener('change', (e) => { camera.mode = e.target.value; });
  $('fov').addEventListener('input', (e) => { camera.setFov(Number(e.target.value) * Math.PI / 180); showFov(); });

  const cameras = await getJson('/api/training_cameras');
  for (const [i, c] of cameras.entries()) $('training-camera').add(new Option(c.name, String(i)));
  $('snap').disabled = cameras.length === 0;
  $('snap').addEventListener('click', () => {
    const c = cameras[Number($('training-camera').value)];
    camera.setFrom(c.camera, distanceTo(c.camera.eye));
    showFov();
    sendCamera(c.camera);
    if (overlay) overlay.draw();
  });

  const display = new DisplayPanel(state.settings, report);

  const frames = new FrameLoop(canvas, (loop) => {
    $('samples').textContent = loop.samples > 0 ? `${loop.samples} spp` : 'moving';
  });
  $('format').addEventListener('change', (e) => { frames.format = e.target.value; });
  setInterval(() => { $('fps').textContent = `${frames.fps()} fps`; }, 250);

  const edits = new EditPanel(report);
  if (state.edits) {
    edits.setStatus(state.edits);
    if (state.bounds) {  // start with a box around everything
      ['x', 'y', 'z'].forEach((a, i) => {
        $(`box-min-${a}`).value = state.bounds.min[i].toFixed(2);
        $(`box-max-${a}`).value = state.bounds.max[i].toFixed(2);
      });
    }
    edits.schedulePreview();
    overlay = new BoxOverlay($('overlay'), canvas, () => camera.current());
    $('show-box').addEventListener('change', (e) => overlay.setVisible(e.target.checked));
    overlay.draw();
  } else {
    for (const id of ['selection-panel', 'operation-panel']) $(id).disabled = true;
    // The scene is the trainer's: show its size as snapshots arrive.
    const showTraining = (s) => { $('gaussians').textContent = `${s.gaussians} Gaussians (training)`; };
    showTraining(state);
    setInterval(() => getJson('/api/state').then(showTraining).catch(() => {}), 2000);
  }
  window.glintViewer = { camera, frames, edits, display, overlay, state };
  frames.run();
}

start().catch((error) => report(`cannot reach the viewer server: ${error.message}`, true));
