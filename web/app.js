// The page: the controls become `bumpmap render`'s options as `name=value` lines, the module
// (crates/bumpmap-web, built by scripts/web.sh) draws on the CPU, and the frame goes to the
// canvas. Nothing here knows a technique, a scene or a default: the names come from the module,
// the defaults and checks from the library's option table.

const $ = (id) => document.getElementById(id);
const form = $("controls");
const canvas = $("frame");
const utf8 = new TextEncoder();

const module = await WebAssembly.compile(await (await fetch("bumpmap_web.wasm")).arrayBuffer());
let bm = (await WebAssembly.instantiate(module, {})).exports;

// Copies `data` into the module's memory; [pointer, length] (null for nothing).
function put(data) {
  if (!data || data.length === 0) return [0, 0];
  const ptr = bm.bm_alloc(data.length);
  if (ptr === 0) {
    throw new Error(`the page's module cannot hold ${(data.length / 2 ** 20).toFixed(0)} MiB more (it has 4 GiB at most)`);
  }
  new Uint8Array(bm.memory.buffer, ptr, data.length).set(data);
  return [ptr, data.length];
}

// Runs `work`; what it threw is shown. A trap (the module aborted: out of its memory, most
// likely) leaves the module unusable, so a fresh one is started and the picture drawn again.
function guarded(work, failed = { status: 1, ms: 0 }) {
  try {
    return work();
  } catch (e) {
    if (e instanceof WebAssembly.RuntimeError) {
      showError(`the module stopped (${e.message}), most likely out of its memory (4 GiB at most); it is started again`);
      prepared = false;
      WebAssembly.instantiate(module, {}).then((fresh) => {
        bm = fresh.exports;
        dropped = null;
        form.file.value = "";
        draw({}, true, true);
      });
    } else {
      showError(e.message);
    }
    return failed;
  }
}

// Calls `fn` with the buffers `inputs` (Uint8Arrays or null) as pointer-length pairs, then
// gives them back; the status and a copy of the answer.
function call(fn, ...inputs) {
  const held = inputs.map(put);
  try {
    const status = bm[fn](...held.flat());
    const answer = new Uint8Array(bm.memory.buffer, bm.bm_answer_ptr(), bm.bm_answer_len()).slice();
    return { status, answer, width: bm.bm_answer_width(), height: bm.bm_answer_height() };
  } finally {
    for (const [ptr, len] of held) if (ptr) bm.bm_free(ptr, len);
  }
}

// A closed set's names (0 techniques, 1 scenes, 2 presets), as the command line spells them.
function names(set) {
  bm.bm_names(set);
  const text = new Uint8Array(bm.memory.buffer, bm.bm_answer_ptr(), bm.bm_answer_len());
  return new TextDecoder().decode(text).split("\n");
}

function fill(select, list, chosen) {
  for (const name of list) select.add(new Option(name, name, false, name === chosen));
}
fill(form.technique, names(0), "single-pass");
fill(form.scene, names(1), null); // the first: the command line's default scene
fill(form.preset, names(2), "bricks");

let dropped = null; // { name, bytes } of the user's own heights or model
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

function showError(text) {
  $("error").hidden = !text;
  $("error").textContent = text || "";
}

let prepared = false;

// Prepares the scene the controls describe (its maps made once); false, with the message shown,
// where it cannot be.
function prepare(extra = {}) {
  const name = dropped && utf8.encode(dropped.name);
  const r = call("bm_view", utf8.encode(options(extra)), name, dropped && dropped.bytes);
  prepared = r.status === 0;
  if (!prepared) {
    showError(new TextDecoder().decode(r.answer));
    $("status").textContent = "";
  }
  return r.status;
}

// Prepares (unless only the light or camera moved) and draws; the status and the time taken.
// `keepError` leaves a message shown by whatever called.
function draw(extra = {}, again = true, keepError = false) {
  return guarded(() => drawNow(extra, again, keepError));
}

