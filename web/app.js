// The page: obscura's wasm package (pkg/, scripts/build-web.sh) on the browser's WebGPU. All AO
// work is the library's; this file only handles controls, the camera and drawing the typed
// arrays a frame returns into a 2D canvas (docs/WEB.md).
import init, * as obscura from './pkg/obscura.js';

const $ = (id) => document.getElementById(id);
const params = new URLSearchParams(location.search);
const state = {
  viewer: null, rows: [], scene: null, camera: null, frames: [null, null],
  split: 0.5, busy: false, dirty: false, firstAoMs: null,
};
// For the browser tests (web/tests): the API and the page's state.
window.obscuraPage = { obscura, state, ready: false, errors: [] };

function showError(message) {
  const box = $('error');
  box.textContent = message;
  box.hidden = false;
  window.obscuraPage.errors.push(message);
}
function clearError() { $('error').hidden = true; }
const errorText = (e) => (e && e.message) ? e.message : String(e);

// ---- camera: orbit around a target, or fly; kept as eye/target/up/fov for the library ----
const v3 = {
  add: (a, b) => a.map((x, i) => x + b[i]), sub: (a, b) => a.map((x, i) => x - b[i]),
  scale: (a, s) => a.map((x) => x * s), dot: (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2],
  cross: (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]],
  norm: (a) => { const l = Math.hypot(...a) || 1; return a.map((x) => x / l); },
};
function orbit(dx, dy) {
  const c = state.camera;
  const offset = v3.sub(c.eye, c.target);
  const r = Math.hypot(...offset);
  let yaw = Math.atan2(offset[0], offset[2]);
  let pitch = Math.asin(Math.max(-1, Math.min(1, offset[1] / r)));
  yaw -= dx * 0.01;
  pitch = Math.max(-1.5, Math.min(1.5, pitch + dy * 0.01));
  c.eye = v3.add(c.target, [r * Math.cos(pitch) * Math.sin(yaw), r * Math.sin(pitch), r * Math.cos(pitch) * Math.cos(yaw)]);
  c.up = [0, 1, 0];
}
function pan(dx, dy) {
  const c = state.camera;
  const forward = v3.norm(v3.sub(c.target, c.eye));
  const right = v3.norm(v3.cross(forward, c.up));
  const up = v3.cross(right, forward);
  const s = Math.hypot(...v3.sub(c.eye, c.target)) * 0.002;
  const move = v3.add(v3.scale(right, -dx * s), v3.scale(up, dy * s));
  c.eye = v3.add(c.eye, move); c.target = v3.add(c.target, move);
}
function zoom(factor) {
  const c = state.camera;
  c.eye = v3.add(c.target, v3.scale(v3.sub(c.eye, c.target), factor));
}
function fly(key) {
  const c = state.camera;
  const forward = v3.norm(v3.sub(c.target, c.eye));
  const right = v3.norm(v3.cross(forward, c.up));
  const step = Math.max(1e-3, (state.scene?.radius || 1) * 0.05);
  const dir = { w: forward, s: v3.scale(forward, -1), d: right, a: v3.scale(right, -1), e: c.up, q: v3.scale(c.up, -1) }[key];
  if (!dir) return false;
  const move = v3.scale(v3.norm(dir), step);
  c.eye = v3.add(c.eye, move); c.target = v3.add(c.target, move);
  return true;
}

