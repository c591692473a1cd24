// The page: loads the module, builds the book of a scene, turns pointer events into grabs,
// drags and releases, advances one frame per animation frame, and draws. Its state is on
// `window.folio` for the browser test (web/test.py) and for anyone curious.
//
// Query: ?scene=URL loads a scene file (TOML) instead of the built-in default;
// ?bench=RUNS times the default scene's recorded page turn RUNS times and shows the mean
// step (web/test.py compares it with the same replay run natively).

import init, { Folio, Bench } from './folio_web.js';
import { Renderer } from './render.js';
import { drawPage, pagesOnView } from './pages.js';

const PAGE_TEXTURE = [512, 680];
const MODELS = { dog: 'page-turn', cone: 'cone-turn', 'mass-spring': 'mass-spring-turn' };
// Pages grabbed with Shift held: a stack.
const STACK = 5;
// Thickness of one sheet (page units): the book's default page_thickness.
const SHEET = 0.0075;

const state = {
  ready: false,
  error: null,
  status: null,
  frames: 0,
  // Frames whose advance() said false: a step failed or the mesh went bad (the status's
  // failedSteps and badFrames say which).
  failedFrames: 0,
  stepMs: 0,
  bench: null,
};
window.folio = state;

const view = document.getElementById('view');
const errorBox = document.getElementById('error');
const statusLine = document.getElementById('status');

function fail(message) {
  state.error = message;
  errorBox.textContent = message;
  errorBox.hidden = false;
}

