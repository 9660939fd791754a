// Takes the README's screenshots of the viewer (docs/images/viewer_*.png) with Debian's
// Chromium. Usage: node screenshots.mjs GLINT_BINARY RUN OUT_FOLDER
import { spawn } from 'node:child_process';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { chromium } from 'playwright-core';

const [glint, run, out] = process.argv.slice(2);
const viewer = spawn(glint, ['view', run, '--port', '0', '--res', '320x240', '--max-samples', '32'],
  { stdio: ['ignore', 'pipe', 'inherit'] });
const url = await new Promise((resolve) => {
  let text = '';
  viewer.stdout.on('data', (d) => { text += d; const m = text.match(/http:\/\/127\.0\.0\.1:\d+\/(\?token=[0-9a-f]+)? /); if (m) resolve(m[0].trim()); });
});
const profile = mkdtempSync(join(tmpdir(), 'glint-shots-'));
const browser = await chromium.launchPersistentContext(profile, {
  executablePath: '/usr/bin/chromium', headless: true, viewport: { width: 760, height: 640 },
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
try {
  const page = await browser.newPage();
  await page.goto(url);
  await page.waitForFunction(() => window.glintViewer !== undefined);
  const settled = () => page.waitForFunction(() => window.glintViewer.frames.samples >= 32, null, { timeout: 300000 });
  await settled();
  // The final image without the selection box drawn over it.
  await page.uncheck('#show-box');
  await page.screenshot({ path: join(out, 'viewer_final.png') });
  // The light of the first reflected segments alone, from the same samples.
  const shown = await page.evaluate(() => window.glintViewer.frames.frameId);
  await page.selectOption('#mode', 'bounce1');
  await page.waitForFunction((id) => window.glintViewer.frames.frameId > id, shown);
  await settled();
  await page.screenshot({ path: join(out, 'viewer_bounce1.png') });
  await page.selectOption('#mode', 'final');
  await page.check('#show-box');
  // A selection with its histogram, box and gizmo, after a roughness edit.
  for (const [id, v] of Object.entries({ 'box-min-x': -0.65, 'box-min-y': -0.05, 'box-min-z': -1.55, 'box-max-x': 0.65, 'box-max-y': 1.25, 'box-max-z': -0.25 }))
    await page.fill(`#${id}`, String(v));
  await page.selectOption('#op-kind', 'roughness');
  await page.fill('#op-roughness', '0.6');
  await page.click('#apply');
  await page.waitForFunction(() => document.getElementById('message').textContent.startsWith('applied'));
  await page.waitForFunction(() => window.glintViewer.frames.samples === 0);
  await settled();
  await page.evaluate(() => { const panel = document.getElementById('panel'); panel.scrollTop = panel.scrollHeight; });
  await page.screenshot({ path: join(out, 'viewer_edit.png') });
} finally {
  await browser.close();
  viewer.kill('SIGINT');
  rmSync(profile, { recursive: true, force: true });
}
