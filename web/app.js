// The page: the controls become `bumpmap render`'s options as `name=value` lines, the module
// (crates/bumpmap-web, built by scripts/web.sh) draws on the CPU in a worker (worker.js), and
// the frame goes to the canvas. Nothing here knows a technique, a scene or a default: the names
// come from the module, the defaults and checks from the library's option table.

const $ = (id) => document.getElementById(id);
const form = $("controls");
const canvas = $("frame");
const text = (bytes) => new TextDecoder().decode(bytes);

// The module's thread: `ask(op, args)` is its answer, in the order asked.
const worker = new Worker("worker.js", { type: "module" });
const waiting = new Map();
let asked = 0;
worker.onmessage = ({ data }) => {
  waiting.get(data.id)(data);
  waiting.delete(data.id);
};
function ask(op, args = [], transfer = []) {
  return new Promise((resolve) => {
    const id = asked++;
    waiting.set(id, resolve);
    worker.postMessage({ id, op, args }, transfer);
  });
}

// Whether the worker failed the call, said in the page. A trap (the module aborted: out of its
// memory, most likely) left it with a fresh module and no file: the page forgets the file too and
// draws the controls' scene again, the message kept.
async function failed(reply) {
  if (reply.trapped) {
    showError(`the module stopped (${reply.trapped}), most likely out of its memory (4 GiB at most); it is started again`);
    prepared = false;
    dropped = null;
    form.file.value = "";
    syncFile();
    await draw({}, true, true);
    return true;
  }
  if (reply.error) {
    showError(reply.error);
    return true;
  }
  return false;
}

function fill(select, list, chosen) {
  for (const name of list) select.add(new Option(name, name, false, name === chosen));
}
// A closed set's names (0 techniques, 1 scenes, 2 presets), as the command line spells them.
const names = async (set) => text((await ask("names", [set])).answer).split("\n");
fill(form.technique, await names(0), "single-pass");
fill(form.scene, await names(1), null); // the first: the command line's default scene
fill(form.preset, await names(2), "bricks");

let dropped = null; // { name, size } of the user's own heights or model (its bytes are the worker's)
// How far the picture has been dragged: the light (turns round, tilt up) and, with Shift or the
// right button, the camera (yaw, pitch), as `bumpmap view`'s mouse turns them.
const turn = { light: [0, 0], camera: [0, 0] };

// The options the controls stand for, one `name=value` a line.
function options(extra = {}) {
  const o = {
    scene: form.scene.value,
    technique: form.technique.value,
    "bump-scale": form["bump-scale"].value,
    width: canvas.width,
    height: canvas.height,
  };
  // A dropped image is the height field, a dropped model the scene: the module tells them apart.
  if (!dropped) o["height-field"] = heightsPreset();
  else if (!isModel(dropped.name) && form["image-is"].value === "normal-map") o["normal-map"] = dropped.name;
  if (form.filter.value) o.filter = form.filter.value;
  return Object.entries({ ...o, ...extra }).map(([k, v]) => `${k}=${v}`).join("\n");
}

function heightsPreset() {
  return form.preset.value.replace("SEED", String(Math.max(0, Math.round(Number(form.seed.value) || 0))));
}

const isModel = (name) => /\.(glb|gltf|obj)$/i.test(name);

function showError(message) {
  $("error").hidden = !message;
  $("error").textContent = message || "";
}

let prepared = false;

// Prepares (unless only the light or camera moved) and draws; the status and the time taken.
// `keepError` leaves a message shown by whatever called.
async function draw(extra = {}, again = true, keepError = false) {
  const t0 = performance.now();
  if (again || !prepared) {
    const r = await ask("view", [options(extra)]);
    if (await failed(r)) return { status: 1, ms: performance.now() - t0 };
    prepared = r.status === 0;
    if (!prepared) {
      showError(text(r.answer));
      $("status").textContent = "";
      return { status: r.status, ms: performance.now() - t0 };
    }
  }
  const r = await ask("draw", [[...turn.light, ...turn.camera]]);
  if (await failed(r)) return { status: 1, ms: performance.now() - t0 };
  const ms = performance.now() - t0;
  if (r.width === 0) {
    showError(text(r.answer));
    return { status: 1, ms };
  }
  if (!keepError) showError("");
  canvas.width = r.width;
  canvas.height = r.height;
  canvas.getContext("2d").putImageData(new ImageData(new Uint8ClampedArray(r.answer.buffer), r.width, r.height), 0, 0);
  const image = form["image-is"].value === "normal-map" ? "normal map" : "heights";
  const on = dropped && isModel(dropped.name) ? dropped.name : `the ${form.scene.value}, ${dropped ? image : "heights"}: ${dropped ? dropped.name : heightsPreset()}`;
  $("status").textContent = `${form.technique.value} on ${on}; ${again ? "prepared and drawn" : "drawn"} in ${ms.toFixed(0)} ms`;
  return { status: 0, ms };
}

// Draws again after a change, one frame at a time: changes made while a frame is drawn are
// drawn together next (prepared again if any of them needs it).
let pending = null;
let drawing = false;
async function redraw(again) {
  pending = (pending ?? false) || again;
  if (drawing) return;
  drawing = true;
  while (pending !== null) {
    const a = pending;
    pending = null;
    await draw({}, a);
  }
  drawing = false;
}

// Saving makes maps from heights: not from a model, nor from an image that is a normal map.
function syncExport() {
  $("export").disabled = Boolean(dropped && (isModel(dropped.name) || form["image-is"].value === "normal-map"));
}

