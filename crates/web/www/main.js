// The page's script: starts the wasm `Page` on the canvas, builds the technique menu from the
// registry's descriptors (`Page.techniques()`), forwards the pointer, and shows the frame time and
// the pass times. The test contract: `?technique=T&frames=N` renders N frames, then sets the title
// to `done: T, N frames, X ms a frame, ...`; any failure is shown on the page and sets the title to
// `error: MESSAGE`. Optional: `scene`, `compare` (a second technique, split view), `amplitude`,
// `scale` and `map` (sizes), `step` (seconds of water a frame, for repeatable water), `panel=0`,
// `filter=1` (the far water's normals filtered by each sample's footprint).
// `technique=none` lights the floor as through flat water under the same waves.
import init, { Page } from "./caustics_web.js";

const query = new URLSearchParams(location.search);
const SCENES = ["pool", "shore", "reef", "underwater"];
const scene = query.get("scene") || "pool";
const frames = query.has("frames") ? Number(query.get("frames")) : null;
const canvas = document.getElementById("view");
let page = null;
let failed = false;

function fail(message) {
  const text = String(message && message.message ? message.message : message);
  failed = true;
  const box = document.getElementById("fatal");
  box.style.display = "flex";
  box.firstElementChild.textContent = text;
  document.title = `error: ${text}`;
}

function canvasSize() {
  const dpr = window.devicePixelRatio || 1;
  return [Math.max(1, Math.round(canvas.clientWidth * dpr)), Math.max(1, Math.round(canvas.clientHeight * dpr))];
}

// One side's menu: the technique and a control per parameter, from its descriptor.
function sideMenu(root, title, techniques, initial, onChange) {
  root.replaceChildren();
  const head = document.createElement("label");
  head.innerHTML = `<span>${title}</span>`;
  const select = document.createElement("select");
  for (const t of techniques) select.add(new Option(t.name, t.name));
  head.append(select);
  const summary = document.createElement("div");
  summary.className = "summary";
  const params = document.createElement("div");
  const error = document.createElement("div");
  error.className = "error";
  root.append(head, summary, params, error);

  const [name0, given] = parseSpec(initial);
  // A name the page does not list (`none`, a misspelling) stays what was asked for, so that the
  // page says why it refuses it rather than showing another technique.
  if (!techniques.some((t) => t.name === name0)) select.add(new Option(name0, name0));
  select.value = name0;
  let values = {};

  function build(preset) {
    const t = techniques.find((x) => x.name === select.value);
    summary.textContent = t ? `${t.paper}: ${t.summary}` : "";
    params.replaceChildren();
    values = { ...preset };
    for (const p of t ? t.params : []) {
      const row = document.createElement("label");
      row.title = p.doc + (p.auto ? ` Default: auto (${p.auto}).` : "");
      row.innerHTML = `<span>${p.label}${p.unit ? ` (${p.unit})` : ""}</span>`;
      let input;
      if (p.kind === "bool") {
        input = document.createElement("input");
        input.type = "checkbox";
        input.checked = p.key in values ? values[p.key] === "true" : p.default === true;
        input.onchange = () => { values[p.key] = String(input.checked); onChange(); };
      } else if (p.kind === "choice") {
        input = document.createElement("select");
        if (p.auto) input.add(new Option(`auto`, ""));
        for (const c of p.choices) input.add(new Option(c, c));
        input.value = values[p.key] ?? (p.default ?? "");
        input.onchange = () => { setOrClear(p.key, input.value); onChange(); };
      } else {
        input = document.createElement("input");
        input.type = "number";
        if (p.min !== null) input.min = p.min;
        if (p.max !== null) input.max = p.max;
        input.step = p.step ?? "any";
        input.placeholder = p.auto ? "auto" : "";
        input.value = values[p.key] ?? (p.default ?? "");
        input.onchange = () => { setOrClear(p.key, input.value); onChange(); };
      }
      row.append(input);
      params.append(row);
    }
  }
  function setOrClear(key, v) {
    if (v === "") delete values[key];
    else values[key] = v;
  }
  select.onchange = () => { build({}); onChange(); };
  build(given);
  return {
    spec() {
      const kv = Object.entries(values).map(([k, v]) => `${k}=${v}`);
      return kv.length ? `${select.value}:${kv.join(",")}` : select.value;
    },
    showError(e) { error.textContent = e || ""; },
  };
}

function parseSpec(s) {
  const [name, rest] = s.split(/:(.*)/s);
  const values = {};
  if (rest) for (const kv of rest.split(",")) {
    const [k, v] = kv.split("=");
    if (k) values[k.trim()] = (v ?? "").trim();
  }
  return [name.trim(), values];
}

function escape(text) {
  const div = document.createElement("div");
  div.textContent = text;
  return div.innerHTML;
}