function drawNow(extra, again, keepError) {
  const t0 = performance.now();
  const status = again || !prepared ? prepare(extra) : 0;
  if (status !== 0) return { status, ms: performance.now() - t0 };
  bm.bm_view_draw(turn.light[0], turn.light[1], turn.camera[0], turn.camera[1]);
  const answer = new Uint8Array(bm.memory.buffer, bm.bm_answer_ptr(), bm.bm_answer_len()).slice();
  const ms = performance.now() - t0;
  const [w, h] = [bm.bm_answer_width(), bm.bm_answer_height()];
  if (w === 0) {
    showError(new TextDecoder().decode(answer));
    return { status: 1, ms };
  }
  if (!keepError) showError("");
  canvas.width = w;
  canvas.height = h;
  canvas.getContext("2d").putImageData(new ImageData(new Uint8ClampedArray(answer.buffer), w, h), 0, 0);
  const image = form["image-is"].value === "normal-map" ? "normal map" : "heights";
  const on = dropped && isModel(dropped.name) ? dropped.name : `the ${form.scene.value}, ${dropped ? image : "heights"}: ${dropped ? dropped.name : heightsPreset()}`;
  $("status").textContent = `${form.technique.value} on ${on}; ${again ? "prepared and drawn" : "drawn"} in ${ms.toFixed(0)} ms`;
  return { status: 0, ms };
}

let pending = null;
function redraw(again) {
  if (pending !== null) {
    pending = pending || again;
    return;
  }
  pending = again;
  requestAnimationFrame(() => {
    const a = pending;
    pending = null;
    draw({}, a);
  });
}

// Saving makes maps from heights: not from a model, nor from an image that is a normal map.
function syncExport() {
  $("export").disabled = Boolean(dropped && (isModel(dropped.name) || form["image-is"].value === "normal-map"));
}