// The controls a file given (or taken away) turns on or off.
function syncFile() {
  // A model is the scene: the built-in scenes and the presets wait until it is taken away.
  const model = Boolean(dropped && isModel(dropped.name));
  form.scene.disabled = model;
  form.preset.disabled = Boolean(dropped);
  form.seed.disabled = Boolean(dropped);
  form["image-is"].disabled = !dropped || model;
  syncExport();
  $("inspect").disabled = !dropped || model;
  $("verdict").hidden = true;
}

form.addEventListener("input", (e) => {
  if (e.target.name === "image-is") syncExport();
  if (e.target.name === "bump-scale") form["scale-shown"].value = e.target.value;
  if (e.target.name !== "file") redraw(true);
});
form.file.addEventListener("change", async () => {
  const file = form.file.files[0];
  const bytes = file ? new Uint8Array(await file.arrayBuffer()) : null;
  dropped = file ? { name: file.name, size: bytes.length } : null;
  syncFile();
  // Sent once, moved rather than copied; a large file takes seconds to prepare: said meanwhile.
  if (await failed(await ask("setFile", [file ? file.name : null, bytes], bytes ? [bytes.buffer] : []))) return;
  if (dropped) $("status").textContent = `preparing ${dropped.name} (${(dropped.size / 2 ** 20).toFixed(1)} MiB)…`;
  redraw(true);
});

let from = null; // where a drag started, and the turn then
canvas.addEventListener("pointerdown", (e) => {
  canvas.setPointerCapture(e.pointerId);
  const which = e.shiftKey || e.button === 2 ? "camera" : "light";
  from = { x: e.clientX, y: e.clientY, which, start: [...turn[which]] };
});
canvas.addEventListener("pointerup", () => (from = null));
canvas.addEventListener("contextmenu", (e) => e.preventDefault());
canvas.addEventListener("pointermove", (e) => {
  if (!from) return;
  const r = canvas.getBoundingClientRect();
  const dx = (e.clientX - from.x) / r.width;
  const dy = (e.clientY - from.y) / r.height;
  turn[from.which] = from.which === "light"
    ? [from.start[0] + dx, from.start[1] - dy * 2]
    : [from.start[0] - dx * Math.PI, from.start[1] + dy * Math.PI];
  redraw(false);
});

// The files `bumpmap normalmap` writes that the page saves, as the module names them (the
// library's MapFile, in its order): [name, suffix of the saved file's name]. The save menu's
// values are NAME-BITS.
const MAP_FILES = (await names(3)).map((line) => line.split(" "));
async function mapFile(args, preset, as) {
  const bits = as.slice(as.lastIndexOf("-") + 1);
  const which = MAP_FILES.findIndex(([name]) => `${name}-${bits}` === as);
  const r = await ask("mapFile", [`${args}\nbits=${bits}`, preset, which]);
  return { ...r, suffix: which >= 0 ? MAP_FILES[which][1] : "" };
}

$("export").addEventListener("click", async () => {
  // The occlusion's horizons take seconds on one thread: said meanwhile.
  $("status").textContent = `making ${form["save-as"].selectedOptions[0].textContent}…`;
  const r = await mapFile(`scale=${form["bump-scale"].value}`, heightsPreset(), form["save-as"].value);
  if (await failed(r)) return;
  if (r.status !== 0) return showError(text(r.answer));
  const a = document.createElement("a");
  a.href = URL.createObjectURL(new Blob([r.answer], { type: r.suffix.endsWith(".ktx2") ? "image/ktx2" : "image/png" }));
  a.download = `${(dropped ? dropped.name.replace(/\.[^.]*$/, "") : heightsPreset().replace(/[:@]/g, "_"))}${r.suffix}`;
  a.click();
  $("status").textContent = `saved ${a.download} (${(r.answer.length / 1024).toFixed(0)} KiB)`;
});

$("inspect").addEventListener("click", async () => {
  const r = await ask("inspect");
  if (await failed(r)) return;
  if (r.status !== 0) return showError(text(r.answer));
  $("verdict").textContent = text(r.answer);
  $("verdict").hidden = false;
});

$("backend").textContent = "CPU renderer in WebAssembly (the emulated GeForce 256, one thread, in a worker); WebGPU is not used yet";

// What the tests drive (scripts/test_web.py): a frame or a normal map for given options, the
// answer as base64 so it crosses the DevTools protocol as text. Each returns a promise.
function base64(u8) {
  let s = "";
  for (let i = 0; i < u8.length; i += 0x8000) s += String.fromCharCode(...u8.subarray(i, i + 0x8000));
  return btoa(s);
}
window.bumpmap = {
  // As the controls would (without any file given), leaving the controls and the turn alone.
  async render(args) {
    let r = await ask("view", [args, false]);
    if (r.status === 0) r = await ask("draw", [[0, 0, 0, 0]]);
    prepared = false; // the page's own scene is prepared again on its next draw
    return { status: r.status, width: r.width, height: r.height, data: r.status === 0 ? base64(r.answer) : text(r.answer) };
  },
  // `as`: a value of the save menu (normal-png-8, heights-png-16, …).
  async mapFile(args, preset, as = "normal-png-8") {
    const r = await mapFile(args, preset, as);
    return { status: r.status, data: r.status === 0 ? base64(r.answer) : text(r.answer) };
  },
  // Prepares and draws (`again`, the default) or draws the kept scene again, turned by `t`.
  draw: (extra = {}, again = true, t = null) => {
    if (t) Object.assign(turn, t);
    return draw(extra, again);
  },
  // What the page does after a trap (as a module out of memory ends in), without one.
  trapForTest: async () => failed(await ask("trap")),
  state: () => ({
    status: $("status").textContent,
    error: $("error").hidden ? "" : $("error").textContent,
    verdict: $("verdict").hidden ? "" : $("verdict").textContent,
  }),
};
await draw();
document.body.dataset.ready = "yes";