// ---- rendering ----
function size() { const [w, h] = $('size').value.split('x').map(Number); return { width: w, height: h }; }
function request(technique) {
  const { width, height } = size();
  const req = { technique, width, height, camera: state.camera, gbuffer: $('view').value !== 'ao', timings: true };
  if ($('preset').value) req.preset = $('preset').value;
  return req;
}
// Render the visible rows; a change while a frame renders asks for one more frame afterwards.
async function render() {
  if (!state.viewer || !state.scene) return;
  if (state.busy) { state.dirty = true; return; }
  state.busy = true;
  try {
    do {
      state.dirty = false;
      const rows = $('split').checked ? [$('rowA').value, $('rowB').value] : [$('rowA').value];
      const timings = [];
      state.frames = [null, null];
      for (let i = 0; i < rows.length; i++) {
        $('status').textContent = `rendering ${rows[i]}…`;
        try {
          const frame = await state.viewer.render(JSON.stringify(request(rows[i])));
          state.frames[i] = frame;
          timings.push(`${rows[i]}: ${frame.timings ? describeTimings(JSON.parse(frame.timings)) : 'no GPU timestamps on this device'}`);
          clearError();
        } catch (e) {
          showError(`${rows[i]}: ${errorText(e)}`);
        }
      }
      draw();
      if (state.frames[0] && state.firstAoMs === null) {
        state.firstAoMs = performance.now();
      }
      $('timings').textContent = timings.join('\n');
      $('status').textContent = `${state.scene.name}: ${state.scene.triangles} triangles`;
    } while (state.dirty);
  } finally {
    state.busy = false;
  }
}
function describeTimings(t) {
  const total = Object.values(t).reduce((a, b) => a + b, 0);
  return `${total.toFixed(2)} ms GPU (` + Object.entries(t).map(([k, v]) => `${k} ${v.toFixed(2)}`).join(', ') + ')';
}
// One pixel of a frame in the chosen view, as sRGB bytes.
function pixel(frame, view, i, out) {
  const ao = frame.aoCache ||= frame.ao;
  const toByte = (x) => Math.max(0, Math.min(255, Math.round(x * 255)));
  if (view === 'ao') { const g = toByte(ao[i]); out[0] = out[1] = out[2] = g; return; }
  if (view === 'depth') {
    const d = (frame.depthCache ||= frame.depth)[i];
    const far = frame.far ||= Math.max(1e-6, ...frame.depthCache);
    const g = d > 0 ? toByte(1 - d / far) : 255; out[0] = out[1] = out[2] = g; return;
  }
  if (view === 'normals') {
    const n = frame.normalsCache ||= frame.normals;
    for (let c = 0; c < 3; c++) out[c] = toByte(0.5 + 0.5 * n[3 * i + c]);
    return;
  }
  const albedo = frame.albedoCache ||= frame.albedo;
  for (let c = 0; c < 3; c++) {
    // AO darkens the linear colour; back to sRGB for the screen.
    const s = albedo[4 * i + c] / 255;
    const lin = s <= 0.04045 ? s / 12.92 : ((s + 0.055) / 1.055) ** 2.4;
    const x = lin * ao[i];
    out[c] = toByte(x <= 0.0031308 ? x * 12.92 : 1.055 * x ** (1 / 2.4) - 0.055);
  }
}
function draw() {
  const [a, b] = state.frames;
  const base = a || b;
  if (!base) return;
  const canvas = $('canvas');
  canvas.width = base.width; canvas.height = base.height;
  const ctx = canvas.getContext('2d');
  const image = ctx.createImageData(base.width, base.height);
  const splitX = b && $('split').checked ? Math.round(state.split * base.width) : base.width;
  const view = $('view').value;
  const px = [0, 0, 0];
  for (let y = 0; y < base.height; y++) {
    for (let x = 0; x < base.width; x++) {
      const i = y * base.width + x;
      const frame = x < splitX ? a : b;
      if (!frame) continue;
      pixel(frame, view, i, px);
      image.data.set([px[0], px[1], px[2], 255], 4 * i);
    }
  }
  ctx.putImageData(image, 0, 0);
  const split = $('split').checked;
  $('divider').hidden = !split;
  $('divider').style.left = `${state.split * 100}%`;
  $('labelA').textContent = $('rowA').value;
  $('labelB').textContent = split ? $('rowB').value : '';
}

// ---- scenes ----
async function useScene(info) {
  state.scene = JSON.parse(info);
  const { width, height } = size();
  state.camera = JSON.parse(state.viewer.defaultCamera(width / height));
  await render();
}
async function loadFile(file) {
  try {
    const bytes = new Uint8Array(await file.arrayBuffer());
    await useScene(state.viewer.loadGltf(file.name, bytes));
    const option = new Option(file.name, '', true, true);
    $('scene').add(option);
  } catch (e) {
    showError(errorText(e));
  }
}

function fillSelect(select, values, chosen) {
  for (const [value, label] of values) select.add(new Option(label, value, value === chosen, value === chosen));
}