form.addEventListener("input", (e) => {
  if (e.target.name === "image-is") syncExport();
  if (e.target.name === "bump-scale") form["scale-shown"].value = e.target.value;
  if (e.target.name !== "file") redraw(true);
});
form.file.addEventListener("change", async () => {
  const file = form.file.files[0];
  dropped = file ? { name: file.name, bytes: new Uint8Array(await file.arrayBuffer()) } : null;
  // A model is the scene: the built-in scenes and the presets wait until it is taken away.
  const model = Boolean(dropped && isModel(dropped.name));
  form.scene.disabled = model;
  form.preset.disabled = Boolean(dropped);
  form.seed.disabled = Boolean(dropped);
  form["image-is"].disabled = !dropped || model;
  syncExport();
  $("inspect").disabled = !dropped || model;
  $("verdict").hidden = true;
  // A large file takes seconds to prepare on one thread: say so before the page waits.
  if (dropped) {
    $("status").textContent = `preparing ${dropped.name} (${(dropped.bytes.length / 2 ** 20).toFixed(1)} MiB)…`;
    await new Promise((painted) => requestAnimationFrame(() => setTimeout(painted, 0)));
  }
  draw();
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

// A file `bumpmap normalmap` writes, as the save menu names it: WHAT-CONTAINER-BITS, WHAT one of
// normal, heights, occlusion (the library's MapFile, in its order).
const MAP_FILES = ["normal-png", "normal-ktx2", "heights-png", "occlusion-png"];
const SUFFIX = { "normal-png": "_normal.png", "normal-ktx2": "_normal.ktx2", "heights-png": "_heights.png", "occlusion-png": "_ao.png" };
function mapFile(args, preset, as) {
  const [what, container, bits] = as.split("-");
  const which = MAP_FILES.indexOf(`${what}-${container}`);
  const held = [utf8.encode(`${args}\nbits=${bits}`), dropped && utf8.encode(dropped.name), dropped && dropped.bytes, utf8.encode(preset)];
  const ptrs = held.map(put);
  try {
    const status = bm.bm_map_file(...ptrs.flat(), which);
    const answer = new Uint8Array(bm.memory.buffer, bm.bm_answer_ptr(), bm.bm_answer_len()).slice();
    return { status, answer, suffix: SUFFIX[`${what}-${container}`] };
  } finally {
    for (const [ptr, len] of ptrs) if (ptr) bm.bm_free(ptr, len);
  }
}

$("export").addEventListener("click", async () => {
  const as = form["save-as"].value;
  // The occlusion's horizons take seconds on one thread: say so before the page waits.
  $("status").textContent = `making ${form["save-as"].selectedOptions[0].textContent}…`;
  await new Promise((painted) => requestAnimationFrame(() => setTimeout(painted, 0)));
  guarded(() => save(as));
});
function save(as) {
  const r = mapFile(`scale=${form["bump-scale"].value}`, heightsPreset(), as);
  if (r.status !== 0) return showError(new TextDecoder().decode(r.answer));
  const a = document.createElement("a");
  a.href = URL.createObjectURL(new Blob([r.answer], { type: r.suffix.endsWith(".ktx2") ? "image/ktx2" : "image/png" }));
  a.download = `${(dropped ? dropped.name.replace(/\.[^.]*$/, "") : heightsPreset().replace(/[:@]/g, "_"))}${r.suffix}`;
  a.click();
  $("status").textContent = `saved ${a.download} (${(r.answer.length / 1024).toFixed(0)} KiB)`;
}

$("inspect").addEventListener("click", () => guarded(() => {
  const r = call("bm_inspect", utf8.encode(dropped.name), dropped.bytes);
  const text = new TextDecoder().decode(r.answer);
  if (r.status !== 0) return showError(text);
  $("verdict").textContent = text;
  $("verdict").hidden = false;
}));

$("backend").textContent = "CPU renderer in WebAssembly (the emulated GeForce 256, one thread); WebGPU is not used yet";

// What the tests drive (scripts/test_web.py): a frame or a normal map for given options, the
// answer as base64 so it crosses the DevTools protocol as text.
function base64(u8) {
  let s = "";
  for (let i = 0; i < u8.length; i += 0x8000) s += String.fromCharCode(...u8.subarray(i, i + 0x8000));
  return btoa(s);
}
window.bumpmap = {
  render(args) {
    // As the controls would, without touching them or the kept scene's turn.
    let r = call("bm_view", utf8.encode(args), null, null);
    if (r.status === 0) {
      bm.bm_view_draw(0, 0, 0, 0);
      r = { status: 0, answer: new Uint8Array(bm.memory.buffer, bm.bm_answer_ptr(), bm.bm_answer_len()).slice(), width: bm.bm_answer_width(), height: bm.bm_answer_height() };
    }
    prepared = false; // the page's own scene is prepared again on its next draw
    return { status: r.status, width: r.width, height: r.height, data: r.status === 0 ? base64(r.answer) : new TextDecoder().decode(r.answer) };
  },
  // `as`: a value of the save menu (normal-png-8, heights-png-16, …).
  mapFile(args, preset, as = "normal-png-8") {
    const r = mapFile(args, preset, as);
    return { status: r.status, data: r.status === 0 ? base64(r.answer) : new TextDecoder().decode(r.answer) };
  },
  // Prepares and draws (`again`, the default) or draws the kept scene again, turned by `t`.
  draw: (extra = {}, again = true, t = null) => {
    if (t) Object.assign(turn, t);
    return draw(extra, again);
  },
  // What the page does after a trap (as a module out of memory ends in), without one.
  trapForTest: () => guarded(() => {
    throw new WebAssembly.RuntimeError("unreachable (a test's)");
  }),
  state: () => ({
    status: $("status").textContent,
    error: $("error").hidden ? "" : $("error").textContent,
    verdict: $("verdict").hidden ? "" : $("verdict").textContent,
  }),
};
draw();
document.body.dataset.ready = "yes";