async function main() {
  const gl = view.getContext('webgl2', { antialias: true });
  if (!gl) {
    fail('Folio needs WebGL2, and this browser does not offer it.');
    return;
  }
  let wasm;
  try {
    wasm = await init();
  } catch (e) {
    fail(`Could not load the simulation (folio_web_bg.wasm): ${e}`);
    return;
  }
  const params = new URLSearchParams(location.search);
  if (params.has('bench')) {
    bench(Number(params.get('bench')) || 5);
    return;
  }
  let sceneText = Folio.builtin('page-turn');
  if (params.has('scene')) {
    try {
      const response = await fetch(params.get('scene'));
      if (!response.ok) throw new Error(`${response.status} ${response.statusText}`);
      sceneText = await response.text();
    } catch (e) {
      fail(`Could not load the scene ${params.get('scene')}: ${e.message}`);
      return;
    }
  }
  const renderer = new Renderer(gl, PAGE_TEXTURE);
  const canvases = [0, 1, 2, 3].map(() => {
    const c = document.createElement('canvas');
    [c.width, c.height] = PAGE_TEXTURE;
    return c;
  });
  let shown = null;
  function showPages(s) {
    const counts = s.left === undefined ? { front: 1, back: 2, leftTop: 0, rightTop: 0 }
      : pagesOnView(s.left, s.right, s.active);
    const numbers = [counts.front, counts.back, counts.leftTop, counts.rightTop];
    const key = numbers.join(',');
    if (key === shown) return;
    shown = key;
    numbers.forEach((n, layer) => {
      drawPage(canvases[layer], Math.max(n, 1));
      renderer.setPage(layer, canvases[layer]);
    });
  }

  let folio = null;
  function load(text, effects) {
    try {
      const next = new Folio(text, effects, view.clientWidth, view.clientHeight);
      if (folio) folio.free();
      folio = next;
      renderer.setStage(folio.stage());
      sceneText = text;
      errorBox.hidden = true;
      state.error = null;
      buildPanel();
    } catch (e) {
      fail(`The scene was refused: ${e.message ?? e}`);
    }
  }

  // The panel: the page model, the effects, and what runs.
  const modelSelect = document.getElementById('model');
  const effectsBox = document.getElementById('effects');
  function buildPanel() {
    const s = JSON.parse(folio.status());
    modelSelect.value = s.model;
    effectsBox.replaceChildren();
    const available = folio.model_effects().split(',').filter((e) => e);
    if (available.length === 0) effectsBox.textContent = 'none';
    for (const name of available) {
      const label = document.createElement('label');
      const box = document.createElement('input');
      box.type = 'checkbox';
      box.checked = s.effects.includes(name);
      box.addEventListener('change', () => {
        const on = [...effectsBox.querySelectorAll('input')]
          .filter((b) => b.checked).map((b) => b.dataset.name);
        load(sceneText, on.join(','));
      });
      box.dataset.name = name;
      label.append(box, ' ', name);
      effectsBox.append(label);
    }
  }
  modelSelect.addEventListener('change', () => load(Folio.builtin(MODELS[modelSelect.value])));
  document.getElementById('scene-file').addEventListener('change', async (event) => {
    const file = event.target.files[0];
    if (file) load(await file.text());
  });

  load(sceneText);
  if (!folio) return;
  // For the browser test: where a book-frame point is seen, and the top of the book.
  state.project = (x, y, z) => folio.project(x, y, z);
  state.top = () => folio.top();

  // Pointer: the first pointer grabs (Shift: a stack) or turns the view; a second one
  // while a page is held puts a finger in the book (finger-bookmarking, seed 000 Sec. 4.1).
  const pointers = new Set();
  const at = (event) => {
    const r = view.getBoundingClientRect();
    return [event.clientX - r.left, event.clientY - r.top];
  };
  view.addEventListener('pointerdown', (event) => {
    view.setPointerCapture(event.pointerId);
    pointers.add(event.pointerId);
    if (pointers.size === 1) {
      folio.pointer_down(...at(event), event.shiftKey ? STACK : 1);
    } else {
      folio.bookmark(true);
    }
    event.preventDefault();
  });
  view.addEventListener('pointermove', (event) => {
    if (pointers.values().next().value === event.pointerId) folio.pointer_move(...at(event));
  });
  const up = (event) => {
    const first = pointers.values().next().value === event.pointerId;
    pointers.delete(event.pointerId);
    if (first) folio.pointer_up();
  };
  view.addEventListener('pointerup', up);
  view.addEventListener('pointercancel', up);
  // Keys: B puts one more page into the grip, N takes one back out.
  window.addEventListener('keydown', (event) => {
    if (event.repeat) return;
    if (event.key === 'b' || event.key === 'B') folio.bookmark(true);
    if (event.key === 'n' || event.key === 'N') folio.bookmark(false);
  });

  function resize() {
    const ratio = window.devicePixelRatio || 1;
    view.width = Math.round(view.clientWidth * ratio);
    view.height = Math.round(view.clientHeight * ratio);
    folio.resize(view.clientWidth, view.clientHeight);
  }
  window.addEventListener('resize', resize);
  resize();

  let last = performance.now();
  let averaged = 0;
  function frame() {
    try {
      draw();
      requestAnimationFrame(frame);
    } catch (e) {
      fail(`Folio stopped: ${e.message ?? e}`);
    }
  }
  function draw() {
    const t0 = performance.now();
    const good = folio.advance();
    const ms = performance.now() - t0;
    averaged = averaged === 0 ? ms : 0.9 * averaged + 0.1 * ms;
    const s = JSON.parse(folio.status());
    state.status = s;
    state.frames += 1;
    state.stepMs = averaged;
    if (!good) state.failedFrames += 1;
    const memory = wasm.memory.buffer;
    const v = folio.vertex_count();
    renderer.setMesh(
      new Float32Array(memory, folio.positions_ptr(), 3 * v),
      new Float32Array(memory, folio.normals_ptr(), 3 * v),
      new Float32Array(memory, folio.uvs_ptr(), 2 * v),
      new Float32Array(memory, folio.materials_ptr(), v),
      new Uint32Array(memory, folio.indices_ptr(), folio.index_count()),
    );
    showPages(s);
    const active = Math.max(s.active ?? 1, 1);
    renderer.draw(new Float32Array(folio.view_projection()), new Float32Array(folio.eye()),
      active * SHEET);
    const now = performance.now();
    const fps = 1000 / Math.max(now - last, 1e-3);
    last = now;
    const counts = s.left === undefined ? '' : `${s.left} | ${s.right}${s.active ? ` (${s.active} held)` : ''} · `;
    statusLine.textContent = `${s.model} · ${counts}${s.phase} · step ${averaged.toFixed(2)} ms · ` +
      `stretch ${(100 * (s.stretch ?? 0)).toFixed(1)} % · ${fps.toFixed(0)} fps` +
      (s.failedSteps + s.badFrames > 0 ? ` · ${s.failedSteps} failed steps, ${s.badFrames} bad frames` : '');
    state.ready = true;
  }
  requestAnimationFrame(frame);
}

// Times the default scene's recorded page turn `runs` times: the mean step of each run and
// their median, in state.bench (web/test.py reads it).
function bench(runs) {
  const means = [];
  let steps = 0, failed = 0, counts = null;
  for (let r = 0; r < runs; r++) {
    const b = new Bench();
    const t0 = performance.now();
    while (b.frame()) { /* every frame of the page turn */ }
    const ms = performance.now() - t0;
    steps = b.steps();
    failed += b.failed();
    counts = Array.from(b.counts());
    means.push(ms / steps);
    b.free();
  }
  const sorted = [...means].sort((a, b) => a - b);
  state.bench = { runs, steps, failed, counts, means, median: sorted[Math.floor(runs / 2)] };
  statusLine.textContent = `bench: ${runs} runs of the page turn (${steps} steps), median ` +
    `${state.bench.median.toFixed(4)} ms per step, ${failed} failures, counts ${counts}`;
  state.ready = true;
}

main().catch((e) => fail(`Folio stopped: ${e.message ?? e}`));