function hud(status) {
  const rows = status.passes
    .slice()
    .sort((a, b) => b[1] - a[1])
    .slice(0, 12)
    .map(([label, ms]) => `<tr><td>${escape(label)}</td><td>${ms.toFixed(2)} ms</td></tr>`)
    .join("");
  const fps = status.frame_ms > 0 ? (1000 / status.frame_ms).toFixed(1) : "-";
  const side = ["left", "right"];
  const failures = status.sides
    .map((s, k) => (s.error ? `<div class="error">${status.sides.length > 1 ? side[k] + " " : ""}${escape(s.technique)}: ${escape(s.error)}</div>` : ""))
    .join("");
  document.getElementById("hud").innerHTML = failures +
    `<div>${status.frame_ms.toFixed(1)} ms a frame (${fps} fps)</div>` +
    `<div class="hint">${escape(status.adapter || "WebGPU adapter")}${status.software ? " (software)" : ""}; ` +
    `image ${status.image[0]} x ${status.image[1]}, map ${status.quality.map}²; water: ${status.water}; ` +
    `steady frames: ${status.steady[1]} created, ${status.steady[2]} bytes uploaded</div>` +
    (status.timestamps ? `<table>${rows}</table>` : `<div class="hint">no GPU timestamps in this browser</div>`);
}