function wire() {
  const rerender = () => render();
  for (const id of ['rowA', 'rowB', 'preset', 'view', 'size', 'split']) $(id).addEventListener('change', id === 'view' ? draw : rerender);
  $('view').addEventListener('change', () => { if ($('view').value !== 'ao' && state.frames[0] && !state.frames[0].depth.length) render(); });
  $('scene').addEventListener('change', async () => {
    if (!$('scene').value) return;
    try { await useScene(state.viewer.loadBuiltin($('scene').value)); } catch (e) { showError(errorText(e)); }
  });
  $('file').addEventListener('change', () => { if ($('file').files[0]) loadFile($('file').files[0]); });
  const stage = $('stage');
  stage.addEventListener('dragover', (e) => { e.preventDefault(); stage.classList.add('drop'); });
  stage.addEventListener('dragleave', () => stage.classList.remove('drop'));
  stage.addEventListener('drop', (e) => {
    e.preventDefault(); stage.classList.remove('drop');
    if (e.dataTransfer.files[0]) loadFile(e.dataTransfer.files[0]);
  });
  $('reset').addEventListener('click', () => { const { width, height } = size(); state.camera = JSON.parse(state.viewer.defaultCamera(width / height)); render(); });
  $('exr').addEventListener('click', () => {
    const frame = state.frames[0];
    if (!frame) return;
    const blob = new Blob([frame.exr()], { type: 'image/x-exr' });
    const a = document.createElement('a');
    a.href = URL.createObjectURL(blob); a.download = `${$('rowA').value}.exr`; a.click();
  });
  // Divider: drag to move the split; camera: drag on the image.
  let dragging = null;
  $('divider').addEventListener('pointerdown', (e) => { dragging = 'divider'; e.stopPropagation(); e.preventDefault(); });
  const canvas = $('canvas');
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('pointerdown', (e) => { dragging = (e.button === 2 || e.shiftKey) ? 'pan' : 'orbit'; canvas.focus(); });
  window.addEventListener('pointerup', () => { dragging = null; });
  window.addEventListener('pointermove', (e) => {
    if (!dragging || !state.camera) return;
    if (dragging === 'divider') {
      const r = canvas.getBoundingClientRect();
      state.split = Math.max(0, Math.min(1, (e.clientX - r.left) / r.width));
      draw();
      return;
    }
    if (dragging === 'orbit') orbit(e.movementX, e.movementY); else pan(e.movementX, e.movementY);
    render();
  });
  canvas.addEventListener('wheel', (e) => { e.preventDefault(); if (state.camera) { zoom(e.deltaY > 0 ? 1.1 : 1 / 1.1); render(); } }, { passive: false });
  canvas.addEventListener('keydown', (e) => { if (state.camera && fly(e.key.toLowerCase())) render(); });
}

async function main() {
  await init();
  state.rows = JSON.parse(obscura.techniques());
  const rowOptions = state.rows.map((r) => [r.name, r.name]);
  fillSelect($('rowA'), rowOptions, params.get('left') || 'gtao');
  fillSelect($('rowB'), rowOptions, params.get('right') || 'sd-vao');
  if (params.get('split') === '0') $('split').checked = false;
  fillSelect($('preset'), [['', 'defaults'], ...obscura.presets().map((p) => [p, p])], '');
  fillSelect($('scene'), obscura.builtinScenes().map((s) => [s, s]), params.get('scene') || 'stairs');
  const body = $('rows').tBodies[0];
  for (const r of state.rows) {
    const tr = body.insertRow();
    tr.insertCell().textContent = r.name;
    tr.insertCell().textContent = r.hiddenDepth ? r.source : `nothing: ${r.source}, depth buffer only`;
    tr.insertCell().textContent = r.summary;
  }
  wire();
  try {
    state.viewer = await obscura.Viewer.create(params.get('limits') || undefined);
  } catch (e) {
    showError(errorText(e));
    $('status').textContent = 'no WebGPU device: nothing can be rendered here';
    window.obscuraPage.ready = true;
    return;
  }
  window.obscuraPage.adapter = JSON.parse(state.viewer.adapterInfo());
  try {
    await useScene(state.viewer.loadBuiltin($('scene').value));
  } catch (e) {
    showError(errorText(e));
  }
  window.obscuraPage.ready = true;
}
main().catch((e) => { showError(errorText(e)); window.obscuraPage.ready = true; });