async function main() {
  if (!navigator.gpu) {
    throw new Error("This browser has no WebGPU (navigator.gpu is missing): use a recent Chrome, Edge or Firefox, or Safari 26, with WebGPU enabled.");
  }
  if (!SCENES.includes(scene)) throw new Error(`unknown scene \`${scene}\`: the page shows ${SCENES.join(", ")}`);
  if (frames !== null && !(Number.isInteger(frames) && frames > 0)) {
    throw new Error(`frames must be a whole number above 0, got \`${query.get("frames")}\``);
  }
  await init();
  [canvas.width, canvas.height] = canvasSize();
  page = await Page.start(canvas, scene, query.get("technique") || "");
  const technique = JSON.parse(page.status()).sides[0].technique;
  const amplitude = query.get("amplitude");
  if (amplitude !== null) page.set_amplitude(parseFloat(amplitude));
  page.set_quality(parseFloat(query.get("scale") || "0"), parseInt(query.get("map") || "0", 10), 0);
  if (query.has("step")) page.set_fixed_step(parseFloat(query.get("step")));

  // The menus.
  // For the console and the tests: `caustics.status()`, `caustics.set_sides(...)`.
  window.caustics = page;
  const techniques = JSON.parse(page.techniques());
  window.techniqueNames = JSON.stringify(techniques.map((t) => t.name));
  if (query.get("panel") === "0") document.getElementById("panel").hidden = true;
  const sceneSelect = document.getElementById("scene");
  for (const s of SCENES) sceneSelect.add(new Option(s, s));
  sceneSelect.value = scene;
  sceneSelect.onchange = () => {
    // Another scene starts with the techniques it offers (a flat-floor one is not offered on
    // the shore).
    query.set("scene", sceneSelect.value);
    for (const key of ["frames", "technique", "compare"]) query.delete(key);
    location.search = query.toString();
  };
  const split = document.getElementById("split");
  const compare = query.get("compare");
  split.checked = compare !== null;
  const sides = [];
  const apply = () => {
    const left = sides[0].spec();
    const right = split.checked ? sides[1].spec() : undefined;
    try {
      page.set_sides(left, right);
      lastGood = [left, right];
      sides.forEach((s) => s.showError(""));
      return true;
    } catch (e) {
      // The side whose spelling was refused says why.
      let k = 0;
      try {
        page.set_sides(left, undefined);
        k = 1;
      } catch (_) {
        k = 0;
      }
      page.set_sides(...lastGood);
      sides[k].showError(String(e.message || e));
      return false;
    }
  };
  let lastGood = [JSON.parse(page.status()).sides[0].technique, undefined];
  sides.push(sideMenu(document.getElementById("side0"), "Technique", techniques, technique, apply));
  sides.push(sideMenu(document.getElementById("side1"), "Right", techniques, compare || "caustic-triangles", apply));
  document.getElementById("side1").hidden = !split.checked;
  split.onchange = () => { document.getElementById("side1").hidden = !split.checked; apply(); };
  if (compare !== null && !apply() && frames !== null) {
    throw new Error(document.querySelector("#side1 .error").textContent || document.querySelector("#side0 .error").textContent);
  }
  document.getElementById("amplitude").oninput = (e) => page.set_amplitude(parseFloat(e.target.value));
  if (amplitude !== null) document.getElementById("amplitude").value = amplitude;
  document.getElementById("calm").onclick = () => page.calm();
  // The sizes, starting at what the page chose for the adapter.
  const quality = JSON.parse(page.status()).quality;
  const mapSelect = document.getElementById("map");
  const scaleSelect = document.getElementById("scale");
  for (const m of [64, 128, 256, 512, 1024, 2048]) mapSelect.add(new Option(`${m}²`, m));
  for (const f of [0.25, 0.5, 0.75, 1]) scaleSelect.add(new Option(String(f), f));
  if (![...mapSelect.options].some((o) => Number(o.value) === quality.map)) mapSelect.add(new Option(`${quality.map}²`, quality.map));
  if (![...scaleSelect.options].some((o) => Number(o.value) === quality.scale)) scaleSelect.add(new Option(String(quality.scale), quality.scale));
  mapSelect.value = String(quality.map);
  scaleSelect.value = String(quality.scale);
  mapSelect.onchange = () => page.set_quality(0, parseInt(mapSelect.value, 10), 0);
  scaleSelect.onchange = () => page.set_quality(parseFloat(scaleSelect.value), 0, 0);
  const filter = document.getElementById("filter");
  filter.checked = query.get("filter") === "1";
  page.set_filter_water(filter.checked);
  filter.onchange = () => page.set_filter_water(filter.checked);

  // The pointer, in canvas pixels.
  const at = (e) => {
    const r = canvas.getBoundingClientRect();
    const dpr = window.devicePixelRatio || 1;
    return [(e.clientX - r.left) * dpr, (e.clientY - r.top) * dpr];
  };
  canvas.addEventListener("contextmenu", (e) => e.preventDefault());
  canvas.addEventListener("pointerdown", (e) => {
    if (!e.isPrimary) return;
    canvas.setPointerCapture(e.pointerId);
    const what = page.pointer_down(...at(e), e.button === 2 || e.shiftKey);
    canvas.style.cursor = what === "orbit" ? "grabbing" : "crosshair";
  });
  canvas.addEventListener("pointermove", (e) => { if (e.isPrimary) page.pointer_move(...at(e)); });
  const up = () => { page.pointer_up(); canvas.style.cursor = ""; };
  canvas.addEventListener("pointerup", up);
  canvas.addEventListener("pointercancel", up);
  // A notch is 100 pixels, or 3 lines (Firefox), or a page.
  const notch = (e) => e.deltaY / [100, 3, 1][e.deltaMode];
  canvas.addEventListener("wheel", (e) => { e.preventDefault(); page.zoom(-notch(e)); }, { passive: false });
  new ResizeObserver(() => page.resize(...canvasSize())).observe(canvas);

  // The frames.
  let count = 0;
  let previous = null;
  // For the tests: stop after the frame in flight (a still page for a screenshot).
  let stopped = false;
  window.stopFrames = () => { stopped = true; };
  const intervals = [];
  const tick = (now) => {
    if (failed || stopped) return;
    let shown;
    try {
      shown = page.frame(now);
    } catch (e) {
      fail(e);
      return;
    }
    if (shown) {
      count += 1;
      if (previous !== null) intervals.push(now - previous);
      previous = now;
    }
    if (count % 10 === 1) hud(JSON.parse(page.status()));
    if (frames !== null && count >= frames) {
      finish();
      return;
    }
    requestAnimationFrame(tick);
  };
  // After the last frame: wait until the queue has done the frames' work, then one more animation
  // frame for the browser's asynchronous WebGPU errors to arrive, then the verdict from the
  // page's own state.
  const finish = () => {
    // The median frame after the first three (which build the pipelines and textures).
    const all = intervals.length > 3 ? intervals.slice(3) : intervals;
    const steady = all.slice().sort((a, b) => a - b);
    const msPerFrame = steady.length ? steady[Math.floor(steady.length / 2)] : 0;
    let waits = 0;
    page.settle();
    const settle = () => {
      try {
        page.check();
      } catch (e) {
        fail(e);
        return;
      }
      if (!page.settled() || waits++ < 1) {
        requestAnimationFrame(settle);
        return;
      }
      const status = JSON.parse(page.status());
      hud(status);
      const errors = status.sides.filter((s) => s.error).map((s) => `${s.technique}: ${s.error}`);
      if (errors.length) {
        fail(errors.join("; "));
        return;
      }
      const names = status.sides.map((s) => s.technique).join(" | ");
      document.title = `done: ${names}, ${count} frames, ${msPerFrame.toFixed(1)} ms a frame, ` +
        `steady ${status.steady[0]} frames: ${status.steady[1]} created, ${status.steady[2]} bytes uploaded, ` +
        `${status.steady[3]} readbacks`;
    };
    settle();
  };
  requestAnimationFrame(tick);
}

main().catch(fail);
